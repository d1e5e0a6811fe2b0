/* coat_closed.c: the host half of coated diffuse in closed form (see
 * coat_closed.h and glsl/trace/bsdf/coated_closed.glsl). Cost class: a few
 * thousand Fresnel evaluations per coated material, once at scene load. */
#include <math.h>

#include "scene/coat_closed.h"
#include "scene/fresnel.h"

/* Cosine after refraction into relative IOR eta; 0 past the critical angle. */
static double refracted_cos(double mu, double eta)
{
    double s2 = (1 - mu * mu) / (eta * eta);
    return s2 >= 1 ? 0 : sqrt(1 - s2);
}

/* The slab's transmittance over height h along a direction of cosine mu
 * (pbrt-v4's Tr, unit extinction). */
static double transmittance(double h, double mu) { return mu > 0 ? exp(-h / mu) : 0; }

struct coat { double eta, thickness; };

/* 2 mu F_inside(mu) Tr(2 thickness, mu) at the inner cosine mu. */
static double r_in_integrand(double mu, const struct coat *c)
{
    return 2 * mu * cv_fresnel_dielectric(-mu, c->eta) * transmittance(2 * c->thickness, mu);
}

/* 2 mu (1 - F(mu)) Tr(thickness, mu') at the outer cosine mu. */
static double t_out_integrand(double mu, const struct coat *c)
{
    double mt = refracted_cos(mu, c->eta);
    return mt > 0 ? 2 * mu * (1 - cv_fresnel_dielectric(mu, c->eta)) * transmittance(c->thickness, mt) : 0;
}

#define SIMPSON_N 4096 /* even */

/* Integral of g over mu in [0, 1]. Past a critical cosine mu_c in (0, 1)
 * Fresnel's terms grow like sqrt(mu - mu_c): that side is integrated in s
 * with mu = mu_c + (1 - mu_c) s^2, where the integrand is smooth. */
static double integrate(double (*g)(double, const struct coat *), const struct coat *c, double mu_c)
{
    double lo = mu_c > 0 && mu_c < 1 ? mu_c : 0, sum = 0, h;
    if (lo > 0) {
        h = lo / SIMPSON_N;
        for (int i = 0; i <= SIMPSON_N; i++)
            sum += (i == 0 || i == SIMPSON_N ? 1 : (i % 2 ? 4 : 2)) * g(i * h, c) * h / 3;
    }
    h = 1.0 / SIMPSON_N;
    for (int i = 0; i <= SIMPSON_N; i++) {
        double s = i * h, w = (i == 0 || i == SIMPSON_N ? 1 : (i % 2 ? 4 : 2)) * h / 3;
        sum += w * g(lo + (1 - lo) * s * s, c) * 2 * (1 - lo) * s;
    }
    return sum;
}

void cv_coat_closed_integrals(double eta, double thickness, double *r_in, double *t_out)
{
    struct coat c = {eta, thickness > 0 ? thickness : 0};
    /* total internal reflection: inside below sqrt(1 - 1/eta^2) for
     * eta > 1, outside below sqrt(1 - eta^2) for eta < 1 */
    double crit_in = eta > 1 ? sqrt(1 - 1 / (eta * eta)) : 0;
    double crit_out = eta < 1 ? sqrt(1 - eta * eta) : 0;
    *r_in = integrate(r_in_integrand, &c, crit_in);
    *t_out = integrate(t_out_integrand, &c, crit_out) / (eta * eta);
}

bool cv_coat_closed_prepare(CvMaterial *m)
{
    if (m->type != CV_MAT_COATED_DIFFUSE || m->specular_tex >= 0 || m->eta_tex >= 0 ||
        m->specular.x > 0 || m->specular.y > 0 || m->specular.z > 0)
        return false;
    double eta = m->eta.x > 0 ? m->eta.x : 1.5; /* as cv_bsdf_at */
    double r_in, t_out;
    cv_coat_closed_integrals(eta, m->roughness.z, &r_in, &t_out);
    m->roughness2.x = (float)r_in;
    m->roughness2.y = (float)t_out;
    m->flags |= CV_MATF_COAT_CLOSED;
    return true;
}
