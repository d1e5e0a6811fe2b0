/* rt_probe.c: how much faster would the RT cores trace the renderer's rays
 * on the same GPU? Loads a pbrt scene through the normal loader, builds the
 * renderer's triangle tree (cv_bvh_build with the CAVALRY_BVH_* knobs) and
 * makes bvh_work's path-tracer-like rays (bench/rays.h), spawned from this
 * traversal's hits. Then traces every query type with two back ends:
 *   gl:     Cavalry's traversal (glsl/trace/test/trace_probe.comp: the
 *           traverse.glsl path intersect.comp and shadow.comp compile),
 *           one dispatch per repeat, timed with GL timestamp queries
 *           (gpu/timer.h);
 *   vulkan: a ray-tracing pipeline over one BLAS of the same triangles
 *           (bench/rt_vk.h), one launch per repeat, timed with Vulkan
 *           timestamp queries.
 * Camera and bounce rays are closest-hit queries, shadow rays any-hit.
 * Prints per query type the median time and rays/s of each back end, their
 * ratio and how often the two agree: closest hits on the same triangle at
 * a t within a relative 1e-3 (or both missing), any-hit queries on
 * occluded or not.
 *   rt_probe SCENE.pbrt [--res N] [--seed S] [--repeats R] [--shuffle]
 * --shuffle traces each set in a random order instead of pixel and parent
 * order: the incoherent end of the range the renderer's compacted queues
 * lie in.
 * Without a Vulkan device that has ray-tracing pipelines the Vulkan columns
 * say why they are empty and the exit status stays 0. Run from the build
 * tree (embedded shaders) or with CAVALRY_DATA_DIR at the source tree. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench/rays.h"
#include "bench/scene_tree.h"
#include "bench/rt_vk.h"
#include "bvh/bvh.h"
#include "cli/knobs.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/program.h"
#include "gpu/timer.h"
#include "scene/scene.h"

#define MAX_REPEATS 64

/* Cavalry's traversal: the programs and the buffers of one ray set. */
struct gl_tracer {
    struct cv_gpu *gpu;
    struct cv_program *closest, *any;
    GLuint rays, results;
    size_t cap;  /* rays the two buffers hold */
};

static struct cv_program *probe_program(struct cv_gpu *gpu, const struct cv_bvh *bvh, bool any,
                                        struct cv_error *err)
{
    const char *defs[3];
    int k = 0;
    if (cv_bvh_stack_define(bvh))
        defs[k++] = cv_bvh_stack_define(bvh);
    if (any)
        defs[k++] = "CV_PROBE_ANY_HIT";
    defs[k] = NULL;
    return cv_program_get(gpu, "trace/test/trace_probe.comp", defs, err);
}

/* Uploads n rays, growing the buffers when needed, and binds them. */
static bool gl_load(struct gl_tracer *g, const struct bench_ray *r, uint32_t n,
                    struct cv_error *err)
{
    if (n > g->cap) {
        cv_buffer_destroy(&g->rays);
        cv_buffer_destroy(&g->results);
        g->cap = n;
        g->rays = cv_buffer_create(n * sizeof(*r), NULL, "probe rays", err);
        g->results = g->rays ? cv_buffer_create_uninit((size_t)n * 8, "probe results", err) : 0;
        if (!g->results) {
            g->cap = 0;
            return false;
        }
    }
    cv_buffer_bind(g->rays, CV_BIND_PROBE_IN);
    cv_buffer_bind(g->results, CV_BIND_PROBE_OUT);
    return n == 0 || cv_buffer_upload(g->rays, 0, n * sizeof(*r), r, err);
}

static void gl_dispatch(const struct gl_tracer *g, bool any, uint32_t n)
{
    const struct cv_program *p = any ? g->any : g->closest;
    cv_program_set_uint(p, "u_n_rays", n);
    cv_program_dispatch_1d(p, n);
}

/* The ray generator's tracer: closest hits through Cavalry's traversal. */
static bool gl_trace(void *ctx, const struct bench_ray *r, uint32_t n, struct bench_hit *out)
{
    struct gl_tracer *g = ctx;
    struct cv_error err = {{0}};
    uint32_t *res = malloc((size_t)n * 8 + 8);
    bool ok = gl_load(g, r, n, &err);
    if (ok && n) {
        gl_dispatch(g, false, n);
        ok = cv_buffer_read(g->results, 0, (size_t)n * 8, res, &err);
    }
    for (uint32_t i = 0; ok && i < n; i++) {
        float t;
        memcpy(&t, &res[2 * i], 4);
        out[i] = (struct bench_hit){.t = t, .prim = res[2 * i + 1]};
    }
    free(res);
    if (!ok)
        fprintf(stderr, "rt_probe: tracing on GL: %s\n", err.msg);
    return ok;
}

/* Puts every set's rays in a random order (Fisher-Yates, xorshift keyed by
 * the seed), after all of them are made: the same rays, none coherent with
 * its neighbours. */
