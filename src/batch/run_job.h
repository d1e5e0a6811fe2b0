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

struct cv_job_result {
    uint32_t spp;                  /* samples per pixel rendered */
    double seconds;                /* wall clock of the whole job */
    bool partial;                  /* stopped by a signal */
    char written[1024];            /* the files written, space-separated */
};

/* Renders and writes the job of plan. gs: its scene uploaded with its BVH
 * (cv_scene_gpu_create), shared by the scene's jobs; the plan's camera
 * applies on top. */
bool cv_run_job(struct cv_gpu *gpu, const struct cv_render_plan *plan,
                const struct cv_scene *scene, const struct cv_scene_gpu *gs,
                struct cv_progress *progress, struct cv_job_result *result,
                struct cv_error *err);

/* Whether every output of the job exists, is complete, and was rendered
 * from the same settings (the settings hash in its metadata). */
bool cv_job_outputs_current(const struct cv_job *job);

#endif
