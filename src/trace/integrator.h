/* integrator.h: the integrators as the renderer (render.c) sees them: a
 * table of operations per integrator. Every integrator runs the same
 * stages (generate, intersect, escaped, shade, shadow, resolve; render.c)
 * and differs in its shade programs, in buffers of its own and in work
 * after each iteration's shade stage. An integrator with no state of its
 * own (path) is data alone. */
#ifndef CV_TRACE_INTEGRATOR_H
#define CV_TRACE_INTEGRATOR_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "gpu/context.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "trace/render.h"

/* What the renderer hands an integrator's create. */
struct cv_integrator_setup {
    struct cv_gpu *gpu;
    const struct cv_scene *scene;
    const struct cv_render_params *params;
    const char *const *defines;   /* the scene's program defines, NULL-terminated
                                   * (at most CV_SCENE_DEFINES_MAX: scene_defines.h) */
    uint32_t n_paths;             /* path slots (glsl/shared/trace.h) */
    /* whole samples: the slots one dispatch runs, at most n_paths (the
     * columns of the integrator's own storage; render.c:
     * choose_wave_paths); n_paths otherwise */
    uint32_t wave_paths;
    uint32_t n_pixels;            /* pixels of the crop */
    uint32_t max_depth;           /* the render's maximum depth */
};

/* At most this many shade programs per integrator. */
#define CV_SHADE_PROGRAMS 3

