/* fresnel.h: the host's dielectric and conductor Fresnel reflectance, for
 * the tables computed at scene load (coat_closed.c, bssrdf_table.c,
 * conductor_fresnel.c); the shaders' is glsl/trace/bsdf/fresnel.glsl. */
#ifndef CV_SCENE_FRESNEL_H
#define CV_SCENE_FRESNEL_H

#include <complex.h>
#include <math.h>

/* Unpolarised reflectance of a dielectric boundary of relative index eta
 * (cos_i < 0: seen from the inside), as pbrt-v4's FrDielectric. */
static inline double cv_fresnel_dielectric(double cos_i, double eta)
{
    cos_i = cos_i < -1 ? -1 : cos_i > 1 ? 1 : cos_i;
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1)
        return 1;
    double cos_t = sqrt(fmax(0, 1 - sin2_t));
    double parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    double perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return (parl * parl + perp * perp) / 2;
}

/* Unpolarised reflectance of a conductor of complex relative index
 * eta + i k at cos_i (clamped to [0, 1]), as pbrt-v4's FrComplex. */
static inline double cv_fresnel_complex(double cos_i, double eta, double k)
{
    cos_i = cos_i < 0 ? 0 : cos_i > 1 ? 1 : cos_i;
    if (eta == 0 && k == 0)
        return 1; /* the limit (a spectrum beyond its pairs is 0) */
    double complex n = eta + k * I;
    double complex sin2_t = (1 - cos_i * cos_i) / (n * n);
    double complex cos_t = csqrt(1 - sin2_t);
    double complex parl = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    double complex perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    double rp = cabs(parl), rs = cabs(perp);
    return (rp * rp + rs * rs) / 2;
}

#endif
