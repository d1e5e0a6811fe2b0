/* medium_grid_test.c: the shipped grid-medium code (glsl/trace/medium/
 * grid.glsl, through glsl/trace/test/grid_probe.comp) on three media read
 * from a pbrt scene (a rotated uniformgrid with pbrt-v4's one-sample
 * Lescale grid, an rgbgrid with RGB sigma_a, sigma_s and Le, a uniformgrid
 * with an Lescale grid), against what is computed here in double:
 * - the lookups at points in and just outside the bounds equal pbrt-v4's
 *   SampledGrid trilinear interpolation (samples at voxel centres, zero
 *   beyond the outermost ones; vacuum outside the bounds);
 * - every majorant bounds sigma_t of every channel at points all over its
 *   cell (16 per cell, and the cell's corners), and is the largest value
 *   pbrt-v4's MaxValue finds for the cell; a majorant grid 2 % too low
 *   fails the same check;
 * - the DDA walk integrates the majorant along random rays as a fine
 *   quadrature does;
 * - ratio tracking's transmittance and delta tracking's pass and collision
 *   weights (the hero channel cycling) average to exp(-optical depth) and
 *   1 minus it per channel, the optical depth integrated here, within 4.5
 *   standard errors. */
#include "config.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "scene/transform.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/trace/grid_probe.h"
#include "trace/scene_upload.h"

#define PER_CELL 16
#define N_RAYS 64
#define N_TRACK 4096

/* The test's grids, from a fixed LCG. */
static uint32_t lcg = 12345;
static double rnd(void)
{
    return cv_test_lcg32(&lcg);
}

struct grid_case {
    const char *name;
    int n[3], comps;
    struct grid_probe_box box;
    double sa[3], ss[3], Le[3]; /* the medium's constants (rgbgrid: scale, Lescale) */
    double *a, *s, *e;          /* the grids (e: NULL = pbrt-v4's one-sample Lescale) */
};

static double *random_grid(size_t n, double lo, double hi)
{
    double *v = cv_xmalloc(n * sizeof(double));
    for (size_t i = 0; i < n; i++)
        v[i] = lo + (hi - lo) * rnd();
    return v;
}

static void append(char **text, size_t *len, const char *fmt, ...)
{
    char buf[256];
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(buf, sizeof(buf), fmt, ap);
    va_end(ap);
    if (k >= (int)sizeof(buf))
        abort();
    *text = realloc(*text, *len + (size_t)k + 1);
    memcpy(*text + *len, buf, (size_t)k + 1);
    *len += (size_t)k;
}

static void append_grid(char **text, size_t *len, const char *type, const char *name,
                        const double *v, size_t n)
{
    append(text, len, "  \"%s %s\" [", type, name);
    for (size_t i = 0; i < n; i++)
        append(text, len, " %.9g", v[i]);
    append(text, len, " ]\n");
}

/* One channel of a grid case's samples (grid_probe_ref_lookup). */
struct channel {
    const double *v;
    const int *n;
    int comps, c;
};

static double channel_at(const void *ctx, int x, int y, int z)
{
    const struct channel *ch = ctx;
    return ch->v[(((size_t)z * ch->n[1] + y) * ch->n[0] + x) * ch->comps + (ch->comps == 3 ? ch->c : 0)];
}

/* pbrt-v4's SampledGrid::Lookup of channel c at g (double); 1 without a grid. */
static double lookup(const double *v, const int n[3], int comps, int c, const double g[3])
{
    if (!v)
        return 1;
    struct channel ch = {v, n, comps, c};
    return grid_probe_ref_lookup(channel_at, &ch, n, g);
}

static void props(const struct grid_case *k, const double g[3], double sa[3], double ss[3],
                  double le[3])
{
    bool in = g[0] >= 0 && g[0] <= 1 && g[1] >= 0 && g[1] <= 1 && g[2] >= 0 && g[2] <= 1;
    static const int one[3] = {1, 1, 1};
    for (int c = 0; c < 3; c++) {
        sa[c] = in ? k->sa[c] * lookup(k->a, k->n, k->comps, c, g) : 0;
        ss[c] = in ? k->ss[c] * lookup(k->s, k->n, k->comps, c, g) : 0;
        if (k->comps == 3)
            le[c] = in && k->e ? k->Le[c] * lookup(k->e, k->n, 3, c, g) * 106.856895 : 0;
        else if (k->e)
            le[c] = in ? k->Le[c] * lookup(k->e, k->n, 1, 0, g) : 0;
        else {
            const double unit = 1;
            le[c] = in ? k->Le[c] * lookup(&unit, one, 1, 0, g) : 0;
        }
    }
}

