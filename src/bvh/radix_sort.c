/* radix_sort.c: see radix_sort.h. Each pass counts digits per tile of 1024
 * keys, scans the digit-major counts and scatters; passes ping-pong between
 * the caller's buffers and ours; after an odd count the result is copied
 * back. */
#include <stdlib.h>

#include "base/mem.h"
#include "bvh/radix_sort.h"
#include "bvh/scan.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

#define RADIX_TILE 1024u

struct cv_radix_sort {
    struct cv_gpu *gpu;
    uint32_t max_n;
    int max_bits;
    GLuint keys, vals, hist;
    struct cv_scan *scan;
    uint64_t bytes;
};

struct cv_radix_sort *cv_radix_sort_create(struct cv_gpu *gpu, uint32_t max_n, int max_bits,
                                           struct cv_error *err)
{
    if (max_bits < 1 || max_bits > 64) {
        cv_fail(err, "radix sort keys of %d bits", max_bits);
        return NULL;
    }
    size_t words = max_bits > 32 ? 2 : 1;
    struct cv_radix_sort *rs = cv_xcalloc(1, sizeof(*rs));
    rs->gpu = gpu;
    rs->max_n = max_n < 1 ? 1 : max_n;
    rs->max_bits = max_bits;
    uint32_t tiles = (rs->max_n + RADIX_TILE - 1) / RADIX_TILE;
    rs->keys = cv_buffer_create((size_t)rs->max_n * 4 * words, NULL, "radix keys", err);
    rs->vals = rs->keys ? cv_buffer_create((size_t)rs->max_n * 4, NULL, "radix vals", err) : 0;
    rs->hist = rs->vals ? cv_buffer_create((size_t)tiles * 16 * 4, NULL, "radix hist", err) : 0;
    rs->scan = rs->hist ? cv_scan_create(gpu, tiles * 16, err) : NULL;
    if (!rs->scan) {
        cv_radix_sort_destroy(&rs);
        return NULL;
    }
    rs->bytes = (uint64_t)rs->max_n * 4 * (words + 1) + (uint64_t)tiles * 64 + cv_scan_bytes(rs->scan);
    return rs;
}

bool cv_radix_sort_run(struct cv_radix_sort *rs, GLuint keys, GLuint vals, uint32_t n,
                       int bits, struct cv_error *err)
{
    if (n > rs->max_n)
        return cv_fail(err, "radix sort of %u keys, scratch holds %u", n, rs->max_n);
    if (bits < 1 || bits > rs->max_bits)
        return cv_fail(err, "radix sort of %d-bit keys, scratch made for %d", bits, rs->max_bits);
    const char *key64[] = {"KEY64", NULL};
    const char *const *defs = bits > 32 ? key64 : NULL;
    size_t words = bits > 32 ? 2 : 1;
    if (n < 2)
        return true;
    struct cv_program *hist, *scatter;
    if (!(hist = cv_program_get(rs->gpu, "bvh/radix_hist.comp", defs, err)) ||
        !(scatter = cv_program_get(rs->gpu, "bvh/radix_scatter.comp", defs, err)))
        return false;
    int passes = (bits + 3) / 4;
    uint32_t tiles = (n + RADIX_TILE - 1) / RADIX_TILE;
    GLuint src_k = keys, src_v = vals, dst_k = rs->keys, dst_v = rs->vals;
    for (int pass = 0; pass < passes; pass++) {
        uint32_t shift = (uint32_t)pass * 4;
        cv_buffer_bind(src_k, CV_BIND_STAGE0);
        cv_buffer_bind(rs->hist, CV_BIND_STAGE0 + 2);
        glProgramUniform1ui(hist->id, glGetUniformLocation(hist->id, "u_n"), n);
        glProgramUniform1ui(hist->id, glGetUniformLocation(hist->id, "u_shift"), shift);
        cv_program_dispatch_1d(hist, (uint64_t)tiles * hist->local_size[0]);
        if (!cv_scan_exclusive(rs->scan, rs->hist, tiles * 16, err))
            return false;
        cv_buffer_bind(src_k, CV_BIND_STAGE0);
        cv_buffer_bind(src_v, CV_BIND_STAGE0 + 1);
        cv_buffer_bind(rs->hist, CV_BIND_STAGE0 + 2);
        cv_buffer_bind(dst_k, CV_BIND_STAGE0 + 3);
        cv_buffer_bind(dst_v, CV_BIND_STAGE0 + 4);
        glProgramUniform1ui(scatter->id, glGetUniformLocation(scatter->id, "u_n"), n);
        glProgramUniform1ui(scatter->id, glGetUniformLocation(scatter->id, "u_shift"), shift);
        cv_program_dispatch_1d(scatter, (uint64_t)tiles * scatter->local_size[0]);
        GLuint tk = src_k, tv = src_v;
        src_k = dst_k;
        src_v = dst_v;
        dst_k = tk;
        dst_v = tv;
    }
    if (src_k != keys) {
        glCopyNamedBufferSubData(src_k, keys, 0, 0, (GLsizeiptr)(n * 4 * words));
        glCopyNamedBufferSubData(src_v, vals, 0, 0, (GLsizeiptr)n * 4);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    return cv_gl_check(err, "radix sort of %u keys", n);
}

uint64_t cv_radix_sort_bytes(const struct cv_radix_sort *rs)
{
    return rs->bytes;
}

void cv_radix_sort_destroy(struct cv_radix_sort **rs)
{
    if (!rs || !*rs)
        return;
    cv_buffer_destroy(&(*rs)->keys);
    cv_buffer_destroy(&(*rs)->vals);
    cv_buffer_destroy(&(*rs)->hist);
    cv_scan_destroy(&(*rs)->scan);
    free(*rs);
    *rs = NULL;
}
