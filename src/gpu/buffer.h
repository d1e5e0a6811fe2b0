/* buffer.h: shader storage buffers and their transfers. Sizes in bytes. */
#ifndef CV_GPU_BUFFER_H
#define CV_GPU_BUFFER_H

#include <stdbool.h>
#include <stddef.h>

#include <epoxy/gl.h>

#include "base/error.h"

/* Immutable storage, updatable from the CPU; data may be NULL (zeroed).
 * Returns 0 on failure with err set (GL_OUT_OF_MEMORY is the usual cause). */
GLuint cv_buffer_create(size_t bytes, const void *data, const char *label, struct cv_error *err);
/* Storage whose contents are undefined until written: for buffers that GPU
 * passes fill completely before anything reads them. Zero-filling fresh
 * storage is not free: it costs host time in proportion to its size
 * (see gpu/buffer_pool.h). 0 on failure with err set. */
GLuint cv_buffer_create_uninit(size_t bytes, const char *label, struct cv_error *err);
/* Accepts a pointer to 0; clears it. */
void cv_buffer_destroy(GLuint *buf);
/* Copies data into buf through a staging buffer and a GPU copy, so that the
 * upload is ordered after every GPU command already queued on buf. (The
 * NVIDIA driver let a glNamedBufferSubData of a few MB land before the clear
 * that cv_buffer_create had queued on a new buffer, which then wiped it.) */
bool cv_buffer_upload(GLuint buf, size_t offset, size_t bytes, const void *data,
                      struct cv_error *err);
/* Waits for the GPU; use outside hot loops only. The NVIDIA driver moves a
 * buffer that the host reads back into host memory, and the GPU's later
 * work on it then crosses the bus: for a buffer the GPU goes on using, see
 * cv_buffer_read_staged. */
bool cv_buffer_read(GLuint buf, size_t offset, size_t bytes, void *dst, struct cv_error *err);
/* The same through `staging` (at least `bytes`; 0: a temporary one), which
 * gets a GPU copy of buf's bytes and is the buffer read and moved. Read
 * straight from them, the render pass counters left the trace queues in
 * host memory, which slowed every pass, and the read of a BVH build's root
 * stalled for as long as its buffer was large (bench/RESULTS.md, "Renderer
 * counters through a copy" and "BVH build: wall time"). */
bool cv_buffer_read_staged(GLuint buf, size_t offset, size_t bytes, GLuint staging, void *dst,
                           struct cv_error *err);
void cv_buffer_zero(GLuint buf);
/* Zeroes `bytes` (a multiple of 4) from `offset` (aligned to 4). */
void cv_buffer_zero_range(GLuint buf, size_t offset, size_t bytes);
void cv_buffer_bind(GLuint buf, unsigned binding);
/* A buffer texture over buf (texels of `format`, e.g. GL_R32UI), for
 * reading it through the texture path or binding it as an image; 0 with
 * err set when the GPU's buffer texture limit is too small. Delete with
 * glDeleteTextures. */
GLuint cv_buffer_texture(GLuint buf, GLenum format, size_t texels, struct cv_error *err);

/* A buffer the shaders see as an imageBuffer: its buffer texture and how
 * it is bound, so the format is written once, where the view is made. */
struct cv_buffer_image {
    GLuint tex;        /* 0: none */
    unsigned unit;     /* CV_IMAGE_* (glsl/shared/bindings.h) */
    GLenum format;     /* e.g. GL_R32UI */
    GLenum access;     /* GL_READ_ONLY, GL_WRITE_ONLY or GL_READ_WRITE */
};

/* Makes *im a view of `texels` texels of buf (cv_buffer_texture) for unit
 * with format and access; false with err set, *im then without a texture. */
bool cv_buffer_image_create(struct cv_buffer_image *im, GLuint buf, size_t texels, unsigned unit,
                            GLenum format, GLenum access, struct cv_error *err);
/* Binds im at its unit. */
void cv_buffer_image_bind(const struct cv_buffer_image *im);
/* Deletes im's texture (not the buffer) and clears it; none: nothing. */
void cv_buffer_image_destroy(struct cv_buffer_image *im);

#endif
