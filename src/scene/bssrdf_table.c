/* bssrdf_table.c: see bssrdf_table.h. The profile is pbrt-v4's
 * (Habel et al. 2013's photon beam diffusion as pbrt-v4 writes it): the
 * multiple-scattering dipole integrated over real source depths along the
 * refracted beam, plus single scattering integrated along the beam below
 * the critical angle; both by 100-point stratified sums over exponential
 * depths, as pbrt-v4 does, so the tables agree. */
#include <math.h>

#include "scene/bssrdf_table.h"
#include "scene/fresnel.h"

#define PI 3.14159265358979323846

/* The Fresnel moments' polynomial fits (d'Eon and Irving 2011), as
 * pbrt-v4 takes them. */
static double fresnel_moment1(double e)
{
    double e2 = e * e, e3 = e2 * e, e4 = e3 * e, e5 = e4 * e;
    if (e < 1)
        return 0.45966 - 1.73965 * e + 3.37668 * e2 - 3.904945 * e3 + 2.49277 * e4 - 0.68441 * e5;
    return -4.61686 + 11.1136 * e - 10.4646 * e2 + 5.11455 * e3 - 1.27198 * e4 + 0.12746 * e5;
}

static double fresnel_moment2(double e)
{
    double e2 = e * e, e3 = e2 * e, e4 = e3 * e, e5 = e4 * e;
    if (e < 1)
        return 0.27614 - 0.87350 * e + 1.12077 * e2 - 0.65095 * e3 + 0.07883 * e4 + 0.04860 * e5;
    double r = 1 / e, r2 = r * r, r3 = r2 * r;
    return -547.033 + 45.3087 * r3 - 218.725 * r2 + 458.843 * r + 404.557 * e - 189.519 * e2 +
           54.9327 * e3 - 9.00603 * e4 + 0.63942 * e5;
}

static double henyey_greenstein(double cos_theta, double g)
{
    g = g < -0.99 ? -0.99 : g > 0.99 ? 0.99 : g;
    double d = 1 + g * g + 2 * g * cos_theta;
    return (1 - g * g) / (4 * PI * d * sqrt(fmax(d, 0)));
}

#define BEAM_SAMPLES 100

/* The stratified depths of an exponential density of rate 1 the beam
 * integrals use (depths at rate a are these over a): computed once. */
static double unit_depth[BEAM_SAMPLES];

static void init_unit_depths(void)
{
    for (int i = 0; i < BEAM_SAMPLES; i++)
        unit_depth[i] = -log(1 - (i + 0.5) / BEAM_SAMPLES);
}

/* Multiple scattering: the dipole's exitance at radius r (unit-free: the
 * coefficients are per unit length). */
static double beam_ms(double sigma_s, double sigma_a, double g, double eta, double r)
{
    double sps = sigma_s * (1 - g), spt = sigma_a + sps, rhop = sps / spt;
    double D = (2 * sigma_a + sps) / (3 * spt * spt);     /* Grosjean's diffusion coefficient */
    double str = sqrt(fmax(0, sigma_a / D));                /* effective transport coefficient */
    double fm1 = fresnel_moment1(eta), fm2 = fresnel_moment2(eta);
    double ze = -2 * D * (1 + 3 * fm2) / (1 - 2 * fm1);    /* extrapolation distance */
    double c_phi = 0.25 * (1 - 2 * fm1), c_e = 0.5 * (1 - 3 * fm2);
    double ed = 0;
    for (int i = 0; i < BEAM_SAMPLES; i++) {
        double zr = unit_depth[i] / spt, zv = -zr + 2 * ze;
        double dr = sqrt(r * r + zr * zr), dv = sqrt(r * r + zv * zv);
        double er = exp(-str * dr), ev = exp(-str * dv);
        double phi = (er / dr - ev / dv) / (4 * PI * D);
        double edn = (zr * (1 + str * dr) * er / (dr * dr * dr) -
                      zv * (1 + str * dv) * ev / (dv * dv * dv)) / (4 * PI);
        double kappa = 1 - exp(-2 * spt * (dr + zr));
        ed += kappa * rhop * rhop * (phi * c_phi + edn * c_e);
    }
    return ed / BEAM_SAMPLES;
}

/* Single scattering along the refracted beam, below the critical angle. */
static double beam_ss(double sigma_s, double sigma_a, double g, double eta, double r)
{
    double st = sigma_a + sigma_s, rho = sigma_s / st;
    double t_crit = r * sqrt(fmax(0, eta * eta - 1));
    double ess = 0;
    for (int i = 0; i < BEAM_SAMPLES; i++) {
        double ti = t_crit + unit_depth[i] / st;
        double d = sqrt(r * r + ti * ti), cos_o = ti / d;
        ess += rho * exp(-st * (d + t_crit)) / (d * d) * henyey_greenstein(cos_o, g) *
               (1 - cv_fresnel_dielectric(-cos_o, eta)) * fabs(cos_o);
    }
    return ess / BEAM_SAMPLES;
}

/* The finite-difference slopes of the spline on segment i of (x, f). */
static void segment_slopes(const float *x, const float *f, int n, int i, double *d0, double *d1)
{
    double w = x[i + 1] - x[i];
    *d0 = i > 0 ? w * (f[i + 1] - f[i - 1]) / (x[i + 1] - x[i - 1]) : f[i + 1] - f[i];
    *d1 = i + 2 < n ? w * (f[i + 2] - f[i]) / (x[i + 2] - x[i]) : f[i + 1] - f[i];
}

