/* rlpath_sort_test.c: the hit grouping of the rlpath integrator
 * (glsl/trace/rlpath/sort.comp, layout in glsl/shared/rlpath.h) on the GPU:
 * given hits whose sort bin and rank within the bin are known, as
 * intersect.comp (CV_HIT_KEYS) leaves them, the scan gives every bin the
 * exclusive prefix of the counts and clears the counts, and the scatter
 * lists every hit exactly once, in bin order, each bin's hits by rank. The
 * bins are skewed (most hits in a few bins, many bins empty, the last one
 * used) like a scene's keys. The render tests (rlpath_converge_test) run
 * it with intersect.comp's counting. */
#include "config.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "trace/rlpath.h"

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    const uint32_t n = 100003, nb = CV_RL_SORT_BINS;
    const char *d0[] = {"SORT_MODE=0", NULL}, *d1[] = {"SORT_MODE=1", NULL};
    struct cv_program *scan = cv_program_get(gpu, "trace/rlpath/sort.comp", d0, &err);
    struct cv_program *scatter = scan ? cv_program_get(gpu, "trace/rlpath/sort.comp", d1, &err)
                                      : NULL;
    if (!tap_ok(scan && scatter, "sort programs: %s", err.msg))
        return tap_done();

    /* bins: a quarter of the hits in bin 7, the others spread over the
     * bins below 1000 with a tail, and a few in the last bin; ranks per bin
     * handed out in a shuffled order, as the atomics would */
    CvHitItem *hit = calloc(n, sizeof(*hit));
    uint32_t *count = calloc(2 * nb, sizeof(uint32_t)), *perm = malloc(n * sizeof(uint32_t));
    uint32_t state = 12345;
    for (uint32_t i = 0; i < n; i++) {
        state = state * 1664525u + 1013904223u;
        uint32_t u = state >> 8;
        hit[i].pad0 = (u & 3) == 0 ? 7u : (i % 997 == 0 ? nb - 1 : (u >> 2) % 1000 * (u % 3 + 1));
        hit[i].ray = i;
        perm[i] = i;
    }
    for (uint32_t i = n - 1; i > 0; i--) {
        state = state * 1664525u + 1013904223u;
        uint32_t j = (state >> 8) % (i + 1), t = perm[i];
        perm[i] = perm[j], perm[j] = t;
    }
    for (uint32_t k = 0; k < n; k++)
        hit[perm[k]].pad1 = count[hit[perm[k]].pad0]++;
    for (uint32_t b = 0; b < nb; b++)
        count[nb + b] = 0xdeadbeefu;   /* offsets: all to be written */

    CvTraceQueues qs;
    memset(&qs, 0, sizeof(qs));
    qs.count[CV_Q_HITS] = n;
    CvPassParams pass;
    memset(&pass, 0, sizeof(pass));
    pass.frame.x = n;
    GLuint queues = cv_buffer_create(sizeof(qs), &qs, "test queues", &err);
    GLuint ubo = cv_buffer_create(sizeof(pass), &pass, "test pass", &err);
    GLuint hits = cv_buffer_create(n * sizeof(*hit), hit, "test hits", &err);
    GLuint sort = cv_buffer_create(2 * nb * sizeof(uint32_t), count, "test sort", &err);
    GLuint order = cv_buffer_create(n * sizeof(uint32_t), NULL, "test order", &err);
    if (!tap_ok(queues && ubo && hits && sort && order, "buffers: %s", err.msg))
        return tap_done();
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_PASS, ubo);
    cv_buffer_bind(queues, CV_BIND_QUEUES);
    cv_buffer_bind(hits, CV_BIND_HITS);
    cv_buffer_bind(sort, CV_BIND_RL_SORT);
    cv_buffer_bind(order, CV_BIND_RL_ORDER);
    glUseProgram(scan->id);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    cv_program_dispatch_1d(scatter, n);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);

    uint32_t *got = malloc(2 * nb * sizeof(uint32_t)), *ord = malloc(n * sizeof(uint32_t));
    if (tap_ok(cv_buffer_read(sort, 0, 2 * nb * sizeof(uint32_t), got, &err) &&
               cv_buffer_read(order, 0, n * sizeof(uint32_t), ord, &err) &&
               cv_gl_check(&err, "sort"), "scan and scatter: %s", err.msg)) {
        uint32_t bad_off = 0, nonzero = 0, run = 0;
        for (uint32_t b = 0; b < nb; b++) {
            bad_off += got[nb + b] != run;
            nonzero += got[b] != 0;
            run += count[b];
        }
        tap_ok(bad_off == 0, "offsets are the exclusive prefix of the counts (%u of %u differ)",
               bad_off, nb);
        tap_ok(nonzero == 0, "counts cleared for the next iteration (%u not)", nonzero);
        uint8_t *seen = calloc(n, 1);
        uint32_t dup = 0, out_of_order = 0;
        for (uint32_t k = 0; k < n; k++) {
            uint32_t i = ord[k];
            if (i >= n || seen[i]) {
                dup++;
                continue;
            }
            seen[i] = 1;
            if (k > 0 && ord[k - 1] < n) {
                const CvHitItem *a = &hit[ord[k - 1]], *c = &hit[i];
                if (a->pad0 > c->pad0 || (a->pad0 == c->pad0 && a->pad1 + 1 != c->pad1))
                    out_of_order++;
            }
        }
        tap_ok(dup == 0, "every hit listed once (%u repeated or out of range)", dup);
        tap_ok(out_of_order == 0, "in bin order, each bin by rank (%u pairs not)",
               out_of_order);
        free(seen);
    }
    free(got);
    free(ord);
    free(hit);
    free(count);
    free(perm);
    GLuint *bufs[] = {&queues, &ubo, &hits, &sort, &order};
    for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
        cv_buffer_destroy(bufs[i]);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
