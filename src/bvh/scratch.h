/* scratch.h: the BVH build's scratch buffers (bvh.c, split.c, radix_sort.c,
 * scan.c): taken from the GPU's buffer pool (gpu/buffer_pool.h), each
 * checked against the largest storage block a shader may address, their
 * bytes added up for the build's stats. */
#ifndef CV_BVH_SCRATCH_H
#define CV_BVH_SCRATCH_H

#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

/* A pooled buffer of at least `bytes` (16 when 0), contents undefined;
 * adds `bytes` to *total. 0 with err set when one storage block cannot hold
 * it or the allocation fails. */
GLuint cv_bvh_scratch(struct cv_gpu *gpu, uint64_t bytes, const char *label, uint64_t *total,
                      struct cv_error *err);

#endif
