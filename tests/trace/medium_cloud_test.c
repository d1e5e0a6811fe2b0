/* medium_cloud_test.c: pbrt-v4's cloud medium as shipped (glsl/lib/noise.glsl,
 * glsl/trace/medium/cloud.glsl and grid.glsl's walk, through
 * glsl/trace/test/grid_probe.comp compiled with CV_MEDIUM_CLOUDS) on two
 * clouds read from a pbrt scene (one rotated and moved with bounds of its
 * own and wisps, one scaled with pbrt-v4's default bounds and none),
 * against pbrt-v4's definitions computed here in double:
 * - Perlin noise and its differences at points near the origin, far out
 *   and past 2^30 (C's fmod), and the cloud's density at points in and
 *   around its bounds; the same check with two entries of the permutation
 *   swapped here must fail;
 * - sigma_a and sigma_s at render-space points are the medium's times the
 *   density at the GPU's own point of the bounds, and vacuum outside;
 * - every majorant bounds sigma_t of every channel at points all over its
 *   cell (16 per cell, and the cell's corners), and the points come within
 *   2 % of it (a majorant 2 % low fails);
 * - ratio tracking's transmittance and delta tracking's pass and collision
 *   weights average to exp(-optical depth) and 1 minus it per channel, the
 *   optical depth integrated here, within 4.5 standard errors. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/perlin.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "scene/transform.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/trace/grid_probe.h"
#include "trace/scene_upload.h"

#define PER_CELL 16
#define N_NOISE 20000
#define N_RAYS 32
#define N_TRACK 2048

static uint32_t lcg = 4321;
static double rnd(void)
{
    return cv_test_lcg32(&lcg);
}

/* pbrt-v4's Noise and DNoise in double, over permutation `perm`. */
static int perm[256] = {CV_PERLIN_PERM};

