/* bvh.h: the GPU BVH over a scene's triangles, built entirely in compute
 * shaders (glsl/bvh): triangle splitting (Karras & Aila 2013, split.h),
 * centroid bounds, 30-bit Morton codes, radix sort, Karras 2012 hierarchy,
 * bottom-up refit, treelet restructuring (Karras & Aila 2013), SAH leaf
 * collapsing, the binary layout and its collapse into the 4-wide tree that
 * traversal reads (widen.h; glsl/shared/bvh.h). Nothing of the tree is read
 * back to the CPU (only the split's reference count, which sizes the build,
 * and the node counts and the root's cost, which size the wide tree and
 * go into the stats).
 * Shaders trace against it with glsl/bvh/scene_buffers.glsl and
 * glsl/bvh/traverse.glsl after cv_bvh_bind(). */
#ifndef CV_BVH_BVH_H
#define CV_BVH_BVH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_bvh_params {
    int treelet_rounds;    /* default 3; 0 = plain LBVH */
    int treelet_size;      /* leaves per treelet, 3..8; default 7 (0 also means 7) */
    bool collapse_leaves;  /* SAH leaf collapse (leaves of up to 8), default true */
    /* Triangle splitting before the build (src/bvh/split.h): at most this
     * many extra references per triangle, shared by priority; 0 = off,
     * up to 4; default 0.3: scenes with long thin triangles render
     * faster, others as fast, for a somewhat longer build
     * (bench/RESULTS.md, "Triangle splitting and pooled scratch"). */
    float split_budget;
    /* Leaf slots per pass of the leaf triangles' scatter (bvh.c); 0: the
     * default, 256 MB of records. Tests make it small to run several. */
    uint32_t leaf_tris_window;
    /* Levels of widening per read-back (widen.h); 0: the default,
     * CV_BVH_WIDEN_LEVELS. Tests make it small to run several. */
    uint32_t widen_levels;
    /* Keep the binary tree that the wide one is collapsed from, for
     * cv_bvh_binary_nodes_buffer (tests and tools; 64 bytes per binary
     * node). Default false. */
    bool keep_binary;
};

/* Defaults as above. The library reads no environment: cavalry-batch and
 * the bench tools set treelet_rounds and split_budget from
 * CAVALRY_BVH_ROUNDS and CAVALRY_BVH_SPLIT (cli/knobs.h). */
struct cv_bvh_params cv_bvh_default_params(void);

struct cv_bvh_stats {
    /* Milliseconds per phase from the build's GPU timer (gpu/timer.h says
     * which clock). ms_total is their sum. ms_collapse covers collapse +
     * layout. */
    double ms_bounds, ms_morton, ms_sort, ms_hierarchy, ms_refit, ms_treelet, ms_collapse,
        ms_total;
    double ms_split;       /* triangle splitting, its read-back and remap (in ms_total) */
    /* ms_split's parts: shares and their read-back, references' boxes, remap. */
    double ms_split_count, ms_split_emit, ms_split_remap;
    double ms_leaf_tris;   /* the leaf triangle records (in ms_total) */
    /* Collapsing the binary tree into the 4-wide one (in ms_total); it
     * includes waiting for the build's one read-back (widen.h). */
    double ms_widen;
    /* SAH cost of the binary tree, before widening: sum over inner nodes
     * of 1.2 * A(node) plus over leaves of 1.0 * A(leaf) * triangles,
     * divided by A(root). */
    double sah_cost;
    uint64_t bytes;        /* GPU bytes the finished BVH keeps (nodes, prims, leaf
                            * triangles; the binary nodes when kept) */
    uint64_t scratch_bytes;/* peak GPU scratch during the build, freed after */
    uint32_t n_nodes;      /* CvBvhNode4 count of the tree traversal reads */
    uint32_t n_binary_nodes; /* CvBvhNode count of the binary tree it was collapsed from */
    uint32_t depth;        /* levels of the CvBvhNode4 tree */
    uint32_t stack_need;   /* most traversal stack entries a query can need */
    uint32_t stack_size;   /* entries of the stack that traces it: CV_BVH_STACK_SIZE,
                            * or more where stack_need is (cv_bvh_stack_define) */
    uint32_t n_refs;       /* leaf slots: the triangles plus split's extra references */
};

