/* bsdf_measured_test.c: the measured BRDF (glsl/trace/bsdf/measured.glsl,
 * through the shipped cv_bsdf_* entry points) on the tables of
 * tests/data/trace/oracle/measured_ggx.bsdf (make_measured.py: an
 * isotropic GGX conductor, alpha 0.3, Schlick Fresnel with R0 varying
 * across the spectrum), loaded by src/scene/rgl_tensor.c and measured.c:
 * - chi-square of cv_bsdf_sample's directions against cv_bsdf_pdf, and
 *   sampled f and pdf equal to cv_bsdf_f and cv_bsdf_pdf, for wo at
 *   several angles and azimuths (the tables are isotropic: phi of the half
 *   vector is relative to wo's);
 * - energy: the integral of f cos over the hemisphere (midpoint
 *   quadrature) stays at most 1 in every channel, as a conductor's must,
 *   and lies within ENERGY_TOL of the analytic GGX conductor the file
 *   tabulates (computed here in C, its R0 turned to RGB with the loader's
 *   weights, scene/spectrum.h); the importance-sampling estimate of the
 *   same integral, f cos / pdf averaged over the samples, agrees with the
 *   quadrature.
 * Fixed seeds; the chi-square runs share alpha 0.01 (Šidák). */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scene/measured.h"
#include "scene/rgl_tensor.h"
#include "scene/spectrum.h"
#include "tests/trace/bsdf_probe.h"
#include "tests/trace/bsdf_stats.h"

#define N_SAMPLES 200000
/* Sampling finds the colour at the point the luminance warp gave,
 * evaluation at the inverse of the visible-normal warp: the same point up
 * to rounding, which the inversion amplifies where the warp's density is
 * near zero (so pbrt-v4 too). At most one sample in 2000 may differ by
 * more than this. */
#define CONSISTENT_TOL 1e-2
/* the tables are coarse (16 x 16 normals, 12 x 12 colours): on theta_i
 * nodes their bilinear interpolation moves the albedo by under 1 % */
#define ENERGY_TOL 0.02

/* make_measured.py's BRDF */
#define ALPHA 0.3
static const float lambdas[8] = {360, 420, 480, 540, 600, 660, 720, 830};
static double r0_of(double l) { return 0.15 + 0.75 / (1.0 + exp(-(l - 540.0) / 30.0)); }

static double ggx_lambda(double c)
{
    double c2 = c * c, t2 = (1 - c2) / c2;
    return (-1 + sqrt(1 + ALPHA * ALPHA * t2)) / 2;
}