static double grad(int x, int y, int z, double dx, double dy, double dz)
{
    int h = perm[(perm[(perm[x & 255] + y) & 255] + z) & 255] & 15;
    double u = h < 8 || h == 12 || h == 13 ? dx : dy;
    double v = h < 4 || h == 12 || h == 13 ? dy : dz;
    return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

static double fade(double t)
{
    return 6 * pow(t, 5) - 15 * pow(t, 4) + 10 * pow(t, 3);
}

static double lerp(double t, double a, double b)
{
    return (1 - t) * a + t * b;
}

static double noise(const double p[3])
{
    double q[3], d[3];
    int i[3];
    for (int a = 0; a < 3; a++) {
        q[a] = fmod(p[a], 1073741824.0);
        double f = floor(q[a]);
        i[a] = (int)f & 255;
        d[a] = q[a] - f;
    }
    double w[8];
    for (int k = 0; k < 8; k++) {
        int ox = k & 1, oy = (k >> 1) & 1, oz = k >> 2;
        w[k] = grad(i[0] + ox, i[1] + oy, i[2] + oz, d[0] - ox, d[1] - oy, d[2] - oz);
    }
    double wx = fade(d[0]), wy = fade(d[1]), wz = fade(d[2]);
    double y0 = lerp(wy, lerp(wx, w[0], w[1]), lerp(wx, w[2], w[3]));
    double y1 = lerp(wy, lerp(wx, w[4], w[5]), lerp(wx, w[6], w[7]));
    return lerp(wz, y0, y1);
}

/* DNoise as pbrt-v4 computes it, in float: the offset points rounded to
 * float as they are there (their rounding, over 0.01, is what the
 * differences are most sensitive to). */
static void dnoise(const float p[3], float out[3])
{
    double q0[3] = {p[0], p[1], p[2]};
    double n = noise(q0);
    for (int a = 0; a < 3; a++) {
        double q[3] = {p[0], p[1], p[2]};
        q[a] = (float)(p[a] + 0.01f);
        out[a] = (float)((noise(q) - n) / 0.01f);
    }
}

struct cloud_case {
    const char *name;
    double density, wispiness, frequency;
    struct grid_probe_box box;
    double sa[3], ss[3];
};

/* pbrt-v4's CloudMedium::Density at medium-space p, in float as there
 * (the differences of DNoise amplify rounding a hundredfold). */
static double density(const struct cloud_case *k, const float p[3])
{
    float pp[3] = {(float)k->frequency * p[0], (float)k->frequency * p[1],
                   (float)k->frequency * p[2]};
    if (k->wispiness > 0) {
        float vomega = 0.05f * (float)k->wispiness, vlambda = 10;
        for (int i = 0; i < 2; i++) {
            float q[3] = {vlambda * pp[0], vlambda * pp[1], vlambda * pp[2]}, dn[3];
            dnoise(q, dn);
            for (int a = 0; a < 3; a++)
                pp[a] += vomega * dn[a];
            vomega *= 0.5f;
            vlambda *= 1.99f;
        }
    }
    double d = 0, omega = 0.5, lambda = 1;
    for (int i = 0; i < 5; i++) {
        double q[3] = {(float)(lambda * pp[0]), (float)(lambda * pp[1]), (float)(lambda * pp[2])};
        d += omega * noise(q);
        omega *= 0.5;
        lambda = (float)(lambda * 1.99f);
    }
    d = fmin(fmax((1 - p[1]) * 4.5 * k->density * d, 0), 1);
    d += 2 * fmax(0, 0.5 - p[1]);
    return fmin(fmax(d, 0), 1);
}

/* sigma_a, sigma_s at g in the bounds' unit cube (vacuum outside). */
static void props(const struct cloud_case *k, const double g[3], double sa[3], double ss[3])
{
    bool in = g[0] >= 0 && g[0] <= 1 && g[1] >= 0 && g[1] <= 1 && g[2] >= 0 && g[2] <= 1;
    float p[3];
    for (int a = 0; a < 3; a++)
        p[a] = (float)k->box.p0[a] + (float)g[a] * (float)(k->box.p1[a] - k->box.p0[a]);
    double d = in ? density(k, p) : 0;
    for (int c = 0; c < 3; c++) {
        sa[c] = k->sa[c] * d;
        ss[c] = k->ss[c] * d;
    }
}

/* Noise, its differences and the density at medium-space points. */
static void check_noise(struct cv_program *prog, const struct cloud_case *k, unsigned medium)
{
    struct cv_error err = {{0}};
    const size_t n = N_NOISE;
    float *in = cv_xmalloc(n * 16), *out = cv_xmalloc(n * 32);
    for (size_t i = 0; i < n; i++) {
        double span = i < n / 2 ? 2 : i < n - 64 ? 400 : 6e9; /* the bounds, far, past 2^30 */
        double lo = i < n / 2 ? -0.5 : -span / 2;
        for (int a = 0; a < 3; a++)
            in[4 * i + a] = (float)(lo + span * rnd());
        in[4 * i + 3] = 0;
    }
    if (!tap_ok(grid_probe_run(prog, 4, medium, N_TRACK, in, n, n, out, 2 * n, &err),
                "%s: noise probe runs %s",
                k->name, err.msg))
        goto done;
    double worst_n = 0, worst_dn = 0, worst_d = 0, swapped = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = in + 4 * i;
        double pd[3] = {p[0], p[1], p[2]};
        float dn[3];
        worst_n = fmax(worst_n, fabs(out[8 * i] - noise(pd)));
        dnoise(p, dn);
        /* a difference over 0.01 of float noise: its rounding over 0.01 */
        for (int a = 0; a < 3; a++)
            worst_dn = fmax(worst_dn, fabs(out[8 * i + 1 + a] - dn[a]));
        /* the density near the bounds (far out, float noise of float
         * points scaled by 1.99 per octave loses its fraction) */
        if (i < n / 2)
            worst_d = fmax(worst_d, fabs(out[8 * i + 4] - density(k, p)));
    }
    /* the same density with two entries of the permutation swapped */
    int t = perm[17];
    perm[17] = perm[18];
    perm[18] = t;
    for (size_t i = 0; i < n / 2; i++)
        swapped = fmax(swapped, fabs(out[8 * i + 4] - density(k, in + 4 * i)));
    perm[18] = perm[17];
    perm[17] = t;
    tap_ok(worst_n < 1e-5, "%s: noise equals pbrt-v4's Noise (worst %.2g)", k->name, worst_n);
    tap_ok(worst_dn < 1e-3, "%s: its differences equal pbrt-v4's DNoise (worst %.2g)", k->name,
           worst_dn);
    tap_ok(worst_d < 1e-3, "%s: the density equals pbrt-v4's CloudMedium::Density (worst %.2g)",
           k->name, worst_d);
    tap_ok(swapped > 2e-2, "%s: the check catches two permutation entries swapped (worst %.2g)",
           k->name, swapped);
done:
    free(in);
    free(out);
}

