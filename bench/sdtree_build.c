/* sdtree_build.c: the CPU time of the host's work at the end of a training
 * iteration of rlpath's sdtree guide (trace/sdtree.c: cv_sdtree_refine and
 * cv_sdtree_table, from the statistics the shaders splatted), for N
 * synthetic training records splatted on the host: points on the walls of a
 * closed box (the orientation class of each wall's normal), directions
 * spread over the hemisphere in front of it, radiance from a bright patch of
 * the ceiling and a dim rest. A benchmark, not a test: figures go to
 * bench/RESULTS.md.
 *
 * usage: bench/sdtree_build [N ...]   (records per iteration; default 4194304) */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "base/mem.h"
#include "trace/sdtree.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static double rnd(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) * 0x1p-53;
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A record on wall cls (normal axis cls / 2, facing + if cls is even) of
 * the box [0, 10]^3, looking into the room. */
static void synth(struct cv_sd_record *r)
{
    int cls = (int)(rnd() * 6) % 6, axis = cls / 2;
    double sign = cls & 1 ? -1 : 1;
    for (int a = 0; a < 3; a++)
        r->p[a] = (float)(10 * rnd());
    r->p[axis] = cls & 1 ? 10.0f : 0.0f;
    /* cosine-weighted about the wall's normal */
    double u1 = rnd(), u2 = rnd(), s = sqrt(u1), phi = 2 * M_PI * u2, c = sqrt(1 - u1);
    double l[3] = {s * cos(phi), s * sin(phi), c}, w[3];
    int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    w[a1] = l[0];
    w[a2] = l[1];
    w[axis] = sign * l[2];
    r->pdf = (float)(c / M_PI);
    r->u = (float)(0.5 * (w[2] + 1)) + (float)cls;
    r->v = (float)((atan2(w[1], w[0]) + M_PI) / (2 * M_PI));
    if (r->v >= 1)
        r->v = 0;
    r->beta = 1;
    /* the ceiling (+z) patch around the box's middle is the light */
    r->L = w[2] > 0.8 ? 20.0f * (float)rnd() : (float)(0.1 * rnd());
}

int main(int argc, char **argv)
{
    const float bmin[3] = {0, 0, 0}, bmax[3] = {10, 10, 10};
    int n_sizes = argc > 1 ? argc - 1 : 1;
    for (int i = 0; i < n_sizes; i++) {
        size_t n = argc > 1 ? strtoull(argv[1 + i], NULL, 10) : (size_t)1 << 22;
        struct cv_sd_record *rec = cv_xcalloc(n ? n : 1, sizeof(*rec));
        for (size_t k = 0; k < n; k++)
            synth(&rec[k]);
        /* a guide learned from the records (untimed: the tree a render's
         * iterations reach), then the records splatted into its training
         * tree's statistics (untimed: the shaders' work) */
        struct cv_sdtree *g = cv_sdtree_create(bmin, bmax);
        cv_sdtree_learn_records(g, rec, n, &cv_sdtree_defaults, NULL);
        float(*t)[4] = NULL;
        size_t nt = 0;
        cv_sdtree_table(g, &cv_sdtree_defaults, &t, &nt);
        size_t words = cv_sdtree_stat_words(g);
        uint32_t *stats = cv_xcalloc(words, sizeof(*stats));
        struct cv_sd_frame f = cv_sdtree_frame(g, &cv_sdtree_defaults);
        for (size_t k = 0; k < n; k++)
            cv_sdtree_splat((const float(*)[4])t, &f, stats, &rec[k]);
        free(t);
        /* the host's work at the end of a training iteration */
        struct cv_sdtree_stats st;
        double t0 = cpu_seconds();
        cv_sdtree_refine(g, stats, &cv_sdtree_defaults, &st);
        cv_sdtree_table(g, &cv_sdtree_defaults, &t, &nt);
        double dt = cpu_seconds() - t0;
        printf("records %zu: refine and table %.3f ms CPU, statistics read back %zu kB, "
               "%u spatial leaves, %u sampling and %u training quadtree nodes, depth %u, "
               "table %zu kB\n",
               n, 1e3 * dt, words * 4 / 1024, st.spatial_leaves, st.quad_nodes, st.train_nodes,
               st.max_quad_depth, nt * 16 / 1024);
        free(t);
        free(stats);
        cv_sdtree_destroy(&g);
        free(rec);
    }
    return 0;
}
