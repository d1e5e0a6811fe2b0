/* storage.c: see storage.h. */
#include <stdlib.h>

#include "base/log.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "gpu/storage.h"

#define MIB (1024.0 * 1024.0)

/* The shader's pattern (storage_probe.comp). */
static uint32_t pattern(uint32_t word)
{
    return word * 2654435761u + 0x5bd1e995u;
}

/* Word indices worth probing in a buffer of `words` words when the driver
 * advertises `limit_words`: both ends, each side of the limit and of every
 * power of two above 2^20 (where a driver that keeps fewer address bits
 * would wrap), and the middle. Duplicates are harmless. */
static uint32_t probe_words(uint64_t words, uint64_t limit_words, uint32_t *out)
{
    uint32_t n = 0;
    uint64_t cand[8] = {0, 1, limit_words - 1, limit_words, limit_words + 1, words / 2,
                        words - 2, words - 1};
    for (int i = 0; i < 8; i++)
        if (cand[i] < words)
            out[n++] = (uint32_t)cand[i];
    for (int k = 20; k < 32; k++) {
        uint64_t w = (uint64_t)1 << k;
        if (w - 1 < words)
            out[n++] = (uint32_t)(w - 1);
        if (w < words)
            out[n++] = (uint32_t)w;
    }
    return n;
}

struct saved_binding {
    GLint buffer;
    GLint64 start, size;
};

static void save_binding(GLuint index, struct saved_binding *s)
{
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, index, &s->buffer);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, index, &s->start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, index, &s->size);
}

static void restore_binding(GLuint index, const struct saved_binding *s)
{
    if (s->buffer && s->size > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, index, (GLuint)s->buffer, s->start, s->size);
    else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, index, (GLuint)s->buffer);
}

/* Dispatches both passes and compares; buffers made and bound by the
 * caller. */
static bool run_probe(struct cv_program *p, GLuint large, GLuint probe, const uint32_t *words,
                      uint32_t n, uint64_t n_words, bool *works, struct cv_error *err)
{
    cv_program_set_uint(p, "u_count", n);
    for (uint32_t pass = 0; pass < 2; pass++) {
        cv_program_set_uint(p, "u_pass", pass);
        cv_program_dispatch_1d(p, (uint64_t)n + 1);
    }
    uint32_t *back = malloc(((size_t)2 * n + 1) * 4);
    if (!back)
        return cv_fail(err, "out of memory");
    bool ok = cv_gl_check(err, "probing a storage buffer of %llu bytes",
                          (unsigned long long)(n_words * 4)) &&
              cv_buffer_read(probe, 0, ((size_t)2 * n + 1) * 4, back, err);
    *works = ok && back[2 * n] == n_words;
    for (uint32_t i = 0; ok && *works && i < n; i++) {
        uint32_t in_memory = 0;
        ok = cv_buffer_read(large, (size_t)words[i] * 4, 4, &in_memory, err);
        *works = ok && back[n + i] == pattern(words[i]) && in_memory == pattern(words[i]);
    }
    free(back);
    return ok;
}

