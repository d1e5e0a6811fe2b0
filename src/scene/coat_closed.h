/* coat_closed.h: which coated diffuse materials may take the closed form
 * of glsl/trace/bsdf/coated_closed.glsl, and the two integrals over
 * directions it reads (they depend on the coat's eta and the slab's
 * thickness alone, so they are computed once per material at scene load). */
#ifndef CV_SCENE_COAT_CLOSED_H
#define CV_SCENE_COAT_CLOSED_H

#include <stdbool.h>

#include "glsl/shared/scene.h"

/* For a smooth dielectric coat of IOR eta (> 0, outside 1) over a slab of
 * the given thickness (>= 0, unit extinction, no scattering):
 * *r_in: the fraction of light leaving the base (Lambertian distribution)
 * that comes back to it: the coat's internal Fresnel reflectance, total
 * internal reflection included, times the slab's transmittance up and
 * down, cosine-weighted over the inner hemisphere. [0, 1)
 * *t_out: the fraction a Lambertian emitter of unit radiance at the base
 * sends out through the coat, per unit of the base's radiance, divided by
 * pi: (1/eta^2) * integral of 2 mu (1 - F(mu)) exp(-thickness / mu') over
 * the outer cosine mu, mu' its refracted cosine. [0, 1] */
void cv_coat_closed_integrals(double eta, double thickness, double *r_in, double *t_out);

/* Marks *m (CV_MATF_COAT_CLOSED, roughness2.xy = r_in, t_out) when it is a
 * coated diffuse whose slab neither scatters (albedo 0, untextured) nor
 * varies its eta by texture; the shader still takes the closed form only
 * where the coat's alpha is at most CV_COAT_CLOSED_ALPHA. Returns whether
 * it marked it. */
bool cv_coat_closed_prepare(CvMaterial *m);

#endif