/* pbrt-v4's MaxValue of sigma_t's largest channel over majorant cell (x, y, z). */
static double cell_max(const struct grid_case *k, int x, int y, int z)
{
    int cell[3] = {x, y, z}, lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        double b0 = (double)cell[a] / CV_MAJORANT_RES, b1 = (double)(cell[a] + 1) / CV_MAJORANT_RES;
        lo[a] = (int)fmax(floor(b0 * k->n[a] - 0.5), 0);
        hi[a] = (int)fmin(floor(b1 * k->n[a] - 0.5) + 1, k->n[a] - 1);
    }
    double best = 0;
    for (int c = 0; c < 3; c++) {
        double ma = 0, ms = 0;
        for (int zz = lo[2]; zz <= hi[2]; zz++)
            for (int yy = lo[1]; yy <= hi[1]; yy++)
                for (int xx = lo[0]; xx <= hi[0]; xx++) {
                    size_t i = (((size_t)zz * k->n[1] + yy) * k->n[0] + xx) * k->comps +
                               (k->comps == 3 ? c : 0);
                    ma = fmax(ma, k->a ? k->a[i] : 1);
                    ms = fmax(ms, k->s ? k->s[i] : 1);
                }
        best = fmax(best, k->sa[c] * ma + k->ss[c] * ms);
    }
    return best;
}

static void check_lookups(struct cv_program *prog, const struct grid_case *k, unsigned medium,
                          const struct cv_scene *s)
{
    struct cv_error err = {{0}};
    const unsigned R = CV_MAJORANT_RES;
    size_t n_cells = (size_t)R * R * R, n, i;
    float *out = grid_probe_lookups(prog, medium, &k->box, PER_CELL, rnd, &n, &err);
    if (!tap_ok(out != NULL, "%s: probe runs %s", k->name, err.msg))
        return;
    double worst = 0, worst_ratio = 0, worst_low = 0;
    size_t below = 0, wrong_max = 0;
    const float *maj = s->medium_grids + s->media[medium].res.w;
    for (i = 0; i < n; i++) {
        const float *o = out + 16 * i;
        double gg[3] = {o[12], o[13], o[14]}, sa[3], ss[3], le[3];
        /* the GPU's own grid point: the render-space round trip is float */
        props(k, gg, sa, ss, le);
        double scale = 1;
        for (int c = 0; c < 3; c++)
            scale = fmax(scale, fmax(sa[c] + ss[c], le[c]));
        for (int c = 0; c < 3; c++) {
            worst = fmax(worst, fabs(o[c] - sa[c]) / scale);
            worst = fmax(worst, fabs(o[4 + c] - ss[c]) / scale);
            worst = fmax(worst, fabs(o[8 + c] - le[c]) / scale);
        }
        if (i >= n_cells * (PER_CELL + 8))
            continue;
        int cell[3];
        for (int a = 0; a < 3; a++)
            cell[a] = (int)fmin(fmax(floor(gg[a] * R), 0), R - 1);
        double m = o[3], m_low = 0.98 * m;
        for (int c = 0; c < 3; c++) {
            double st = (double)o[c] + o[4 + c];
            if (st > m)
                below++;
            worst_ratio = fmax(worst_ratio, st / m);
            worst_low = fmax(worst_low, st / m_low);
        }
        double cm = cell_max(k, cell[0], cell[1], cell[2]);
        if (fabs(m - cm) > 1e-4 * fmax(cm, 1e-3) + 1e-7 ||
            maj[((size_t)cell[2] * R + cell[1]) * R + cell[0]] != o[3])
            wrong_max++;
    }
    tap_ok(worst < 2e-5, "%s: lookups equal pbrt-v4's trilinear interpolation (worst %.2g of "
                         "the largest value)", k->name, worst);
    tap_ok(below == 0, "%s: every majorant bounds sigma_t in its cell (%zu points above; the "
                       "closest %.6f of it)", k->name, below, worst_ratio);
    /* the density grid's majorant is tight (an RGB grid's adds the maxima
     * of two grids): there a majorant 2 % low must fail the check */
    if (k->comps == 1)
        tap_ok(worst_low > 1, "%s: the check catches a majorant 2 %% too low (sigma_t up to "
                              "%.4f of it)", k->name, worst_low);
    tap_ok(wrong_max == 0, "%s: each majorant is pbrt-v4's MaxValue of its cell (%zu differ)",
           k->name, wrong_max);
    free(out);
}