bool cv_gpu_storage_probe(struct cv_gpu *gpu, uint64_t bytes, const char *const *defines,
                          bool *works, struct cv_error *err)
{
    *works = false;
    uint64_t n_words = bytes / 4;
    if (n_words < 2 || n_words > UINT32_MAX)
        return true;  /* nothing to probe, or beyond 32-bit word indices */
    uint64_t limit = gpu->info.max_ssbo_bytes > 0 ? (uint64_t)gpu->info.max_ssbo_bytes : bytes;
    struct cv_program *p = cv_program_get(gpu, "gpu/storage_probe.comp", defines, err);
    if (!p)
        return false;
    uint32_t words[8 + 24];
    uint32_t n = probe_words(n_words, limit / 4, words);
    uint32_t *init = calloc((size_t)2 * n + 1, 4);
    if (!init)
        return cv_fail(err, "out of memory");
    for (uint32_t i = 0; i < n; i++)
        init[i] = words[i];

    struct saved_binding b0, b1;
    GLint program = 0;
    save_binding(CV_BIND_CHECK_IN, &b0);
    save_binding(CV_BIND_CHECK_OUT, &b1);
    glGetIntegerv(GL_CURRENT_PROGRAM, &program);
    /* No data and no zero fill: a whole-buffer clear of a probe of
     * gigabytes would cost more than the probe, and the words checked are
     * all written first. */
    GLuint large = cv_buffer_create_uninit((size_t)bytes, "storage probe", err);
    GLuint probe = large ? cv_buffer_create(((size_t)2 * n + 1) * 4, init, "storage probe words",
                                            err)
                         : 0;
    bool ok = large && probe;
    if (ok) {
        cv_buffer_bind(large, CV_BIND_CHECK_IN);
        cv_buffer_bind(probe, CV_BIND_CHECK_OUT);
        ok = run_probe(p, large, probe, words, n, n_words, works, err);
    }
    cv_buffer_destroy(&large);
    cv_buffer_destroy(&probe);
    restore_binding(CV_BIND_CHECK_IN, &b0);
    restore_binding(CV_BIND_CHECK_OUT, &b1);
    glUseProgram((GLuint)program);
    free(init);
    gpu->storage.probes++;
    return ok;
}

GLuint cv_gpu_storage_buffer(struct cv_gpu *gpu, size_t bytes, const void *data,
                             const char *label, struct cv_error *err)
{
    return cv_gpu_storage_fits(gpu, bytes, label, err) ? cv_buffer_create(bytes, data, label, err)
                                                       : 0;
}

GLuint cv_gpu_storage_buffer_uninit(struct cv_gpu *gpu, size_t bytes, const char *label,
                                    struct cv_error *err)
{
    return cv_gpu_storage_fits(gpu, bytes, label, err) ? cv_buffer_create_uninit(bytes, label, err)
                                                       : 0;
}

uint64_t cv_gpu_storage_known(const struct cv_gpu *gpu)
{
    if (gpu->info.max_ssbo_bytes <= 0)
        return 0;
    uint64_t limit = (uint64_t)gpu->info.max_ssbo_bytes;
    return gpu->storage.works > limit ? gpu->storage.works : limit;
}

bool cv_gpu_storage_fits(struct cv_gpu *gpu, uint64_t bytes, const char *label,
                         struct cv_error *err)
{
    uint64_t known = cv_gpu_storage_known(gpu);
    if (known == 0 || bytes <= known)
        return true;
    if (bytes / 4 > UINT32_MAX)
        return cv_fail(err, "%s needs %llu bytes in one storage buffer, more than 32-bit indices "
                            "address", label, (unsigned long long)bytes);
    bool works = false;
    if (!gpu->storage.fails || bytes < gpu->storage.fails) {
        if (!cv_gpu_storage_probe(gpu, (bytes + 3) & ~(uint64_t)3, NULL, &works, err)) {
            cv_error_prefix(err, "%s needs %llu bytes in one storage buffer, more than the driver "
                                 "advertises (%lld), and the probe of that size failed: ",
                            label, (unsigned long long)bytes, gpu->info.max_ssbo_bytes);
            return false;
        }
        if (works) {
            gpu->storage.works = bytes;
            cv_info("storage buffers of %.0f MiB work on this driver (probed; it advertises "
                    "%.0f MiB)", bytes / MIB, gpu->info.max_ssbo_bytes / MIB);
            return true;
        }
        gpu->storage.fails = bytes;
    }
    return cv_fail(err, "%s needs %llu bytes in one storage buffer; the driver advertises %lld "
                        "and a probe found it cannot address %llu", label,
                   (unsigned long long)bytes, gpu->info.max_ssbo_bytes,
                   (unsigned long long)gpu->storage.fails);
}
