/* render.h: the wavefront path tracer's host API, which the batch stage
 * drives: create a renderer for a scene, add passes of samples per pixel
 * (progressive: the image is valid after any pass), resolve or read back the
 * film. All GPU work of a pass is queued without CPU read-back; counters and
 * images are the only read-backs. */
#ifndef CV_TRACE_RENDER_H
#define CV_TRACE_RENDER_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"
#include "manifest/enums.h"
#include "scene/scene.h"

struct cv_bvh_params;

/* Where a miss starts its path slot's next sample, in the passes where
 * either way renders the same image (no environment light, and not while
 * an integrator learns from misses): in the intersect stage itself, or in
 * an escaped stage after it. The first costs the traversal kernel the
 * camera's code on every ray, the second a dispatch an iteration and
 * work per miss (bench/RESULTS.md, "Misses by scene"). CV_MISSES_AUTO
 * chooses by the share of rays that left the scene so far, from the
 * second pass on, or from the first after learning for an integrator that
 * learns from misses (render.c: choose_misses). */
enum cv_misses { CV_MISSES_AUTO, CV_MISSES_INTERSECT, CV_MISSES_STAGE, CV_MISSES_COUNT };
/* their names (cavalry-batch: CAVALRY_MISSES), a manifest/enums.h table */
extern const struct cv_names cv_misses_names;

struct cv_render_params {
    /* Camera and film (scene/film.h fits one to a resolution); NULL: the
     * scene's. Read at creation only. */
    const CvCamera *camera;
    uint32_t max_depth;          /* 0: the scene's */
    uint64_t seed;               /* job seed: same seed, same image */
    enum cv_integrator integrator;  /* CV_INTEGRATOR_PATH by default */
    bool aovs;                   /* keep albedo, normal and depth per pixel */
    /* Film transparency (a job's alpha): coverage of camera rays that hit a
     * surface is the resolved alpha, and the environment seen directly adds
     * nothing to the colour (Cycles' transparent film). */
    bool alpha;
    bool id_mattes;              /* keep the object and material of sample 0's first hit */
    bool cryptomatte;            /* keep ranked (id, weight) pairs per pixel */
    enum { CV_SAMPLER_SOBOL, CV_SAMPLER_INDEPENDENT } sampler;
    /* rlpath only (grid and directions 0, a negative mix: the default, see
     * trace/rlpath.h): cells along the scene's longest axis, direction bins
     * per cell, share of guided sampling in [0, 1] (0: BSDF sampling alone,
     * as path; a zero-initialised struct asks for that). */
    uint32_t rl_grid, rl_directions;
    float rl_mix;
    /* rlpath: guide by the learned radiance less lamps seen directly
     * (rlpath.guide: indirect) instead of all of it */
    bool rl_guide_indirect;
    /* rlpath: samples per pixel during which the table learns; then the
     * guide is frozen (0: CV_RL_DEFAULT_TRAIN; CV_RL_TRAIN_ALWAYS: every
     * pass) */
    uint32_t rl_train;
    /* Samples per pixel the job will render, 0 where not known (a render
     * run pass by pass until someone stops it). Read before the render
     * starts: an integrator that learns for a number of samples builds no
     * program for the passes after learning where the job ends within it
     * (trace/integrator.h: frozen_programs). Passes past it still render
     * right, with the learning programs, which then do not learn. */
    uint32_t spp;
    /* rlpath: learn Müller et al.'s spatial-directional trees
     * (rlpath.method: sdtree, trace/rlpath_sd.h) instead of the Q-table */
    bool rl_sdtree;
    /* rlpath sdtree: the training splat's filters, CV_SD_FILTER_* bits
     * (rlpath.filter), where rl_sd_filter_set; else trace/sdtree.c's */
    bool rl_sd_filter_set;
    uint32_t rl_sd_filter;
    /* rlpath: after training, whether the passes go on guided or with
     * path's programs (trace/guide_choice.h): CV_RL_CHOICE_MEASURE (0, the
     * default) measures which reaches the same error sooner; the others
     * fix it (rlpath.fallback: false keeps guiding; CV_RL_CHOICE_UNGUIDED
     * is for tests) */
    enum { CV_RL_CHOICE_MEASURE, CV_RL_CHOICE_GUIDED, CV_RL_CHOICE_UNGUIDED } rl_choice;
    /* Paths in flight per pixel (path slots, glsl/shared/trace.h). 0: as
     * many as keep the GPU busy (CV_WAVE_PATHS in all, at most
     * CV_MAX_PATHS_PER_PIXEL), within the advertised storage-buffer size and
     * an eighth of the free GPU memory where the driver reports it. It
     * changes the order in which a pixel's samples are summed, nothing else:
     * each sample traces the same path. The automatic choice counts the
     * full film's pixels, also for a crop, so that a tile sums as the
     * whole image does (bit-identical tiles). */
    uint32_t paths_per_pixel;
    /* Time every dispatch by stage (gpu/timer.h), for cv_render_counters'
     * stage times and a per-stage log line when the renderer is destroyed:
     * a diagnostic, slower (cavalry-batch: CAVALRY_STAGE_TIMES). */
    bool stage_times;
    /* cv_renderer_create's own BVH build; NULL: cv_bvh_default_params() */
    const struct cv_bvh_params *bvh;
    /* Tests only: no next-event estimation. Every light is then found by
     * BSDF sampling alone, at full weight, so point, spot and distant
     * lights add nothing; the image of area and environment lights must
     * match the one with light sampling within noise. */
    bool no_nee;
    /* bdpt only (a test hook, as pbrt-v4's visualizestrategies): when
     * bdpt_t > 0, only strategy (bdpt_s, bdpt_t) runs, without its MIS
     * weight: its image alone (glsl/trace/bdpt/bdpt.comp). */
    uint32_t bdpt_s, bdpt_t;
    /* bdpt (whole-sample integrators): at most this many path slots in one
     * dispatch, whose subpaths the vertex store holds at once; 0: as many
     * as fit one storage buffer and a quarter of the free GPU memory (at
     * most the film's slots). A round of samples over more slots runs in
     * waves of this many (render.c: choose_wave_paths), with the same
     * image: it changes where subpaths are kept, not the samples
     * (cavalry-batch: CAVALRY_BDPT_SLOTS). */
    uint32_t bdpt_slots;
    /* a diagnostic, for benchmarks and tests: where misses start their
     * slots' next samples (enum cv_misses; CAVALRY_MISSES) */
    enum cv_misses misses;
};

