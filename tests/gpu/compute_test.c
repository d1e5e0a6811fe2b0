/* compute_test.c: a compute shader loaded through the GLSL loader writes a
 * buffer that is read back and checked element by element. Built twice: for
 * the default backend and (CV_TEST_OSMESA) for OSMesa. */
#include "config.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

int main(void)
{
#ifdef CV_TEST_OSMESA
#ifndef HAVE_OSMESA
    return tap_skip_all("built without OSMesa");
#endif
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_OSMESA);
    tap_ok(strcmp(gpu->info.backend, "osmesa") == 0, "backend is osmesa (%s)", gpu->info.backend);
#else
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
#endif
    struct cv_error err = {{0}};
    tap_ok(gpu->info.gl_major * 10 + gpu->info.gl_minor >= 43, "OpenGL 4.3+ (%d.%d)",
           gpu->info.gl_major, gpu->info.gl_minor);

    const char *defines[] = {"SELFTEST_MUL=3u", NULL};
    struct cv_program *prog = cv_program_get(gpu, "gpu/selftest.comp", defines, &err);
    if (!tap_ok(prog != NULL, "selftest.comp compiles: %s", prog ? "yes" : err.msg))
        return tap_done();
    tap_ok(prog->local_size[0] == 64, "local size read back (%u)", prog->local_size[0]);
    tap_ok(cv_program_get(gpu, "gpu/selftest.comp", defines, &err) == prog,
           "second request is served from the cache");

    /* More than 65535 groups' worth would split across y on llvmpipe; keep
     * it small but not a multiple of the group size. */
    const uint32_t n = 100003;
    uint32_t *in = malloc(n * sizeof(*in)), *out = malloc(n * sizeof(*out));
    uint32_t state = 12345;
    for (uint32_t i = 0; i < n; i++) {
        state = state * 1664525u + 1013904223u;
        in[i] = state;
    }
    GLuint b_in = cv_buffer_create(n * sizeof(*in), in, "selftest in", &err);
    GLuint b_out = cv_buffer_create(n * sizeof(*out), NULL, "selftest out", &err);
    tap_ok(b_in && b_out, "buffers created");
    cv_buffer_bind(b_in, CV_BIND_CHECK_IN);
    cv_buffer_bind(b_out, CV_BIND_CHECK_OUT);
    glUseProgram(prog->id);
    glUniform1ui(glGetUniformLocation(prog->id, "u_count"), n);
    cv_program_dispatch_1d(prog, n);
    tap_ok(cv_buffer_read(b_out, 0, n * sizeof(*out), out, &err), "read back");
    uint32_t bad = 0, first_bad = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (out[i] != in[i] * 3u + i && bad++ == 0)
            first_bad = i;
    }
    tap_ok(bad == 0, "every element equals in*3+i (%u wrong, first at %u)", bad, first_bad);
    /* Staged reads (gpu/buffer.h): a slice from an offset, through a
     * temporary and through a given staging buffer. */
    uint32_t part[2][16];
    GLuint staging = cv_buffer_create_uninit(sizeof(part[0]), "selftest staging", &err);
    bool staged =
        staging && cv_buffer_read_staged(b_out, 100 * 4, sizeof(part[0]), 0, part[0], &err) &&
        cv_buffer_read_staged(b_out, 200 * 4, sizeof(part[1]), staging, part[1], &err);
    tap_ok(staged && memcmp(part[0], &out[100], sizeof(part[0])) == 0 &&
               memcmp(part[1], &out[200], sizeof(part[1])) == 0,
           "staged reads return the slices read directly%s%s", staged ? "" : ": ",
           staged ? "" : err.msg);
    cv_buffer_destroy(&staging);
    cv_buffer_destroy(&b_in);
    cv_buffer_destroy(&b_out);
    tap_ok(b_in == 0, "destroy clears the handle");
    free(in);
    free(out);
    cv_gpu_destroy(&gpu);
    tap_ok(gpu == NULL, "context destroyed");
    return tap_done();
}
