/* batch.h: runs a manifest's jobs on one GPU context. The whole manifest and
 * every scene its selected jobs name are validated before anything renders;
 * a failing job does not stop the others unless fail_fast. */
#ifndef CV_BATCH_BATCH_H
#define CV_BATCH_BATCH_H

#include <stdbool.h>

#include "batch/plan.h"
#include "batch/progress.h"
#include "gpu/context.h"

struct cv_bvh_params;
struct cv_worker_link;

struct cv_batch_options {
    const char *const *only;       /* run only jobs matching one of these fnmatch(3)
                                    * patterns; n_only 0: all */
    size_t n_only;
    struct cv_gpu_params gpu;
    bool check_only;               /* validate manifest and scenes, render nothing */
    bool dry_run;                  /* print the plan, render nothing */
    bool json;                     /* --dry-run: the plan as one JSON document */
    bool resume;                   /* skip jobs whose outputs came from the same settings */
    bool force;                    /* overwrite outputs even when resuming would skip */
    bool fail_fast;                /* stop at the first failed job */
    bool strict;                   /* scene warnings are errors */
    const char *scene_root;        /* files scenes read must lie in it; NULL: anywhere */
    unsigned shard_index, shard_count;  /* shard_count 0: no sharding */
    bool all_shards;               /* --dry-run: every shard's jobs, each with its shard */
    struct cv_plan_overrides overrides;  /* --spp, --resolution, --output-dir */
    double time_limit;             /* [s] per job, 0: only the manifest's */
    enum cv_progress_mode progress;
    const struct cv_bvh_params *bvh;  /* the scenes' BVH builds; NULL: defaults */
    bool stage_times;              /* time every render stage (trace/render.h) */
    struct cv_worker_link *worker; /* a worker of a multi-GPU batch: jobs and events
                                    * go through its parent (workers.h); NULL: none */
    bool serial_compile;           /* no compiling ahead (gpu/program.h) */
    uint32_t bdpt_slots;           /* bdpt's slots a dispatch (trace/render.h); 0: automatic */
    enum cv_misses misses;         /* where misses restart (trace/render.h); a diagnostic */
};

enum cv_batch_status {
    CV_BATCH_OK,                   /* every selected job done (or skipped) */
    CV_BATCH_JOBS_FAILED,
    CV_BATCH_INVALID,              /* manifest or a scene is invalid: nothing rendered */
    CV_BATCH_NO_GPU,
    CV_BATCH_INTERRUPTED,          /* SIGINT/SIGTERM: the job in flight wrote a partial image */
};

/* manifest_path "-": the manifest on standard input. */
enum cv_batch_status cv_batch_run(const char *manifest_path, const struct cv_batch_options *opt);

#endif
