/* bvh.c: see bvh.h. The host only allocates, binds and dispatches; every
 * phase runs in glsl/bvh. Each phase is a named row of the build's GPU
 * timer (gpu/timer.h); the total is the sum of the phases. */
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "bvh/bounds.h"
#include "bvh/bvh.h"
#include "bvh/radix_sort.h"
#include "bvh/scan.h"
#include "bvh/scratch.h"
#include "bvh/split.h"
#include "bvh/treelet_schedule.h"
#include "bvh/widen.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/bvh.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "gpu/storage.h"
#include "gpu/timer.h"

/* 30-bit Morton codes (10 bits per axis): 8 sort passes instead of 15 for
 * 60 bits (two words, KEY64 in the shaders, which support both). Equal
 * codes are split by index and treelet restructuring repairs the crowding:
 * on bvh_bench's meshes the restructured SAH differs by under 0.01 % at
 * 1 M, 4 M and 16 M triangles, while the sort makes half the passes
 * (bench/RESULTS.md, "Figures behind the code"). */
#define MORTON_BITS 30

/* Refit gathers each leaf's box by triangle index, in random order for
 * meshes in random order. Over more than a few hundred MiB that gather runs
 * into a cliff on NVIDIA (random access past what address translation
 * covers, it seems), so refit runs one pass per window of this many
 * triangles (128 MiB of boxes), each gathering from its window only
 * (bench/RESULTS.md, "Figures behind the code"). */
#define REFIT_WINDOW (4u << 20)

enum {
    PH_BOUNDS, PH_MORTON, PH_SORT, PH_HIERARCHY, PH_REFIT, PH_TREELET, PH_COLLAPSE,
    PH_SPLIT, PH_SPLIT_EMIT, PH_SPLIT_REMAP, PH_LEAF_TRIS, PH_WIDEN_FIND, PH_WIDEN_EMIT, PH_COUNT
};

/* The build timer's rows (PH_SPLIT counts the references: ms_split_count). */
static const char *const phase_names[PH_COUNT] = {
    "bounds", "morton",      "sort",      "hierarchy",  "refit",      "treelet",    "collapse",
    "split",  "split-emit",  "split-remap", "leaf-tris", "widen-find", "widen-emit",
};

/* The tree's own buffers come from the GPU's buffer pool too and go back
 * to it when the tree is destroyed, so that a batch's next scene, or the
 * next build of the same one, writes no fresh memory for them either:
 * they are ~130 bytes per triangle, and fresh memory costs host time
 * that grows with its size, several times the GPU phases of a large build
 * (bench/RESULTS.md, "BVH build: wall time"). A pooled buffer may be
 * larger than asked, so each is bound as the range the tree uses
 * (traversal reads the nodes' and leaf triangles' lengths). `binary` is
 * kept only when asked (params). */
struct cv_bvh {
    struct cv_gpu *gpu;
    GLuint nodes, prims, tris, binary;
    size_t nodes_bytes, prims_bytes, tris_bytes;
    struct cv_bvh_stats stats;
    char stack_define[32];  /* cv_bvh_stack_define's; empty for the default */
};

/* A buffer for the tree, from the pool when one there is no more than a
 * quarter larger. */
static GLuint own_buffer(struct cv_bvh *bvh, size_t bytes, size_t *kept, const char *label,
                         struct cv_error *err)
{
    *kept = bytes;
    return cv_buffer_pool_get_within(bvh->gpu->scratch, bytes, bytes + bytes / 4, label, err);
}

/* Scratch of one build, from the GPU's buffer pool (gpu/buffer_pool.h);
 * everything here goes back to it when the build ends, so the next build
 * touches no fresh memory. */
struct build {
    struct cv_gpu *gpu;
    uint32_t n;
    GLuint bounds_a, bounds_b, keys, vals, nodes, counters, offsets, live, starts, info, out_nodes,
        schedule;
    struct cv_radix_sort *sort;
    struct cv_scan *scan;
    struct cv_bvh_split *split; /* NULL: one reference per triangle */
    struct cv_gpu_timer *timer; /* a row per phase */
    uint64_t scratch;
};

#define PHASE(name, in_total) {#name, offsetof(struct cv_bvh_stats, ms_##name), in_total}
const struct cv_bvh_phase cv_bvh_phases[CV_BVH_N_PHASES] = {
    PHASE(split, true),        PHASE(bounds, true),      PHASE(morton, true),
    PHASE(sort, true),         PHASE(hierarchy, true),   PHASE(refit, true),
    PHASE(treelet, true),      PHASE(collapse, true),    PHASE(leaf_tris, true),
    PHASE(widen, true),        PHASE(split_count, false), PHASE(split_emit, false),
    PHASE(split_remap, false), PHASE(total, false),
};
#undef PHASE