/* The automatic paths_per_pixel aims at this many paths in flight: the
 * traversal stages reach their rate only with a few million rays in flight
 * (bench/RESULTS.md, "Paths in flight per pixel"). */
#define CV_WAVE_PATHS (1u << 22)
#define CV_MAX_PATHS_PER_PIXEL 8u

struct cv_renderer;

/* Uploads the scene (the renderer keeps no pointer to it), builds the BVH and
 * compiles the stage programs. */
bool cv_renderer_create(struct cv_gpu *gpu, const struct cv_scene *scene,
                        const struct cv_render_params *p, struct cv_renderer **out,
                        struct cv_error *err);

/* The same on a scene already uploaded with its BVH built
 * (trace/scene_upload.h: cv_scene_gpu_create from this scene, or from one
 * that differs only in camera and render settings, as a job's overrides
 * make). The renderer borrows gs, which must outlive it; camera, film,
 * filter, queues and the rlpath table stay the renderer's own. */
struct cv_scene_gpu;
bool cv_renderer_create_shared(struct cv_gpu *gpu, const struct cv_scene_gpu *gs,
                               const struct cv_scene *scene, const struct cv_render_params *p,
                               struct cv_renderer **out, struct cv_error *err);

/* Starts compiling the stage programs a render of scene with p will use
 * (gpu/program.h: cv_program_request), before its upload and BVH build, so
 * the driver compiles while they run. A BVH that needs a deeper traversal
 * stack is traced with programs compiled at create. Nothing to fail: errors
 * show at create. */
void cv_renderer_prefetch(struct cv_gpu *gpu, const struct cv_scene *scene,
                          const struct cv_render_params *p);

/* Adds spp samples per pixel, continuing the pixel sample sequences where the
 * last pass stopped. Queues GPU work only. */
bool cv_renderer_pass(struct cv_renderer *r, uint32_t spp, struct cv_error *err);

uint32_t cv_renderer_spp_done(const struct cv_renderer *r);

/* Rendered pixels of the crop: width and height of the film buffers. */
void cv_renderer_size(const struct cv_renderer *r, uint32_t *width, uint32_t *height);

/* Totals since creation: rays traced by kind and GPU time of all passes
 * [milliseconds] (a timer row around each pass, gpu/timer.h). Reading
 * waits for the GPU. */
