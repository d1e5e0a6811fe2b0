/* scattering_presets.h: pbrt-v4's named measured scattering media (Jensen
 * et al. 2001, Narasimhan et al. 2006), by the names pbrt-v4 gives them:
 * the subsurface material's "name" and a homogeneous medium's "preset"
 * (media.c). One table for every user. */
#ifndef CV_SCENE_SCATTERING_PRESETS_H
#define CV_SCENE_SCATTERING_PRESETS_H

#include <stdbool.h>

/* sigma_a and the reduced sigma_s' (per mm, linear sRGB as pbrt-v4 reads
 * them) of the medium called name; false when there is none. */
bool cv_scattering_preset(const char *name, double sigma_a[3], double sigma_s[3]);

#endif
