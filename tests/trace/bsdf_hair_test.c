/* bsdf_hair_test.c: the hair BSDF (glsl/trace/bsdf/hair.glsl, through the
 * shipped cv_bsdf_* entry points), after pbrt-v4's hair tests:
 * - white furnace: with sigma_a 0 the fibre absorbs nothing, so f |cos|
 *   integrates to 1 over the sphere for every beta_m, beta_n, h and wo
 *   (midpoint quadrature in sin theta and phi about the fibre, where the
 *   measure is uniform);
 * - sampling weights: with sigma_a 0 sampling is exact, so every sample's
 *   f |cos| / pdf is 1; sampled f and pdf equal cv_bsdf_f and cv_bsdf_pdf;
 * - chi-square of the samples against cv_bsdf_pdf, with absorption;
 * - the material's colour rules: sigma_a, reflectance and melanin give the
 *   same f as the sigma_a they stand for.
 * Fixed seeds; the chi-square runs share alpha 0.01 (Šidák). */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/trace/bsdf_probe.h"
#include "tests/trace/bsdf_stats.h"

#define FURNACE_NX 200   /* sin theta steps over [-1, 1] */
#define FURNACE_NPHI 400 /* phi steps over [0, 2 pi) */
#define N_SAMPLES 100000

static CvMaterial hair_sigma(float sa_r, float sa_g, float sa_b, float beta_m, float beta_n, float alpha)
{
    CvMaterial m = probe_material(CV_MAT_HAIR);
    m.flags = CV_MATF_HAIR_SIGMA_A;
    m.reflectance = (cv_vec4){sa_r, sa_g, sa_b, 0};
    m.eta = (cv_vec4){1.55f, 1.55f, 1.55f, 0};
    m.roughness = (cv_vec4){beta_m, beta_n, alpha, 0};
    return m;
}

/* Directions (sin theta, cos theta cos phi, cos theta sin phi) at the
 * quadrature's midpoints: the probe's frame has x = dpdu (along the fibre)
 * and z = the normal, so these are local and world at once. */
static float *furnace_dirs(size_t *n)
{
    *n = (size_t)FURNACE_NX * FURNACE_NPHI;
    float *d = calloc(*n * 4, sizeof(float));
    for (int i = 0; i < FURNACE_NX; i++)
        for (int j = 0; j < FURNACE_NPHI; j++) {
            double x = -1 + (i + 0.5) * 2.0 / FURNACE_NX, c = sqrt(1 - x * x);
            double phi = (j + 0.5) * 2 * M_PI / FURNACE_NPHI;
            float *w = d + 4 * ((size_t)i * FURNACE_NPHI + j);
            w[0] = (float)x;
            w[1] = (float)(c * cos(phi));
            w[2] = (float)(c * sin(phi));
        }
    return d;
}

/* wo at angle theta_deg from the normal plane of the fibre, phi_deg around it. */
static void hair_dir(double theta_deg, double phi_deg, float w[3])
{
    double t = theta_deg * M_PI / 180, ph = phi_deg * M_PI / 180;
    w[0] = (float)sin(t);
    w[1] = (float)(cos(t) * cos(ph));
    w[2] = (float)(cos(t) * sin(ph));
}

