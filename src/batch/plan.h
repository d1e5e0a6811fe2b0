/* plan.h: one job on its scene → the concrete render plan: film and
 * camera, samples, integrator, depth, seed, time limit, colour, outputs.
 * batch.c makes the plan of every selected job after loading the scenes and
 * before any GPU work, so that --check, --dry-run and the render see the
 * same plan and the same problems; run_job.c reads the plan and derives
 * nothing again. */
#ifndef CV_BATCH_PLAN_H
#define CV_BATCH_PLAN_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "color/color_params.h"
#include "manifest/manifest.h"
#include "scene/env_file.h"
#include "scene/relight.h"
#include "scene/scene.h"
#include "trace/render.h"

struct cv_plan_options {
    const char *manifest_path;   /* for "manifest:line:col" in messages */
    bool strict;                 /* what would be a warning about the job fails it */
    double time_limit;           /* --time-limit [seconds]; 0: none */
    bool check_color;            /* open the colour config to check the names: a
                                  * CPU cost per job, paid before any render */
    bool stage_times;            /* time every render stage (trace/render.h) */
    uint32_t bdpt_slots;         /* bdpt's slots a dispatch (trace/render.h); 0: automatic */
    enum cv_misses misses;       /* where misses restart (trace/render.h); a diagnostic */
    /* The images of the jobs' env.file, each loaded once for the batch
     * (scene/env_file.h); NULL: a job with env.file fails its plan. */
    struct cv_env_files *env_files;
};

struct cv_render_plan {
    const struct cv_job *job;    /* borrowed: the manifest outlives the plan */
    CvCamera camera;             /* the scene's, with the job's overrides, fitted
                                  * to the film; crop.xy are the pixels rendered */
    uint32_t width, height;      /* full film [pixels] */
    uint32_t spp;                /* target samples per pixel, >= 1 */
    double time_limit;           /* [seconds]: the job's or --time-limit, the
                                  * shorter; 0: none */
    enum cv_integrator integrator;
    uint32_t max_depth;          /* >= 1 */
    uint32_t seed;
    /* The scene's integrator when Cavalry renders it with another (pbrt's
     * bdpt, volpath, sppm, ...); NULL otherwise. Borrowed from the scene. */
    const char *substituted;
    struct cv_color_params color;  /* strings borrowed from the job */
    bool stage_times;            /* a diagnostic: cv_plan_options.stage_times */
    uint32_t bdpt_slots;         /* cv_plan_options.bdpt_slots */
    enum cv_misses misses;       /* cv_plan_options.misses */
    /* What --resume compares (16 hex digits): the job's settings hash
     * (manifest/job_hash.h) with the size and mtime of every file the scene
     * reads, of the effective OCIO config for PNG outputs, and Cavalry's
     * version. */
    char settings_hash[17];
    /* The job's env.* and lights.* overrides, checked against the scene:
     * applied to its light records per job (scene/relight.h), never by
     * loading it again. relit false: the scene's lights as they are. */
    bool relit;
    struct cv_relight relight;
};

/* Command-line overrides (cavalry-batch --spp, --resolution, --output-dir),
 * applied to a job as if its manifest said them, before its plan is made:
 * --dry-run shows them and the settings hash that --resume compares sees
 * them. Ranges are the manifest key table's (manifest/keys.h). */
struct cv_plan_overrides {
    uint32_t spp;                /* 0: the job's */
    uint32_t width, height;      /* [pixels]; 0: the job's */
    const char *output_dir;      /* outputs that lie in the manifest's folder (all
                                  * relative templates) go under it instead; NULL: none */
};

/* Checks the overrides against the key table's ranges; the message names
 * the flag ("--spp: ..."). */
bool cv_plan_overrides_check(const struct cv_plan_overrides *ov, struct cv_error *err);

/* Applies ov to job (manifest_dir: the folder its outputs were resolved
 * against, "" for the working folder) and updates its settings hash. */
bool cv_plan_override_job(struct cv_job *job, const char *manifest_dir,
                          const struct cv_plan_overrides *ov, struct cv_error *err);

/* Makes the plan of job on scene. Problems come back as
 * "manifest:line:col: job \"name\": ..." (the line of the key at fault,
 * else of the job), warnings go to the log; with o->strict a warning fails
 * the plan. */
bool cv_plan_make(const struct cv_job *job, const struct cv_scene *scene,
                  const struct cv_plan_options *o, struct cv_render_plan *out,
                  struct cv_error *err);

/* The renderer's parameters of a plan; .camera points into plan, which
 * must outlive their use. */
struct cv_render_params cv_plan_render_params(const struct cv_render_plan *plan);

#endif
