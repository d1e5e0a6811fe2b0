/* run_job.h: one job, start to finish: plan → renderer → passes →
 * colour → files. */
#ifndef CV_BATCH_RUN_JOB_H
#define CV_BATCH_RUN_JOB_H

#include <stdbool.h>
#include <stdint.h>

#include "batch/batch.h"
#include "batch/plan.h"
#include "batch/progress.h"
#include "gpu/context.h"
#include "manifest/manifest.h"
#include "scene/scene.h"
#include "trace/scene_upload.h"

/* Why a job stopped: its image's cavalry.status (cv_job_status_name). */
enum cv_job_stop {
    CV_STOP_COMPLETE,              /* the spp target reached */
    CV_STOP_SIGNAL,                /* "partial": SIGTERM/SIGINT */
    CV_STOP_TIME_LIMIT,            /* "time-limit": time_limit / --time-limit */
};

const char *cv_job_status_name(enum cv_job_stop stop);

struct cv_job_result {
    uint32_t spp;                  /* samples per pixel rendered */
    double seconds;                /* wall clock of cv_run_job: compile, render, write */
    double render_seconds;         /* wall clock of the render passes */
    bool partial;                  /* stopped before the spp target */
    enum cv_job_stop stop;         /* why it stopped */
    char *outputs[2];              /* the files written (one per format); owned */
    size_t n_outputs;
    uint64_t nonfinite;            /* samples left out for a NaN or infinite value (a bug) */
    char *warning;                 /* owned; NULL: none. What the job's events report
                                    * as its detail: the nonfinite count */
};

/* Frees the result's outputs; the result may be reused after. */
void cv_job_result_clear(struct cv_job_result *r);

/* Renders and writes the job of plan. gs: its scene uploaded with its BVH
 * (cv_scene_gpu_create), shared by the scene's jobs; the plan's camera
 * applies on top. */
bool cv_run_job(struct cv_gpu *gpu, const struct cv_render_plan *plan,
                const struct cv_scene *scene, const struct cv_scene_gpu *gs,
                struct cv_progress *progress, struct cv_job_result *result,
                struct cv_error *err);

/* Whether every output of the plan's job exists, is complete (not
 * "partial" nor "time-limit"), decodes fully, and was rendered from the same
 * settings (the plan's settings hash in its metadata). */
bool cv_job_outputs_current(const struct cv_render_plan *plan);

#endif
