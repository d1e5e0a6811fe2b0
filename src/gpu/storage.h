/* storage.h: how large a shader storage buffer the context can bind and
 * address whole. Drivers advertise GL_MAX_SHADER_STORAGE_BLOCK_SIZE, and
 * some advertise less than they address: Mesa's llvmpipe says 128 MiB, so
 * by that figure a BVH build stops near 1.4 M triangles (2 n build nodes
 * of 48 bytes), yet its shaders index buffers of up to 2 GiB correctly.
 * Rather than trust the figure or ignore it, a size beyond it is probed
 * once on the context (glsl/gpu/storage_probe.comp: words written and read
 * back at the limit, past it, at powers of two and at the end) and used
 * only if every word lands where it should. */
#ifndef CV_GPU_STORAGE_H
#define CV_GPU_STORAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

/* True when a storage buffer of `bytes` may be bound whole. Within the
 * advertised limit: at once. Beyond it: after a probe of that size (cached:
 * a size at or below one that worked passes, one at or above one that
 * failed fails). False with err naming `label`, the size and the limit. */
bool cv_gpu_storage_fits(struct cv_gpu *gpu, uint64_t bytes, const char *label,
                         struct cv_error *err);

/* cv_buffer_create (gpu/buffer.h) of a buffer that passes
 * cv_gpu_storage_fits first; 0 with err set when either fails. */
GLuint cv_gpu_storage_buffer(struct cv_gpu *gpu, size_t bytes, const void *data,
                             const char *label, struct cv_error *err);
/* The same, of undefined contents (cv_buffer_create_uninit): for storage
 * written before it is read, which spares fresh storage its zero-fill. */
GLuint cv_gpu_storage_buffer_uninit(struct cv_gpu *gpu, size_t bytes, const char *label,
                                    struct cv_error *err);

/* The largest size known to fit without probing: the advertised limit or
 * the largest size a probe passed, whichever is larger; 0 when the driver
 * advertises none (then every size is taken to fit). */
uint64_t cv_gpu_storage_known(const struct cv_gpu *gpu);

/* Runs the probe for `bytes` (a multiple of 4) and sets *works; `defines`
 * go to the probe shader (tests pass CV_STORAGE_PROBE_WRAP=N to act as a
 * driver that wraps addresses). Leaves the context's shader-storage
 * bindings 0 and 1 and its current program as they were. False only when
 * the probe could not run (err set): the probe buffer could not be made. */
bool cv_gpu_storage_probe(struct cv_gpu *gpu, uint64_t bytes, const char *const *defines,
                          bool *works, struct cv_error *err);

#endif
