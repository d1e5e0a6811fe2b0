/* workers.h: one batch over several GPUs of a node (--gpu all, --gpu 0,1,
 * --workers N). The process the user started becomes the parent: it starts
 * one worker process per device (itself again, with --worker=GPU), hands
 * out the selected jobs one at a time, in manifest order, to whichever
 * worker asks next, and shows one progress stream made of every worker's
 * events (progress_wire.h), each job's tagged with its worker and device.
 *
 * Processes rather than threads: each GL context lives alone in its
 * process, as in a single-GPU batch (the path every test covers), a driver
 * crash or a lost device takes down one worker and not the batch, and
 * nothing in the render path has to become thread-safe. The cost is that
 * every worker parses the manifest and its scenes itself, once per worker
 * as a single process does once per batch.
 *
 * The parent gives a job to one worker only, and a worker asks for its next
 * job only when the last has ended, so every job runs once; each worker
 * still takes the job's lock (job_lock.h) against other processes on the
 * manifest. A job whose worker dies is reported failed once, by the parent;
 * the other workers render the rest. A signal to the parent goes to every
 * worker: each stops after its pass and writes its job's image marked
 * partial, as a single process does. */
#ifndef CV_BATCH_WORKERS_H
#define CV_BATCH_WORKERS_H

#include <stdbool.h>
#include <stddef.h>

#include "batch/batch.h"

/* Most workers one batch starts. */
#define CV_MAX_WORKERS 64

struct cv_workers_params {
    const int *gpus;               /* EGL device index per worker, -1: the default
                                    * choice; worker i uses gpus[i % n_gpus] */
    size_t n_gpus;
    unsigned n_workers;            /* >= 1 */
    char *const *argv;             /* the command line: argv[1 .. n_options] are its
                                    * options (getopt_long's order), then the manifest */
    int n_options;
    /* A worker's exit status as a batch status (the command line owns the
     * mapping); false for one that is none of them (a crash). */
    bool (*status_of_exit)(int code, enum cv_batch_status *status);
};

/* Runs the batch on n_workers worker processes; returns the batch's status
 * as cv_batch_run does. opt->progress is the parent's stream. */
enum cv_batch_status cv_workers_run(const char *manifest_path, const struct cv_batch_options *opt,
                                    const struct cv_workers_params *wp);

/* In a worker process (--worker): the link to the parent on standard
 * output, which then carries the progress (CV_PROGRESS_WIRE), the log and
 * the requests for jobs. Signals leave stopping to the parent. */
struct cv_worker_link *cv_worker_attach(void);

/* The batch loop's next job: the selection index k of n_jobs. Without a
 * link, next counts through them in order; with one, the parent decides.
 * False when there is none left. */
bool cv_batch_next_job(struct cv_worker_link *link, size_t n_jobs, size_t *next, size_t *k);

#endif
