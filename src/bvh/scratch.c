/* scratch.c: see scratch.h. */
#include "bvh/scratch.h"
#include "gpu/buffer_pool.h"
#include "gpu/storage.h"

GLuint cv_bvh_scratch(struct cv_gpu *gpu, uint64_t bytes, const char *label, uint64_t *total,
                      struct cv_error *err)
{
    if (bytes == 0)
        bytes = 16;
    if (!cv_gpu_storage_fits(gpu, bytes, label, err))
        return 0;
    *total += bytes;
    return cv_buffer_pool_get(gpu->scratch, (size_t)bytes, label, err);
}
