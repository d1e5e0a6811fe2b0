/* widen.h: the 4-wide traversal tree (CvBvhNode4, glsl/shared/bvh.h),
 * collapsed on the GPU from the binary tree that the build lays out
 * (glsl/bvh/widen.glsl says which children each wide node takes: least
 * summed node area). Two steps, because the wide tree is sized by its
 * node count:
 *   find: each binary node's parent (glsl/bvh/widen_up.comp), then the
 *         costs of covering its children with 2, 3 and 4 slots, bottom-up
 *         (glsl/bvh/widen_cost.comp); then level by level from the root,
 *         each wide node's inner children
 *         queued and flagged (glsl/bvh/widen_level.comp); the host reads
 *         the build's info words back once per batch of levels, which is
 *         once per build for trees up to CV_BVH_WIDEN_LEVELS deep (a
 *         generated 16 M-triangle scene's is 23: bvh_bench);
 *   emit: the flags' prefix sum numbers the wide nodes in preorder, and
 *         each is written there (glsl/bvh/widen_emit.comp).
 * Only `info`'s words are ever read back, never the tree. */
#ifndef CV_BVH_WIDEN_H
#define CV_BVH_WIDEN_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "bvh/scan.h"
#include "glsl/shared/bvh.h"
#include "gpu/context.h"

/* Levels run between two read-backs, by default. */
#define CV_BVH_WIDEN_LEVELS 24

/* Buffers of one widening. bin: the binary CvBvhNode tree, its node count
 * at info[CV_BVH_INFO_NODES] (CV_BVH_INFO_* words), at most n_max; queue:
 * room for the wide nodes, one uint each, and `need` as many (each wide
 * node is a distinct binary node, so n_max is always room); flags and up:
 * one uint per binary node; cost: one vec4 per binary node. */
struct cv_bvh_widen {
    struct cv_gpu *gpu;
    GLuint bin, info, queue, need, flags, up, cost;
    uint32_t n_max;
    uint32_t levels;  /* per read-back; 0: CV_BVH_WIDEN_LEVELS */
};

/* Finds the wide nodes (see the top), leaving the queue and flags for
 * cv_bvh_widen_emit. Ends with info's words read back into `words`:
 * words[CV_BVH_INFO_WIDE] is the wide node count, [CV_BVH_INFO_DEPTH] its
 * levels and [CV_BVH_INFO_STACK] the most traversal stack entries a query
 * can need (glsl/bvh/widen_level.comp). Binds stage-private slots
 * CV_BIND_WIDEN_* and the indirect dispatch buffer (unbound after).
 * Fails when the queue overflows or the levels do not end. */
bool cv_bvh_widen_find(const struct cv_bvh_widen *w, uint32_t words[CV_BVH_INFO_WORDS],
                       struct cv_error *err);

/* Writes the n_wide nodes into `out` (at least n_wide CvBvhNode4) after
 * cv_bvh_widen_find; n_bin binary nodes. `scan` must take n_bin elements;
 * the flags become the nodes' indices. Binds CV_BIND_WIDEN_* and
 * CV_BIND_BVH_NODES. */
bool cv_bvh_widen_emit(const struct cv_bvh_widen *w, struct cv_scan *scan, uint32_t n_bin,
                       uint32_t n_wide, GLuint out, struct cv_error *err);

/* Starts compiling the programs of find and emit (gpu/program.h:
 * cv_program_request). */
void cv_bvh_widen_prefetch(struct cv_gpu *gpu);

#endif