/* Coefficients and majorants at render-space points all over the bounds. */
static void check_lookups(struct cv_program *prog, const struct cloud_case *k, unsigned medium)
{
    struct cv_error err = {{0}};
    const unsigned R = CV_MAJORANT_RES;
    size_t n_cells = (size_t)R * R * R, n, i;
    float *out = grid_probe_lookups(prog, medium, &k->box, PER_CELL, rnd, &n, &err);
    if (!tap_ok(out != NULL, "%s: probe runs %s", k->name, err.msg))
        return;
    double worst = 0, worst_ratio = 0, scale = 0;
    size_t above = 0, inside = 0;
    for (int c = 0; c < 3; c++)
        scale = fmax(scale, k->sa[c] + k->ss[c]);
    for (i = 0; i < n; i++) {
        const float *o = out + 16 * i;
        double gg[3] = {o[12], o[13], o[14]}, sa[3], ss[3];
        props(k, gg, sa, ss);
        for (int c = 0; c < 3; c++) {
            worst = fmax(worst, fabs(o[c] - sa[c]) / scale);
            worst = fmax(worst, fabs(o[4 + c] - ss[c]) / scale);
        }
        if (i >= n_cells * (PER_CELL + 8))
            continue;
        inside += o[0] + o[4] > 0;
        for (int c = 0; c < 3; c++) {
            double st = (double)o[c] + o[4 + c];
            above += st > o[3];
            worst_ratio = fmax(worst_ratio, st / o[3]);
        }
    }
    tap_ok(worst < 1e-3, "%s: sigma_a and sigma_s are the medium's times pbrt-v4's density, "
                         "vacuum outside (worst %.2g of the largest sigma_t)", k->name, worst);
    tap_ok(above == 0 && inside > n_cells, "%s: every majorant bounds sigma_t in its cell (%zu "
                                           "points above; the closest %.6f of it)", k->name, above,
           worst_ratio);
    /* the density reaches 1 (below y 0.5 of medium space): a majorant 2 %
     * lower would fail the check above */
    tap_ok(worst_ratio > 0.98, "%s: the check catches a majorant 2 %% too low (sigma_t up to "
                               "%.4f of it)", k->name, worst_ratio);
    free(out);
}

/* The optical depth per channel along a ray, by midpoint quadrature. */
static void quadrature(const struct cloud_case *k, const double o[3], const double d[3],
                       double t1, double tau[3])
{
    struct cv_mat4 inv;
    cv_mat4_inverse(&k->box.ctm, &inv);
    const int steps = 20000;
    double dt = t1 / steps;
    tau[0] = tau[1] = tau[2] = 0;
    for (int i = 0; i < steps; i++) {
        double p[3], q[3], g[3], sa[3], ss[3];
        for (int a = 0; a < 3; a++)
            p[a] = o[a] + (i + 0.5) * dt * d[a];
        cv_mat4_point(&inv, p, q);
        for (int a = 0; a < 3; a++)
            g[a] = (q[a] - k->box.p0[a]) / (k->box.p1[a] - k->box.p0[a]);
        props(k, g, sa, ss);
        for (int c = 0; c < 3; c++)
            tau[c] += (sa[c] + ss[c]) * dt;
    }
}

