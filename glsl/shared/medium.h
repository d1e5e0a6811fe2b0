/* glsl/shared/medium.h: participating media as the host (src/scene/media.c
 * builds them, src/trace/scene_upload.c uploads them) and the volumetric
 * stages (glsl/trace/medium) see them.
 *
 * Media are numbered from 1; 0 is vacuum (no medium), and media[0] is a
 * vacuum placeholder so that a medium's number indexes the buffer. A ray
 * carries the number of the medium it travels in (glsl/shared/trace.h,
 * CV_RAYF_MEDIUM_SHIFT), which leaves room for CV_MAX_MEDIA of them.
 *
 * A surface's MediumInterface sits in its material's `media` word
 * (glsl/shared/scene.h): CV_MEDIA_TRANSITION with inside in bits 0..7 and
 * outside in bits 8..15; 0 where the surface separates no media (pbrt-v4:
 * inside and outside are the same, or none given), and a ray keeps its
 * medium across it. Inside is the side the geometric normal points away
 * from, as pbrt-v4's GetMedium(w). */
#ifndef CV_SHARED_MEDIUM_H
#define CV_SHARED_MEDIUM_H

#include "shared/common.h"

#define CV_MEDIUM_VACUUM 0u
#define CV_MEDIUM_HOMOGENEOUS 1u

#define CV_MAX_MEDIA 31u          /* numbers 1..31 fit the ray's 5 bits */
#define CV_MEDIA_TRANSITION 0x80000000u
#define CV_MEDIA_WORD(inside, outside) (CV_MEDIA_TRANSITION | (inside) | ((outside) << 8))

/* Coefficients are per unit of scene length, "scale" applied; the colour
 * channels are the render's RGB (linear Rec.709). */
CV_STRUCT(CvMedium) {
    cv_vec4 sigma_a;   /* rgb: absorption; w: Henyey-Greenstein g in (-1, 1) */
    cv_vec4 sigma_s;   /* rgb: scattering; w: unused */
    cv_vec4 Le;        /* rgb: emitted radiance (Le x Lescale); w: unused */
    CV_UINT type;      /* CV_MEDIUM_* */
    CV_UINT emissive;  /* 1 when Le is not black */
    CV_UINT pad0;
    CV_UINT pad1;
} CV_END(CvMedium)
CV_CHECK_SIZE(CvMedium, 64);

#endif
