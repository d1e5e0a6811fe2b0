/* context_platform.h: what each backend file (context_egl.c,
 * context_osmesa.c) offers context.c. Internal to src/gpu. */
#ifndef CV_GPU_CONTEXT_PLATFORM_H
#define CV_GPU_CONTEXT_PLATFORM_H

#include "gpu/context.h"

/* One device a backend can open. */
struct cv_gpu_candidate {
    int index;            /* EGL device index, -1 for surfaceless/OSMesa */
    char device[160];
    bool software;
    int cuda_id;          /* EGL_NV_device_cuda id, -1 when absent */
    int kind;             /* backend-private */
};

/* Fills up to `max` candidates in preference order and returns the count. */
int cv_egl_candidates(struct cv_gpu_candidate *out, int max);
/* Makes a context current for a candidate; sets gpu->platform. */
bool cv_egl_open(const struct cv_gpu_candidate *cand, bool debug, struct cv_gpu *gpu,
                 struct cv_error *err);

#ifdef HAVE_OSMESA
bool cv_osmesa_open(bool debug, struct cv_gpu *gpu, struct cv_error *err);
#endif

#endif