static void check_walks(struct cv_program *prog, const struct cloud_case *k, unsigned medium)
{
    struct cv_error err = {{0}};
    float in[N_RAYS * 8];
    float *ratio = cv_xmalloc((size_t)N_RAYS * N_TRACK * 32);
    float *delta = cv_xmalloc((size_t)N_RAYS * N_TRACK * 32);
    double o[N_RAYS][3], d[N_RAYS][3], t1[N_RAYS];
    grid_probe_rays(&k->box, rnd, N_RAYS, o, d, t1, in);
    if (!tap_ok(grid_probe_track(prog, medium, N_TRACK, in, N_RAYS, ratio, delta, &err),
                "%s: walk probes run %s", k->name, err.msg))
        goto done;
    double tau[N_RAYS][3];
    for (int i = 0; i < N_RAYS; i++)
        quadrature(k, o[i], d[i], t1[i], tau[i]);
    grid_probe_check_tracking(k->name, ratio, delta, N_RAYS, N_TRACK, tau, 0.5);
done:
    free(ratio);
    free(delta);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cloud_case cases[2] = {
        {.name = "wispy cloud", .density = 1.2, .wispiness = 1.5, .frequency = 3,
         .box = {.p0 = {-1, -0.5, 0}, .p1 = {1.5, 2, 1}}, .sa = {0.3, 0.5, 0.2},
         .ss = {1, 0.7, 1.4}},
        {.name = "plain cloud", .density = 2, .wispiness = 0, .frequency = 7,
         .box = {.p0 = {0, 0, 0}, .p1 = {1, 1, 1}}, .sa = {1, 1, 1}, .ss = {1, 1, 1}},
    };
    struct cv_mat4 t = cv_mat4_translate(0.3, -0.2, 0.5), r = cv_mat4_rotate(25, 1, 1, 0);
    cases[0].box.ctm = cv_mat4_mul(&t, &r);
    cases[1].box.ctm = cv_mat4_scale(1, 2, 0.5);
    const char *text =
        "WorldBegin\nAttributeBegin\nTranslate 0.3 -0.2 0.5\nRotate 25 1 1 0\n"
        "MakeNamedMedium \"a\" \"string type\" \"cloud\" \"float density\" 1.2\n"
        "  \"float wispiness\" 1.5 \"float frequency\" 3 \"point3 p0\" [-1 -0.5 0]\n"
        "  \"point3 p1\" [1.5 2 1] \"rgb sigma_a\" [0.3 0.5 0.2] \"rgb sigma_s\" [1 0.7 1.4]\n"
        "  \"float g\" 0.3\nAttributeEnd\nScale 1 2 0.5\n"
        "MakeNamedMedium \"b\" \"string type\" \"cloud\" \"float density\" 2\n"
        "  \"float wispiness\" 0 \"float frequency\" 7\n";
    struct cv_scene_load_params lp = {.strict = true};
    struct cv_scene *s = NULL;
    struct cv_scene_gpu g = {0};
    bool loaded = cv_scene_load_string("cloud.pbrt", text, strlen(text), &lp, &s, &err);
    if (tap_ok(loaded && s->n_media == 3 && s->media[1].type == CV_MEDIUM_CLOUD &&
                   s->media[2].type == CV_MEDIUM_CLOUD,
               "the clouds load: %s", err.msg) &&
        tap_ok(cv_scene_upload(gpu, s, NULL, &g, &err), "the scene uploads: %s", err.msg)) {
        tap_ok(g.has_medium_cloud && g.has_medium_grids,
               "the scene asks for the cloud's code (CV_MEDIUM_CLOUDS) and the grid walk");
        cv_scene_bind(&g);
        static const char *const defines[] = {"CV_MEDIUM_CLOUDS", NULL};
        struct cv_program *prog = cv_program_get(gpu, "trace/test/grid_probe.comp", defines, &err);
        if (tap_ok(prog != NULL, "grid_probe.comp compiles with CV_MEDIUM_CLOUDS: %s",
                   prog ? "" : err.msg))
            for (unsigned m = 0; m < 2; m++) {
                check_noise(prog, &cases[m], m + 1);
                check_lookups(prog, &cases[m], m + 1);
                check_walks(prog, &cases[m], m + 1);
            }
        cv_scene_gpu_release(&g);
    }
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
