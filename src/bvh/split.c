/* split.c: see split.h. The host only allocates, binds and dispatches;
 * the one read-back is the total of the shares, which sizes the build.
 * Everything is allocated up front (for the budget's most references), so
 * that the build's timer queries measure GPU work only. */
#include <stdlib.h>

#include "base/mem.h"
#include "bvh/bounds.h"
#include "bvh/scan.h"
#include "bvh/scratch.h"
#include "bvh/split.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

struct cv_bvh_split {
    struct cv_gpu *gpu;
    uint32_t n, max_extra, n_refs;
    uint32_t shift;            /* fraction bits of the shares (split_count.comp) */
    GLuint bounds;             /* the scene box at [0..1] (bounds.h) */
    GLuint bounds_counter;
    GLuint sums_a, sums_b;     /* reduction levels of the priorities' sum */
    GLuint counts;             /* priorities, then shares, then their prefix sum (n + 1) */
    GLuint ref_tris;           /* n + max_extra (n_refs used) */
    GLuint total;              /* one word: staging for the prefix sum's last element */
    struct cv_scan *scan;
    uint64_t bytes;
};

/* Every pass writes its buffer before reading it (bounds.c clears the
 * bounds counter), so the build's pool serves. */
static GLuint split_buffer(struct cv_bvh_split *s, uint64_t bytes, const char *label,
                           struct cv_error *err)
{
    return cv_bvh_scratch(s->gpu, bytes, label, &s->bytes, err);
}

/* Sums the per-workgroup priority sums (m of them, in `a`) down to one, in
 * place of a level buffer; returns the buffer holding it. */
static GLuint reduce_sums(struct cv_program *sum, GLuint a, GLuint b, uint32_t m)
{
    for (; m > 1; m = (m + 255) / 256) {
        cv_buffer_bind(a, CV_BIND_SPLIT_SUM_IN);
        cv_buffer_bind(b, CV_BIND_SPLIT_SUM_OUT);
        cv_program_set_uint(sum, "u_n", m);
        cv_program_dispatch_1d(sum, m);
        GLuint t = a;
        a = b;
        b = t;
    }
    return a;
}

struct cv_bvh_split *cv_bvh_split_create(struct cv_gpu *gpu, uint32_t n, uint32_t max_extra,
                                         struct cv_error *err)
{
    struct cv_bvh_split *s = cv_xcalloc(1, sizeof(*s));
    s->gpu = gpu;
    s->n = n;
    s->max_extra = max_extra;
    /* As many fraction bits as keep the prefix sum within 31 bits. */
    while (s->shift < 16 && ((uint64_t)max_extra + 1) << (s->shift + 1) <= (1ull << 31))
        s->shift++;
    uint64_t g0 = (n + 255) / 256, g1 = (g0 + 255) / 256;
    if (!(s->bounds = split_buffer(s, cv_bvh_bounds_bytes(n), "bvh split bounds", err)) ||
        !(s->bounds_counter = split_buffer(s, 4, "bvh split bounds counter", err)) ||
        !(s->sums_a = split_buffer(s, g0 * 4, "bvh split sums", err)) ||
        !(s->sums_b = split_buffer(s, g1 * 4, "bvh split sums", err)) ||
        !(s->counts = split_buffer(s, ((uint64_t)n + 1) * 4, "bvh split counts", err)) ||
        !(s->ref_tris = split_buffer(s, ((uint64_t)n + max_extra) * 4, "bvh split refs", err)) ||
        /* Not the pool's: the host reads it (gpu/buffer.h says why). */
        !(s->total = cv_buffer_create_uninit(4, "bvh split total", err)) ||
        !(s->scan = cv_scan_create(gpu, n + 1, err))) {
        cv_bvh_split_destroy(&s);
        return NULL;
    }
    s->bytes += cv_scan_bytes(s->scan);
    return s;
}

/* The splitter's programs: the scene box, priorities, their sum, the
 * counts, then emit and remap where references were added. */
static const char *const box_defs[] = {"SCENE_BOX", NULL};
static const char *const split_files[6] = {"bvh/bounds.comp", "bvh/split_priority.comp",
                                           "bvh/split_sum.comp", "bvh/split_count.comp",
                                           "bvh/split_emit.comp", "bvh/split_remap.comp"};

void cv_bvh_split_prefetch(struct cv_gpu *gpu)
{
    for (int i = 0; i < 6; i++)
        cv_program_request(gpu, split_files[i], i == 0 ? box_defs : NULL);
}