struct cv_bvh_params cv_bvh_default_params(void)
{
    return (struct cv_bvh_params){.treelet_rounds = 3, .treelet_size = 7,
                                  .collapse_leaves = true, .split_budget = 0.3f};
}

/* Every pass writes its scratch before reading it, or clears it itself
 * (live, starts, the treelet counters, the bounds counter and info;
 * hierarchy.comp resets the refit counters). */
static GLuint scratch(struct build *b, uint64_t bytes, const char *label, struct cv_error *err)
{
    return cv_bvh_scratch(b->gpu, bytes, label, &b->scratch, err);
}

/* The treelet shader's work lists (src/bvh/treelet_schedule.h). */
static GLuint treelet_schedule(struct build *b, int leaves, struct cv_error *err)
{
    uint32_t sched[CV_TREELET_SCHEDULE_MAX];
    size_t n = cv_treelet_schedule(leaves, sched);
    b->scratch += n * 4;
    return cv_buffer_create(n * 4, sched, "bvh treelet schedule", err);
}

static void build_free(struct build *b)
{
    GLuint *bufs[] = {&b->bounds_a, &b->bounds_b, &b->keys, &b->vals, &b->nodes,
                      &b->counters, &b->offsets, &b->live, &b->starts, &b->info, &b->out_nodes};
    for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
        cv_buffer_pool_put(b->gpu->scratch, bufs[i]);
    cv_buffer_destroy(&b->schedule);
    cv_radix_sort_destroy(&b->sort);
    cv_scan_destroy(&b->scan);
    cv_bvh_split_destroy(&b->split);
    cv_gpu_timer_destroy(&b->timer);
}

