/* rlpath_sd_sample_test.c: rlpath's sdtree guide on the GPU (glsl/trace/
 * rlpath/sdtree.glsl, through test_sd_sample.comp) against the host's
 * table (trace/sdtree.c), for a tree built from synthetic records (a
 * bright spot of directions over a dimmer half of the sphere) and uploaded
 * as the renderer does (cv_rlpath_sd_build): the spatial lookup finds the
 * host's leaf, weight and light estimate (the adjoint-driven roulette's,
 * sd_shade.comp); directions drawn from the leaf's quadtree are
 * unit vectors whose pdf at sampling equals the pdf evaluated at them and
 * the host's; their histogram over 64 x 64 equal-area cells follows the
 * pdf (chi-square against the exact integral of the host's piecewise
 * constant density over each cell, p >= 0.01); the same for the one-sample
 * mixture with a Lambertian lobe as sd_shade.comp draws it (density m pQ +
 * (1 - m) pBSDF); the guide's draws again with the quadtrees' top blocks
 * of fewer levels (0, 2 and 4, as tables with many quadtrees that guide get
 * them); the GPU's pdf on a grid of directions equals the host's.
 * The spatial lookup through the table's grid block and the GPU's full
 * descent name the leaf of the host's descent for random points inside
 * and outside the root cube, on the grid's planes and the tree's split
 * planes and a float step either side, and points not finite; in this
 * tree and in a deep one (records in a small cluster) over a cube far
 * from the origin. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/sdtree.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/trace/rlpath_stats.h"
#include "trace/rlpath_sd.h"
#include "trace/sdtree.h"

#define PI 3.14159265358979323846
#define N 200000u
#define H 64u

static const double normal[3] = {0.3, -0.5, 0.812404};
static const float point[3] = {0.5f, 0.25f, 0.75f};

static uint64_t rng_state = 0x2545f4914f6cdd1dull;
static double rnd(void)
{
    return cv_test_lcg64(&rng_state);
}

static void square_of(const double w[3], double *u, double *v)
{
    *u = fmin(fmax((w[2] + 1) * 0.5, 0), 1 - 1e-12);
    *v = fmin(fmax((atan2(w[1], w[0]) + PI) / (2 * PI), 0), 1 - 1e-12);
}

static void dir_of(double u, double v, double w[3])
{
    double z = 2 * u - 1, phi = 2 * PI * v - PI, r = sqrt(fmax(0, 1 - z * z));
    w[0] = r * cos(phi);
    w[1] = r * sin(phi);
    w[2] = z;
}

static double lambert(const double w[3])
{
    return fmax(w[0] * normal[0] + w[1] * normal[1] + w[2] * normal[2], 0) / PI;
}

/* The integral of the quadtree's density over [x0,x1) x [y0,y1) (on the
 * square), from its node q over the square at (ox, oy) of the given side
 * with density `pdf` so far. */
static double integrate_rect(const float (*t)[4], uint32_t q, double ox, double oy, double side,
                             double pdf, double x0, double x1, double y0, double y1)
{
    double s = 0, h = side / 2;
    float pr[4];
    uint32_t ch[4];
    cv_sdtree_node(t, q, pr, ch);
    for (int k = 0; k < 4; k++) {
        double ax = ox + h * (k & 1), ay = oy + h * (k >> 1);
        double ix = fmin(ax + h, x1) - fmax(ax, x0), iy = fmin(ay + h, y1) - fmax(ay, y0);
        if (ix <= 0 || iy <= 0)
            continue;
        double p = pdf * 4 * pr[k];
        uint32_t c = ch[k];
        s += c ? integrate_rect(t, c, ax, ay, h, p, x0, x1, y0, y1) : p * ix * iy;
    }
    return s;
}

static struct cv_sd_record *make_records(size_t n)
{
    struct cv_sd_record *r = calloc(n, sizeof(*r));
    for (size_t i = 0; i < n; i++) {
        for (int a = 0; a < 3; a++)
            r[i].p[a] = (float)rnd();
        r[i].pdf = (float)(1 / (4 * PI));
        r[i].beta = 1;
        if (rnd() < 0.05) {
            r[i].u = (float)(0.8 + 0.02 * (rnd() - 0.5));
            r[i].v = (float)(0.3 + 0.02 * (rnd() - 0.5));
            r[i].L = 20;
        } else {
            r[i].u = (float)(0.4 + 0.6 * rnd());
            r[i].v = (float)rnd();
            r[i].L = (float)rnd();
        }
        r[i].u += 4;   /* the class of `normal` (+z); the other classes get none */
    }
    return r;
}

