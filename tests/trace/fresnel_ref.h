/* fresnel_ref.h: CPU references of the BSDF tests, in double: Fresnel
 * reflectance of dielectric and conductor boundaries. */
#ifndef CV_TESTS_TRACE_FRESNEL_REF_H
#define CV_TESTS_TRACE_FRESNEL_REF_H

#include <complex.h>
#include <math.h>

/* Unpolarised reflectance of a dielectric boundary, eta = inside over
 * outside, outside on +z (cos_i < 0: seen from the inside). */
static inline double ref_fresnel_dielectric(double cos_i, double eta)
{
    if (cos_i < 0) {
        eta = 1 / eta;
        cos_i = -cos_i;
    }
    double sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1)
        return 1;
    double cos_t = sqrt(1 - sin2_t);
    double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return (rs * rs + rp * rp) / 2;
}

/* Unpolarised reflectance of a conductor of complex index eta (n + i k),
 * cos_i >= 0. */
static inline double ref_fresnel_conductor(double cos_i, double complex eta)
{
    double complex sin2_t = (1 - cos_i * cos_i) / (eta * eta);
    double complex cos_t = csqrt(1 - sin2_t);
    double complex rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    double complex rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return (cabs(rs) * cabs(rs) + cabs(rp) * cabs(rp)) / 2;
}

#endif
