/* memory.h: how much GPU memory the device has and has free, where the
 * driver says (GL_NVX_gpu_memory_info on NVIDIA; Mesa does not). */
#ifndef CV_GPU_MEMORY_H
#define CV_GPU_MEMORY_H

#include <stdbool.h>
#include <stdint.h>

#include "gpu/context.h"

/* Bytes of dedicated memory in all and currently free. False (outputs
 * untouched) when the driver does not report them. */
bool cv_gpu_memory(const struct cv_gpu *gpu, uint64_t *total, uint64_t *avail);

#endif
