/* signals.h: SIGINT and SIGTERM ask the batch to stop after the current
 * pass; the job in flight then writes what it has as a complete image marked
 * partial. A second signal of either kind exits at once. */
#ifndef CV_BATCH_SIGNALS_H
#define CV_BATCH_SIGNALS_H

#include <stdbool.h>

void cv_signals_install(void);
bool cv_signals_interrupted(void);

#endif