struct rig {
    struct cv_gpu *gpu;
    struct cv_rlpath_sd *sd;
    GLuint out, in;
};

/* Runs TEST_MODE mode over n items; out gets 8 floats per item. */
static bool run(struct rig *g, int mode, uint32_t n, uint32_t seed, float *out,
                struct cv_error *err)
{
    char def[32];
    snprintf(def, sizeof(def), "TEST_MODE=%d", mode);
    const char *defines[] = {def, NULL};
    struct cv_program *prog = cv_program_get(g->gpu, "trace/rlpath/test_sd_sample.comp", defines,
                                             err);
    if (!prog)
        return false;
    cv_rlpath_sd_bind(g->sd);
    cv_buffer_bind(g->out, CV_BIND_RL_PROBE_OUT);
    cv_buffer_bind(g->in, CV_BIND_RL_PROBE_IN);
    glUseProgram(prog->id);
    glUniform1ui(0, n);
    glUniform1ui(1, seed);
    glUniform3f(2, point[0], point[1], point[2]);
    cv_program_dispatch_1d(prog, n);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return cv_buffer_read(g->out, 0, (size_t)n * 8 * sizeof(float), out, err) &&
           cv_gl_check(err, "test_sd_sample mode %d", mode);
}

/* The shaders' splat (sd_flush.comp, with float atomics where the driver
 * has them, then with compare-and-swap) into the statistics of the
 * uploaded guide's training tree equals the host's (cv_sdtree_splat) of
 * the same records, both filters on (spatial box, directional bilinear):
 * counts exactly, flux within float rounding of a sum in another order.
 * The records: the build's, in every class, some dark, some without
 * density, one not finite. */
/* The GPU's frame of a guide over [lo, hi]: its root cube as
 * cv_rlpath_sd_create makes it. */
static struct cv_sd_frame guide_frame(const float lo[3], const float hi[3],
                                      const struct cv_sdtree_opts *o)
{
    struct cv_sdtree *c = cv_sdtree_create(lo, hi);
    struct cv_sd_frame f = cv_sdtree_frame(c, o);
    cv_sdtree_destroy(&c);
    return f;
}

/* The spatial nodes of table t: they end at the first class texel, the
 * lowest a leaf names. */
static uint32_t spatial_nodes(const float (*t)[4])
{
    uint32_t ns = UINT32_MAX;
    for (uint32_t k = 0; k < ns; k++)
        if (t[k][0] == (float)CV_SD_LEAF && (uint32_t)t[k][2] < ns)
            ns = (uint32_t)t[k][2];
    return ns;
}

static void splat_test(struct rig *g, const float (*t)[4])
{
    const size_t n = 30000;
    struct cv_sd_record *r = make_records(n);
    for (size_t i = 0; i < n; i++) {
        r[i].u = r[i].u - 4 + (float)(i % CV_SD_CLASSES);
        if (i % 7 == 0)
            r[i].L = 0;
        if (i % 101 == 0)
            r[i].pdf = 0;
    }
    r[5].L = NAN;
    for (int cas = 0; cas <= 1; cas++) {
        struct cv_error err = {{0}};
        uint32_t *gs = NULL;
        size_t words = 0;
        /* both filters: every path of the splat */
        cv_rlpath_sd_set_filter(g->sd, CV_SD_FILTER_SPATIAL | CV_SD_FILTER_DIRECTIONAL);
        bool ok = cv_rlpath_sd_splat(g->sd, r, n, cas, &gs, &words, &err);
        if (!tap_ok(ok, "splat %zu records on the GPU (%s): %s", n,
                    cas ? "compare-and-swap" : "float atomics where there", err.msg)) {
            free(gs);
            continue;
        }
        uint32_t *hs = calloc(words, sizeof(*hs));
        /* the GPU's frame: the guide's cube (made as cv_rlpath_sd_create
         * makes it) and both filters */
        const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};   /* main's */
        struct cv_sd_frame f = guide_frame(lo, hi, &cv_sdtree_defaults);
        f.filter = CV_SD_FILTER_SPATIAL | CV_SD_FILTER_DIRECTIONAL;
        for (size_t i = 0; i < n; i++)
            cv_sdtree_splat(t, &f, hs, &r[i]);
        /* the flux words: the first four of each training node's eight,
         * after the classes' */
        uint32_t ns = spatial_nodes(t), classes = 0, bad_count = 0, bad_flux = 0;
        for (uint32_t k = 0; k < ns; k++)
            classes += t[k][0] == (float)CV_SD_LEAF ? CV_SD_CLASSES : 0;
        uint64_t counted = 0;
        double flux = 0;
        size_t node0 = CV_SD_CLASS_WORDS * classes;
        for (size_t w = 0; w < words; w++) {
            bool is_flux = w >= node0 && (w - node0) % CV_SD_NODE_WORDS < 4;
            if (is_flux) {
                float a, b;
                memcpy(&a, &gs[w], 4);
                memcpy(&b, &hs[w], 4);
                bad_flux += !(fabs(a - b) <= 1e-4 * fabs(b) + 1e-6);
                flux += b;
            } else {
                bad_count += gs[w] != hs[w];
                counted += w < node0 && w % 2 == 0 ? hs[w] : 0;
            }
        }
        tap_ok(bad_count == 0 && counted > n / 2,
               "%s: record counts equal the host's (%u of %zu words differ; %llu records)",
               cas ? "compare-and-swap" : "float atomics", bad_count, words,
               (unsigned long long)counted);
        tap_ok(bad_flux == 0 && flux > 0, "%s: flux sums equal the host's within 1e-4 (%u differ)",
               cas ? "compare-and-swap" : "float atomics", bad_flux);
        free(hs);
        free(gs);
    }
    free(r);
}

