/* bsdf_layered_test.c: coateddiffuse and coatedconductor against pbrt-v4's
 * layered model, through the shipped GLSL (bsdf_probe.comp).
 * The reference is an analog CPU simulation of the physics written here:
 * light arrives along -wo, a smooth dielectric coat reflects it with
 * Fresnel's probability (the delta lobe, outside f) or refracts it into a
 * slab of unit extinction, given thickness, albedo and Henyey-Greenstein g;
 * distances are drawn from the exponential law; the base reflects it
 * (Lambertian, or a GGX conductor by cosine sampling weighted by pi f);
 * from inside the coat reflects or lets it out. A walk holds at most
 * maxdepth events after entering (base, coat underside, exit, medium
 * scattering), as pbrt-v4's estimators do. Energy is counted, so the eta^2
 * radiance factors of entering and leaving cancel. A rough coat is crossed
 * by drawing a GGX visible normal (Heitz 2018) and reflecting or refracting
 * about it with Fresnel's probability, weight G / G1(wo), lost where the
 * microfacet sends the light to the wrong side (no multiple scattering
 * between microfacets, as pbrt-v4's dielectric).
 * 1. f.cos against the reference: for several theta_o, the integral of f.cos
 *    over three bands of theta_i, from evaluations at cosine-distributed wi
 *    (many evaluations average the stochastic f), within 4 standard errors
 *    + 0.5 % relative per band, 4 standard errors + 0.2 % for the whole lobe
 *    (a 2 % error fails it up to 60 degrees; the tolerance is printed).
 * 2. Sampling: the same bands from sampled directions weighted by f.cos/pdf
 *    (non-delta samples). pbrt-v4's pdf is a stochastic estimate mixed with
 *    a uniform term, so the density of the samples is not the returned pdf
 *    and a chi-square of pdf against the histogram does not apply; the
 *    weighted histogram must still integrate f.cos in every band.
 * 3. White furnace: white coated diffuse, albedo 0, no thickness, deep walks:
 *    the evaluated albedo (pi E[f] at cosine-distributed wi, plus the delta
 *    reflection's Fresnel) and the sampled albedo (delta lobe included) are
 *    <= 1 and >= 0.99 within 4 standard errors. */
#include "config.h"

#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/rng.h"
#include "tests/trace/bsdf_probe.h"
#include "tests/trace/fresnel_ref.h"

#define N_EVAL 131072
#define N_REF 800000
#define BANDS 3

struct lcase {
    const char *name;
    CvMaterial m;
    bool conductor;
    double alpha, r, alpha2, thick, albedo, g;
    int maxdepth;
};

/* ---- CPU reference ---- */
static uint64_t rs = 0x9E3779B97F4A7C15ull;
static double rnd(void)
{
    return cv_test_xorshift64(&rs);
}


static double ggx_lambda(double a, const double w[3])
{
    double c2 = w[2] * w[2], t2 = (1 - c2) / c2;
    return (-1 + sqrt(1 + a * a * t2)) / 2;
}

/* pi * f(wo, wi) of a GGX conductor (cosine sampling weight). */
static double cond_weight(double a, double complex eta, const double wo[3], const double wi[3])
{
    double m[3] = {wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]};
    double l = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (int i = 0; i < 3; i++)
        m[i] /= l;
    double c2 = m[2] * m[2], t2 = (1 - c2) / c2, e = 1 + t2 / (a * a);
    double D = 1 / (M_PI * a * a * c2 * c2 * e * e);
    double G = 1 / (1 + ggx_lambda(a, wo) + ggx_lambda(a, wi));
    double F = ref_fresnel_conductor(fabs(wo[0] * m[0] + wo[1] * m[1] + wo[2] * m[2]), eta);
    return M_PI * D * G * F / (4 * wo[2] * wi[2]);
}

static void cosine_dir(double w[3])
{
    double r = sqrt(rnd()), ph = 2 * M_PI * rnd();
    w[0] = r * cos(ph);
    w[1] = r * sin(ph);
    w[2] = sqrt(fmax(0, 1 - r * r));
}

