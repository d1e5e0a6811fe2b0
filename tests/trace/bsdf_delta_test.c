/* bsdf_delta_test.c: sampling of the BSDFs with a delta lobe, which
 * bsdf_chi2_test.c leaves out (smooth conductor, mirror, smooth and thin
 * dielectric, smooth coats over a diffuse or rough conductor base). Per
 * material and direction wo, from the shipped GLSL (bsdf_probe.comp):
 *  - every delta sample leaves in the mirror or the refracted (or, thin,
 *    straight-through) direction;
 *  - per lobe, the mean of the sample weight f |cos| / pdf times "this lobe
 *    was picked" is the lobe's reflectance or transmittance computed here on
 *    the CPU from the Fresnel equations (dielectric, thin slab, complex
 *    conductor), within Z_BOUND standard errors of the mean: this checks
 *    the selection probability and the weight together;
 *  - the non-delta samples pass the chi-square test against the pdf
 *    (bsdf_stats.h), and the pdf integrates to their share.
 * Fixed seeds; Šidák-corrected significance 0.01 for the chi-square runs. */
#include "config.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/trace/bsdf_probe.h"
#include "tests/trace/bsdf_stats.h"
#include "tests/trace/fresnel_ref.h"

#define N_SAMPLES 200000
/* standard errors allowed between a lobe's mean weight and its Fresnel
 * value: a normal deviate this large has probability 6e-5 per check */
#define Z_BOUND 4.0

enum lobe { LOBE_R, LOBE_T, N_LOBES };

struct cfg {
    const char *name;
    CvMaterial m;
    double wo_theta[3];
    int n_wo;
};

static CvMaterial conductor(float a)
{
    CvMaterial m = probe_material(CV_MAT_CONDUCTOR);
    m.eta = (cv_vec4){0.2f, 0.92f, 1.1f, 0};
    m.k = (cv_vec4){3.9f, 2.45f, 2.14f, 0};
    m.roughness = (cv_vec4){a, a, 0, 0};
    return m;
}

static CvMaterial dielectric(unsigned type, float eta)
{
    CvMaterial m = probe_material(type);
    m.eta = (cv_vec4){eta, eta, eta, 0};
    m.reflectance = m.specular = (cv_vec4){1, 1, 1, 0};
    return m;
}

/* Expected mean weight of each lobe for material m at wo (per channel),
 * and the lobes' directions. */
static void expected(const CvMaterial *m, const float wo[3], double e[N_LOBES][3], float dir[N_LOBES][3])
{
    double c = wo[2];
    memset(e, 0, sizeof(double) * N_LOBES * 3);
    dir[LOBE_R][0] = -wo[0];
    dir[LOBE_R][1] = -wo[1];
    dir[LOBE_R][2] = wo[2];
    dir[LOBE_T][0] = -wo[0];
    dir[LOBE_T][1] = -wo[1];
    dir[LOBE_T][2] = -wo[2];
    const float *eta = &m->eta.x, *k = &m->k.x;
    switch (m->type) {
    case CV_MAT_CONDUCTOR:
        for (int ch = 0; ch < 3; ch++)
            e[LOBE_R][ch] = ref_fresnel_conductor(fabs(c), eta[ch] + I * k[ch]);
        break;
    case CV_MAT_MIRROR:
        for (int ch = 0; ch < 3; ch++)
            e[LOBE_R][ch] = (&m->reflectance.x)[ch];
        break;
    case CV_MAT_DIELECTRIC: {
        double F = ref_fresnel_dielectric(c, eta[0]);
        double etap = c > 0 ? eta[0] : 1 / eta[0];
        /* Snell: wt = -wo / etap + (cos_i / etap - cos_t) n, n on wo's side */
        double ci = fabs(c), s2t = (1 - ci * ci) / (etap * etap);
        if (s2t < 1) {
            double ct = sqrt(1 - s2t), sg = c > 0 ? 1 : -1;
            for (int i = 0; i < 2; i++)
                dir[LOBE_T][i] = (float)(-wo[i] / etap);
            dir[LOBE_T][2] = (float)(-wo[2] / etap + sg * (ci / etap - ct));
        }
        for (int ch = 0; ch < 3; ch++) {
            e[LOBE_R][ch] = F;
            e[LOBE_T][ch] = (1 - F) / (etap * etap); /* radiance: divided by etap^2 */
        }
        break;
    }
    case CV_MAT_THIN_DIELECTRIC: {
        /* the slab's inter-reflections: R + T^2 R / (1 - R^2) */
        double R = ref_fresnel_dielectric(fabs(c), eta[0]), T = 1 - R;
        if (R < 1)
            R += T * T * R / (1 - R * R);
        for (int ch = 0; ch < 3; ch++) {
            e[LOBE_R][ch] = R;
            e[LOBE_T][ch] = 1 - R;
        }
        break;
    }
    case CV_MAT_COATED_DIFFUSE:
        for (int ch = 0; ch < 3; ch++)
            e[LOBE_R][ch] = ref_fresnel_dielectric(fabs(c), eta[0]);
        break;
    case CV_MAT_COATED_CONDUCTOR:
        for (int ch = 0; ch < 3; ch++)
            e[LOBE_R][ch] = ref_fresnel_dielectric(fabs(c), m->eta.w);
        break;
    }
}