/* f cos(wi) of the analytic conductor with RGB R0 */
static void ggx_fcos(const double r0[3], const float wo[3], const float wi[3], double out[3])
{
    out[0] = out[1] = out[2] = 0;
    if (wo[2] <= 0 || wi[2] <= 0)
        return;
    double h[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    double l = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (int k = 0; k < 3; k++)
        h[k] /= l;
    double c2 = h[2] * h[2], t2 = (1 - c2) / c2, e = 1 + t2 / (ALPHA * ALPHA);
    double d = 1 / (M_PI * ALPHA * ALPHA * c2 * c2 * e * e);
    double g = 1 / (1 + ggx_lambda(wo[2]) + ggx_lambda(wi[2]));
    double cwh = wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2], s = pow(1 - cwh, 5);
    for (int k = 0; k < 3; k++)
        out[k] = (r0[k] + (1 - r0[k]) * s) * d * g / (4 * wo[2]);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/oracle/measured_ggx.bsdf", dir ? dir : "tests/data");
    struct cv_tensor_file t;
    uint32_t *words = NULL;
    size_t n_words = 0;
    bool loaded = cv_tensor_load(path, &t, &err);
    if (loaded) {
        loaded = cv_measured_tables(path, &t, &words, &n_words, &err);
        cv_tensor_free(&t);
    }
    free(path);
    if (!tap_ok(loaded, "measured_ggx.bsdf loads: %s", err.msg))
        return tap_done();

    double w[3 * 8], r0[3] = {0, 0, 0};
    cv_spectrum_rgb_weights(lambdas, 8, w);
    for (int k = 0; k < 8; k++)
        for (int c = 0; c < 3; c++)
            r0[c] += w[3 * k + c] * r0_of(lambdas[k]);
    tap_diag("R0 in Rec.709: %.4f %.4f %.4f", r0[0], r0[1], r0[2]);

    CvMaterial m = probe_material(CV_MAT_MEASURED);
    m.mix_a = 0;
    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, &m, 1, &err), "probe shader and buffers: %s", err.msg))
        return tap_done();
    GLuint tables = cv_buffer_create(n_words * 4, words, "measured tables", &err);
    free(words);
    GLuint tables_tex = tables ? cv_buffer_texture(tables, GL_R32UI, n_words, &err) : 0;
    if (!tap_ok(tables_tex != 0, "measured tables as a buffer texture: %s", err.msg))
        return tap_done();
    glBindTextureUnit(CV_TEXUNIT_MEASURED, tables_tex);

    /* wo on theta_i nodes of the file (u 0.4, 0.6, 0.8: 14.4, 32.4, 57.6
     * degrees) and between its last two (57.6 and 90), where only the
     * energy bound is checked: there the tables' interpolation over
     * theta_i itself departs from the analytic BRDF by up to a sixth */
    static const double wos[][2] = {{14.4, 0}, {32.4, 40}, {57.6, 135}, {80, 250}};
    const int n_wo = (int)(sizeof(wos) / sizeof(wos[0]));
    double alpha = stats_sidak(0.01, n_wo);
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = malloc(n_grid * 4 * sizeof(float));
    float *samples = malloc((size_t)N_SAMPLES * 12 * sizeof(float));
    double *observed = malloc(CHI_CELLS * sizeof(double)), *cell = malloc(CHI_CELLS * sizeof(double));
    unsigned seed = 7;
    for (int k = 0; k < n_wo; k++) {
        float wo[3];
        probe_dir(wos[k][0], wos[k][1], wo);
        if (!probe_run(&p, 0, 0, wo, seed++, NULL, N_SAMPLES, samples, &err) ||
            !probe_run(&p, 1, 0, wo, 0, grid, n_grid, grid_out, &err)) {
            tap_ok(false, "wo %.0f: GPU run: %s", wos[k][0], err.msg);
            continue;
        }
        /* ---- chi-square and sample consistency ---- */
        memset(observed, 0, CHI_CELLS * sizeof(double));
        size_t ok = 0, bad = 0;
        double est[3] = {0, 0, 0};
        for (size_t i = 0; i < N_SAMPLES; i++) {
            const float *s = samples + 12 * i;
            if (s[3] < 0)
                continue;
            ok++;
            observed[stats_cell(s)] += 1;
            if (fabs(s[3] - s[11]) > CONSISTENT_TOL * s[3])
                bad++;
            for (int c = 0; c < 3; c++) {
                if (!(s[4 + c] >= 0) || fabs(s[4 + c] - s[8 + c]) > CONSISTENT_TOL * fmax(s[4 + c], 1e-3)) {
                    bad++;
                    break;
                }
            }
            for (int c = 0; c < 3; c++)
                est[c] += s[4 + c] * s[2] / s[3];
        }
        stats_integrate(grid_out + 3, 4, cell);
        struct stats_chi2 r = stats_chi2_test(observed, cell, N_SAMPLES);
        /* samples whose reflection falls below the horizon fail, as in
         * pbrt-v4: the pdf integrates to the fraction that succeeds */
        double frac = (double)ok / N_SAMPLES;
        tap_ok(bad <= ok / 2000 && !r.zero_cell_hit && r.total_expected < 1.005 &&
                   fabs(r.total_expected - frac) < 0.01 && frac > 0.8 && r.p_value >= alpha,
               "chi2 wo (%.0f, %.0f): chi2 %.1f dof %d p %.3g (pdf integral %.4f, %.4f of samples valid, "
               "%zu inconsistent with f and pdf)",
               wos[k][0], wos[k][1], r.chi2, r.dof, r.p_value, r.total_expected, frac, bad);

        /* ---- energy: quadrature of f cos, against the analytic conductor ---- */
        double q[3] = {0, 0, 0}, a[3] = {0, 0, 0};
        size_t i = 0;
        double dt = M_PI / CHI_THETA / CHI_SUB, dp = 2 * M_PI / CHI_PHI / CHI_SUB;
        for (int ct = 0; ct < CHI_THETA; ct++)
            for (int cp = 0; cp < CHI_PHI; cp++)
                for (int si = 0; si < CHI_SUB; si++) {
                    double theta = (ct + (si + 0.5) / CHI_SUB) * M_PI / CHI_THETA;
                    for (int sj = 0; sj < CHI_SUB; sj++, i++) {
                        const float *wi = grid + 4 * i;
                        double dw = sin(theta) * dt * dp, g[3];
                        ggx_fcos(r0, wo, wi, g);
                        for (int c = 0; c < 3; c++) {
                            q[c] += grid_out[4 * i + c] * fmax(wi[2], 0) * dw;
                            a[c] += g[c] * dw;
                        }
                    }
                }
        double worst = 0, worst_est = 0;
        for (int c = 0; c < 3; c++) {
            est[c] /= N_SAMPLES;
            worst = fmax(worst, fabs(q[c] / a[c] - 1));
            worst_est = fmax(worst_est, fabs(est[c] / q[c] - 1));
        }
        tap_ok(q[0] <= 1 && q[1] <= 1 && q[2] <= 1 && (wos[k][0] > 60 || worst < ENERGY_TOL),
               "energy wo (%.0f, %.0f): integral of f cos %.4f %.4f %.4f (analytic GGX %.4f %.4f %.4f, "
               "worst %.2f %%)",
               wos[k][0], wos[k][1], q[0], q[1], q[2], a[0], a[1], a[2], 100 * worst);
        tap_ok(worst_est < 0.01, "energy wo (%.0f, %.0f): f cos / pdf over the samples %.4f %.4f %.4f "
               "(quadrature off by %.2f %%)", wos[k][0], wos[k][1], est[0], est[1], est[2], 100 * worst_est);
    }

    /* the lower hemisphere mirrors the upper (two-sided, as pbrt-v4) */
    {
        float wo[3], wo_d[3], dirs[8] = {0.3f, 0.2f, 0.93f, 0, 0.3f, 0.2f, -0.93f, 0}, out[8], out_d[8];
        probe_dir(40, 30, wo);
        wo_d[0] = wo[0], wo_d[1] = wo[1], wo_d[2] = -wo[2];
        bool ran = probe_run(&p, 1, 0, wo, 0, dirs, 2, out, &err) && probe_run(&p, 1, 0, wo_d, 0, dirs, 2, out_d, &err);
        tap_ok(ran && out[0] > 0 && out[3] > 0 && fabs(out_d[4] - out[0]) < 1e-5 * out[0] &&
                   fabs(out_d[7] - out[3]) < 1e-5 * out[3] && out[4] == 0 && out_d[0] == 0,
               "two-sided: f %.4f pdf %.4f from above, %.4f %.4f mirrored below", out[0], out[3], out_d[4], out_d[7]);
    }

    glDeleteTextures(1, &tables_tex);
    cv_buffer_destroy(&tables);
    free(grid);
    free(grid_out);
    free(samples);
    free(observed);
    free(cell);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
