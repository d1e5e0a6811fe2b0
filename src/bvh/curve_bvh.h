/* curve_bvh.h: the curves' own binary BVH, built on the host: curves are
 * few beside triangles (a strand is tens of primitives), and their boxes
 * need the Bezier pieces, which the triangle build on the GPU does not
 * know. The result is the one vec4 array glsl/bvh/curves.glsl reads. */
#ifndef CV_BVH_CURVE_BVH_H
#define CV_BVH_CURVE_BVH_H

#include <stddef.h>
#include <stdint.h>

#include "glsl/shared/scene.h"

/* Most curves per leaf. */
#define CV_CURVE_LEAF 4

/* The packed buffer for n >= 1 curves (layout: glsl/bvh/curves.glsl):
 * header, binary nodes (median splits of the boxes' centres along their
 * widest axis, at most CV_CURVE_LEAF curves a leaf), one record per
 * moving shape, the curves in leaf order, then the n_xforms transforms
 * of curves kept in their object space (CvCurveXform). The static curves (info.w 0)
 * form the tree from node 0; each of n_shapes moving shapes' curves
 * (info.w = 1 + the shape, src/scene/scene.h) a tree of its own over
 * their object-space boxes, which glsl/bvh/motion.glsl walks with the ray
 * in that space. *n_vec4 gets its length in vec4s; the caller frees it.
 * The trees' depth stays below glsl/bvh/curves.glsl's stack (log2 of n). */
float *cv_curve_bvh_pack(const CvCurve *curves, uint32_t n, const CvCurveXform *xforms, uint32_t n_xforms,
                         uint32_t n_shapes, size_t *n_vec4);

/* Box of curve c: its piece's control points over [u_min, u_max], grown
 * by half the wider end's width; for a curve kept in its object space,
 * that box's image under its transform (xforms[xf - 1]). */
void cv_curve_box(const CvCurve *c, const CvCurveXform *xforms, float lo[3], float hi[3]);

#endif