static bool same_dir(const float *a, const float *b)
{
    return fabsf(a[0] - b[0]) < 1e-4f && fabsf(a[1] - b[1]) < 1e-4f && fabsf(a[2] - b[2]) < 1e-4f;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    CvMaterial mirror = probe_material(CV_MAT_MIRROR);
    mirror.reflectance = (cv_vec4){0.9f, 0.6f, 0.3f, 0};
    /* Coated materials are pbrt-v4's stochastic layered BSDFs: their pdf is
     * an estimate, so a chi-square against it does not apply; their
     * sampling is checked against an independent random walk in
     * bsdf_layered_test. */
    struct cfg cfgs[] = {
        {"smooth conductor", conductor(0), {30, 75, 120}, 3},
        {"mirror", mirror, {20, 80}, 2},
        {"smooth dielectric eta 1.5", dielectric(CV_MAT_DIELECTRIC, 1.5f), {30, 70, 150}, 3},
        {"smooth dielectric eta 1.5, total internal reflection", dielectric(CV_MAT_DIELECTRIC, 1.5f),
         {135}, 1},
        {"smooth dielectric eta 0.7", dielectric(CV_MAT_DIELECTRIC, 0.7f), {30, 160}, 2},
        {"thin dielectric eta 1.5", dielectric(CV_MAT_THIN_DIELECTRIC, 1.5f), {30, 80, 140}, 3},
    };
    size_t n_cfg = CV_ARRAY_SIZE(cfgs);
    CvMaterial *mats = cv_xcalloc(n_cfg, sizeof(*mats));
    int n_chi = 0;
    for (size_t i = 0; i < n_cfg; i++) {
        mats[i] = cfgs[i].m;
        if (mats[i].type == CV_MAT_COATED_DIFFUSE || mats[i].type == CV_MAT_COATED_CONDUCTOR)
            n_chi += cfgs[i].n_wo;
    }
    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, mats, n_cfg, &err), "probe shader and buffers: %s", err.msg))
        return tap_done();
    double alpha = stats_sidak(0.01, n_chi);
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = malloc(n_grid * 4 * sizeof(float));
    float *samples = malloc((size_t)N_SAMPLES * 12 * sizeof(float));
    double *observed = malloc(CHI_CELLS * sizeof(double));
    double *cell = malloc(CHI_CELLS * sizeof(double));
    unsigned seed = 101;
    for (size_t c = 0; c < n_cfg; c++) {
        for (int j = 0; j < cfgs[c].n_wo; j++) {
            const char *nm = cfgs[c].name;
            double th = cfgs[c].wo_theta[j];
            float wo[3];
            probe_dir(th, 20, wo);
            bool mixed = mats[c].type == CV_MAT_COATED_DIFFUSE || mats[c].type == CV_MAT_COATED_CONDUCTOR;
            if (!probe_run(&p, 0, (unsigned)c, wo, seed++, NULL, N_SAMPLES, samples, &err) ||
                (mixed && !probe_run(&p, 1, (unsigned)c, wo, 0, grid, n_grid, grid_out, &err))) {
                tap_ok(false, "%s wo %.0f: GPU run: %s", nm, th, err.msg);
                continue;
            }
            double e[N_LOBES][3];
            float dir[N_LOBES][3];
            expected(&mats[c], wo, e, dir);
            double sum[N_LOBES][3] = {{0}}, sum2[N_LOBES][3] = {{0}};
            size_t n_delta = 0, stray = 0, bad = 0, picked[N_LOBES] = {0};
            memset(observed, 0, CHI_CELLS * sizeof(double));
            for (size_t i = 0; i < N_SAMPLES; i++) {
                const float *s = samples + 12 * i;
                if (s[3] < 0)
                    continue; /* no sample: weight 0 */
                if (!((unsigned)s[7] & 4u)) {
                    observed[stats_cell(s)] += 1;
                    continue;
                }
                n_delta++;
                int lobe = same_dir(s, dir[LOBE_R]) ? LOBE_R : same_dir(s, dir[LOBE_T]) ? LOBE_T : -1;
                if (lobe < 0) {
                    stray++;
                    continue;
                }
                picked[lobe]++;
                for (int ch = 0; ch < 3; ch++) {
                    double w = s[4 + ch] * fabs(s[2]) / s[3];
                    if (!isfinite(w) || w < 0) {
                        bad++;
                        break;
                    }
                    sum[lobe][ch] += w;
                    sum2[lobe][ch] += w * w;
                }
            }
            tap_ok(stray == 0 && bad == 0,
                   "%s wo %.0f: delta samples leave in the lobes' directions with finite weights "
                   "(%zu stray, %zu bad of %zu)", nm, th, stray, bad, n_delta);
            static const char *const lname[N_LOBES] = {"reflection", "transmission"};
            for (int l = 0; l < N_LOBES; l++) {
                if (l == LOBE_T && !picked[l] && e[l][0] == 0 && e[l][1] == 0 && e[l][2] == 0)
                    continue;
                double worst = 0, mean[3], se[3];
                for (int ch = 0; ch < 3; ch++) {
                    mean[ch] = sum[l][ch] / N_SAMPLES;
                    double var = sum2[l][ch] / N_SAMPLES - mean[ch] * mean[ch];
                    /* a lobe picked always has an exact weight: allow float round-off */
                    se[ch] = fmax(sqrt(fmax(var, 0) / N_SAMPLES), 1e-5 * e[l][ch]) + 1e-7;
                    worst = fmax(worst, fabs(mean[ch] - e[l][ch]) / se[ch]);
                }
                tap_ok(worst < Z_BOUND,
                       "%s wo %.0f: %s weight (%.5f %.5f %.5f) vs Fresnel (%.5f %.5f %.5f), "
                       "picked %.4f, %.1f standard errors", nm, th, lname[l], mean[0], mean[1], mean[2],
                       e[l][0], e[l][1], e[l][2], (double)picked[l] / N_SAMPLES, worst);
            }
            if (!mixed)
                continue;
            stats_integrate(grid_out + 3, 4, cell);
            struct stats_chi2 r = stats_chi2_test(observed, cell, N_SAMPLES);
            /* the pdf of the non-delta part integrates to the share of
             * samples it yields (sampling may fail: the coated conductor
             * drops light that the coat reflects back down) */
            double cont = 0;
            for (int i = 0; i < CHI_CELLS; i++)
                cont += observed[i];
            cont /= N_SAMPLES;
            tap_ok(fabs(cont - r.total_expected) < 0.005,
                   "%s wo %.0f: non-delta samples %.4f, the pdf's integral %.4f (delta %.4f, failed %.4f)",
                   nm, th, cont, r.total_expected, (double)n_delta / N_SAMPLES,
                   1 - cont - (double)n_delta / N_SAMPLES);
            tap_ok(!r.zero_cell_hit && r.p_value >= alpha, "%s wo %.0f: non-delta part chi2 %.1f dof %d p %.3g",
                   nm, th, r.chi2, r.dof, r.p_value);
        }
    }
    free(grid);
    free(grid_out);
    free(samples);
    free(observed);
    free(cell);
    probe_close(&p);
    free(mats);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
