/* bsdf_coat_closed_test.c: coated diffuse in closed form
 * (glsl/trace/bsdf/coated_closed.glsl, src/scene/coat_closed.c) against
 * the random walk it stands for (layered.glsl, pbrt-v4's estimator, itself
 * checked by bsdf_layered_test and the oracle), through the shipped GLSL.
 * 1. The host integrals against a plain midpoint rule (2^20 points, no
 *    change of variable), and 1 - r_in = t_out without thickness
 *    (reciprocity: what the base sends up either comes back or leaves).
 * 2. f: for a table of (eta, thickness, base reflectance per channel,
 *    white among them, maxdepth odd and even, coat alpha 0 and 0.001), at
 *    theta_o 5 to 85: pi f at the same cosine-distributed wi from both
 *    materials, per band of theta_i and channel: the mean difference
 *    within 4 standard errors + 0.25 %; pooled over theta_o and bands per
 *    channel, the same bound, which must itself be below 1 % (a 1 % error
 *    fails).
 * 3. Sampling: the sampled albedo (f cos / pdf, the delta lobe included)
 *    per channel against the walk's, same bounds (even maxdepth: for an
 *    odd one pbrt-v4's sampling walk stops one visit of the base short of
 *    its f, coated_closed.glsl); the delta samples' frequency against
 *    their probability.
 * 4. Chi-square (smooth coats: the non-delta samples) of the samples
 *    against cv_bsdf_pdf, Šidák-corrected alpha 0.01, and sampled f and
 *    pdf equal to cv_bsdf_f and cv_bsdf_pdf (nearly smooth coats: their
 *    ratio; a lobe of alpha 0.001 is far too narrow for the chi-square
 *    grid, and its directions come from the microfacet sampler that
 *    bsdf_chi2_test checks).
 * 5. Which materials the host allows: a scattering or textured slab
 *    albedo, a coated conductor: no. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scene/coat_closed.h"
#include "tests/rng.h"
#include "tests/trace/bsdf_probe.h"
#include "tests/trace/fresnel_ref.h"
#include "tests/trace/bsdf_stats.h"

#define N_DEFAULT 131072
#define BANDS 3
static size_t N = N_DEFAULT;

struct ccase {
    const char *name;
    double eta, thick, r[3];
    int maxdepth;
    double alpha;
};

static uint64_t rs = 0x2545F4914F6CDD1Dull;
static double rnd(void)
{
    return cv_test_xorshift64(&rs);
}

/* r_in, t_out by the midpoint rule straight from their definitions. */
static void integrals_ref(double eta, double th, double *r_in, double *t_out)
{
    const int n = 1 << 20;
    double r = 0, t = 0;
    for (int i = 0; i < n; i++) {
        double mu = (i + 0.5) / n;
        r += 2 * mu * ref_fresnel_dielectric(-mu, eta) * exp(-2 * th / mu);
        double s2 = (1 - mu * mu) / (eta * eta);
        if (s2 < 1)
            t += 2 * mu * (1 - ref_fresnel_dielectric(mu, eta)) * exp(-th / sqrt(1 - s2));
    }
    *r_in = r / n;
    *t_out = t / n / (eta * eta);
}

static CvMaterial coat_mat(const struct ccase *c, bool closed)
{
    CvMaterial m = probe_material(CV_MAT_COATED_DIFFUSE);
    m.reflectance = (cv_vec4){(float)c->r[0], (float)c->r[1], (float)c->r[2], 0};
    m.eta = (cv_vec4){(float)c->eta, (float)c->eta, (float)c->eta, (float)c->eta};
    m.roughness = (cv_vec4){(float)c->alpha, (float)c->alpha, (float)c->thick, 0};
    m.roughness2 = (cv_vec4){0, 0, (float)c->maxdepth, 1};
    if (closed)
        cv_coat_closed_prepare(&m);
    return m;
}