bool cv_bvh_split_count(struct cv_bvh_split *s, GLuint vertices, GLuint triangles,
                        uint32_t *n_refs, struct cv_error *err)
{
    struct cv_program *box, *prio, *sum, *count;
    if (!(box = cv_program_get(s->gpu, split_files[0], box_defs, err)) ||
        !(prio = cv_program_get(s->gpu, split_files[1], NULL, err)) ||
        !(sum = cv_program_get(s->gpu, split_files[2], NULL, err)) ||
        !(count = cv_program_get(s->gpu, split_files[3], NULL, err)))
        return false;
    uint32_t n = s->n, g0 = (n + 255) / 256;
    cv_buffer_bind(vertices, CV_BIND_VERTICES);
    cv_buffer_bind(triangles, CV_BIND_TRIANGLES);
    /* The scene box, which the Morton grid divides. */
    cv_bvh_bounds_dispatch(box, n, s->bounds, s->bounds_counter);

    cv_buffer_bind(s->bounds, CV_BIND_SPLIT_BOUNDS);
    cv_buffer_bind(s->counts, CV_BIND_SPLIT_COUNTS);
    cv_buffer_bind(s->sums_a, CV_BIND_SPLIT_SUMS);
    cv_program_set_uint(prio, "u_n", n);
    cv_program_dispatch_1d(prio, n);
    GLuint psum = reduce_sums(sum, s->sums_a, s->sums_b, g0);

    cv_buffer_bind(s->counts, CV_BIND_SPLIT_COUNTS);
    cv_buffer_bind(psum, CV_BIND_SPLIT_SUMS);
    cv_program_set_uint(count, "u_n", n);
    cv_program_set_uint(count, "u_shift", s->shift);
    glProgramUniform1f(count->id, glGetUniformLocation(count->id, "u_budget"),
                       (float)s->max_extra);
    cv_program_dispatch_1d(count, (uint64_t)n + 1);
    uint32_t fixed_total = 0;
    if (!cv_scan_exclusive(s->scan, s->counts, n + 1, err))
        return false;
    /* Staged through a one-word buffer: read straight from the prefix
     * sum's, the read-back stalls for longer the larger that buffer is
     * (gpu/buffer.h; bench/RESULTS.md, "Figures behind the code"). */
    if (!cv_buffer_read_staged(s->counts, (size_t)n * 4, 4, s->total, &fixed_total, err))
        return false;
    uint32_t extra = fixed_total >> s->shift;
    if (extra > s->max_extra)
        return cv_fail(err, "%u extra references for a budget of %u", extra, s->max_extra);
    s->n_refs = n + extra;
    *n_refs = s->n_refs;
    return cv_gl_check(err, "splitting %u triangles", n);
}

bool cv_bvh_split_emit(struct cv_bvh_split *s, GLuint boxes, struct cv_error *err)
{
    struct cv_program *emit = cv_program_get(s->gpu, split_files[4], NULL, err);
    if (!emit)
        return false;
    cv_buffer_bind(s->bounds, CV_BIND_SPLIT_BOUNDS);
    cv_buffer_bind(s->counts, CV_BIND_SPLIT_COUNTS);
    cv_buffer_bind(s->ref_tris, CV_BIND_SPLIT_REF_TRIS);
    cv_buffer_bind(boxes, CV_BIND_SPLIT_REF_BOXES);
    cv_program_set_uint(emit, "u_n", s->n);
    cv_program_set_uint(emit, "u_n_refs", s->n_refs);
    cv_program_set_uint(emit, "u_shift", s->shift);
    cv_program_dispatch_1d(emit, s->n_refs);
    return cv_gl_check(err, "writing %u references of %u triangles", s->n_refs, s->n);
}

bool cv_bvh_split_remap(struct cv_bvh_split *s, GLuint prims, struct cv_error *err)
{
    struct cv_program *remap = cv_program_get(s->gpu, split_files[5], NULL, err);
    if (!remap)
        return false;
    cv_buffer_bind(s->ref_tris, CV_BIND_SPLIT_REF_TRIS);
    cv_buffer_bind(prims, CV_BIND_BVH_PRIMS);
    cv_program_set_uint(remap, "u_n", s->n_refs);
    cv_program_dispatch_1d(remap, s->n_refs);
    return cv_gl_check(err, "mapping %u references to triangles", s->n_refs);
}

GLuint cv_bvh_split_ref_tris(const struct cv_bvh_split *s)
{
    return s->ref_tris;
}

uint64_t cv_bvh_split_bytes(const struct cv_bvh_split *s)
{
    return s->bytes;
}

void cv_bvh_split_destroy(struct cv_bvh_split **s)
{
    if (!s || !*s)
        return;
    struct cv_buffer_pool *pool = (*s)->gpu->scratch;
    GLuint *bufs[] = {&(*s)->bounds, &(*s)->bounds_counter, &(*s)->sums_a, &(*s)->sums_b,
                      &(*s)->counts, &(*s)->ref_tris};
    for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
        cv_buffer_pool_put(pool, bufs[i]);
    cv_buffer_destroy(&(*s)->total);
    cv_scan_destroy(&(*s)->scan);
    free(*s);
    *s = NULL;
}
