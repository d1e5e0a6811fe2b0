/* buf.h: a typed GPU buffer that knows its size and use, for buffers that
 * one stage hands to another (the renderer's resolved film to the colour
 * stage): the receiver checks sizes against the handle instead of asking GL,
 * and the stage that creates a buffer is the one that frees it. Raw GL
 * names and their transfers stay in gpu/buffer.h for a stage's own
 * buffers. */
#ifndef CV_GPU_BUF_H
#define CV_GPU_BUF_H

#include <stdbool.h>
#include <stddef.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_buf_params {
    size_t size;           /* [bytes] */
    bool storable;         /* bound as a shader storage buffer: checked against
                            * what the context can bind whole (gpu/storage.h) */
    bool host_readable;    /* read back with cv_buf_read */
    const void *initial;   /* `size` bytes to start with; NULL: zeroed */
    const char *label;     /* for errors and GL debug output; copied */
};

struct cv_buf {
    GLuint id;
    struct cv_buf_params params;  /* as created; initial is NULL, label owned */
};

/* NULL with err set when the size does not fit a storage binding or GL
 * cannot allocate it. */
struct cv_buf *cv_buf_create(struct cv_gpu *gpu, const struct cv_buf_params *p,
                             struct cv_error *err);

/* Binds the whole buffer at a shader storage binding (made storable). */
void cv_buf_bind(const struct cv_buf *b, unsigned binding);

/* Copies bytes at offset to dst; fails (err naming the buffer) outside the
 * buffer or for one not made host_readable. Waits for the GPU. */
bool cv_buf_read(const struct cv_buf *b, size_t offset, size_t bytes, void *dst,
                 struct cv_error *err);

/* Accepts NULL and *b == NULL; clears the pointer. */
void cv_buf_destroy(struct cv_buf **b);

#endif