/* Henyey-Greenstein about the travel direction d. */
static void hg_dir(double g, double d[3])
{
    double u = rnd(), c;
    if (fabs(g) < 1e-3)
        c = 1 - 2 * u;
    else {
        double t = (1 - g * g) / (1 - g + 2 * g * u);
        c = (1 + g * g - t * t) / (2 * g);
    }
    double s = sqrt(fmax(0, 1 - c * c)), ph = 2 * M_PI * rnd();
    double a[3] = {1, 0, 0};
    if (fabs(d[0]) > 0.9)
        a[0] = 0, a[1] = 1;
    double x[3] = {a[1] * d[2] - a[2] * d[1], a[2] * d[0] - a[0] * d[2], a[0] * d[1] - a[1] * d[0]};
    double l = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int i = 0; i < 3; i++)
        x[i] /= l;
    double y[3] = {d[1] * x[2] - d[2] * x[1], d[2] * x[0] - d[0] * x[2], d[0] * x[1] - d[1] * x[0]};
    double n[3];
    for (int i = 0; i < 3; i++)
        n[i] = s * cos(ph) * x[i] + s * sin(ph) * y[i] + c * d[i];
    memcpy(d, n, sizeof(n));
}

static double cv_sqr_d(double x) { return x * x; }

static int band_of(double cos_i) { int b = (int)(cos_i * BANDS); return b >= BANDS ? BANDS - 1 : b; }