/* The optical depth (per channel) and majorant integral along a ray,
 * by midpoint quadrature. */
static void quadrature(const struct grid_case *k, const struct cv_scene *s, unsigned medium,
                       const double o[3], const double d[3], double t1, double tau[3],
                       double *maj_int, double *maj_max)
{
    struct cv_mat4 inv;
    cv_mat4_inverse(&k->box.ctm, &inv);
    const int steps = 40000;
    const unsigned R = CV_MAJORANT_RES;
    const float *maj = s->medium_grids + s->media[medium].res.w;
    double dt = t1 / steps;
    tau[0] = tau[1] = tau[2] = 0;
    *maj_int = 0;
    *maj_max = 0;
    for (int i = 0; i < steps; i++) {
        double p[3], q[3], g[3], sa[3], ss[3], le[3];
        for (int a = 0; a < 3; a++)
            p[a] = o[a] + (i + 0.5) * dt * d[a];
        cv_mat4_point(&inv, p, q);
        bool in = true;
        for (int a = 0; a < 3; a++) {
            g[a] = (q[a] - k->box.p0[a]) / (k->box.p1[a] - k->box.p0[a]);
            in = in && g[a] >= 0 && g[a] <= 1;
        }
        props(k, g, sa, ss, le);
        for (int c = 0; c < 3; c++)
            tau[c] += (sa[c] + ss[c]) * dt;
        if (in) {
            int cx = (int)fmin(g[0] * R, R - 1), cy = (int)fmin(g[1] * R, R - 1),
                cz = (int)fmin(g[2] * R, R - 1);
            double m = maj[((size_t)cz * R + cy) * R + cx];
            *maj_int += m * dt;
            *maj_max = fmax(*maj_max, m);
        }
    }
}

