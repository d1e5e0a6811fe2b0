/* gpu_test_util.h: opens a context for a GPU test, or skips the test with
 * the reason when this machine has none (TAP "1..0 # SKIP"); and asks a
 * program which uniforms its code reads. */
#ifndef CV_TESTS_GPU_UTIL_H
#define CV_TESTS_GPU_UTIL_H

#include <stdlib.h>

#include "gpu/context.h"
#include "gpu/program.h"
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

/* How many of the uniforms names[0..n) program `file` built with `defines`
 * declares after linking, which drops what no code reads (-1, reported as
 * a failed test: it did not build). */
static inline int test_uniforms_read(struct cv_gpu *gpu, const char *file,
                                     const char *const *defines, const char *const *names,
                                     int n)
{
    struct cv_error err = {{0}};
    struct cv_program *p = cv_program_get(gpu, file, defines, &err);
    if (!tap_ok(p != NULL, "%s builds: %s", file, err.msg))
        return -1;
    int k = 0;
    for (int i = 0; i < n; i++)
        k += glGetProgramResourceIndex(p->id, GL_UNIFORM, names[i]) != GL_INVALID_INDEX;
    return k;
}

#endif