/* Writes the n leaf triangle records into `tris` (at least one record). */
static bool leaf_tris_fill(struct cv_gpu *gpu, GLuint tris, GLuint vertices, GLuint triangles,
                           GLuint prims, uint32_t n, struct cv_error *err)
{
    struct cv_program *prog = cv_program_get(gpu, "bvh/leaf_tris.comp", NULL, err);
    if (!prog)
        return false;
    if (n == 0) {
        /* No triangle to read: the all-zero record hits nothing. */
        cv_buffer_zero(tris);
    } else {
        cv_buffer_bind(vertices, CV_BIND_VERTICES);
        cv_buffer_bind(triangles, CV_BIND_TRIANGLES);
        cv_buffer_bind(prims, CV_BIND_BVH_PRIMS);
        cv_buffer_bind(tris, CV_BIND_BVH_TRIS);
        cv_program_set_uint(prog, "u_n", n);
        cv_program_dispatch_1d(prog, n);
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    return cv_gl_check(err, "writing %u leaf triangles", n);
}

static size_t leaf_tris_bytes(uint32_t n)
{
    return (size_t)(n ? n : 1) * sizeof(CvBvhTri);
}

/* 0 or 1 triangles: one root whose first child is the triangle (with a
 * box that every ray enters) and whose other children are empty; the
 * binary form, when kept, the same with one empty child. */
static bool build_trivial(struct cv_bvh *bvh, GLuint vertices, GLuint triangles, uint32_t n,
                          bool keep_binary, struct cv_error *err)
{
    const float big = (float)CV_BVH_EMPTY;
    float lo = n ? -big : big;
    CvBvhNode4 wide = {
        .lox = {lo, big, big, big}, .hix = {-lo, -big, -big, -big},
        .loy = {lo, big, big, big}, .hiy = {-lo, -big, -big, -big},
        .loz = {lo, big, big, big}, .hiz = {-lo, -big, -big, -big},
        .count = {(int32_t)n, 0, 0, 0},
    };
    CvBvhNode bin = {.lmin = {lo, lo, lo, 0}, .lmax = {-lo, -lo, -lo, 0},
                     .rmin = {big, big, big, 0}, .rmax = {-big, -big, -big, 0}};
    int32_t count = (int32_t)n;
    memcpy(&bin.lmax.w, &count, 4);
    uint32_t prim = 0;
    bvh->nodes = cv_buffer_create(sizeof(wide), &wide, "bvh nodes", err);
    bvh->prims = bvh->nodes ? cv_buffer_create(4, &prim, "bvh prims", err) : 0;
    if (bvh->prims && keep_binary &&
        !(bvh->binary = cv_buffer_create(sizeof(bin), &bin, "bvh binary nodes", err)))
        return false;
    bvh->nodes_bytes = sizeof(wide);
    bvh->prims_bytes = 4;
    bvh->stats.bytes = sizeof(wide) + 4 + sizeof(CvBvhTri) + (keep_binary ? sizeof(bin) : 0);
    bvh->stats.n_nodes = 1;
    bvh->stats.n_binary_nodes = 1;
    bvh->stats.depth = 1;
    bvh->stats.stack_need = 0;
    bvh->stats.n_refs = n;
    bvh->stats.sah_cost = n;
    return bvh->prims &&
           (bvh->tris = own_buffer(bvh, leaf_tris_bytes(n), &bvh->tris_bytes, "bvh leaf triangles",
                                   err)) != 0 &&
           leaf_tris_fill(bvh->gpu, bvh->tris, vertices, triangles, bvh->prims, n, err);
}

GLuint cv_bvh_leaf_tris_create(struct cv_gpu *gpu, GLuint vertices, GLuint triangles,
                               GLuint prims, uint32_t n, struct cv_error *err)
{
    /* leaf_tris.comp writes every slot: no zero-fill (fresh memory is dear,
     * see gpu/buffer_pool.h). */
    size_t bytes = leaf_tris_bytes(n);
    GLuint tris = cv_gpu_storage_fits(gpu, bytes, "bvh leaf triangles", err)
                      ? cv_buffer_create_uninit(bytes, "bvh leaf triangles", err)
                      : 0;
    if (tris && !leaf_tris_fill(gpu, tris, vertices, triangles, prims, n, err))
        cv_buffer_destroy(&tris);
    return tris;
}

/* The phases' programs and their defines for params p, over split
 * references or not: one home for run_phases and cv_bvh_prefetch. Holds
 * pointers into itself: not to be copied. */
enum { PHASE_BOUNDS, PHASE_MORTON, PHASE_HIER, PHASE_REFIT, PHASE_TREELET, PHASE_LAYOUT,
       PHASE_EMIT, PHASE_PROGRAMS };
static const char *const phase_files[PHASE_PROGRAMS] = {
    "bvh/bounds.comp", "bvh/morton.comp", "bvh/hierarchy.comp", "bvh/refit.comp",
    "bvh/treelet.comp", "bvh/layout.comp", "bvh/emit.comp"};
struct phase_programs {
    char tdef[32];
    const char *bounds[2], *morton[3], *key[2], *refit[2], *treelet[3];
    const char *const *defs[PHASE_PROGRAMS];
};

static void phase_programs(const struct cv_bvh_params *p, bool split, struct phase_programs *pp)
{
    snprintf(pp->tdef, sizeof(pp->tdef), "TREELET_SIZE=%d", p->treelet_size);
    /* Over split references, bounds and keys come from their boxes. */
    const char *from = split ? "FROM_BOXES" : NULL;
    const char *nc = p->collapse_leaves ? NULL : "CV_BVH_NO_COLLAPSE";
    const char *key64 = MORTON_BITS > 32 ? "KEY64" : NULL;
    pp->bounds[0] = from, pp->bounds[1] = NULL;
    pp->refit[0] = nc, pp->refit[1] = NULL;
    pp->key[0] = key64, pp->key[1] = NULL;
    pp->morton[0] = from, pp->morton[1] = key64, pp->morton[2] = NULL;
    pp->treelet[0] = pp->tdef, pp->treelet[1] = nc, pp->treelet[2] = NULL;
    const char *const *defs[PHASE_PROGRAMS] = {pp->bounds, pp->morton, pp->key, pp->refit,
                                              pp->treelet, NULL, NULL};
    memcpy(pp->defs, defs, sizeof(defs));
}

/* leaf_tris_scatter's */
static const char *const leaf_scatter_defs[] = {"SCATTER", NULL};

static bool run_phases(struct build *b, const struct cv_bvh_params *p, GLuint vertices,
                       GLuint triangles, struct cv_error *err)
{
    uint32_t n = b->n;
    struct phase_programs pp;
    phase_programs(p, b->split != NULL, &pp);
    struct cv_program *prog[PHASE_PROGRAMS];
    for (int i = 0; i < PHASE_PROGRAMS; i++)
        if (!(prog[i] = cv_program_get(b->gpu, phase_files[i], pp.defs[i], err)))
            return false;
    struct cv_program *bounds = prog[PHASE_BOUNDS], *morton = prog[PHASE_MORTON],
                      *hier = prog[PHASE_HIER], *refit = prog[PHASE_REFIT],
                      *treelet = prog[PHASE_TREELET], *layout = prog[PHASE_LAYOUT],
                      *emit = prog[PHASE_EMIT];

    /* Pooled buffers hold whatever their last user left. */
    cv_buffer_zero(b->info);
    cv_buffer_bind(vertices, CV_BIND_VERTICES);
    cv_buffer_bind(triangles, CV_BIND_TRIANGLES);

    /* Centroid bounds: one dispatch, whose last group reduces the groups'
     * pairs (bounds.comp); bounds_b holds its counter. */
    cv_gpu_timer_begin(b->timer, PH_BOUNDS, 0);
    cv_buffer_bind(b->out_nodes, CV_BIND_LEAF_BOXES);
    cv_bvh_bounds_dispatch(bounds, n, b->bounds_a, b->bounds_b);
    cv_gpu_timer_end(b->timer);

    /* The triangles' boxes, from morton to refit, borrow out_nodes, which
     * only emit writes: (n - 1) * 64 bytes hold n * 32 for n >= 2. Split
     * references' boxes are there already (cv_bvh_split_emit). */
    cv_gpu_timer_begin(b->timer, PH_MORTON, 0);
    cv_buffer_bind(b->bounds_a, CV_BIND_BUILD_BOUNDS);
    cv_buffer_bind(b->keys, CV_BIND_MORTON_KEYS);
    cv_buffer_bind(b->vals, CV_BIND_MORTON_VALS);
    cv_buffer_bind(b->out_nodes, CV_BIND_LEAF_BOXES);
    cv_program_set_uint(morton, "u_n", n);
    cv_program_dispatch_1d(morton, n);
    cv_gpu_timer_end(b->timer);

    cv_gpu_timer_begin(b->timer, PH_SORT, 0);
    bool ok = cv_radix_sort_run(b->sort, b->keys, b->vals, n, MORTON_BITS, err);
    cv_gpu_timer_end(b->timer);
    if (!ok)
        return false;

    cv_gpu_timer_begin(b->timer, PH_HIERARCHY, 0);
    cv_buffer_bind(b->keys, CV_BIND_BUILD_KEYS);
    cv_buffer_bind(b->nodes, CV_BIND_BUILD_NODES);
    cv_buffer_bind(b->counters, CV_BIND_BUILD_COUNTERS);
    cv_program_set_uint(hier, "u_n", n);
    cv_program_dispatch_1d(hier, n);
    cv_gpu_timer_end(b->timer);

    cv_gpu_timer_begin(b->timer, PH_REFIT, 0);
    cv_buffer_bind(b->vals, CV_BIND_BUILD_VALS);
    cv_buffer_bind(b->out_nodes, CV_BIND_LEAF_BOXES);
    cv_program_set_uint(refit, "u_n", n);
    for (uint32_t lo = 0; lo < n; lo += REFIT_WINDOW) {
        cv_program_set_uint(refit, "u_tri_lo", lo);
        cv_program_set_uint(refit, "u_tri_hi", n - lo > REFIT_WINDOW ? lo + REFIT_WINDOW : n);
        cv_program_dispatch_1d(refit, n);
    }
    cv_gpu_timer_end(b->timer);

    cv_gpu_timer_begin(b->timer, PH_TREELET, 0);
    cv_program_set_uint(treelet, "u_n", n);
    /* The rounds' change stamps borrow `live`, which layout fills later;
     * the leaf boxes at STAGE0 + 3 are not needed after refit. */
    cv_buffer_zero(b->live);
    cv_buffer_bind(b->live, CV_BIND_TREELET_STAMPS);
    cv_buffer_bind(b->schedule, CV_BIND_TREELET_SCHEDULE);
    for (int r = 0; r < p->treelet_rounds; r++) {
        cv_buffer_zero(b->counters);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        cv_program_set_uint(treelet, "u_round", (uint32_t)r + 1);
        /* Every round restructures every subtree of at least treelet_size
         * triangles: doubling that bound per round (as Karras & Aila
         * suggest for speed) cost 4-5 % SAH on our test meshes. */
        cv_program_set_uint(treelet, "u_gamma", (uint32_t)p->treelet_size);
        cv_program_dispatch_1d(treelet, n);
    }
    cv_gpu_timer_end(b->timer);

    cv_gpu_timer_begin(b->timer, PH_COLLAPSE, 0);
    cv_buffer_bind(b->vals, CV_BIND_BUILD_VALS);
    cv_buffer_bind(b->nodes, CV_BIND_BUILD_NODES);
    cv_buffer_bind(b->offsets, CV_BIND_BUILD_OFFSETS);
    /* `live` now holds each node's count of left turns (layout.comp), and
     * the prefix sum of `starts` counts final leaves per slot: emit.comp
     * adds them into depth-first node indices. */
    cv_buffer_bind(b->live, CV_BIND_BUILD_LEFTS);
    cv_buffer_zero(b->starts);
    cv_buffer_bind(b->starts, CV_BIND_BUILD_STARTS);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    cv_program_set_uint(layout, "u_n", n);
    cv_program_dispatch_1d(layout, 2 * (uint64_t)n - 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    ok = cv_scan_exclusive(b->scan, b->starts, n, err);
    if (ok) {
        cv_buffer_bind(b->nodes, CV_BIND_BUILD_NODES);
        cv_buffer_bind(b->offsets, CV_BIND_BUILD_OFFSETS);
        cv_buffer_bind(b->live, CV_BIND_BUILD_LEFTS);
        cv_buffer_bind(b->info, CV_BIND_EMIT_INFO);
        cv_buffer_bind(b->starts, CV_BIND_EMIT_LEAVES);
        cv_buffer_bind(b->out_nodes, CV_BIND_BVH_NODES);
        cv_program_set_uint(emit, "u_n", n);
        cv_program_dispatch_1d(emit, n);
    }
    cv_gpu_timer_end(b->timer);
    if (!ok)
        return false;
    return cv_gl_check(err, "building the BVH of %u triangles", n);
}

static double half_area(const float lo[3], const float hi[3])
{
    double e[3];
    for (int i = 0; i < 3; i++)
        e[i] = hi[i] > lo[i] ? (double)hi[i] - lo[i] : 0.0;
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

/* Triangle splitting (split.h), before the build's buffers are sized: the
 * build then runs over the references, as many as the budget and the
 * build's largest buffer (2 n - 1 build nodes) allow. When no extra
 * reference comes of it, the plain build runs, as without splitting. */
static bool split_first(struct build *b, const struct cv_bvh_params *p, GLuint vertices,
                        GLuint triangles, struct cv_error *err)
{
    uint64_t most = (uint64_t)((double)p->split_budget * b->n);
    /* Beyond what the driver is known to address, the whole budget is
     * probed for (gpu/storage.h); where that fails, the references stop at
     * what is known to fit. */
    struct cv_error probe_err;
    uint64_t need = (2 * (b->n + most) - 1) * sizeof(CvBvhBuildNode);
    if (most > 0 && !cv_gpu_storage_fits(b->gpu, need, "bvh build nodes", &probe_err)) {
        uint64_t fit = (cv_gpu_storage_known(b->gpu) / sizeof(CvBvhBuildNode) + 1) / 2;
        most = fit > b->n ? (most < fit - b->n ? most : fit - b->n) : 0;
    }
    most = most < CV_BVH_COUNT_MASK - b->n ? most : CV_BVH_COUNT_MASK - b->n;
    if (most == 0)
        return true;
    uint32_t n_refs = 0;
    if (!(b->split = cv_bvh_split_create(b->gpu, b->n, (uint32_t)most, err)))
        return false;
    cv_gpu_timer_begin(b->timer, PH_SPLIT, 0);
    bool ok = cv_bvh_split_count(b->split, vertices, triangles, &n_refs, err);
    cv_gpu_timer_end(b->timer);
    if (ok && n_refs == b->n) {
        cv_bvh_split_destroy(&b->split);
    } else if (ok) {
        b->scratch += cv_bvh_split_bytes(b->split);
        b->n = n_refs;
    }
    return ok;
}

/* Slots per pass of the leaf triangles' scatter: 256 MB of output
 * (glsl/bvh/leaf_tris.comp says why). */
#define LEAF_TRIS_WINDOW ((256u << 20) / (uint32_t)sizeof(CvBvhTri))

/* A full stack would drop subtrees (glsl/bvh/traverse.glsl), so a tree
 * that needs more than the default is traced with programs compiled with
 * more: the need rounded up to STACK_STEP, so that trees of similar depth
 * share their programs. Only such trees pay for the larger stack. */
#define STACK_STEP 16
static void set_stack_size(struct cv_bvh *bvh, uint64_t n)
{
    struct cv_bvh_stats *s = &bvh->stats;
    s->stack_size = CV_BVH_STACK_SIZE;
    bvh->stack_define[0] = '\0';
    if (s->stack_need <= CV_BVH_STACK_SIZE)
        return;
    s->stack_size = (s->stack_need + STACK_STEP - 1) / STACK_STEP * STACK_STEP;
    snprintf(bvh->stack_define, sizeof(bvh->stack_define), "CV_BVH_STACK_SIZE=%u",
             s->stack_size);
    cv_info("the BVH over %llu triangles may need %u traversal stack entries: tracing it with a "
            "stack of %u instead of %d (slower)", (unsigned long long)n, s->stack_need,
            s->stack_size, CV_BVH_STACK_SIZE);
}

/* The tree's leaf triangles, scattered from reference order
 * (glsl/bvh/leaf_tris.comp says why), while `prims` still holds references.
 * The Morton keys, dead since the hierarchy, hold each reference's slot. */
static bool leaf_tris_scatter(struct build *b, struct cv_bvh *bvh, uint32_t window,
                              GLuint vertices, GLuint triangles, struct cv_error *err)
{
    if (window == 0)
        window = LEAF_TRIS_WINDOW;
    struct cv_program *slots, *scatter;
    uint32_t n = b->n;
    if (!(slots = cv_program_get(b->gpu, "bvh/leaf_slots.comp", NULL, err)) ||
        !(scatter = cv_program_get(b->gpu, "bvh/leaf_tris.comp", leaf_scatter_defs, err)) ||
        !cv_gpu_storage_fits(b->gpu, leaf_tris_bytes(n), "bvh leaf triangles", err) ||
        !(bvh->tris = own_buffer(bvh, leaf_tris_bytes(n), &bvh->tris_bytes, "bvh leaf triangles",
                                 err)))
        return false;
    cv_gpu_timer_begin(b->timer, PH_LEAF_TRIS, 0);
    cv_buffer_bind(bvh->prims, CV_BIND_BVH_PRIMS);
    cv_buffer_bind(b->keys, CV_BIND_BUILD_SLOT_OF);
    cv_program_set_uint(slots, "u_n", n);
    cv_program_dispatch_1d(slots, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    cv_buffer_bind(vertices, CV_BIND_VERTICES);
    cv_buffer_bind(triangles, CV_BIND_TRIANGLES);
    /* Unsplit, reference r is triangle r and the shader reads no ref_tris. */
    cv_buffer_bind(b->split ? cv_bvh_split_ref_tris(b->split) : b->keys, CV_BIND_SPLIT_REF_TRIS);
    cv_buffer_bind(bvh->tris, CV_BIND_BVH_TRIS);
    cv_program_set_uint(scatter, "u_n", n);
    cv_program_set_uint(scatter, "u_split", b->split != NULL);
    for (uint32_t lo = 0; lo < n; lo += window) {
        cv_program_set_uint(scatter, "u_slot_lo", lo);
        cv_program_set_uint(scatter, "u_slot_hi", n - lo > window ? lo + window : n);
        cv_program_dispatch_1d(scatter, n);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    cv_gpu_timer_end(b->timer);
    return cv_gl_check(err, "writing %u leaf triangles", n);
}

static bool build_full(struct cv_bvh *bvh, struct build *b, const struct cv_bvh_params *p,
                       GLuint vertices, GLuint triangles, struct cv_error *err)
{
    b->timer = cv_gpu_timer_create(b->gpu, &(struct cv_gpu_timer_params){
                                               .names = phase_names, .n_names = PH_COUNT});
    if (!split_first(b, p, vertices, triangles, err))
        return false;
    uint64_t n = b->n;
    if (!(b->bounds_a = scratch(b, cv_bvh_bounds_bytes(b->n), "bvh bounds", err)) ||
        !(b->bounds_b = scratch(b, 16, "bvh bounds counter", err)) ||
        !(b->keys = scratch(b, n * (MORTON_BITS > 32 ? 8 : 4), "bvh keys", err)) ||
        !(b->vals = scratch(b, n * 4, "bvh ids", err)) ||
        !(b->nodes = scratch(b, (2 * n - 1) * sizeof(CvBvhBuildNode), "bvh build nodes", err)) ||
        !(b->counters = scratch(b, (n - 1) * 4, "bvh counters", err)) ||
        !(b->offsets = scratch(b, (2 * n - 1) * 4, "bvh offsets", err)) ||
        !(b->live = scratch(b, (n - 1) * 4, "bvh left turns", err)) ||
        !(b->starts = scratch(b, n * 4, "bvh leaf starts", err)) ||
        !(b->info = scratch(b, CV_BVH_INFO_WORDS * 4, "bvh info", err)) ||
        !(b->schedule = treelet_schedule(b, p->treelet_size, err)) ||
        !(b->out_nodes = scratch(b, (n - 1) * sizeof(CvBvhNode), "bvh nodes", err)) ||
        /* layout.comp writes every slot. */
        !(bvh->prims = own_buffer(bvh, n * 4, &bvh->prims_bytes, "bvh prims", err)))
        return false;
    cv_buffer_bind(bvh->prims, CV_BIND_BVH_PRIMS);
    if (!(b->sort = cv_radix_sort_create(b->gpu, b->n, MORTON_BITS, err)) ||
        !(b->scan = cv_scan_create(b->gpu, b->n, err)))
        return false;
    b->scratch += cv_radix_sort_bytes(b->sort) + cv_scan_bytes(b->scan);
    if (b->split) {
        cv_gpu_timer_begin(b->timer, PH_SPLIT_EMIT, 0);
        bool ok = cv_bvh_split_emit(b->split, b->out_nodes, err);
        cv_gpu_timer_end(b->timer);
        if (!ok)
            return false;
    }
    if (!run_phases(b, p, vertices, triangles, err) ||
        !leaf_tris_scatter(b, bvh, p->leaf_tris_window, vertices, triangles, err))
        return false;
    if (b->split) {
        cv_gpu_timer_begin(b->timer, PH_SPLIT_REMAP, 0);
        bool ok = cv_bvh_split_remap(b->split, bvh->prims, err);
        cv_gpu_timer_end(b->timer);
        if (!ok)
            return false;
    }

    /* The one sync of the build: widening's first read-back (widen.h) also
     * brings the binary node count and the root, which joins them in
     * `info` so that it is read staged (gpu/buffer.h). Read straight from
     * the build nodes, the read took as long as that buffer was large (the
     * driver moves a buffer the host reads to host memory), and a pooled
     * buffer read directly would serve the next build's GPU work from host
     * memory (bench/RESULTS.md, "BVH build: wall time").
     * Widening's queue, stack needs and flags borrow the counters, the
     * left turns and the leaf starts, free since emit; its parents and
     * costs the offsets and the build nodes, free once the root is copied
     * (48 and 4 bytes per build node hold 16 and 4 per binary node). */
    uint32_t words[CV_BVH_INFO_WORDS];
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(b->nodes, b->info, 0, CV_BVH_INFO_ROOT * 4, sizeof(CvBvhBuildNode));
    struct cv_bvh_widen widen = {.gpu = b->gpu, .bin = b->out_nodes, .info = b->info,
                                 .queue = b->counters, .need = b->live, .flags = b->starts,
                                 .up = b->offsets, .cost = b->nodes,
                                 .n_max = (uint32_t)(n - 1), .levels = p->widen_levels};
    cv_gpu_timer_begin(b->timer, PH_WIDEN_FIND, 0);
    bool found = cv_bvh_widen_find(&widen, words, err);
    cv_gpu_timer_end(b->timer);
    if (!found)
        return false;
    uint32_t n_nodes = words[CV_BVH_INFO_NODES], n_wide = words[CV_BVH_INFO_WIDE];
    CvBvhBuildNode root;
    memcpy(&root, &words[CV_BVH_INFO_ROOT], sizeof(root));
    if (n_nodes == 0 || n_nodes > n - 1)
        return cv_fail(err, "BVH build produced %u nodes for %llu triangles", n_nodes,
                       (unsigned long long)n);
    if (n_wide == 0 || n_wide > n_nodes)
        return cv_fail(err, "BVH widening found %u nodes in a binary tree of %u", n_wide, n_nodes);
    if (!(bvh->nodes = own_buffer(bvh, (size_t)n_wide * sizeof(CvBvhNode4), &bvh->nodes_bytes,
                                  "bvh nodes", err)))
        return false;
    cv_gpu_timer_begin(b->timer, PH_WIDEN_EMIT, 0);
    bool emitted = cv_bvh_widen_emit(&widen, b->scan, n_nodes, n_wide, bvh->nodes, err);
    cv_gpu_timer_end(b->timer);
    if (!emitted)
        return false;
    if (p->keep_binary) {
        size_t kept;
        if (!(bvh->binary = own_buffer(bvh, (size_t)n_nodes * sizeof(CvBvhNode), &kept,
                                       "bvh binary nodes", err)))
            return false;
        glCopyNamedBufferSubData(b->out_nodes, bvh->binary, 0, 0,
                                 (GLsizeiptr)n_nodes * sizeof(CvBvhNode));
    }
    glMemoryBarrier(GL_ALL_BARRIER_BITS);

    struct cv_bvh_stats *s = &bvh->stats;
    double *ms[PH_COUNT] = {&s->ms_bounds, &s->ms_morton, &s->ms_sort, &s->ms_hierarchy,
                            &s->ms_refit, &s->ms_treelet, &s->ms_collapse,
                            &s->ms_split_count, &s->ms_split_emit, &s->ms_split_remap,
                            &s->ms_leaf_tris, &s->ms_widen, &s->ms_widen};
    s->ms_total = 0;
    cv_gpu_timer_collect(b->timer);
    for (int i = 0; i < PH_COUNT; i++) {
        double t = cv_gpu_timer_ms(b->timer, (unsigned)i);
        *ms[i] += t;
        s->ms_total += t;
    }
    s->ms_split = s->ms_split_count + s->ms_split_emit + s->ms_split_remap;
    float lo[3] = {root.bmin.x, root.bmin.y, root.bmin.z};
    float hi[3] = {root.bmax.x, root.bmax.y, root.bmax.z};
    double a = half_area(lo, hi);
    s->sah_cost = a > 0 ? root.bmin.w / a : 0.0;
    s->n_nodes = n_wide;
    s->n_binary_nodes = n_nodes;
    s->depth = words[CV_BVH_INFO_DEPTH];
    s->stack_need = words[CV_BVH_INFO_STACK];
    set_stack_size(bvh, n);
    s->n_refs = (uint32_t)n;
    s->bytes = (uint64_t)n_wide * sizeof(CvBvhNode4) + n * (4 + sizeof(CvBvhTri)) +
               (p->keep_binary ? (uint64_t)n_nodes * sizeof(CvBvhNode) : 0);
    s->scratch_bytes = b->scratch;
    return cv_gl_check(err, "finishing the BVH");
}

/* params, else the defaults, with the treelet size's 0 resolved */
static struct cv_bvh_params resolved_params(const struct cv_bvh_params *params)
{
    struct cv_bvh_params p = params ? *params : cv_bvh_default_params();
    if (p.treelet_size == 0)
        p.treelet_size = 7;
    return p;
}

void cv_bvh_prefetch(struct cv_gpu *gpu, const struct cv_bvh_params *params)
{
    struct cv_bvh_params p = resolved_params(params);
    /* Whether splitting adds references shows only on the GPU: with a
     * budget, both variants of the phases that read them. */
    for (int split = 0; split <= (p.split_budget > 0); split++) {
        struct phase_programs pp;
        phase_programs(&p, split, &pp);
        for (int i = 0; i < PHASE_PROGRAMS; i++)
            cv_program_request(gpu, phase_files[i], pp.defs[i]);
    }
    if (p.split_budget > 0)
        cv_bvh_split_prefetch(gpu);
    cv_radix_sort_prefetch(gpu, MORTON_BITS);
    cv_scan_prefetch(gpu);
    cv_bvh_widen_prefetch(gpu);
    cv_program_request(gpu, "bvh/leaf_slots.comp", NULL);
    cv_program_request(gpu, "bvh/leaf_tris.comp", leaf_scatter_defs);
}

bool cv_bvh_build(struct cv_gpu *gpu, GLuint vertices, GLuint triangles, uint32_t n_triangles,
                  const struct cv_bvh_params *params, struct cv_bvh **out, struct cv_error *err)
{
    *out = NULL;
    struct cv_bvh_params p = resolved_params(params);
    if (p.treelet_size < 3 || p.treelet_size > 8)
        return cv_fail(err, "BVH treelet size %d is outside 3..8", p.treelet_size);
    if (p.treelet_rounds < 0 || p.treelet_rounds > 32)
        return cv_fail(err, "BVH treelet rounds %d is outside 0..32", p.treelet_rounds);
    if (!(p.split_budget >= 0 && p.split_budget <= 4))
        return cv_fail(err, "BVH split budget %g is outside 0..4", p.split_budget);
    if (n_triangles > CV_BVH_COUNT_MASK)
        return cv_fail(err, "%u triangles are more than the BVH can hold", n_triangles);
    struct cv_bvh *bvh = cv_xcalloc(1, sizeof(*bvh));
    bvh->gpu = gpu;
    bvh->stats.stack_size = CV_BVH_STACK_SIZE;
    bool ok;
    if (n_triangles < 2) {
        ok = build_trivial(bvh, vertices, triangles, n_triangles, p.keep_binary, err);
    } else {
        cv_bvh_prefetch(gpu, &p);
        struct build b = {.gpu = gpu, .n = n_triangles};
        ok = build_full(bvh, &b, &p, vertices, triangles, err);
        build_free(&b);
    }
    if (!ok) {
        cv_error_prefix(err, "building the BVH");
        cv_bvh_destroy(&bvh);
        return false;
    }
    *out = bvh;
    return true;
}

void cv_bvh_bind(const struct cv_bvh *bvh)
{
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CV_BIND_BVH_NODES, bvh->nodes, 0,
                      (GLsizeiptr)bvh->nodes_bytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CV_BIND_BVH_PRIMS, bvh->prims, 0,
                      (GLsizeiptr)bvh->prims_bytes);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, CV_BIND_BVH_TRIS, bvh->tris, 0,
                      (GLsizeiptr)bvh->tris_bytes);
}

const char *cv_bvh_stack_define(const struct cv_bvh *bvh)
{
    return bvh && bvh->stack_define[0] ? bvh->stack_define : NULL;
}

const struct cv_bvh_stats *cv_bvh_stats(const struct cv_bvh *bvh)
{
    return &bvh->stats;
}

GLuint cv_bvh_nodes_buffer(const struct cv_bvh *bvh)
{
    return bvh->nodes;
}

GLuint cv_bvh_prims_buffer(const struct cv_bvh *bvh)
{
    return bvh->prims;
}

GLuint cv_bvh_binary_nodes_buffer(const struct cv_bvh *bvh)
{
    return bvh->binary;
}

void cv_bvh_destroy(struct cv_bvh **bvh)
{
    if (!bvh || !*bvh)
        return;
    /* The trivial tree's buffers are not the pool's: put deletes them. */
    struct cv_buffer_pool *pool = (*bvh)->gpu->scratch;
    cv_buffer_pool_put(pool, &(*bvh)->nodes);
    cv_buffer_pool_put(pool, &(*bvh)->prims);
    cv_buffer_pool_put(pool, &(*bvh)->tris);
    cv_buffer_pool_put(pool, &(*bvh)->binary);
    free(*bvh);
    *bvh = NULL;
}