static void set_h(struct probe *p, double h)
{
    p->uv[0] = 0.5f;
    p->uv[1] = (float)((h + 1) / 2);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};

    /* materials: furnace (sigma_a 0) over beta_m x beta_n, then the rest */
    static const float betas_m[] = {0.1f, 0.3f, 0.5f, 0.7f, 0.9f}, betas_n[] = {0.1f, 0.5f, 0.9f};
    enum { N_FURNACE = 15 };
    CvMaterial mats[N_FURNACE + 8];
    for (int i = 0; i < N_FURNACE; i++)
        mats[i] = hair_sigma(0, 0, 0, betas_m[i / 3], betas_n[i % 3], i % 2 ? 2.0f : 0.0f);
    /* chi-square: absorbing, tilted */
    const int chi0 = N_FURNACE;
    mats[chi0 + 0] = hair_sigma(0.25f, 0.25f, 0.25f, 0.3f, 0.3f, 2);
    mats[chi0 + 1] = hair_sigma(0.5f, 1.0f, 2.0f, 0.2f, 0.5f, 3);
    mats[chi0 + 2] = hair_sigma(0.1f, 0.2f, 0.4f, 0.6f, 0.8f, 0);
    /* colour rules: reflectance and melanin against their sigma_a */
    const int col0 = chi0 + 3;
    CvMaterial refl = hair_sigma(0.6f, 0.4f, 0.2f, 0.3f, 0.4f, 2);
    refl.flags = CV_MATF_HAIR_REFLECTANCE;
    CvMaterial mel = hair_sigma(1.3f, 0.5f, 0, 0.3f, 0.4f, 2);
    mel.flags = 0;
    mats[col0 + 0] = refl;
    mats[col0 + 1] = mel;
    {
        /* Chiang et al.'s fit and pbrt-v4's pigment coefficients, in C */
        double b = 0.4, d = 5.969 - 0.215 * b + 2.532 * b * b - 10.73 * pow(b, 3) + 5.574 * pow(b, 4) +
                            0.245 * pow(b, 5);
        double c[3] = {0.6, 0.4, 0.2}, sa[3];
        for (int k = 0; k < 3; k++)
            sa[k] = pow(log(c[k]) / d, 2);
        mats[col0 + 2] = hair_sigma((float)sa[0], (float)sa[1], (float)sa[2], 0.3f, 0.4f, 2);
        mats[col0 + 3] = hair_sigma((float)(1.3 * 0.419 + 0.5 * 0.187), (float)(1.3 * 0.697 + 0.5 * 0.4),
                                    (float)(1.3 * 1.37 + 0.5 * 1.05), 0.3f, 0.4f, 2);
    }
    const int n_mats = col0 + 4;

    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, mats, (size_t)n_mats, &err), "probe shader and buffers: %s", err.msg))
        return tap_done();
    /* x along the fibre, z the normal */
    float z[3] = {0, 0, 1}, x[3] = {1, 0, 0};
    probe_frame(&p, z, z, x);

    /* ---- white furnace by quadrature ---- */
    size_t n_fd;
    float *fdirs = furnace_dirs(&n_fd);
    float *fout = malloc(n_fd * 4 * sizeof(float));
    static const double hs[] = {0.0, -0.6, 0.9, 0.35, -0.95};
    static const double wos[][2] = {{10, 40}, {-50, 100}, {75, 200}, {0, 90}, {-20, 300}};
    double worst = 0;
    for (int c = 0; c < N_FURNACE; c++) {
        double h = hs[c % 5];
        float wo[3];
        hair_dir(wos[(c / 5 + c) % 5][0], wos[(c / 5 + c) % 5][1], wo);
        set_h(&p, h);
        if (!probe_run(&p, 1, (unsigned)c, wo, 0, fdirs, n_fd, fout, &err)) {
            tap_ok(false, "furnace %d: GPU run: %s", c, err.msg);
            continue;
        }
        double sum[3] = {0, 0, 0};
        bool finite = true;
        for (size_t i = 0; i < n_fd; i++) {
            const float *f = fout + 4 * i;
            double cz = fabs(fdirs[4 * i + 2]);
            for (int k = 0; k < 3; k++) {
                finite = finite && isfinite(f[k]) && f[k] >= 0;
                sum[k] += f[k] * cz;
            }
        }
        double dw = (2.0 / FURNACE_NX) * (2 * M_PI / FURNACE_NPHI);
        double e = sum[1] * dw;
        worst = fmax(worst, fabs(e - 1));
        tap_ok(finite && fabs(e - 1) < 0.01 && fabs(sum[0] - sum[2]) < 1e-6 * sum[1],
               "white furnace beta_m %.1f beta_n %.1f alpha %.0f h %.2f: integral of f|cos| %.5f", mats[c].roughness.x,
               mats[c].roughness.y, mats[c].roughness.z, h, e);
    }
    tap_diag("white furnace: worst |integral - 1| %.2g", worst);

    /* ---- sampling weights with sigma_a 0 ---- */
    float *samples = malloc((size_t)N_SAMPLES * 12 * sizeof(float));
    unsigned seed = 7;
    for (int c = 0; c < N_FURNACE; c++) {
        double h = hs[(c + 2) % 5];
        float wo[3];
        hair_dir(wos[(c + 1) % 5][0], wos[(c + 1) % 5][1], wo);
        set_h(&p, h);
        size_t n = 20000;
        if (!probe_run(&p, 0, (unsigned)c, wo, seed++, NULL, n, samples, &err)) {
            tap_ok(false, "weights %d: GPU run: %s", c, err.msg);
            continue;
        }
        size_t failed = 0, off = 0, bad_eval = 0;
        double wsum = 0, wmin = 1e30, wmax = 0;
        for (size_t i = 0; i < n; i++) {
            const float *s = samples + 12 * i;
            if (s[3] < 0) {
                failed++;
                continue;
            }
            double w = s[5] * fabs(s[2]) / s[3];
            wsum += w;
            wmin = fmin(wmin, w);
            wmax = fmax(wmax, w);
            if (!(w > 0.99 && w < 1.01))
                off++;
            if (fabs(s[3] - s[11]) > 1e-3 * s[3] || fabs(s[5] - s[9]) > 1e-3 * fmax(s[5], 1e-3))
                bad_eval++;
        }
        tap_ok(failed <= n / 10000 && off <= n / 10000 && bad_eval <= n / 10000 &&
                   fabs(wsum / (double)(n - failed) - 1) < 1e-3,
               "sampling weights beta_m %.1f beta_n %.1f h %.2f: f|cos|/pdf in [%.5f, %.5f], mean %.5f "
               "(%zu outside [0.99, 1.01], %zu failed, %zu differ from f/pdf evaluated)",
               mats[c].roughness.x, mats[c].roughness.y, h, wmin, wmax, wsum / (double)(n - failed), off, failed,
               bad_eval);
    }

    /* ---- chi-square with absorption ---- */
    static const double chi_h[] = {0.3, -0.5, 0.9};
    static const double chi_wo[][2] = {{20, 60}, {-45, 170}};
    int n_chi = 3 * 2;
    double alpha = stats_sidak(0.01, n_chi);
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = malloc(n_grid * 4 * sizeof(float));
    double *observed = malloc(CHI_CELLS * sizeof(double));
    double *cell = malloc(CHI_CELLS * sizeof(double));
    for (int c = 0; c < 3; c++)
        for (int k = 0; k < 2; k++) {
            float wo[3];
            hair_dir(chi_wo[k][0], chi_wo[k][1], wo);
            set_h(&p, chi_h[c]);
            unsigned mat = (unsigned)(chi0 + c);
            if (!probe_run(&p, 0, mat, wo, seed++, NULL, N_SAMPLES, samples, &err) ||
                !probe_run(&p, 1, mat, wo, 0, grid, n_grid, grid_out, &err)) {
                tap_ok(false, "chi2 %d: GPU run: %s", c, err.msg);
                continue;
            }
            memset(observed, 0, CHI_CELLS * sizeof(double));
            size_t ok = 0, bad = 0;
            for (size_t i = 0; i < N_SAMPLES; i++) {
                const float *s = samples + 12 * i;
                if (s[3] < 0)
                    continue;
                ok++;
                observed[stats_cell(s)] += 1;
                if (fabs(s[3] - s[11]) > 1e-3 * s[3])
                    bad++;
                for (int ch = 0; ch < 3; ch++)
                    if (!(s[4 + ch] >= 0) || fabs(s[4 + ch] - s[8 + ch]) > 1e-3 * fmax(s[4 + ch], 1e-3)) {
                        bad++;
                        break;
                    }
            }
            stats_integrate(grid_out + 3, 4, cell);
            struct stats_chi2 r = stats_chi2_test(observed, cell, N_SAMPLES);
            const CvMaterial *m = &mats[mat];
            tap_ok(bad <= ok / 10000 && !r.zero_cell_hit && fabs(r.total_expected - 1) < 0.005 &&
                       ok >= N_SAMPLES - N_SAMPLES / 10000 && r.p_value >= alpha,
                   "chi2 sigma_a (%.2g %.2g %.2g) beta_m %.1f beta_n %.1f alpha %.0f h %.1f wo %.0f: chi2 %.1f "
                   "dof %d p %.3g (pdf integral %.4f, %zu of %zu samples inconsistent)",
                   m->reflectance.x, m->reflectance.y, m->reflectance.z, m->roughness.x, m->roughness.y,
                   m->roughness.z, chi_h[c], chi_wo[k][0], r.chi2, r.dof, r.p_value, r.total_expected, bad, ok);
        }

    /* ---- colour rules ---- */
    {
        float wo[3];
        hair_dir(25, 80, wo);
        set_h(&p, 0.2);
        size_t n = 2048;
        float *a = malloc(n * 4 * sizeof(float)), *b = malloc(n * 4 * sizeof(float));
        const char *names[2] = {"reflectance", "eumelanin 1.3, pheomelanin 0.5"};
        for (int r = 0; r < 2; r++) {
            /* every 100th direction of the furnace grid */
            float *dirs = malloc(n * 4 * sizeof(float));
            for (size_t i = 0; i < n; i++)
                memcpy(dirs + 4 * i, fdirs + 4 * ((i * 157) % n_fd), 4 * sizeof(float));
            bool ran = probe_run(&p, 1, (unsigned)(col0 + r), wo, 0, dirs, n, a, &err) &&
                       probe_run(&p, 1, (unsigned)(col0 + 2 + r), wo, 0, dirs, n, b, &err);
            double worst_rel = 0, total = 0;
            for (size_t i = 0; ran && i < n; i++)
                for (int k = 0; k < 3; k++) {
                    total += b[4 * i + k];
                    worst_rel = fmax(worst_rel, fabs(a[4 * i + k] - b[4 * i + k]) / fmax(b[4 * i + k], 1e-4));
                }
            tap_ok(ran && total > 0 && worst_rel < 1e-3, "%s gives the f of its sigma_a (worst rel %.2g)",
                   names[r], worst_rel);
            free(dirs);
        }
        free(a);
        free(b);
    }

    free(fdirs);
    free(fout);
    free(samples);
    free(grid);
    free(grid_out);
    free(observed);
    free(cell);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