/* Mode 3 (the class texel of each input point, through the grid block
 * and by the full descent) against the host's descent in table t of nt
 * texels, uploaded to g->sd: M points, a quarter random in and about the
 * cube (lo, side), half on a plane of the grid block's bounds or of an
 * inner node's split (or a float step off it) with the other coordinates
 * random, half of each near centre (within side / 1000), and a few not
 * finite. */
static void lookup_test(struct rig *g, const char *what, const float (*t)[4], size_t nt,
                        const float lo[3], float side, const float centre[3])
{
    const uint32_t M = 256 * 256;
    float *in = calloc((size_t)M * 4, sizeof(float));
    float *out = malloc((size_t)M * 8 * sizeof(float));
    const float(*b)[4] = t + nt - CV_SD_GRID_TEXELS;
    uint32_t ns = spatial_nodes(t), planes = 0;
    /* the spatial tree's depth (children follow their parents) */
    uint32_t *depth = calloc(ns, sizeof(*depth)), dmax = 0;
    for (uint32_t i = 0; i < ns; i++)
        if (t[i][0] != (float)CV_SD_LEAF)
            for (uint32_t k = 0; k < 2; k++) {
                uint32_t c = (uint32_t)t[i][2] + k;
                depth[c] = depth[i] + 1;
                dmax = depth[c] > dmax ? depth[c] : dmax;
            }
    free(depth);
    for (uint32_t i = 0; i < M; i++) {
        float *p = &in[4 * (size_t)i];
        uint32_t kind = i % 4;
        bool near = (i / 4) % 2;
        for (int a = 0; a < 3; a++)
            p[a] = near ? centre[a] + side * 2e-3f * (float)(rnd() - 0.5)
                        : lo[a] + side * (float)(1.6 * rnd() - 0.3);
        if (kind >= 2) {
            /* a plane: the grid's or a split's, then a float step either
             * side or none */
            int a;
            float x;
            if (kind == 2 || ns < 2) {
                a = (int)(3 * rnd());
                uint32_t j = (uint32_t)(CV_SD_GRID_CELLS * rnd());
                x = b[a * CV_SD_GRID_CELLS + j][rnd() < 0.5 ? 0 : 1];
            } else {
                uint32_t k;
                do
                    k = (uint32_t)(ns * rnd());
                while (t[k][0] == (float)CV_SD_LEAF);
                a = (int)t[k][0];
                x = t[k][1];
            }
            int step = (int)(3 * rnd()) - 1;
            p[a] = step ? nextafterf(x, step * INFINITY) : x;
            planes++;
        }
    }
    const float odd[] = {NAN, INFINITY, -INFINITY, 1e30f, -1e30f};
    for (uint32_t k = 0; k < 15; k++)
        in[4 * (size_t)(k * 7 + 1) + k % 3] = odd[k % 5];
    glNamedBufferSubData(g->in, 0, (GLsizeiptr)M * 16, in);
    struct cv_error err = {{0}};
    if (tap_ok(run(g, 3, M, 0, out, &err), "%s: look up %u points: %s", what, M, err.msg)) {
        uint32_t bad_grid = 0, bad_full = 0, inner = 0;
        for (uint32_t i = 0; i < M; i++) {
            uint32_t leaf = cv_sdtree_leaf(t, &in[4 * (size_t)i]);
            float want = t[leaf][2] + (float)(i % CV_SD_CLASSES);
            bad_grid += out[8 * (size_t)i] != want;
            bad_full += out[8 * (size_t)i + 1] != want;
        }
        for (uint32_t c = 0; c < CV_SD_GRID_CELLS * CV_SD_GRID_CELLS * CV_SD_GRID_CELLS; c++)
            inner += b[3 * CV_SD_GRID_CELLS + c / 4][c % 4] >= 0;
        tap_ok(bad_grid == 0 && bad_full == 0,
               "%s: lookups through the grid (%u differ) and by the full descent (%u differ) "
               "name the host's leaf, %u points on planes, the deepest leaf %u deep, %u cells "
               "inner", what, bad_grid, bad_full, planes, dmax, inner);
    }
    free(in);
    free(out);
}

