/* glsl/shared/bvh.h: the BVH as both the C host (src/bvh) and GLSL
 * (glsl/bvh, the path tracer) see it.
 *
 * Final layout, bound at CV_BIND_BVH_NODES: a binary tree of CvBvhNode, the
 * root at index 0, both child boxes stored in the parent (Aila & Laine 2009)
 * so one 64-byte fetch decides which children a ray visits. The .w words hold
 * integers (floatBitsToInt / memcpy):
 *   lmin.w  left child: node index when lmax.w == 0, else first leaf slot
 *   lmax.w  left leaf primitive count (0: the child is an inner node)
 *   rmin.w, rmax.w  the same for the right child.
 * A leaf's primitives are cv_bvh_prims[first .. first+count-1] (triangle
 * indices, bound at CV_BIND_BVH_PRIMS). An empty child has count 0 and an
 * inverted box (min > max) that no ray enters, and node index 0; traversal
 * rejects it by its box. A tree over 0 or 1 triangles is one node.
 *
 * Beside cv_bvh_prims, the same leaf slots hold CvBvhTri records (bound at
 * CV_BIND_BVH_TRIS, written by glsl/bvh/leaf_tris.comp): the triangle's
 * three positions copied in leaf order, so a triangle test reads 48
 * contiguous bytes instead of prims -> triangles -> three vertex loads, each
 * waiting on the one before. */
#ifndef CV_SHARED_BVH_H
#define CV_SHARED_BVH_H

/* Relative to this file, so both C and the GLSL loader find it. */
#include "common.h"

CV_STRUCT(CvBvhNode) {
    CV_VEC4 lmin;
    CV_VEC4 lmax;
    CV_VEC4 rmin;
    CV_VEC4 rmax;
} CV_END(CvBvhNode)
CV_CHECK_SIZE(CvBvhNode, 64);

/* v0.w holds the triangle index (floatBitsToUint); v1.w, v2.w are 0. A slot
 * whose primitive is not a triangle holds zeros (a degenerate triangle that
 * no ray hits). */
CV_STRUCT(CvBvhTri) {
    CV_VEC4 v0;
    CV_VEC4 v1;
    CV_VEC4 v2;
} CV_END(CvBvhTri)
CV_CHECK_SIZE(CvBvhTri, 48);

/* Build-time node (scratch only). Nodes 0..n-2 are inner nodes (0 is the
 * root), n-1..2n-2 the leaves in Morton order.
 *   bmin.w: SAH cost C(n) of the subtree (not normalised by the root area)
 *   link: left, right, parent (-1 at the root), primitive count with
 *         CV_BVH_COLLAPSE set when the subtree is cheaper as one leaf. */
CV_STRUCT(CvBvhBuildNode) {
    CV_VEC4 bmin;
    CV_VEC4 bmax;
    CV_IVEC4 link;
} CV_END(CvBvhBuildNode)
CV_CHECK_SIZE(CvBvhBuildNode, 48);

#define CV_BVH_COLLAPSE 0x40000000
#define CV_BVH_COUNT_MASK 0x3fffffff

/* SAH constants: cost of one box test (inner node) and one triangle test. */
#define CV_BVH_COST_INNER 1.2
#define CV_BVH_COST_TRI 1.0
/* Largest leaf that SAH collapsing may form. */
#define CV_BVH_MAX_LEAF 8

#endif
