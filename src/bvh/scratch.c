/* scratch.c: see scratch.h. */
#include "bvh/scratch.h"
#include "gpu/buffer_pool.h"

GLuint cv_bvh_scratch(struct cv_gpu *gpu, uint64_t bytes, const char *label, uint64_t *total,
                      struct cv_error *err)
{
    if (bytes == 0)
        bytes = 16;
    if (gpu->info.max_ssbo_bytes > 0 && bytes > (uint64_t)gpu->info.max_ssbo_bytes) {
        cv_fail(err, "%s needs %llu bytes, more than one storage buffer may hold (%lld)", label,
                (unsigned long long)bytes, gpu->info.max_ssbo_bytes);
        return 0;
    }
    *total += bytes;
    return cv_buffer_pool_get(gpu->scratch, (size_t)bytes, label, err);
}
