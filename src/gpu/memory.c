/* memory.c: see memory.h. */
#include <epoxy/gl.h>

#include "gpu/memory.h"

/* GL_NVX_gpu_memory_info tokens (values in KiB). */
#define NVX_TOTAL_AVAILABLE_MEMORY 0x9048
#define NVX_CURRENT_AVAILABLE_VIDMEM 0x9049

bool cv_gpu_memory(const struct cv_gpu *gpu, uint64_t *total, uint64_t *avail)
{
    if (!gpu || !gpu->info.has_nvx_memory_info)
        return false;
    GLint t = 0, a = 0;
    glGetIntegerv(NVX_TOTAL_AVAILABLE_MEMORY, &t);
    glGetIntegerv(NVX_CURRENT_AVAILABLE_VIDMEM, &a);
    /* A driver that lists the extension but refuses the query must not
     * leave its error for the next cv_gl_check to blame on other work. */
    bool ok = glGetError() == GL_NO_ERROR && t > 0 && a >= 0;
    while (glGetError() != GL_NO_ERROR)
        ;
    if (!ok)
        return false;
    *total = (uint64_t)t * 1024;
    *avail = (uint64_t)a * 1024;
    return true;
}
