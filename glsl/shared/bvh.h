/* glsl/shared/bvh.h: the BVH as both the C host (src/bvh) and GLSL
 * (glsl/bvh, the path tracer) see it.
 *
 * Final layout, bound at CV_BIND_BVH_NODES: a 4-wide tree of CvBvhNode4,
 * the root at index 0, the boxes of all four children stored in the parent
 * so one 128-byte fetch decides which children a ray visits. Half as deep as
 * the binary tree it is collapsed from (glsl/bvh/widen.glsl), it shortens
 * the chain of dependent node fetches that bounds traversal
 * (bench/RESULTS.md, "The 4-wide tree, built on the GPU"). Per child
 * slot k (vector component k):
 *   lox..hiz  the child's box, by axis, so four slab tests run as vec4 ops
 *   word      inner child: its node index; leaf child: its first leaf slot
 *   count     leaf child: its primitive count (1..CV_BVH_MAX_LEAF);
 *             0: an inner child, or an unused slot
 * An unused slot has word 0, count 0 and the box lo = CV_BVH_EMPTY,
 * hi = -CV_BVH_EMPTY, which no ray enters; traversal rejects it by its box
 * (and word 0: the root is nobody's child). Used slots come first, in the
 * binary tree's left-to-right order, and the nodes are numbered in
 * depth-first preorder, so a node's first inner child is its next node.
 * A tree over 0 or 1 triangles is one node.
 *
 * A leaf's primitives are cv_bvh_prims[first .. first+count-1] (triangle
 * indices, bound at CV_BIND_BVH_PRIMS). Beside them, the same leaf slots
 * hold CvBvhTri records (bound at CV_BIND_BVH_TRIS, written by
 * glsl/bvh/leaf_tris.comp): the triangle's three positions copied in leaf
 * order, so a triangle test reads 48 contiguous bytes instead of prims ->
 * triangles -> three vertex loads, each waiting on the one before.
 *
 * The build first lays out a binary tree of CvBvhNode (glsl/bvh/emit.comp),
 * in the same preorder, with the same leaf slots: both child boxes in the
 * parent (Aila & Laine 2009), their .w words integers (floatBitsToInt /
 * memcpy):
 *   lmin.w  left child: node index when lmax.w == 0, else first leaf slot
 *   lmax.w  left leaf primitive count (0: the child is an inner node)
 *   rmin.w, rmax.w  the same for the right child.
 * Only a tree of 0 or 1 triangles has an empty binary child (count 0,
 * inverted box, node index 0). */
#ifndef CV_SHARED_BVH_H
#define CV_SHARED_BVH_H

/* Relative to this file, so both C and the GLSL loader find it. */
#include "common.h"

CV_STRUCT(CvBvhNode) {
    cv_vec4 lmin;
    cv_vec4 lmax;
    cv_vec4 rmin;
    cv_vec4 rmax;
} CV_END(CvBvhNode)
CV_CHECK_SIZE(CvBvhNode, 64);

CV_STRUCT(CvBvhNode4) {
    cv_vec4 lox;
    cv_vec4 hix;
    cv_vec4 loy;
    cv_vec4 hiy;
    cv_vec4 loz;
    cv_vec4 hiz;
    cv_ivec4 word;
    cv_ivec4 count;
} CV_END(CvBvhNode4)
CV_CHECK_SIZE(CvBvhNode4, 128);

/* An unused CvBvhNode4 slot's box: lo at +CV_BVH_EMPTY, hi at -CV_BVH_EMPTY.
 * Finite, so the root's box (the union of its slots) stays finite for the
 * slab padding (glsl/bvh/traverse.glsl) even in an empty tree. */
#define CV_BVH_EMPTY 1.0e38

/* Words of the build's small info buffer (src/bvh/bvh.c), shared by
 * emit.comp, the widening shaders and the host that reads them back. */
#define CV_BVH_INFO_NODES 0          /* binary node count (emit.comp) */
#define CV_BVH_INFO_WIDE 1           /* wide nodes found so far (widen_level.comp) */
#define CV_BVH_INFO_LEVEL_LO 2       /* the level being widened: queue[lo..hi) */
#define CV_BVH_INFO_LEVEL_HI 3
#define CV_BVH_INFO_DISPATCH 4       /* its indirect dispatch: x, y, z */
#define CV_BVH_INFO_DEPTH 7          /* levels of the wide tree so far */
#define CV_BVH_INFO_STACK 8          /* most stack entries a query can need */
#define CV_BVH_INFO_ROOT 12          /* the root's CvBvhBuildNode, copied by the host */
#define CV_BVH_INFO_WORDS 24

/* v0.w holds the triangle index (floatBitsToUint); v1.w, v2.w are 0. A slot
 * whose primitive is not a triangle holds zeros (a degenerate triangle that
 * no ray hits). */
CV_STRUCT(CvBvhTri) {
    cv_vec4 v0;
    cv_vec4 v1;
    cv_vec4 v2;
} CV_END(CvBvhTri)
CV_CHECK_SIZE(CvBvhTri, 48);

/* Build-time node (scratch only). Nodes 0..n-2 are inner nodes (0 is the
 * root), n-1..2n-2 the leaves in Morton order.
 *   bmin.w: SAH cost C(n) of the subtree (not normalised by the root area)
 *   link: left, right, parent (-1 at the root), primitive count with
 *         CV_BVH_COLLAPSE set when the subtree is cheaper as one leaf. */
CV_STRUCT(CvBvhBuildNode) {
    cv_vec4 bmin;
    cv_vec4 bmax;
    cv_ivec4 link;
} CV_END(CvBvhBuildNode)
CV_CHECK_SIZE(CvBvhBuildNode, 48);

#define CV_BVH_COLLAPSE 0x40000000
#define CV_BVH_COUNT_MASK 0x3fffffff

/* SAH constants: cost of one box test (inner node) and one triangle test. */
#define CV_BVH_COST_INNER 1.2
#define CV_BVH_COST_TRI 1.0
/* Entries of traversal's stack (glsl/bvh/traverse.glsl). A query visiting
 * a node that has k inner children pushes at most k - 1, so the most it
 * can need is the largest sum of those along a path; widening works that
 * out (CV_BVH_INFO_STACK). This is the size for trees that need no more;
 * the programs that trace a tree needing more are compiled with a larger
 * one (cv_bvh_stack_define, src/bvh/bvh.h), so no valid tree ever fills
 * its stack. Not larger for every tree: the stack lives in local memory,
 * whose size per query sets how many queries the NVIDIA driver runs at
 * once, and traversal slows sharply as it grows (bench/RESULTS.md, "The
 * 4-wide tree, built on the GPU"). */
#ifndef CV_BVH_STACK_SIZE
#define CV_BVH_STACK_SIZE 64
#endif

/* Largest leaf that SAH collapsing may form. */
#define CV_BVH_MAX_LEAF 8

#endif