static void cosine_dirs(float *dirs, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double r = sqrt(rnd()), ph = 2 * M_PI * rnd();
        dirs[4 * i] = (float)(r * cos(ph));
        dirs[4 * i + 1] = (float)(r * sin(ph));
        dirs[4 * i + 2] = (float)sqrt(fmax(0, 1 - r * r));
        dirs[4 * i + 3] = 0;
    }
}

static int band_of(double c)
{
    int b = (int)(c * BANDS);
    return b >= BANDS ? BANDS - 1 : (b < 0 ? 0 : b);
}

static void test_integrals(void)
{
    const double etas[] = {1.5, 1.33, 2.0, 0.8}, ths[] = {0, 0.01, 0.3};
    double worst = 0, worst_recip = 0;
    for (size_t i = 0; i < CV_ARRAY_SIZE(etas); i++)
        for (size_t j = 0; j < CV_ARRAY_SIZE(ths); j++) {
            double r, t, rr, tr;
            cv_coat_closed_integrals(etas[i], ths[j], &r, &t);
            integrals_ref(etas[i], ths[j], &rr, &tr);
            worst = fmax(worst, fmax(fabs(r - rr), fabs(t - tr)));
            if (ths[j] == 0)
                worst_recip = fmax(worst_recip, fabs(1 - r - t));
            tap_diag("eta %.2f thickness %.2f: r_in %.6f (midpoint %.6f) t_out %.6f (midpoint %.6f)", etas[i],
                     ths[j], r, rr, t, tr);
        }
    tap_ok(worst < 1e-5, "host integrals match the midpoint rule (worst %.2g)", worst);
    tap_ok(worst_recip < 1e-5, "without thickness 1 - r_in = t_out (worst %.2g)", worst_recip);
    double r15, t15;
    cv_coat_closed_integrals(1.5, 0, &r15, &t15);
    tap_ok(fabs(r15 - 0.5963) < 2e-4, "eta 1.5: internal diffuse reflectance %.4f (the textbook 0.596)", r15);
}

static void test_prepare(void)
{
    struct ccase c = {"", 1.5, 0.01, {0.5, 0.5, 0.5}, 10, 0};
    CvMaterial m = coat_mat(&c, false);
    CvMaterial a = m;
    a.specular = (cv_vec4){0, 0.2f, 0, 0};
    CvMaterial t = m;
    t.specular_tex = 0;
    CvMaterial k = m;
    k.type = CV_MAT_COATED_CONDUCTOR;
    bool ok = cv_coat_closed_prepare(&m) && (m.flags & CV_MATF_COAT_CLOSED) && m.roughness2.x > 0.5f &&
              m.roughness2.z == 10;
    tap_ok(ok, "a clear slab under a coat takes the closed form (r_in %.4f)", m.roughness2.x);
    tap_ok(!cv_coat_closed_prepare(&a) && !(a.flags & CV_MATF_COAT_CLOSED), "a scattering slab does not");
    tap_ok(!cv_coat_closed_prepare(&t) && !(t.flags & CV_MATF_COAT_CLOSED), "a textured slab albedo does not");
    tap_ok(!cv_coat_closed_prepare(&k) && !(k.flags & CV_MATF_COAT_CLOSED), "a coated conductor does not");
}

