/* gpu_test_util.h: opens a context for a GPU test, or skips the test with
 * the reason when this machine has none (TAP "1..0 # SKIP"). */
#ifndef CV_TESTS_GPU_UTIL_H
#define CV_TESTS_GPU_UTIL_H

#include <stdlib.h>

#include "gpu/context.h"
#include "tests/tap.h"

static inline struct cv_gpu *test_gpu_open(enum cv_gpu_backend backend)
{
    struct cv_gpu_params p = {.gpu_index = -1, .backend = backend, .debug = true};
    const char *b = getenv("CV_TEST_BACKEND");
    if (b && backend == CV_BACKEND_AUTO)
        p.backend = b[0] == 'o' ? CV_BACKEND_OSMESA : CV_BACKEND_EGL;
    struct cv_gpu *gpu = NULL;
    struct cv_error err = {{0}};
    if (!cv_gpu_create(&p, &gpu, &err)) {
        char reason[CV_ERROR_MAX + 32];
        snprintf(reason, sizeof(reason), "no GPU context: %s", err.msg);
        exit(tap_skip_all(reason));
    }
    tap_diag("GPU: %s | %s | %s", gpu->info.backend, gpu->info.renderer, gpu->info.version);
    return gpu;
}

#endif
