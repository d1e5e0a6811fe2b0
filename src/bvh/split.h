/* split.h: triangle splitting before the LBVH (Karras & Aila 2013, "Fast
 * Parallel Construction of High-Quality Bounding Volume Hierarchies", §5),
 * on the GPU (glsl/bvh/split_*.comp). A long thin or diagonal triangle has
 * a box mostly empty, and every ray entering the box tests the triangle:
 * splitting gives it several references, each with a tight box around one
 * piece of it, and the tree is built over the references. Each triangle
 * gets a priority from how much its box wastes and how coarse a grid plane
 * it crosses; a budget of extra references is shared in proportion (a
 * prefix sum places them); each triangle is then cut along the scene's
 * Morton grid planes. The leaf slots end up holding triangle indices with
 * some triangles more than once, which traversal (ties to the lower index)
 * does not mind.
 *
 * Used by src/bvh/bvh.c:
 *   cv_bvh_split_create   scratch
 *   cv_bvh_split_count    priorities, shares, prefix sum; reads back the
 *                         reference count (the only read-back)
 *   cv_bvh_split_emit     the references' boxes and triangles
 *   (the LBVH, over the references' boxes)
 *   cv_bvh_split_remap    leaf slots: reference index -> triangle index */
#ifndef CV_BVH_SPLIT_H
#define CV_BVH_SPLIT_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_bvh_split;

/* Scratch for splitting n (>= 1) triangles into at most n + max_extra
 * references (a triangle gets at most 255 extra). NULL with err set on
 * failure. */
struct cv_bvh_split *cv_bvh_split_create(struct cv_gpu *gpu, uint32_t n, uint32_t max_extra,
                                         struct cv_error *err);
/* Priorities and shares over the n CvTriangle of `triangles` indexing
 * CvVertex of `vertices` (bound by this call at CV_BIND_VERTICES and
 * CV_BIND_TRIANGLES); sets *n_refs to n plus the extra references the
 * shares come to (waits for the GPU to read that back). Uses stage-private
 * bindings. */
bool cv_bvh_split_count(struct cv_bvh_split *split, GLuint vertices, GLuint triangles,
                        uint32_t *n_refs, struct cv_error *err);
/* Writes reference r's box as two vec4 (min, max; w = 0) at boxes[2r],
 * boxes[2r + 1] (a buffer of at least 32 * n_refs bytes) and keeps its
 * triangle. References 0..n-1 are the triangles' first pieces, in order.
 * The scene buffers must still be bound as count left them. */
bool cv_bvh_split_emit(struct cv_bvh_split *split, GLuint boxes, struct cv_error *err);
/* Replaces each of prims[0..n_refs) (a reference index) by its triangle. */
bool cv_bvh_split_remap(struct cv_bvh_split *split, GLuint prims, struct cv_error *err);
/* The references' triangles (n_refs uint32), for tests. */
GLuint cv_bvh_split_ref_tris(const struct cv_bvh_split *split);
/* GPU bytes held. */
uint64_t cv_bvh_split_bytes(const struct cv_bvh_split *split);
/* Accepts NULL; clears the pointer. */
void cv_bvh_split_destroy(struct cv_bvh_split **split);

/* Starts compiling the splitter's programs (gpu/program.h:
 * cv_program_request). */
void cv_bvh_split_prefetch(struct cv_gpu *gpu);

#endif