int main(void)
{
    if (getenv("CV_TEST_N"))
        N = (size_t)atol(getenv("CV_TEST_N"));
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    test_integrals();
    test_prepare();
    struct cv_error err = {{0}};
    const struct ccase cases[] = {
        {"coffee's orange, smooth", 1.5, 0.01, {1, 0.378676, 0.013473}, 10, 0},
        {"white, thickness 0.1", 1.5, 0.1, {1, 1, 1}, 10, 0},
        {"white, thickness 0.1, maxdepth 100", 1.5, 0.1, {1, 1, 1}, 100, 0},
        {"eta 1.33, maxdepth 3", 1.33, 0.01, {0.5, 0.8, 1}, 3, 0},
        {"eta 2, thickness 0.3, maxdepth 1", 2.0, 0.3, {1, 0.5, 0}, 1, 0},
        {"eta 1.1, no thickness, maxdepth 40", 1.1, 0, {1, 0.9, 0.2}, 40, 0},
        {"coffee's orange, alpha 0.001 (the limit)", 1.5, 0.01, {1, 0.378676, 0.013473}, 10, 0.001},
        {"white, thickness 0.1, maxdepth 16, alpha 0.001", 1.5, 0.1, {1, 1, 1}, 16, 0.001},
    };
    size_t nc = CV_ARRAY_SIZE(cases);
    CvMaterial *mats = cv_xcalloc(2 * nc, sizeof(*mats));
    for (size_t c = 0; c < nc; c++) {
        mats[2 * c] = coat_mat(&cases[c], false);
        mats[2 * c + 1] = coat_mat(&cases[c], true);
    }
    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, mats, 2 * nc, &err), "probe shader and buffers: %s", err.msg))
        return tap_done();
    const double thetas[] = {5, 30, 60, 85};
    float *dirs = malloc(N * 4 * sizeof(float));
    float *oc = malloc(N * 12 * sizeof(float)), *ow = malloc(N * 12 * sizeof(float));
    unsigned seed = 11;
    for (size_t c = 0; c < nc; c++) {
        const struct ccase *cc = &cases[c];
        bool ran = true, pass_f = true, pass_s = true, pass_delta = true;
        double worst_f = 0, worst_s = 0;
        /* pooled over theta_o and bands, per channel: value, difference, its variance */
        double pf[3] = {0}, pfd[3] = {0}, pfv[3] = {0}, ps_c[3] = {0}, ps_d[3] = {0}, ps_v[3] = {0};
        bool sampled = cc->maxdepth % 2 == 0;
        for (size_t k = 0; k < CV_ARRAY_SIZE(thetas) && ran; k++) {
            float wo[3];
            probe_dir(thetas[k], 40, wo);
            cosine_dirs(dirs, N);
            if (!probe_run(&p, 1, (unsigned)(2 * c + 1), wo, seed++, dirs, N, oc, &err) ||
                !probe_run(&p, 1, (unsigned)(2 * c), wo, seed++, dirs, N, ow, &err)) {
                ran = false;
                break;
            }
            double v[BANDS][3] = {{0}}, d[BANDS][3] = {{0}}, d2[BANDS][3] = {{0}};
            for (size_t i = 0; i < N; i++) {
                int b = band_of(dirs[4 * i + 2]);
                for (int ch = 0; ch < 3; ch++) {
                    double x = M_PI * (ow[4 * i + ch] - oc[4 * i + ch]);
                    /* (the value scales the tolerance: the rare wi in a
                     * nearly smooth coat's reflection lobe, the same in both
                     * and cancelling in x, would inflate it) */
                    v[b][ch] += fmin(M_PI * oc[4 * i + ch], 10);
                    d[b][ch] += x;
                    d2[b][ch] += x * x;
                }
            }
            char line[512];
            int len = snprintf(line, sizeof(line), "%s theta %2.0f: walk/closed", cc->name, thetas[k]);
            for (int b = 0; b < BANDS; b++)
                for (int ch = 0; ch < 3; ch++) {
                    double mv = v[b][ch] / N, md = d[b][ch] / N;
                    double se = sqrt(fmax(d2[b][ch] / N - md * md, 0) / N);
                    double tol = 4 * se + 0.0025 * mv + 2e-5;
                    if (fabs(md) > tol)
                        pass_f = false;
                    if (mv > 0.01)
                        worst_f = fmax(worst_f, fabs(md / mv));
                    pf[ch] += mv;
                    pfd[ch] += md;
                    pfv[ch] += se * se;
                    len += snprintf(line + len, sizeof(line) - (size_t)len, "%s%.4f", ch ? "," : " ",
                                    mv > 0 ? 1 + md / mv : 0);
                }
            tap_diag("%s", line);
            if (!sampled)
                continue;
            /* sampled albedo, delta lobe included */
            if (!probe_run(&p, 0, (unsigned)(2 * c + 1), wo, seed++, NULL, N, oc, &err) ||
                !probe_run(&p, 0, (unsigned)(2 * c), wo, seed++, NULL, N, ow, &err)) {
                ran = false;
                break;
            }
            double sc[3] = {0}, sc2[3] = {0}, sw[3] = {0}, sw2[3] = {0}, n_delta = 0, p_delta = -1;
            for (size_t i = 0; i < N; i++) {
                const float *a = oc + 12 * i, *w = ow + 12 * i;
                if ((unsigned)a[7] & 4u) {
                    n_delta++;
                    p_delta = a[3];
                }
                for (int ch = 0; ch < 3; ch++) {
                    double x = a[3] > 0 ? a[4 + ch] * fabs(a[2]) / a[3] : 0;
                    double y = w[3] > 0 ? w[4 + ch] * fabs(w[2]) / w[3] : 0;
                    sc[ch] += x;
                    sc2[ch] += x * x;
                    sw[ch] += y;
                    sw2[ch] += y * y;
                }
            }
            for (int ch = 0; ch < 3; ch++) {
                double mc = sc[ch] / N, mw = sw[ch] / N;
                double se = hypot(sqrt(fmax(sc2[ch] / N - mc * mc, 0) / N), sqrt(fmax(sw2[ch] / N - mw * mw, 0) / N));
                double tol = 4 * se + 0.0025 * mc + 2e-5;
                if (fabs(mc - mw) > tol)
                    pass_s = false;
                if (mc > 0.01)
                    worst_s = fmax(worst_s, fabs(mw / mc - 1));
                ps_c[ch] += mc;
                ps_d[ch] += mw - mc;
                ps_v[ch] += se * se;
                tap_diag("%s theta %2.0f ch %d: sampled albedo closed %.4f walk %.4f (tolerance %.2f %%)", cc->name,
                         thetas[k], ch, mc, mw, 100 * tol / fmax(mc, 1e-9));
            }
            if (cc->alpha == 0) {
                double f = n_delta / N, pd = p_delta < 0 ? 0 : p_delta;
                if (fabs(f - pd) > 4 * sqrt(pd * (1 - pd) / N) + 1e-4)
                    pass_delta = false;
                tap_diag("%s theta %2.0f: delta samples %.4f of all, their pdf %.4f", cc->name, thetas[k], f, pd);
            }
        }
        if (!tap_ok(ran, "%s: GPU runs: %s", cc->name, err.msg))
            continue;
        tap_ok(pass_f, "%s: f equals the random walk's mean (worst %.2f %%)", cc->name, 100 * worst_f);
        if (sampled) {
            tap_ok(pass_s, "%s: sampled albedo equals the walk's (worst %.2f %%)", cc->name, 100 * worst_s);
            if (cc->alpha == 0)
                tap_ok(pass_delta, "%s: delta samples as often as their probability", cc->name);
        }
        /* pooled: every channel within 4 standard errors + 0.25 %, a bound
         * that must itself be under 1 % where the base reflects 0.3 or more */
        bool pool_ok = true, catches = true;
        double worst_tol = 0;
        for (int ch = 0; ch < 3; ch++) {
            double t1 = 4 * sqrt(pfv[ch]) + 0.0025 * pf[ch], t2 = 4 * sqrt(ps_v[ch]) + 0.0025 * ps_c[ch];
            pool_ok = pool_ok && fabs(pfd[ch]) <= t1 && (!sampled || fabs(ps_d[ch]) <= t2);
            if (cc->r[ch] >= 0.3) {
                worst_tol = fmax(worst_tol, fmax(t1 / pf[ch], sampled ? t2 / ps_c[ch] : 0));
                catches = catches && t1 < 0.01 * pf[ch] && (!sampled || t2 < 0.01 * ps_c[ch]);
            }
            tap_diag("%s ch %d pooled: f walk/closed %.4f +- %.4f%s", cc->name, ch, 1 + pfd[ch] / fmax(pf[ch], 1e-9),
                     sqrt(pfv[ch]) / fmax(pf[ch], 1e-9), sampled ? "" : " (odd maxdepth: f only)");
            if (sampled)
                tap_diag("%s ch %d pooled: sampled albedo walk/closed %.4f +- %.4f", cc->name, ch,
                         1 + ps_d[ch] / fmax(ps_c[ch], 1e-9), sqrt(ps_v[ch]) / fmax(ps_c[ch], 1e-9));
        }
        tap_ok(pool_ok, "%s: pooled over theta_o, closed form and walk agree per channel", cc->name);
        tap_ok(catches, "%s: the pooled bounds catch a 1 %% error (largest %.2f %%)", cc->name, 100 * worst_tol);
    }

    /* chi-square and f / pdf consistency of the closed form's samples */
    int n_chi = 0;
    for (size_t c = 0; c < nc; c++)
        n_chi += cases[c].alpha == 0 ? 2 : 0;
    double alpha = stats_sidak(0.01, n_chi);
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = malloc(n_grid * 4 * sizeof(float));
    double *observed = malloc(CHI_CELLS * sizeof(double)), *cell = malloc(CHI_CELLS * sizeof(double));
    const double chi_thetas[] = {30, 75};
    for (size_t c = 0; c < nc; c++)
        for (size_t k = 0; k < CV_ARRAY_SIZE(chi_thetas); k++) {
            const char *nm = cases[c].name;
            double th = chi_thetas[k];
            float wo[3];
            probe_dir(th, 20, wo);
            if (!probe_run(&p, 0, (unsigned)(2 * c + 1), wo, seed++, NULL, N, oc, &err) ||
                !probe_run(&p, 1, (unsigned)(2 * c + 1), wo, 0, grid, n_grid, grid_out, &err)) {
                tap_ok(false, "%s wo %.0f: GPU run: %s", nm, th, err.msg);
                continue;
            }
            memset(observed, 0, CHI_CELLS * sizeof(double));
            size_t bad = 0, ok = 0;
            for (size_t i = 0; i < N; i++) {
                const float *s = oc + 12 * i;
                if (s[3] < 0 || ((unsigned)s[7] & 4u))
                    continue;
                ok++;
                observed[stats_cell(s)] += 1;
                bool same = true;
                if (cases[c].alpha == 0) {
                    same = fabs(s[3] - s[11]) <= 1e-4 * s[3];
                    for (int ch = 0; ch < 3; ch++)
                        same = same && fabs(s[4 + ch] - s[8 + ch]) <= 1e-4 * fmax(s[4 + ch], 1e-3);
                } else {
                    /* a lobe of alpha 0.001 changes by up to a few per cent
                     * with the float rounding of its direction (world to
                     * local and back), in f and pdf alike: their ratio, the
                     * sample's weight, stays */
                    for (int ch = 0; ch < 3; ch++) {
                        double w = s[4 + ch] / s[3], we = s[11] > 0 ? s[8 + ch] / s[11] : -1;
                        same = same && fabs(w - we) <= 1e-3 * fmax(w, 1e-3);
                    }
                }
                bad += !same;
            }
            tap_ok(ok > 1000 && bad <= ok / 10000, "%s wo %.0f: sampled f and pdf equal cv_bsdf_f and cv_bsdf_pdf (%zu of %zu differ)",
                   nm, th, bad, ok);
            if (cases[c].alpha != 0)
                continue;
            stats_integrate(grid_out + 3, 4, cell);
            struct stats_chi2 r = stats_chi2_test(observed, cell, N);
            tap_ok(!r.zero_cell_hit && r.p_value >= alpha, "%s wo %.0f: chi2 %.1f dof %d p %.3g (pdf integral %.4f)",
                   nm, th, r.chi2, r.dof, r.p_value, r.total_expected);
        }
    free(grid);
    free(grid_out);
    free(observed);
    free(cell);
    free(dirs);
    free(oc);
    free(ow);
    free(mats);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