/* Every phase time of struct cv_bvh_stats, by name, for reports
 * (bench/stages.c, tests/bvh/bvh_bench.c): the phases in build order, then
 * split's parts (in_total false: ms_split is their sum) and the total. */
struct cv_bvh_phase {
    const char *name;
    size_t offset;   /* of its double in struct cv_bvh_stats */
    bool in_total;   /* one of the phases that ms_total adds up */
};
#define CV_BVH_N_PHASES 14
extern const struct cv_bvh_phase cv_bvh_phases[CV_BVH_N_PHASES];

static inline double cv_bvh_phase_ms(const struct cv_bvh_stats *s, const struct cv_bvh_phase *p)
{
    return *(const double *)((const char *)s + p->offset);
}

struct cv_bvh;

/* Starts compiling every program a build with params (NULL: defaults)
 * runs (gpu/program.h: cv_program_request), so the driver compiles them
 * side by side; cv_bvh_build calls it, and a caller that knows the
 * parameters earlier (before the scene is parsed) may too. */
void cv_bvh_prefetch(struct cv_gpu *gpu, const struct cv_bvh_params *params);

/* Builds over n_triangles CvTriangle of `triangles` indexing CvVertex of
 * `vertices` (glsl/shared/scene.h); the caller keeps both buffers alive and
 * unchanged while the BVH is used. params NULL: defaults. Changes buffer
 * bindings: the two scene buffers end bound at CV_BIND_VERTICES/TRIANGLES,
 * the build's stage-private slots (glsl/shared/bindings.h) and the BVH
 * slots hold scratch, so call cv_bvh_bind() before tracing. Waits for the GPU once, near the
 * end (widening reads back the node counts and the root's cost). The
 * scratch (~264 bytes per
 * triangle with the default splitting) is taken from gpu->scratch and left
 * there for the next build; cv_buffer_pool_trim(gpu->scratch) frees it
 * (scene upload keeps it or not, trace/scene_upload.c). The tree's own
 * buffers (~130 bytes per triangle) come from that pool too and go back to
 * it when the tree is destroyed, which must happen before the context's.
 * A single SSBO must hold 48 bytes per node of the build tree (2n - 1
 * nodes). Beyond the driver's advertised block size (llvmpipe: 128 MiB, n
 * near 1.39 M) that buffer is used after a probe (gpu/storage.h); NVIDIA
 * advertises 2 GiB, about 22 M.
 * Splitting makes no more references than fit. */
bool cv_bvh_build(struct cv_gpu *gpu, GLuint vertices, GLuint triangles, uint32_t n_triangles,
                  const struct cv_bvh_params *params, struct cv_bvh **out, struct cv_error *err);
/* Binds the nodes at CV_BIND_BVH_NODES and the primitive order at
 * CV_BIND_BVH_PRIMS (not the scene buffers). */
void cv_bvh_bind(const struct cv_bvh *bvh);
const struct cv_bvh_stats *cv_bvh_stats(const struct cv_bvh *bvh);
/* The define ("CV_BVH_STACK_SIZE=N") that every program tracing this tree
 * must be compiled with, or NULL where the default stack is enough (and
 * for bvh NULL). The string is the tree's. */
const char *cv_bvh_stack_define(const struct cv_bvh *bvh);
/* The GL buffers (owned by the BVH), for tests and tools: the CvBvhNode4
 * tree, the leaf slots' primitives, and the binary CvBvhNode tree (0
 * unless params.keep_binary). */
GLuint cv_bvh_nodes_buffer(const struct cv_bvh *bvh);
GLuint cv_bvh_prims_buffer(const struct cv_bvh *bvh);
GLuint cv_bvh_binary_nodes_buffer(const struct cv_bvh *bvh);

/* A new buffer of n (at least 1) CvBvhTri records in leaf order: slot i
 * holds the positions of triangle prims[i] (glsl/bvh/leaf_tris.comp; a
 * triangle index or vertex index out of range gives an all-zero record).
 * cv_bvh_build makes the tree's own; tests make them for trees of their
 * own. Returns 0 with err set on failure; the caller owns the buffer. */
GLuint cv_bvh_leaf_tris_create(struct cv_gpu *gpu, GLuint vertices, GLuint triangles,
                               GLuint prims, uint32_t n, struct cv_error *err);
/* Accepts NULL; clears the pointer. */
void cv_bvh_destroy(struct cv_bvh **bvh);

#endif
