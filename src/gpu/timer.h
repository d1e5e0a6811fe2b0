/* timer.h: GPU time of named dispatches and phases, the one timing facility
 * of the GPU stages. A timer is made with a table of row names (a stage's
 * dispatches, or a build's phases); the work between cv_gpu_timer_begin and
 * cv_gpu_timer_end adds its time to its row and, optionally, to a slot of
 * that row (the iteration of a pass, say). cv_gpu_timer_report logs every
 * row that ran in one format.
 *
 * The clock: GL_TIMESTAMP queries around the scope, read when collected, so
 * timing adds no wait while work is queued (each scope still costs two
 * queries: time every dispatch only as a diagnostic). Software renderers
 * (llvmpipe) report no time for queries around compute work, so there the
 * host clock is read after glFinish at both ends instead, which serializes.
 *
 * A NULL timer is off: every function accepts it and does nothing (reads
 * return 0), so a stage can mark its scopes unconditionally. */
#ifndef CV_GPU_TIMER_H
#define CV_GPU_TIMER_H

#include <stdbool.h>

#include "gpu/context.h"

struct cv_gpu_timer_params {
    const char *const *names;  /* n_names row names, borrowed for the timer's life */
    unsigned n_names;
    unsigned n_slots;          /* slots per row, 0: none */
};

struct cv_gpu_timer;

/* Needs the context current; never fails. */
struct cv_gpu_timer *cv_gpu_timer_create(const struct cv_gpu *gpu,
                                         const struct cv_gpu_timer_params *p);

/* Opens a scope of `row`, counted also in `slot` when slot < n_slots.
 * Scopes do not nest: one is open at a time. */
void cv_gpu_timer_begin(struct cv_gpu_timer *t, unsigned row, unsigned slot);
/* Closes the open scope. */
void cv_gpu_timer_end(struct cv_gpu_timer *t);

/* Adds the scopes closed so far to their rows; waits for the GPU to reach
 * their ends (not for use between a stage's dispatches). */
void cv_gpu_timer_collect(struct cv_gpu_timer *t);

/* Milliseconds collected for a row, for one slot of it, and whether any of
 * its scopes ran. */
double cv_gpu_timer_ms(const struct cv_gpu_timer *t, unsigned row);
double cv_gpu_timer_slot_ms(const struct cv_gpu_timer *t, unsigned row, unsigned slot);
bool cv_gpu_timer_ran(const struct cv_gpu_timer *t, unsigned row);

/* Collects, then logs (info) one line per row with time: `what`, the row's
 * name, its milliseconds and its share of all rows' time. */
void cv_gpu_timer_report(struct cv_gpu_timer *t, const char *what);

/* Accepts NULL; clears the pointer. Needs the context current. */
void cv_gpu_timer_destroy(struct cv_gpu_timer **t);

#endif
