/* buffer_pool.h: scratch storage buffers kept for reuse, one pool per GPU
 * context (cv_gpu.scratch). Fresh GPU memory is dear on NVIDIA: its first
 * use costs host time in proportion to its size when the buffer is
 * zero-filled at creation, or GPU time in the first pass that writes it,
 * far more than a BVH build's own work; and a GPU left idle meanwhile
 * lowers its clocks under the next builds (bench/RESULTS.md, "Triangle
 * splitting and pooled scratch"). A pool
 * hands out a buffer of at least the size asked and takes it back; later
 * requests reuse it. Buffers handed out have undefined contents. */
#ifndef CV_GPU_BUFFER_POOL_H
#define CV_GPU_BUFFER_POOL_H

#include <stddef.h>

#include <epoxy/gl.h>

#include "base/error.h"

struct cv_buffer_pool;

struct cv_buffer_pool *cv_buffer_pool_create(void);
/* The idle buffer of the fewest bytes that holds `bytes`, or a new one
 * (labelled `label`). pool NULL: a new buffer, which put deletes. 0 on
 * failure with err set. */
GLuint cv_buffer_pool_get(struct cv_buffer_pool *pool, size_t bytes, const char *label,
                          struct cv_error *err);
/* The same, reusing only an idle buffer of at most `most` bytes: for
 * buffers that outlive the round (a BVH's own, bvh/bvh.c), so that a small
 * scene's tree does not hold on to a large scene's scratch. */
GLuint cv_buffer_pool_get_within(struct cv_buffer_pool *pool, size_t bytes, size_t most,
                                 const char *label, struct cv_error *err);
/* Returns *buf (0 is accepted) to the pool and clears the pointer; the
 * caller must have issued the GPU work that uses it (GL orders later work
 * after it). */
void cv_buffer_pool_put(struct cv_buffer_pool *pool, GLuint *buf);
/* How many buffers the pool has created (not reused) so far, for tests. */
size_t cv_buffer_pool_created(const struct cv_buffer_pool *pool);
/* Bytes of the idle buffers. Accepts NULL (returns 0). */
size_t cv_buffer_pool_idle(const struct cv_buffer_pool *pool);
/* Deletes the idle buffers (those handed out stay handed out). */
void cv_buffer_pool_trim(struct cv_buffer_pool *pool);
/* Ends a round of use (one BVH build): deletes the idle buffers that were
 * not handed out since the last settle, so that a pool kept from job to job
 * holds one round's working set, not every size it ever made. Returns the
 * bytes of the idle buffers it keeps. Accepts NULL (returns 0). */
size_t cv_buffer_pool_settle(struct cv_buffer_pool *pool);
/* Deletes every buffer; needs the context current. Accepts NULL; clears the
 * pointer. */
void cv_buffer_pool_destroy(struct cv_buffer_pool **pool);

#endif