void cv_bssrdf_table_compute(double g, double eta, float *t)
{
    if (unit_depth[0] == 0)
        init_unit_depths();
    float *rho = t + CV_BSSRDF_RHO, *rad = t + CV_BSSRDF_RADIUS;
    rad[0] = 0;
    rad[1] = 2.5e-3f;
    for (int j = 2; j < CV_BSSRDF_N_RADIUS; j++)
        rad[j] = rad[j - 1] * 1.2f;
    for (int i = 0; i < CV_BSSRDF_N_RHO; i++)
        rho[i] = (float)((1 - exp(-8.0 * i / (CV_BSSRDF_N_RHO - 1))) / (1 - exp(-8.0)));
    for (int i = 0; i < CV_BSSRDF_N_RHO; i++) {
        float *prof = t + CV_BSSRDF_PROFILE + i * CV_BSSRDF_N_RADIUS;
        float *cdf = t + CV_BSSRDF_CDF + i * CV_BSSRDF_N_RADIUS;
        for (int j = 0; j < CV_BSSRDF_N_RADIUS; j++) {
            double r = rad[j];
            prof[j] = (float)(2 * PI * r * (beam_ss(rho[i], 1 - rho[i], g, eta, r) +
                                            beam_ms(rho[i], 1 - rho[i], g, eta, r)));
        }
        /* the spline's running integral (pbrt-v4's IntegrateCatmullRom) */
        double sum = 0;
        cdf[0] = 0;
        for (int j = 0; j + 1 < CV_BSSRDF_N_RADIUS; j++) {
            double d0, d1;
            segment_slopes(rad, prof, CV_BSSRDF_N_RADIUS, j, &d0, &d1);
            sum += (rad[j + 1] - rad[j]) * ((prof[j] + prof[j + 1]) / 2 + (d0 - d1) / 12);
            cdf[j + 1] = (float)sum;
        }
        t[CV_BSSRDF_RHO_EFF + i] = (float)sum;
    }
}

/* The segment i with nodes[i] <= x < nodes[i + 1], clamped to 0..n-2
 * (pbrt-v4's FindInterval). */
static int find_interval(const float *nodes, int n, float x)
{
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (nodes[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

bool cv_catmull_rom_weights(const float *nodes, int n, float x, int *offset, float w[4])
{
    if (!(x >= nodes[0] && x <= nodes[n - 1]))
        return false;
    int i = find_interval(nodes, n, x);
    *offset = i - 1;
    float x0 = nodes[i], x1 = nodes[i + 1];
    float s = (x - x0) / (x1 - x0), s2 = s * s, s3 = s2 * s;
    w[1] = 2 * s3 - 3 * s2 + 1;
    w[2] = -2 * s3 + 3 * s2;
    if (i > 0) {
        float w0 = (s3 - 2 * s2 + s) * (x1 - x0) / (x1 - nodes[i - 1]);
        w[0] = -w0;
        w[2] += w0;
    } else {
        float w0 = s3 - 2 * s2 + s;
        w[0] = 0;
        w[1] -= w0;
        w[2] += w0;
    }
    if (i + 2 < n) {
        float w3 = (s3 - s2) * (x1 - x0) / (nodes[i + 2] - x0);
        w[1] -= w3;
        w[3] = w3;
    } else {
        float w3 = s3 - s2;
        w[1] -= w3;
        w[2] += w3;
        w[3] = 0;
    }
    return true;
}

float cv_bssrdf_rho_eff(const float *t, float rho)
{
    int off;
    float w[4];
    if (!cv_catmull_rom_weights(t + CV_BSSRDF_RHO, CV_BSSRDF_N_RHO, rho, &off, w))
        return 0;
    float v = 0;
    for (int k = 0; k < 4; k++)
        if (w[k] != 0)
            v += w[k] * t[CV_BSSRDF_RHO_EFF + off + k];
    return v;
}

float cv_bssrdf_invert_rho_eff(const float *t, float u)
{
    const float *x = t + CV_BSSRDF_RHO, *f = t + CV_BSSRDF_RHO_EFF;
    int n = CV_BSSRDF_N_RHO;
    if (!(u > f[0]))
        return x[0];
    if (!(u < f[n - 1]))
        return x[n - 1];
    int i = find_interval(f, n, u);
    double d0, d1;
    segment_slopes(x, f, n, i, &d0, &d1);
    double f0 = f[i], f1 = f[i + 1];
    /* Newton steps kept inside a shrinking bracket on the spline's t */
    double a = 0, b = 1, s = (u - f0) / (f1 - f0);
    for (int it = 0; it < 64; it++) {
        if (!(s > a && s < b))
            s = (a + b) / 2;
        double s2 = s * s, s3 = s2 * s;
        double F = (2 * s3 - 3 * s2 + 1) * f0 + (-2 * s3 + 3 * s2) * f1 + (s3 - 2 * s2 + s) * d0 +
                   (s3 - s2) * d1 - u;
        double dF = (6 * s2 - 6 * s) * f0 + (-6 * s2 + 6 * s) * f1 + (3 * s2 - 4 * s + 1) * d0 +
                    (3 * s2 - 2 * s) * d1;
        if (F < 0)
            a = s;
        else
            b = s;
        if (b - a < 1e-7 || fabs(F) < 1e-7)
            break;
        s -= F / dF;
    }
    return (float)(x[i] + s * (x[i + 1] - x[i]));
}

void cv_bssrdf_from_diffuse(const float *t, float r, float mfp, float *sigma_a, float *sigma_s)
{
    float rho = cv_bssrdf_invert_rho_eff(t, r);
    *sigma_s = rho / mfp;
    *sigma_a = (1 - rho) / mfp;
}