/* A guide over a cube far from the origin, learned from records of which
 * most lie in a small cluster (leaves deeper than the grid block's 3 g
 * levels), uploaded to a guide of its own. */
static void deep_test(struct rig *g)
{
    const float lo[3] = {-1.5f, 1000.25f, 7.0f}, hi[3] = {0.5f, 1001.75f, 8.0f};
    const size_t n = 60000;
    struct cv_sd_record *r = make_records(n);
    float centre[3];
    for (int a = 0; a < 3; a++)
        centre[a] = lo[a] + 0.3f * (hi[a] - lo[a]);
    for (size_t i = 0; i < n; i++)
        for (int a = 0; a < 3; a++)
            r[i].p[a] = i % 10 ? centre[a] + (float)(1e-3 * (rnd() - 0.5))
                               : lo[a] + (hi[a] - lo[a]) * (float)rnd();
    struct cv_sd_record *copy = malloc(n * sizeof(*r));
    memcpy(copy, r, n * sizeof(*r));
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(lo, hi, copy, n, &cv_sdtree_defaults, &t, &nt, &st);
    struct cv_error err = {{0}};
    struct rig d = *g;
    d.sd = NULL;
    if (tap_ok(cv_rlpath_sd_create(g->gpu, lo, hi, 64, -1, 0, &d.sd, &err) &&
                   cv_rlpath_sd_build(d.sd, r, n, &err),
               "cluster: create, build and upload: %s", err.msg)) {
        struct cv_sd_frame f = guide_frame(lo, hi, &cv_sdtree_defaults);
        tap_ok(st.max_spatial_depth > 3 * CV_SD_GRID_LOG2, "cluster: leaves to depth %u (the "
               "grid block's cells end at %u)", st.max_spatial_depth, 3 * CV_SD_GRID_LOG2);
        lookup_test(&d, "cluster", (const float(*)[4])t, nt, f.cube, f.cube[3], centre);
    }
    cv_rlpath_sd_destroy(&d.sd);
    free(t);
    free(r);
    free(copy);
}

/* The class texel of the test point's leaf in table t, in the class of
 * the shader's TEST_NORMAL (+z): its quadtree root and weight. */
static uint32_t point_class(const float (*t)[4])
{
    return (uint32_t)t[cv_sdtree_leaf(t, point)][2] + 4;
}

/* Draws N directions on the GPU in TEST_MODE mode (0: the guide, 1: the
 * mixture) with seed, at the quadtree at texel root of the host's table t
 * (weight m) that the uploaded guide must find, and checks them against
 * the host's density (out: 8 floats a draw). */