static void shuffle_sets(struct bench_rayset sets[BENCH_Q_TYPES], uint64_t seed)
{
    uint64_t x = 0x2545F4914F6CDD1Dull ^ (seed * 0x9E3779B97F4A7C15ull);
    for (int q = 0; q < BENCH_Q_TYPES; q++)
        for (uint32_t i = sets[q].n; i > 1; i--) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            uint32_t j = (uint32_t)(x % i);
            struct bench_ray t = sets[q].r[i - 1];
            sets[q].r[i - 1] = sets[q].r[j];
            sets[q].r[j] = t;
        }
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(const double *v, int n)
{
    double s[MAX_REPEATS];
    memcpy(s, v, sizeof(double) * (size_t)n);
    qsort(s, (size_t)n, sizeof(double), cmp_double);
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

/* Fractions of rays on which the back ends agree: `same` the result (the
 * triangle, or occluded or not), `t_ok` the distance alone (closest hits
 * on another triangle at the same t: coplanar or shared edges). */
static void agreement(const uint32_t *a, const uint32_t *b, uint32_t n, bool any, double *same,
                      double *t_ok)
{
    uint32_t s = 0, t = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t pa = a[2 * i + 1], pb = b[2 * i + 1];
        bool ha = pa != UINT32_MAX, hb = pb != UINT32_MAX;
        float ta, tb;
        memcpy(&ta, &a[2 * i], 4);
        memcpy(&tb, &b[2 * i], 4);
        bool close = fabsf(ta - tb) <= 1e-3f * fmaxf(fabsf(ta), fabsf(tb));
        if (any) {
            s += ha == hb;
            t += ha == hb;
        } else {
            s += (!ha && !hb) || (ha && hb && pa == pb && close);
            t += (!ha && !hb) || (ha && hb && close);
        }
    }
    *same = n ? (double)s / n : 1;
    *t_ok = n ? (double)t / n : 1;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s SCENE.pbrt [--res N] [--seed S] [--repeats R] [--shuffle]\n",
                argv[0]);
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    const char *path = argv[1];
    int res = 512, repeats = 5;
    uint64_t seed = 1;
    bool shuffle = false;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        bool has_v = i + 1 < argc;
        if (has_v && !strcmp(a, "--res"))
            res = atoi(argv[++i]);
        else if (has_v && !strcmp(a, "--seed"))
            seed = strtoull(argv[++i], NULL, 10);
        else if (has_v && !strcmp(a, "--repeats"))
            repeats = atoi(argv[++i]);
        else if (!strcmp(a, "--shuffle"))
            shuffle = true;
        else {
            fprintf(stderr, "rt_probe: unknown argument %s\n", a);
            return 2;
        }
    }
    if (res < 1 || res > 8192 || repeats < 1 || repeats > MAX_REPEATS) {
        fprintf(stderr, "rt_probe: --res 1..8192, --repeats 1..%d\n", MAX_REPEATS);
        return 2;
    }
    struct cv_error err = {{0}};
    struct cv_bvh_params params = cv_knobs_from_environment().bvh;
    struct bench_scene_tree tree;
    if (!bench_scene_tree_open(path, &params, &tree, &err)) {
        fprintf(stderr, "rt_probe: %s\n", err.msg);
        return 1;
    }
    struct cv_scene *sc = tree.sc;
    struct bench_tris m = tree.m;
    struct cv_gpu *gpu = tree.gpu;
    struct cv_bvh *bvh = tree.bvh;
    struct gl_tracer g = {.gpu = gpu};
    if (!(g.closest = probe_program(gpu, bvh, false, &err)) ||
        !(g.any = probe_program(gpu, bvh, true, &err))) {
        fprintf(stderr, "rt_probe: %s\n", err.msg);
        return 1;
    }

    /* the static triangles' indices, packed for the BLAS (which reads
     * the scene's vertex array as it is) */
    uint32_t *idx = malloc(sizeof(uint32_t) * 3 * (size_t)m.n);
    for (uint32_t t = 0; t < m.n; t++)
        for (int j = 0; j < 3; j++)
            idx[3 * t + j] = (&m.t[t].idx.x)[j];
    struct bench_rayset sets[BENCH_Q_TYPES] = {{0}};
    if (!bench_rays_make(&(struct bench_rays_params){.sc = sc, .m = &m, .res = res,
                                                     .seed = seed, .trace = gl_trace, .ctx = &g},
                         sets))
        return 1;
    if (shuffle)
        shuffle_sets(sets, seed);

    fprintf(stderr, "rt_probe: %u rays made\n",
            sets[0].n + sets[1].n + sets[2].n + sets[3].n);
    /* Cavalry's traversal: one untimed dispatch, then the timed ones */
    struct cv_gpu_timer *timer = cv_gpu_timer_create(
        gpu, &(struct cv_gpu_timer_params){.names = bench_q_names, .n_names = BENCH_Q_TYPES,
                                           .n_slots = (unsigned)repeats});
    uint32_t *gl_res[BENCH_Q_TYPES] = {0};
    double gl_ms[BENCH_Q_TYPES][MAX_REPEATS];
    for (int q = 0; q < BENCH_Q_TYPES; q++) {
        uint32_t n = sets[q].n;
        bool any = q == BENCH_Q_SHADOW;
        gl_res[q] = malloc((size_t)n * 8 + 8);
        if (!gl_load(&g, sets[q].r, n, &err)) {
            fprintf(stderr, "rt_probe: %s\n", err.msg);
            return 1;
        }
        if (n)
            gl_dispatch(&g, any, n);
        for (int k = 0; k < repeats && n; k++) {
            cv_gpu_timer_begin(timer, (unsigned)q, (unsigned)k);
            gl_dispatch(&g, any, n);
            cv_gpu_timer_end(timer);
        }
        cv_gpu_timer_collect(timer);
        for (int k = 0; k < repeats; k++)
            gl_ms[q][k] = cv_gpu_timer_slot_ms(timer, (unsigned)q, (unsigned)k);
        if (n && !cv_buffer_read(g.results, 0, (size_t)n * 8, gl_res[q], &err)) {
            fprintf(stderr, "rt_probe: %s\n", err.msg);
            return 1;
        }
    }

    /* GL is done with before Vulkan starts: the NVIDIA Vulkan driver
     * lives in its GLX library, and once that is loaded libepoxy can no
     * longer tell which of GLX or EGL owns the context, aborting on the
     * first GL entry point it has not resolved yet */
    char gl_name[512];
    snprintf(gl_name, sizeof(gl_name), "%s, %s", gpu->info.renderer, gpu->info.version);
    uint32_t tree_nodes = cv_bvh_stats(bvh)->n_nodes;
    cv_gpu_timer_destroy(&timer);
    cv_buffer_destroy(&g.rays);
    cv_buffer_destroy(&g.results);
    bench_scene_tree_close_gpu(&tree);

    fprintf(stderr, "rt_probe: GL traversal timed\n");

    /* the RT cores */
    struct rt_vk *vk = NULL;
    struct rt_vk_info vi;
    struct cv_error vk_err = {{0}};
    bool have_vk = rt_vk_create(sc->vertices, sizeof(CvVertex), sc->n_vertices, idx, m.n, &vk,
                                &vi, &vk_err);
    uint32_t *vk_res[BENCH_Q_TYPES] = {0};
    double vk_ms[BENCH_Q_TYPES][MAX_REPEATS];
    for (int q = 0; q < BENCH_Q_TYPES && have_vk; q++) {
        vk_res[q] = malloc((size_t)sets[q].n * 8 + 8);
        have_vk = rt_vk_trace(vk, sets[q].r, sets[q].n, q == BENCH_Q_SHADOW, repeats, vk_ms[q],
                              vk_res[q], &vk_err);
    }

    printf("%s: %u static triangles, %u lights; rays from a %d-wide camera grid, seed %llu, "
           "%s; median of %d repeats\n",
           path, m.n, sc->n_lights, res, (unsigned long long)seed,
           shuffle ? "shuffled" : "in pixel order", repeats);
    printf("gl: %s; tree %u nodes\n", gl_name, tree_nodes);
    if (have_vk)
        printf("vulkan: %s, %s; BLAS %.3f ms (%.1f MiB), TLAS %.3f ms\n", vi.device, vi.driver,
               vi.blas_ms, vi.blas_mb, vi.tlas_ms);
    else
        printf("vulkan: unavailable: %s\n", vk_err.msg);
    printf("%-8s %9s %10s %10s %10s %10s %7s %7s %7s\n", "query", "rays", "gl ms", "gl Mray/s",
           "vk ms", "vk Mray/s", "vk/gl", "same%", "t-ok%");
    double all_rays = 0, all_gl = 0, all_vk = 0;
    for (int q = 0; q < BENCH_Q_TYPES; q++) {
        uint32_t n = sets[q].n;
        double gm = median(gl_ms[q], repeats);
        all_rays += n;
        all_gl += gm;
        printf("%-8s %9u %10.4f %10.1f", bench_q_names[q], n, gm, gm > 0 ? n / gm * 1e-3 : 0);
        if (have_vk) {
            double vm = median(vk_ms[q], repeats), same, t_ok;
            all_vk += vm;
            agreement(gl_res[q], vk_res[q], n, q == BENCH_Q_SHADOW, &same, &t_ok);
            printf(" %10.4f %10.1f %7.2f %7.2f %7.2f", vm, vm > 0 ? n / vm * 1e-3 : 0,
                   vm > 0 ? gm / vm : 0, 100 * same, 100 * t_ok);
        }
        printf("\n");
    }
    printf("%-8s %9.0f %10.4f %10.1f", "all", all_rays, all_gl,
           all_gl > 0 ? all_rays / all_gl * 1e-3 : 0);
    if (have_vk)
        printf(" %10.4f %10.1f %7.2f", all_vk, all_vk > 0 ? all_rays / all_vk * 1e-3 : 0,
               all_vk > 0 ? all_gl / all_vk : 0);
    printf("\n");

    for (int q = 0; q < BENCH_Q_TYPES; q++) {
        free(gl_res[q]);
        free(vk_res[q]);
    }
    rt_vk_destroy(&vk);
    bench_rays_free(sets);
    free(idx);
    bench_scene_tree_close(&tree);
    return 0;
}