struct cv_integrator_ops {
    /* Misses go through the escaped stage while the integrator learns,
     * built with escaped_define added when not NULL (else through it only
     * with an environment light, or where the renderer finds it faster:
     * render.h, enum cv_misses). */
    bool escaped_stage;
    const char *escaped_define;
    /* The shadow stage is built with shadow_define added when not NULL. */
    const char *shadow_define;
    /* The stages pass data to each other through images while the
     * integrator learns (rlpath's sdtree records): a barrier for image
     * access after every stage of a learning pass (the shade programs of
     * one iteration share none); passes that do not learn write none. */
    bool image_stages;
    /* A pass that learns gives each path slot one path at most: the
     * renderer splits a longer one into passes of paths_per_pixel samples,
     * so every path of a learning pass has ended at its pass_done.
     * rlpath's sdtree method sets it: its records wait in per-slot storage
     * until then, and where slots started their next paths within a
     * learning pass, its stages that touch that storage took several times
     * longer a ray on the GPU, more the longer the pass (bench/RESULTS.md,
     * "sdtree's learning passes of one path a slot"). */
    bool learn_path_a_slot;
    /* The stages track participating media (volpath: every stage built
     * with CV_MEDIA where the scene has media, glsl/trace/medium); else
     * media are ignored, as by pbrt-v4's path integrator. */
    bool media;
    /* The shade stage: n_shade programs, each over the hits of the
     * CV_ARGS_* slot args[k] (glsl/shared/trace.h). They share no data
     * (each path's hit is in one bin; queue slots come from atomics), so
     * they run without a barrier between them and may overlap. Program k
     * is file[k] built with the scene's defines plus define[k] (when not
     * NULL); a NULL file[k] is create's shade[k]. */
    int n_shade;
    const char *file[CV_SHADE_PROGRAMS];
    /* Whole samples (bdpt): the renderer runs shade program 0 once per
     * round of samples over the path slots (u_pass.iteration: the round;
     * each slot runs its next sample of the pass), in place of the
     * wavefront stages, which are not built (nor their queues). A round
     * runs in waves: dispatches over at most wave_paths slots each
     * (cv_integrator_setup), the program's uint uniforms u_wave_first (the
     * wave's first slot) and u_wave_paths (wave_paths) telling it which:
     * slot u_wave_first + i keeps its state in column i of the
     * integrator's own storage. max_paths: at most this many path slots,
     * and slots a wave, where the renderer chooses (0: no bound of its
     * own); resolve_define: added to the resolve stage's defines when not
     * NULL. */
    bool whole_samples;
    uint32_t max_paths;
    /* May be NULL: bytes of the integrator's own storage per path slot at
     * maximum depth max_depth (per column, for whole samples), which
     * bounds the slots a wave runs to what one storage buffer holds */
    uint64_t (*slot_bytes)(uint32_t max_depth);
    const char *resolve_define;
    const char *define[CV_SHADE_PROGRAMS];
    uint32_t args[CV_SHADE_PROGRAMS];
    /* The shade bins program k shades (bit b: bin b, trace/shade_bins.h);
     * 0: every bin. A program of bin 1 or 2 alone is built and run only
     * for scenes whose materials (or, for bin 1, media) use its bin. */
    uint32_t bins[CV_SHADE_PROGRAMS];
    /* rlpath's methods: the shade programs of bins whose materials the
     * guide never serves are built with CV_RL_UNGUIDED, without its
     * lookups (trace/shade_bins.h: cv_shade_bins_guided) */
    bool guides;
    /* The remaining operations may be NULL: no state of its own. create
     * makes the state (its buffers and programs) and fills the shade
     * programs that file leaves out; bind binds its buffers after the
     * renderer's own; after_shade queues its work after each iteration's
     * shade stage (after_shade_name: its row of CAVALRY_STAGE_TIMES);
     * destroy accepts NULL and clears the pointer. */
    bool (*create)(const struct cv_integrator_setup *s, void **state,
                   struct cv_program shade[CV_SHADE_PROGRAMS], struct cv_error *err);
    void (*bind)(const void *state);
    void (*after_shade)(const void *state);
    const char *after_shade_name;
    void (*destroy)(void **state);
    /* May be NULL. Requests the programs create will get, with the scene's
     * defines, so the driver compiles them beside the renderer's own
     * (gpu/program.h: cv_program_request). */
    void (*prefetch)(struct cv_gpu *gpu, const struct cv_render_params *p,
                     const char *const *defines);
    /* May be NULL: the integrator learns in every pass, or not at all.
     * learn_spp gives the samples per pixel after which it stops learning
     * (0: never stops); the renderer splits a pass that would cross it and
     * from it on calls set_learning(state, false) before each pass (true
     * before) and no longer queues after_shade. */
    uint32_t (*learn_spp)(const void *state);
    void (*set_learning)(void *state, bool learning);
    /* With learn_spp: learn_spp's value for a job with params p, asked
     * before the integrator exists (the programs of the passes after
     * learning are requested with the others; none where the job's
     * samples, p->spp, end within its learning, so that no build is
     * started that no pass uses). */
    uint32_t (*train_spp)(const struct cv_render_params *p);
    /* With train_spp: the passes that do not learn run shade and shadow
     * programs built without the learning code (render.c: the shade
     * programs with CV_FROZEN, the shadow stage without shadow_define,
     * whose code for the integrator only learns): code that never runs
     * still costs a kernel its registers. rlpath's sdtree method sets it;
     * Q-learning does not, whose frozen build was no faster on the GPU
     * (bench/RESULTS.md, "What rlpath's passes after training pay for
     * learning"). Both drop the escaped stage's learning code after
     * learning (escaped_stage). */
    bool frozen_programs;
    /* May be NULL: after each pass that learned, with the samples per pixel
     * done (rlpath's sdtree: splats the pass's records into the statistics
     * and, at the end of a training iteration, reads them back and refines
     * the guide); false fails the pass with err set. */
    bool (*pass_done)(void *state, uint32_t spp_done, struct cv_error *err);
};

/* The operations of integrator id (CV_RENDER_*); NULL for an unknown id. */
const struct cv_integrator_ops *cv_integrator_find(enum cv_integrator id);
/* The operations that render parameters p run: their integrator's, or a
 * variant of it that they choose (rlpath's sdtree method); NULL for an
 * unknown integrator. */
const struct cv_integrator_ops *cv_integrator_for(const struct cv_render_params *p);

#endif
