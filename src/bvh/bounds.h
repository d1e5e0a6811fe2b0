/* bounds.h: one dispatch of glsl/bvh/bounds.comp, the scene-wide (min, max)
 * reduction that the build (centroid bounds) and triangle splitting (the
 * scene box) both need. */
#ifndef CV_BVH_BOUNDS_H
#define CV_BVH_BOUNDS_H

#include <stdint.h>

#include <epoxy/gl.h>

#include "gpu/program.h"

/* Bytes of the result buffer for n elements: the (min, max) pair first,
 * then one pair per workgroup. */
uint64_t cv_bvh_bounds_bytes(uint32_t n);

/* Reduces n elements into out[0..1] (two vec4). counter: one word of
 * scratch, any contents (cleared here), where bounds.comp counts its
 * finished groups. The program's inputs (vertices and triangles, or boxes)
 * are bound by the caller. */
void cv_bvh_bounds_dispatch(struct cv_program *bounds, uint32_t n, GLuint out, GLuint counter);

#endif