static void check_walks(struct cv_program *prog, const struct grid_case *k, unsigned medium,
                        const struct cv_scene *s)
{
    struct cv_error err = {{0}};
    float in[N_RAYS * 8], walk[N_RAYS * 4];
    float *ratio = cv_xmalloc((size_t)N_RAYS * N_TRACK * 32);
    float *delta = cv_xmalloc((size_t)N_RAYS * N_TRACK * 32);
    double o[N_RAYS][3], d[N_RAYS][3], t1[N_RAYS];
    grid_probe_rays(&k->box, rnd, N_RAYS, o, d, t1, in);
    if (!tap_ok(grid_probe_run(prog, 1, medium, 1, in, 2 * N_RAYS, N_RAYS, walk, N_RAYS, &err) &&
                    grid_probe_track(prog, medium, N_TRACK, in, N_RAYS, ratio, delta, &err),
                "%s: walk probes run %s", k->name, err.msg)) {
        free(ratio);
        free(delta);
        return;
    }
    double worst_walk = 0, tau[N_RAYS][3];
    int entered = 0;
    for (int i = 0; i < N_RAYS; i++) {
        double mi, mm;
        quadrature(k, s, medium, o[i], d[i], t1[i], tau[i], &mi, &mm);
        worst_walk = fmax(worst_walk, fabs(walk[4 * i] - mi) / fmax(mm * t1[i], 1e-6));
        entered += walk[4 * i + 1] > 0;
    }
    tap_ok(worst_walk < 2e-3 && entered > N_RAYS / 4,
           "%s: the DDA walk integrates the majorant as a fine quadrature does (worst %.2g of "
           "the largest majorant times the length; %d of %d rays enter)", k->name, worst_walk,
           entered, N_RAYS);
    grid_probe_check_tracking(k->name, ratio, delta, N_RAYS, N_TRACK, tau, 0);
    free(ratio);
    free(delta);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct grid_case cases[3] = {
        {.name = "uniformgrid", .n = {5, 3, 7}, .comps = 1,
         .box = {.p0 = {-1, -0.5, 0}, .p1 = {1.5, 2, 1}}, .sa = {0.3, 0.5, 0.2},
         .ss = {1, 0.7, 1.4}, .Le = {1, 2, 3}},
        {.name = "rgbgrid", .n = {37, 20, 3}, .comps = 3,
         .box = {.p0 = {0, 0, 0}, .p1 = {2, 1, 0.5}}, .sa = {0.7, 0.7, 0.7},
         .ss = {0.7, 0.7, 0.7}, .Le = {2, 2, 2}},
        {.name = "uniformgrid Lescale", .n = {2, 2, 2}, .comps = 1,
         .box = {.p0 = {0, 0, 0}, .p1 = {1, 1, 1}}, .sa = {2, 1, 0.5}, .ss = {0, 0, 0},
         .Le = {0.5, 1, 1.5}},
    };
    cases[0].a = cases[0].s = random_grid(5 * 3 * 7, 0, 3);
    cases[1].a = random_grid(37 * 20 * 3 * 3, 0, 0.5);
    cases[1].s = random_grid(37 * 20 * 3 * 3, 0, 2);
    cases[1].e = random_grid(37 * 20 * 3 * 3, 0, 0.01);
    cases[2].a = cases[2].s = random_grid(8, 0, 1);
    cases[2].e = random_grid(8, 0, 4);
    struct cv_mat4 t = cv_mat4_translate(0.3, -0.2, 0.5), r = cv_mat4_rotate(25, 1, 1, 0);
    cases[0].box.ctm = cv_mat4_mul(&t, &r);
    cases[1].box.ctm = cv_mat4_identity();
    cases[2].box.ctm = cv_mat4_scale(1, 2, 0.5);

    char *text = NULL;
    size_t len = 0;
    append(&text, &len, "WorldBegin\nAttributeBegin\nTranslate 0.3 -0.2 0.5\nRotate 25 1 1 0\n");
    append(&text, &len, "MakeNamedMedium \"a\" \"string type\" \"uniformgrid\" \"integer nx\" 5 "
                        "\"integer ny\" 3 \"integer nz\" 7\n");
    append(&text, &len, "  \"point3 p0\" [-1 -0.5 0] \"point3 p1\" [1.5 2 1] ");
    append(&text, &len, "\"rgb sigma_a\" [0.3 0.5 0.2] \"rgb sigma_s\" [1 0.7 1.4]");
    append(&text, &len, " \"rgb Le\" [1 2 3]\n");
    append_grid(&text, &len, "float", "density", cases[0].a, 5 * 3 * 7);
    append(&text, &len, "AttributeEnd\nMakeNamedMedium \"b\" \"string type\" \"rgbgrid\" ");
    append(&text, &len, "\"integer nx\" 37 \"integer ny\" 20 \"integer nz\" 3\n");
    append(&text, &len, "  \"point3 p1\" [2 1 0.5] \"float scale\" 0.7 \"float Lescale\" 2\n");
    append_grid(&text, &len, "rgb", "sigma_a", cases[1].a, 37 * 20 * 3 * 3);
    append_grid(&text, &len, "rgb", "sigma_s", cases[1].s, 37 * 20 * 3 * 3);
    append_grid(&text, &len, "rgb", "Le", cases[1].e, 37 * 20 * 3 * 3);
    append(&text, &len, "Scale 1 2 0.5\nMakeNamedMedium \"c\" \"string type\" \"uniformgrid\" ");
    append(&text, &len, "\"integer nx\" 2 \"integer ny\" 2 \"integer nz\" 2\n");
    append(&text, &len, "  \"rgb sigma_a\" [2 1 0.5] \"rgb sigma_s\" [0 0 0] \"rgb Le\" [0.5 1 1.5]\n");
    append_grid(&text, &len, "float", "density", cases[2].a, 8);
    append_grid(&text, &len, "float", "Lescale", cases[2].e, 8);

    struct cv_scene_load_params lp = {.strict = true};
    struct cv_scene *s = NULL;
    struct cv_scene_gpu g = {0};
    bool loaded = cv_scene_load_string("grid.pbrt", text, len, &lp, &s, &err);
    free(text);
    if (tap_ok(loaded && s->n_media == 4, "the grid media load: %s", err.msg) &&
        tap_ok(cv_scene_upload(gpu, s, NULL, &g, &err), "the scene uploads: %s", err.msg)) {
        cv_scene_bind(&g);
        struct cv_program *prog = cv_program_get(gpu, "trace/test/grid_probe.comp", NULL, &err);
        if (tap_ok(prog != NULL, "grid_probe.comp compiles: %s", prog ? "" : err.msg))
            for (unsigned m = 0; m < 3; m++) {
                check_lookups(prog, &cases[m], m + 1, s);
                check_walks(prog, &cases[m], m + 1, s);
            }
        cv_scene_gpu_release(&g);
    }
    cv_scene_destroy(&s);
    free(cases[0].a);
    free(cases[1].a);
    free(cases[1].s);
    free(cases[1].e);
    free(cases[2].a);
    free(cases[2].e);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