static double dot3(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/* A GGX visible normal for w (Heitz 2018), mirrored to +z. */
static void vndf(double a, const double w[3], double wm[3])
{
    double h[3] = {a * w[0], a * w[1], w[2]};
    double l = sqrt(dot3(h, h));
    for (int i = 0; i < 3; i++)
        h[i] /= h[2] < 0 ? -l : l;
    double t1[3] = {1, 0, 0};
    if (h[2] < 0.99999) {
        double c[3] = {-h[1], h[0], 0};
        double lc = sqrt(dot3(c, c));
        for (int i = 0; i < 3; i++)
            t1[i] = c[i] / lc;
    }
    double t2[3] = {h[1] * t1[2] - h[2] * t1[1], h[2] * t1[0] - h[0] * t1[2], h[0] * t1[1] - h[1] * t1[0]};
    double r = sqrt(rnd()), ph = 2 * M_PI * rnd();
    double px = r * cos(ph), py = r * sin(ph);
    double s = (1 + h[2]) / 2, hh = sqrt(fmax(0, 1 - px * px));
    py = (1 - s) * hh + s * py;
    double pz = sqrt(fmax(0, 1 - px * px - py * py));
    double n[3];
    for (int i = 0; i < 3; i++)
        n[i] = px * t1[i] + py * t2[i] + pz * h[i];
    wm[0] = a * n[0];
    wm[1] = a * n[1];
    wm[2] = fmax(1e-6, n[2]);
    l = sqrt(dot3(wm, wm));
    for (int i = 0; i < 3; i++)
        wm[i] /= l;
}

/* A photon travelling along d meets the coat (normal +z, IOR eta below it,
 * alpha 0: smooth). Returns 0: lost (a microfacet sends it back into the
 * surface), 1: reflected, 2: transmitted; d and *w updated. */
static int coat_cross(double alpha, double eta, double d[3], double *w)
{
    double wo[3] = {-d[0], -d[1], -d[2]}, m[3] = {0, 0, 1};
    if (alpha > 0)
        vndf(alpha, wo, m);
    double c = dot3(wo, m);
    double F = ref_fresnel_dielectric(c, eta);
    double wi[3];
    bool refl = rnd() < F;
    if (refl) {
        for (int i = 0; i < 3; i++)
            wi[i] = -wo[i] + 2 * c * m[i];
    } else {
        double e = c > 0 ? eta : 1 / eta, ci = fabs(c), sgn = c > 0 ? 1 : -1;
        double s2t = (1 - ci * ci) / (e * e);
        if (s2t >= 1)
            return 0;
        double ct = sqrt(1 - s2t);
        for (int i = 0; i < 3; i++)
            wi[i] = -wo[i] / e + (ci / e - ct) * sgn * m[i];
    }
    if ((wi[2] * wo[2] > 0) != refl || wi[2] == 0)
        return 0;
    if (alpha > 0)
        *w *= (1 + ggx_lambda(alpha, wo)) / (1 + ggx_lambda(alpha, wo) + ggx_lambda(alpha, wi));
    memcpy(d, wi, sizeof(wi));
    return refl ? 1 : 2;
}

/* Reflected energy per band of exit cos theta (delta coat reflection left out). */
static void reference(const struct lcase *c, double cos_o, double out[BANDS], double sd[BANDS])
{
    const double eta = 1.5;
    double complex ceta = 0;
    if (c->conductor) {
        double r = 0.9999; /* white "reflectance" conductor, as bsdf.glsl clamps it */
        ceta = (1 + I * (2 * sqrt(r) / sqrt(1 - r))) / eta;
    }
    double sin_o = sqrt(1 - cos_o * cos_o);
    double acc[BANDS] = {0}, acc2[BANDS] = {0};
    for (long n = 0; n < N_REF; n++) {
        double d[3] = {-sin_o, 0, -cos_o}, w = 1;
        int k = coat_cross(c->alpha, eta, d, &w);
        if (k == 0 || (k == 1 && c->alpha == 0))
            continue; /* lost, or the smooth coat's delta lobe */
        if (k == 1) {
            acc[band_of(d[2])] += w;
            acc2[band_of(d[2])] += w * w;
            continue;
        }
        double z = c->thick;
        for (int ev = 0; ev < c->maxdepth; ev++) {
            double dz = -log(1 - rnd()) * fabs(d[2]);
            double zp = d[2] > 0 ? z + dz : z - dz;
            if (zp > 0 && zp < c->thick) {
                w *= c->albedo;
                if (w == 0)
                    break;
                hg_dir(c->g, d);
                z = zp;
                continue;
            }
            if (d[2] < 0) { /* base */
                z = 0;
                double wo[3] = {-d[0], -d[1], -d[2]}, wi[3];
                cosine_dir(wi);
                w *= c->conductor ? cond_weight(c->alpha2, ceta, wo, wi) : c->r;
                memcpy(d, wi, sizeof(wi));
            } else { /* coat underside */
                z = c->thick;
                k = coat_cross(c->alpha, eta, d, &w);
                if (k == 0)
                    break;
                if (k == 2) {
                    acc[band_of(d[2])] += w;
                    acc2[band_of(d[2])] += w * w;
                    break;
                }
            }
        }
    }
    for (int b = 0; b < BANDS; b++) {
        out[b] = acc[b] / N_REF;
        sd[b] = sqrt(fmax(acc2[b] / N_REF - out[b] * out[b], 0) / N_REF);
    }
}

static CvMaterial coated(const struct lcase *c)
{
    CvMaterial m = probe_material(c->conductor ? CV_MAT_COATED_CONDUCTOR : CV_MAT_COATED_DIFFUSE);
    m.reflectance = (cv_vec4){(float)c->r, (float)c->r, (float)c->r, 0};
    m.roughness = (cv_vec4){(float)c->alpha, (float)c->alpha, (float)c->thick, (float)c->g};
    m.roughness2 = (cv_vec4){(float)c->alpha2, (float)c->alpha2, (float)c->maxdepth, 1};
    m.specular = (cv_vec4){(float)c->albedo, (float)c->albedo, (float)c->albedo, 0};
    if (c->conductor)
        m.flags |= CV_MATF_CONDUCTOR_REFLECTANCE;
    m.eta.w = 1.5f;
    return m;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct lcase cases[] = {
        {"coated conductor white, smooth coat, base alpha 0.3", {0}, true, 0, 1, 0.3, 0.01, 0, 0, 10},
        {"coated diffuse white, thickness 0.1", {0}, false, 0, 1, 0, 0.1, 0, 0, 10},
        {"coated diffuse defaults (R 0.5, thickness 0.01)", {0}, false, 0, 0.5, 0, 0.01, 0, 0, 10},
        {"coated diffuse R 0.8, medium albedo 0.8 g 0.5, thickness 0.3", {0}, false, 0, 0.8, 0, 0.3, 0.8, 0.5, 100},
        {"coated diffuse R 0.8, coat alpha 0.3", {0}, false, 0.3, 0.8, 0, 0.01, 0, 0, 10},
        {"coated conductor white, coat alpha 0.2, base alpha 0.3, albedo 0.5 g -0.3, thickness 0.1", {0}, true,
         0.2, 1, 0.3, 0.1, 0.5, -0.3, 100},
        {"furnace: coated diffuse white, no thickness, maxdepth 100", {0}, false, 0, 1, 0, 0, 0, 0, 100},
    };
    size_t nc = CV_ARRAY_SIZE(cases);
    CvMaterial mats[CV_ARRAY_SIZE(cases)];
    for (size_t i = 0; i < nc; i++)
        mats[i] = cases[i].m = coated(&cases[i]);
    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, mats, nc, &err), "probe shader and buffers: %s", err.msg))
        return tap_done();
    const double thetas[] = {5, 30, 60, 85};
    float *dirs = malloc((size_t)N_EVAL * 4 * sizeof(float));
    float *out = malloc((size_t)N_EVAL * 12 * sizeof(float));
    float *out_eval = malloc((size_t)N_EVAL * 4 * sizeof(float));
    unsigned seed = 7;
    for (size_t c = 0; c + 1 < nc; c++) {
        double worst_eval = 0, worst_samp = 0, worst_tol = 0;
        bool pass_eval = true, pass_samp = true, pass_total = true, ran = true;
        for (size_t k = 0; k < CV_ARRAY_SIZE(thetas); k++) {
            float wo[3];
            probe_dir(thetas[k], 0, wo);
            double ref[BANDS], ref_sd[BANDS];
            reference(&cases[c], wo[2], ref, ref_sd);
            /* evaluations at cosine-distributed wi: pi f per band */
            for (size_t i = 0; i < N_EVAL; i++) {
                double w[3];
                cosine_dir(w);
                for (int j = 0; j < 3; j++)
                    dirs[4 * i + j] = (float)w[j];
                dirs[4 * i + 3] = 0;
            }
            if (!probe_run(&p, 1, (unsigned)c, wo, seed++, dirs, N_EVAL, out, &err) ) {
                ran = false;
                break;
            }
            double se[BANDS] = {0}, se2[BANDS] = {0}, pint = 0;
            for (size_t i = 0; i < N_EVAL; i++)
                pint += M_PI * out[4 * i + 3] / fmax(dirs[4 * i + 2], 1e-6);
            pint = pint / N_EVAL + 0.05;
            tap_diag("%s theta %2.0f: pdf estimate integrates to %.3f (no refraction Jacobian, as pbrt-v4)",
                     cases[c].name, thetas[k], pint);
            for (size_t i = 0; i < N_EVAL; i++) {
                double v = M_PI * out[4 * i + 1];
                int b = band_of(dirs[4 * i + 2]);
                se[b] += v;
                se2[b] += v * v;
            }
            /* sampled directions weighted by f cos / pdf */
            memcpy(out_eval, out, (size_t)N_EVAL * 4 * sizeof(float));
            if (!probe_run(&p, 0, (unsigned)c, wo, seed++, NULL, N_EVAL, out, &err)) {
                ran = false;
                break;
            }
            double ss[BANDS] = {0}, ss2[BANDS] = {0};
            for (size_t i = 0; i < N_EVAL; i++) {
                const float *s = out + 12 * i;
                if (s[3] <= 0 || ((unsigned)s[7] & 4u) || s[2] <= 0)
                    continue;
                double v = s[5] * s[2] / s[3];
                int b = band_of(s[2]);
                ss[b] += v;
                ss2[b] += v * v;
            }
            /* the whole lobe: sum of the bands (their estimates are independent per band
             * only for the reference; the GPU sums are recomputed from the samples) */
            double te = 0, te2 = 0, tr = 0, tr2 = 0;
            for (int b = 0; b < BANDS; b++) {
                te += se[b];
                tr += ref[b];
                tr2 += ref_sd[b] * ref_sd[b];
            }
            for (size_t i = 0; i < N_EVAL; i++)
                te2 += cv_sqr_d(M_PI * out_eval[4 * i + 1]);
            double me_t = te / N_EVAL, sd_t = sqrt(fmax(te2 / N_EVAL - me_t * me_t, 0) / N_EVAL);
            double tol_t = 4 * hypot(sd_t, sqrt(tr2)) + 0.002 * tr;
            if (fabs(me_t - tr) > tol_t)
                pass_total = false;
            worst_tol = fmax(worst_tol, tol_t / tr);
            tap_diag("%s theta %2.0f: albedo (delta lobe out) ref %.4f shader %.4f ratio %.4f (tolerance %.2f %%; se %.2f %% gpu, %.2f %% cpu)",
                     cases[c].name, thetas[k], tr, me_t, me_t / tr, 100 * tol_t / tr, 100 * sd_t / tr, 100 * sqrt(tr2) / tr);
            char line[256];
            int len = snprintf(line, sizeof(line), "theta %2.0f:", thetas[k]);
            for (int b = 0; b < BANDS; b++) {
                double me = se[b] / N_EVAL, ve = se2[b] / N_EVAL - me * me;
                double ms = ss[b] / N_EVAL, vs = ss2[b] / N_EVAL - ms * ms;
                double sd_e = sqrt(fmax(ve, 0) / N_EVAL), sd_s = sqrt(fmax(vs, 0) / N_EVAL);
                double sd_r = ref_sd[b];
                double tol_e = 4 * hypot(sd_e, sd_r) + 0.005 * ref[b] + 1e-4;
                double tol_s = 4 * hypot(sd_s, sd_r) + 0.005 * ref[b] + 1e-4;
                if (fabs(me - ref[b]) > tol_e)
                    pass_eval = false;
                if (fabs(ms - ref[b]) > tol_s)
                    pass_samp = false;
                if (ref[b] > 0.01) {
                    worst_eval = fmax(worst_eval, fabs(me / ref[b] - 1));
                    worst_samp = fmax(worst_samp, fabs(ms / ref[b] - 1));
                }
                len += snprintf(line + len, sizeof(line) - (size_t)len, "  band %d ref %.4f eval/ref %.3f samp/ref %.3f",
                                b, ref[b], ref[b] > 0 ? me / ref[b] : 0, ref[b] > 0 ? ms / ref[b] : 0);
            }
            tap_diag("%s %s", cases[c].name, line);
        }
        if (!tap_ok(ran, "%s: GPU runs: %s", cases[c].name, err.msg))
            continue;
        tap_ok(pass_total, "%s: albedo matches the CPU random walk at every theta (tolerance <= %.2f %%)",
               cases[c].name, 100 * worst_tol);
        tap_ok(pass_eval, "%s: f cos matches the CPU random walk (worst %.2f %%)", cases[c].name, 100 * worst_eval);
        tap_ok(pass_samp, "%s: sampled f cos / pdf matches it too (worst %.2f %%)", cases[c].name, 100 * worst_samp);
    }
    /* furnace: pi E[f] at cosine-distributed wi plus the coat's delta
     * reflection, and the sampled albedo (delta lobe included) */
    size_t fc = nc - 1;
    double lo = 2, hi = 0;
    bool ran = true;
    for (size_t k = 0; k < CV_ARRAY_SIZE(thetas); k++) {
        float wo[3];
        probe_dir(thetas[k], 30, wo);
        double e = 0, e2 = 0;
        const int reps = 4;
        for (int r = 0; r < reps && ran; r++) {
            for (size_t i = 0; i < N_EVAL; i++) {
                double w[3];
                cosine_dir(w);
                for (int j = 0; j < 3; j++)
                    dirs[4 * i + j] = (float)w[j];
                dirs[4 * i + 3] = 0;
            }
            ran = probe_run(&p, 1, (unsigned)fc, wo, seed++, dirs, N_EVAL, out, &err);
            for (size_t i = 0; ran && i < N_EVAL; i++) {
                double v = M_PI * out[4 * i + 1];
                e += v;
                e2 += v * v;
            }
        }
        if (!ran)
            break;
        double ne = (double)reps * N_EVAL;
        double me = e / ne + ref_fresnel_dielectric(wo[2], 1.5);
        double sde = sqrt(fmax(e2 / ne - cv_sqr_d(e / ne), 0) / ne);
        tap_diag("furnace theta %2.0f: evaluated albedo %.4f +- %.4f", thetas[k], me, sde);
        lo = fmin(lo, me + 4 * sde);
        hi = fmax(hi, me - 4 * sde);
        if (!probe_run(&p, 0, (unsigned)fc, wo, seed++, NULL, N_EVAL, out, &err)) {
            ran = false;
            break;
        }
        double s = 0, s2 = 0;
        for (size_t i = 0; i < N_EVAL; i++) {
            const float *q = out + 12 * i;
            if (q[3] <= 0)
                continue;
            double v = q[5] * fabs(q[2]) / q[3];
            s += v;
            s2 += v * v;
        }
        double m = s / N_EVAL, sd = sqrt(fmax(s2 / N_EVAL - m * m, 0) / N_EVAL);
        tap_diag("furnace theta %2.0f: albedo %.4f +- %.4f", thetas[k], m, sd);
        lo = fmin(lo, m + 4 * sd);
        hi = fmax(hi, m - 4 * sd - 1e-4); /* float rounding of weights of exactly 1 */
    }
    if (tap_ok(ran, "furnace GPU runs: %s", err.msg)) {
        tap_ok(hi <= 1.0, "furnace: white coated diffuse reflects <= 1 (%.4f)", hi);
        tap_ok(lo >= 0.99, "furnace: and close to 1 (%.4f)", lo);
    }
    free(dirs);
    free(out_eval);
    free(out);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
