/* signals.h: SIGINT, SIGTERM and SIGHUP ask the batch to stop after the
 * current pass; the job in flight then writes what it has as a complete image
 * marked partial, and the process exits with 128 + the signal's number, as a
 * shell reports a process killed by it. A second signal exits at once.
 * SIGPIPE is ignored: a closed stdout does not stop a render. */
#ifndef CV_BATCH_SIGNALS_H
#define CV_BATCH_SIGNALS_H

#include <stdbool.h>

void cv_signals_install(void);
/* In a worker of a multi-GPU batch (workers.h): the first signal stops it
 * after the pass, quietly (its parent speaks); later ones are ignored, since
 * a terminal sends each to the parent and its workers alike, and the parent
 * passes the first one on. */
void cv_signals_as_worker(void);
bool cv_signals_interrupted(void);
/* The signal number received first, 0 when none. */
int cv_signals_which(void);

#endif
