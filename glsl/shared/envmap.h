/* glsl/shared/envmap.h: layout of the environment-map sampling
 * distributions (piecewise-constant 2D, one per image infinite light), as
 * src/trace/envmap_dist.c writes them and glsl/trace/light/envmap.glsl reads
 * them. All maps share one float buffer at CV_BIND_ENV_DIST; a
 * CV_LIGHT_INFINITE_MAP light's `prim` field is the float offset `o` of its
 * distribution:
 *   o + 0: width W (uint bits), o + 1: height H (uint bits),
 *   o + 2: integral of the function over [0,1]^2 (its mean), o + 3: flags,
 *   func[H][W]        at CV_ENV_FUNC(o): row 0 is the image's top row
 *   cond_cdf[H][W+1]  at CV_ENV_COND(o, W, H): per row, 0 .. 1
 *   marg_cdf[H+1]     at CV_ENV_MARG(o, W, H): over rows, 0 .. 1
 * Image coordinates (u, v) in [0,1]^2 have v = 0 at the top row. Lat-long
 * maps (pbrt-v3): phi = 2 pi u, theta = pi v in light space; equal-area
 * octahedral maps (pbrt-v4): direction = EqualAreaSquareToSphere(u, v). */
#ifndef CV_SHARED_ENVMAP_H
#define CV_SHARED_ENVMAP_H

#include "shared/bindings.h"

#define CV_ENV_HEADER_FLOATS 4u
#define CV_ENV_FLAG_EQUAL_AREA 1u
#define CV_ENV_FUNC(o) ((o) + CV_ENV_HEADER_FLOATS)
#define CV_ENV_COND(o, w, h) (CV_ENV_FUNC(o) + (w) * (h))
#define CV_ENV_MARG(o, w, h) (CV_ENV_COND(o, w, h) + (h) * ((w) + 1u))
#define CV_ENV_FLOATS(w, h) (CV_ENV_HEADER_FLOATS + (w) * (h) + (h) * ((w) + 1u) + (h) + 1u)

#endif