static void sample_test(struct rig *g, int mode, const float (*t)[4], uint32_t root, float m,
                        const char *what, uint32_t seed, float *out)
{
    struct cv_error err = {{0}};
    if (!tap_ok(run(g, mode, N, seed, out, &err), "%s: sample %u: %s", what, N, err.msg))
        return;
    double *obs = calloc((size_t)H * H, sizeof(double));
    double *expc = calloc((size_t)H * H, sizeof(double));
    uint32_t bad_len = 0, bad_pdf = 0, bad_ref = 0, bad_leaf = 0;
    /* the class's light estimate (at its training root), -1 where none */
    const float *est = t[(uint32_t)t[point_class(t)][2] + 1];
    float light = est[3] > 0 ? est[2] : -1.0f;
    for (uint32_t i = 0; i < N; i++) {
        const float *r = out + 8 * (size_t)i;
        double w[3] = {r[0], r[1], r[2]}, u, v;
        double len = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        bad_len += fabs(len - 1) > 1e-4;
        square_of(w, &u, &v);
        uint32_t cu = (uint32_t)(u * H), cv = (uint32_t)(v * H);
        obs[(size_t)(cu < H ? cu : H - 1) * H + (cv < H ? cv : H - 1)] += 1;
        double pq = cv_sdtree_pdf_square(t, root, u, v) / (4 * PI);
        if (mode == 0) {
            bad_pdf += fabs(r[3] - r[4]) > 1e-4 * r[4];
            bad_ref += fabs(r[4] - pq) > 1e-3 * pq;
            bad_leaf += r[5] != m || (uint32_t)r[6] != root || r[7] != light;
        } else {
            double mix = m * r[4] + (1 - m) * r[5];
            bad_pdf += fabs(r[3] - mix) > 1e-5 * mix;
            bad_ref += fabs(r[4] - pq) > 1e-3 * pq || fabs(r[5] - lambert(w)) > 1e-4;
        }
    }
    tap_ok(bad_len == 0, "%s: unit directions (%u not)", what, bad_len);
    if (mode == 0) {
        tap_ok(bad_leaf == 0 && light > 0, "%s: the lookup finds the host's leaf (texel %u), "
               "weight and light estimate %g (%u differ)", what, root, light, bad_leaf);
        tap_ok(bad_pdf <= N / 1000, "%s: pdf at sampling equals the pdf at w (%u of %u "
               "differ, quadrant edges allowed: %u)", what, bad_pdf, N, N / 1000);
    } else {
        tap_ok(bad_pdf == 0, "%s: pdf m pQ + (1-m) pBSDF (%u differ)", what, bad_pdf);
    }
    tap_ok(bad_ref <= N / 1000, "%s: GPU pdfs equal the host's (%u of %u differ)", what,
           bad_ref, N);
    for (uint32_t a = 0; a < H; a++)
        for (uint32_t b = 0; b < H; b++) {
            double x0 = (double)a / H, y0 = (double)b / H;
            double e = integrate_rect(t, root, 0, 0, 1, 1, x0, x0 + 1.0 / H, y0, y0 + 1.0 / H);
            if (mode) {
                /* the lobe by an 8 x 8 midpoint rule per cell (smooth) */
                double l = 0;
                for (int i = 0; i < 8; i++)
                    for (int j = 0; j < 8; j++) {
                        double w[3];
                        dir_of(x0 + (i + 0.5) / (8.0 * H), y0 + (j + 0.5) / (8.0 * H), w);
                        l += lambert(w);
                    }
                l *= 4 * PI / (64.0 * H * H);
                e = m * e + (1 - m) * l;
            }
            expc[(size_t)a * H + b] = N * e;
        }
    rl_chi2_check(obs, expc, H, H, what);
    free(obs);
    free(expc);
}

/* The guide of records rec (weight mix) with top blocks of `levels`
 * levels, as a table with many quadtrees that guide gets them: the host's
 * table says so, and the GPU's draws at the test point agree with it. */
static void levels_test(struct rig *g, uint32_t levels, const struct cv_sd_record *rec, size_t n,
                        float mix, float *out)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    struct cv_sdtree_opts o = cv_sdtree_defaults;
    o.mix = mix;
    o.block_log2 = levels;
    float(*t)[4] = NULL;
    size_t nt = 0;
    cv_sdtree_build(lo, hi, rec, n, &o, &t, &nt, NULL);
    uint32_t key = point_class((const float(*)[4])t);
    char what[64];
    snprintf(what, sizeof(what), "guide, top blocks of %u levels", levels);
    tap_ok(t[0][3] == (float)levels, "%s: the table's root says %g", what, t[0][3]);
    struct cv_error err = {{0}};
    struct rig d = *g;
    d.sd = NULL;
    bool ok = cv_rlpath_sd_create(g->gpu, lo, hi, 64, mix, 0, &d.sd, &err);
    if (ok)
        cv_rlpath_sd_set_block_log2(d.sd, levels);
    ok = ok && cv_rlpath_sd_build(d.sd, rec, n, &err);
    if (tap_ok(ok, "%s: create, build and upload: %s", what, err.msg))
        sample_test(&d, 0, (const float(*)[4])t, (uint32_t)t[key][0], t[key][1], what,
                    21 + levels, out);
    cv_rlpath_sd_destroy(&d.sd);
    free(t);
}

