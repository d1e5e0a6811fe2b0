/* storage_test.c: storage buffers beyond the driver's advertised size
 * (gpu/storage.h). Within the limit nothing is probed; beyond it the probe
 * of glsl/gpu/storage_probe.comp runs once and its answer is kept; a driver
 * that wraps addresses (acted out by the probe shader's test define) is
 * caught; sizes past 32-bit indices and sizes at or above a failed probe
 * fail without probing, naming the buffer; the probe leaves bindings 0
 * and 1 and the current program as they were. llvmpipe advertises 128 MiB
 * and addresses more, so there the probe must pass (the BVH build of
 * tests/bvh/bvh_test beyond that size checks the addressing for real). */
#include "config.h"

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "gpu/buffer.h"
#include "gpu/program.h"
#include "gpu/storage.h"
#include "tests/gpu/gpu_test_util.h"

#define MIB (1024 * 1024)

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    long long limit = gpu->info.max_ssbo_bytes;
    tap_diag("advertised GL_MAX_SHADER_STORAGE_BLOCK_SIZE: %lld", limit);
    if (limit <= 0) {
        cv_gpu_destroy(&gpu);
        return tap_skip_all("the driver advertises no storage block size");
    }
    tap_ok(cv_gpu_storage_fits(gpu, (uint64_t)limit, "at the limit", &err) &&
               gpu->storage.probes == 0,
           "the advertised size fits without a probe");
    tap_ok(cv_gpu_storage_known(gpu) == (uint64_t)limit, "known size before probing: the limit");

    bool huge = cv_gpu_storage_fits(gpu, (uint64_t)20 << 30, "the huge buffer", &err);
    tap_ok(!huge && strstr(err.msg, "the huge buffer") && strstr(err.msg, "32-bit") &&
               gpu->storage.probes == 0,
           "20 GiB fails without a probe, naming the buffer: %s", err.msg);

    if (limit > 512LL * MIB) {
        tap_ok(true, "# SKIP the driver advertises %lld MiB: probing beyond it needs more memory "
                     "than a test should take", limit / MIB);
        cv_gpu_destroy(&gpu);
        return tap_done();
    }

    /* Bindings 0 and 1 hold something else; the probe must put it back. */
    GLuint a = cv_buffer_create(1024, NULL, "binding 0", &err);
    GLuint b = cv_buffer_create(4096, NULL, "binding 1", &err);
    cv_buffer_bind(a, 0);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, b, 256, 512);
    struct cv_program *self = cv_program_get(gpu, "gpu/selftest.comp",
                                             (const char *const[]){"SELFTEST_MUL=3", NULL}, &err);
    glUseProgram(self ? self->id : 0);

    uint64_t beyond = (uint64_t)limit + 4 * MIB;
    char wrap[48];
    snprintf(wrap, sizeof(wrap), "CV_STORAGE_PROBE_WRAP=%llu", (unsigned long long)(limit / 4));
    bool works = true;
    bool ran = cv_gpu_storage_probe(gpu, beyond, (const char *const[]){wrap, NULL}, &works, &err);
    tap_ok(ran && !works, "a driver that wraps addresses at the limit fails the probe%s%s",
           ran ? "" : ": ", ran ? "" : err.msg);

    GLint now0 = 0, now1 = 0, prog = 0;
    GLint64 start1 = 0, size1 = 0;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 0, &now0);
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 1, &now1);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, 1, &start1);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, 1, &size1);
    glGetIntegerv(GL_CURRENT_PROGRAM, &prog);
    tap_ok((GLuint)now0 == a && (GLuint)now1 == b && start1 == 256 && size1 == 512 && self &&
               (GLuint)prog == self->id,
           "the probe restores bindings 0 and 1 (range 256+512) and the current program");

    unsigned before = gpu->storage.probes;
    bool fits = cv_gpu_storage_fits(gpu, beyond, "beyond", &err);
    tap_diag("%llu bytes beyond the limit: %s (%s)", (unsigned long long)beyond,
             fits ? "fits" : "does not fit", fits ? "probed" : err.msg);
    tap_ok(gpu->storage.probes == before + 1, "one probe for a size beyond the limit");
    if (strstr(gpu->info.renderer, "llvmpipe"))
        tap_ok(fits && gpu->storage.works == beyond && cv_gpu_storage_known(gpu) == beyond,
               "llvmpipe addresses %llu MiB (advertises %lld)", (unsigned long long)beyond / MIB,
               limit / MIB);
    tap_ok(cv_gpu_storage_fits(gpu, beyond - 4096, "below", &err) == fits &&
               gpu->storage.probes == before + 1,
           "a smaller size is answered from the kept result");

    /* After a failed probe, that size and larger fail at once. */
    gpu->storage.fails = beyond + 8 * MIB;
    before = gpu->storage.probes;
    bool past = cv_gpu_storage_fits(gpu, beyond + 9 * MIB, "the nodes", &err);
    tap_ok(!past && strstr(err.msg, "the nodes") && gpu->storage.probes == before,
           "a size at or above a failed probe fails without probing: %s", err.msg);

    cv_buffer_destroy(&a);
    cv_buffer_destroy(&b);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
