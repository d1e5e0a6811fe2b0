/* fresnel.h: the host's dielectric Fresnel reflectance, for the tables
 * computed at scene load (coat_closed.c, bssrdf_table.c); the shaders'
 * is glsl/trace/bsdf/fresnel.glsl. */
#ifndef CV_SCENE_FRESNEL_H
#define CV_SCENE_FRESNEL_H

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

#endif