struct cv_render_counters {
    uint64_t primary_rays, secondary_rays, shadow_rays;
    uint64_t path_slots;     /* paths in flight at most: pixels times paths_per_pixel */
    uint64_t wave_slots;     /* whole samples (bdpt): slots a dispatch runs (render_params'
                              * bdpt_slots); path_slots otherwise */
    uint64_t iterations;     /* bounce iterations of the wave (paths are regenerated) */
    /* passes run: cv_renderer_pass's, each split where the learning
     * integrator's training ends and, for one that asks for it
     * (integrator.h: learn_path_a_slot), into passes of one path a slot */
    uint64_t passes;
    /* radiance samples and path throughputs dropped for a NaN or infinite
     * value since the renderer was made (glsl/trace/common.glsl:
     * cv_film_reject): 0 unless a bug; the caller reports any */
    uint64_t nonfinite_samples;
    /* closest-hit rays (primary and secondary) that left the scene */
    uint64_t missed_rays;
    /* the last pass started misses' next samples in an escaped stage
     * (enum cv_misses), not in the intersect stage */
    bool escaped_stage;
    /* rlpath: the passes after training run path's programs (params'
     * rl_choice, trace/guide_choice.h) */
    bool unguided;
    /* rlpath: the choice was measured, and its figures
     * (cv_guide_choice_measures): relative squared error a sample and GPU
     * milliseconds a sample, guided [0] and path's [1], and the test's z */
    bool choice_measured;
    double choice_err[2], choice_ms[2], choice_z;
    double gpu_ms;
    /* With params' stage_times: GPU time of the closest-hit (intersect)
     * and any-hit (shadow) stages over the same passes; else 0. The part of
     * intersect_ms spent in the first iteration of each pass, whose rays are
     * all camera rays (n_pixels * min(spp, paths_per_pixel) of them): when
     * no pass has more spp than paths_per_pixel, no path is regenerated and
     * the other iterations trace bounce rays alone. */
    double intersect_ms, shadow_ms, intersect_first_ms;
    /* The same for each pass's second iteration: with no path regenerated,
     * its rays are all the first bounces of the pass's camera rays, traced
     * as one wave. */
    double first_bounce_ms;
    uint64_t first_bounce_rays;
};
bool cv_renderer_counters(struct cv_renderer *r, struct cv_render_counters *c,
                          struct cv_error *err);

/* A storage buffer of one vec4 per pixel of the crop (linear Rec.709 RGB =
 * sum / weight, alpha 1), row-major, top row first, for the colour stage.
 * Owned by the renderer, valid until the next resolve or destroy. NULL on
 * error. */
struct cv_buf;
const struct cv_buf *cv_renderer_resolve(struct cv_renderer *r, struct cv_error *err);

/* The same for the colour stage: with alpha, colour with the alpha divided
 * out (straight, as PNG stores it; black where alpha is 0); otherwise
 * cv_renderer_resolve's. */
const struct cv_buf *cv_renderer_resolve_display(struct cv_renderer *r, struct cv_error *err);

/* The matte words of every path slot (glsl/shared/trace.h: CV_MATTE_*),
 * stride uints a slot, and each slot's filter weight; slot s belongs to
 * crop pixel s % n_pixels. For renderers made with alpha, id_mattes or
 * cryptomatte. Reads back from the GPU: once per job. Free with
 * cv_matte_slots_free. */
struct cv_matte_slots {
    uint32_t *words;
    float *weight;
    uint32_t stride, slots_per_pixel, n_pixels;
};
bool cv_renderer_read_matte_slots(struct cv_renderer *r, struct cv_matte_slots *out,
                                  struct cv_error *err);
void cv_matte_slots_free(struct cv_matte_slots *m);

/* CPU copies: rgba 4 floats per pixel; albedo3 and normal3 3 floats, depth1
 * one (camera distance to the first hit, 0 where the ray escaped); the AOV
 * pointers may be NULL, and must be when the renderer was made without
 * aovs. Buffers hold width * height pixels (cv_renderer_size). */
bool cv_renderer_read(struct cv_renderer *r, float *rgba, float *albedo3, float *normal3,
                      float *depth1, struct cv_error *err);

/* Accepts NULL; clears the pointer. */
void cv_renderer_destroy(struct cv_renderer **r);

#endif
