/* program_copy.h: fetches a cached program and copies it out. The program
 * cache (src/gpu/program.c) keeps its entries in a growing array, so a
 * pointer it returned dangles after a later first compile; copies (id,
 * local size, path string) stay valid for the context's life. */
#ifndef CV_BVH_PROGRAM_COPY_H
#define CV_BVH_PROGRAM_COPY_H

#include <stdbool.h>

#include "gpu/program.h"

static inline bool cv_bvh_program(struct cv_gpu *gpu, const char *path,
                                  const char *const *defines, struct cv_program *out,
                                  struct cv_error *err)
{
    struct cv_program *p = cv_program_get(gpu, path, defines, err);
    if (!p)
        return false;
    *out = *p;
    return true;
}

#endif
