/* job_lock.h: an advisory lock per job, so that several processes on one
 * manifest (a farm starting N identical workers) never render the same job
 * at the same time. The lock is flock(2) on an empty file beside the job's
 * output, ".<name>.lock" in the output's folder, taken without waiting: a
 * job whose lock another process holds is skipped. The kernel drops the
 * lock when its process ends, however it ends, so a killed worker leaves
 * nothing to clean up; the file itself stays (removing it would race with
 * a worker opening it). With --resume, a worker that gets the lock checks
 * the outputs again, so a job another worker has just finished is not
 * rendered a second time. */
#ifndef CV_BATCH_JOB_LOCK_H
#define CV_BATCH_JOB_LOCK_H

#include "base/error.h"
#include "manifest/manifest.h"

enum cv_lock_status {
    CV_LOCK_TAKEN,     /* *lock holds it until cv_job_lock_release */
    CV_LOCK_BUSY,      /* another process holds it */
    CV_LOCK_FAILED,    /* the lock file could not be made: err says why */
};

struct cv_job_lock;

/* Creates the output's folder when needed, then tries the lock. */
enum cv_lock_status cv_job_lock_take(const struct cv_job *job, struct cv_job_lock **lock,
                                     struct cv_error *err);
/* Accepts NULL; clears the pointer. */
void cv_job_lock_release(struct cv_job_lock **lock);

#endif