int main(void)
{
    struct cv_error err = {{0}};
    struct rig g = {0};
    g.gpu = test_gpu_open(CV_BACKEND_AUTO);
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const size_t NR = 100000;
    struct cv_sd_record *recs = make_records(NR);
    struct cv_sd_record *copy = malloc(NR * sizeof(*recs));
    memcpy(copy, recs, NR * sizeof(*recs));
    /* the host's table, from the same records in the same order */
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_opts o = cv_sdtree_defaults;
    o.mix = 0.6f;
    cv_sdtree_build(lo, hi, copy, NR, &o, &t, &nt, NULL);
    uint32_t key = point_class((const float(*)[4])t);
    uint32_t root = (uint32_t)t[key][0];
    float m = t[key][1];

    float *out = malloc((size_t)N * 8 * sizeof(float));
    bool ok = tap_ok(cv_rlpath_sd_create(g.gpu, lo, hi, 64, o.mix, 0, &g.sd, &err),
                     "create: %s", err.msg) &&
              tap_ok(cv_rlpath_sd_build(g.sd, recs, NR, &err), "build and upload: %s", err.msg);
    g.out = cv_buffer_create((size_t)N * 8 * sizeof(float), NULL, "probe out", &err);
    g.in = cv_buffer_create((size_t)256 * 256 * 16, NULL, "probe in", &err);
    if (!ok || !tap_ok(g.out && g.in, "probe buffers: %s", err.msg))
        return tap_done();
    tap_ok(m == o.mix && t[key - 1][1] == 0, "the test point's leaf guides with the weight %g "
           "in the normal's class, not in another", m);

    for (int mode = 0; mode <= 1; mode++)
        sample_test(&g, mode, (const float(*)[4])t, root, m, mode ? "mixture" : "guide",
                    11 + mode, out);
    for (uint32_t l = 0; l < CV_SD_BLOCK_MAX_LOG2; l += 2)
        levels_test(&g, l, recs, NR, o.mix, out);

    /* the pdf on a grid of directions */
    const uint32_t G = 256;
    float *in = calloc((size_t)G * G * 4, sizeof(float));
    for (uint32_t a = 0; a < G; a++)
        for (uint32_t b = 0; b < G; b++) {
            double w[3];
            dir_of((a + 0.5) / G, (b + 0.5) / G, w);
            for (int k = 0; k < 3; k++)
                in[4 * ((size_t)a * G + b) + k] = (float)w[k];
        }
    glNamedBufferSubData(g.in, 0, (GLsizeiptr)G * G * 16, in);
    if (tap_ok(run(&g, 2, G * G, 0, out, &err), "evaluate on %ux%u directions: %s", G, G,
               err.msg)) {
        uint32_t bad = 0;
        double sum = 0;
        for (uint32_t i = 0; i < G * G; i++) {
            double w[3] = {in[4 * i], in[4 * i + 1], in[4 * i + 2]}, u, v;
            square_of(w, &u, &v);
            double ref = cv_sdtree_pdf_square((const float(*)[4])t, root, u, v) / (4 * PI);
            bad += fabs(out[8 * i] - ref) > 1e-4 * ref;
            sum += out[8 * i];
        }
        tap_ok(bad == 0, "pdf on the grid equals the host's (%u of %u differ)", bad, G * G);
        tap_ok(fabs(sum * 4 * PI / (G * G) - 1) < 0.05, "midpoint integral of the pdf %.4f",
               sum * 4 * PI / (G * G));
    }
    free(in);
    free(out);
    splat_test(&g, (const float(*)[4])t);
    {
        struct cv_sd_frame f = guide_frame(lo, hi, &o);
        lookup_test(&g, "unit box", (const float(*)[4])t, nt, f.cube, f.cube[3], point);
    }
    free(t);
    deep_test(&g);
    free(recs);
    free(copy);
    cv_buffer_destroy(&g.out);
    cv_buffer_destroy(&g.in);
    cv_rlpath_sd_destroy(&g.sd);
    cv_gpu_destroy(&g.gpu);
    return tap_done();
}
