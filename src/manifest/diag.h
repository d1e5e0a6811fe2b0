/* diag.h: collects every problem found in a manifest, so that the user sees
 * all of them at once instead of fixing one per run. Each message carries
 * the 1-based line and column it is about; cv_diag_finish() sorts them into
 * document order, drops exact repeats (a mapping merged into several jobs
 * would otherwise report the same bad key once per job) and joins them,
 * newline-separated, into a cv_error. */
#ifndef CV_MANIFEST_DIAG_H
#define CV_MANIFEST_DIAG_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

struct cv_diag_msg {
    size_t line, col;     /* 1-based; 0 sorts first (messages about the file) */
    size_t seq;           /* order of discovery, keeps the sort stable */
    char *text;           /* "file:line:col: message", owned */
};

struct cv_diag {
    const char *file;     /* borrowed: the manifest path as the user gave it */
    struct cv_diag_msg *msgs;
    size_t n, cap;
};

/* Adds "file:line:col: <fmt>". */
void cv_diag_add(struct cv_diag *d, size_t line, size_t col, const char *fmt, ...)
    CV_PRINTF(4, 5);

/* True when nothing was reported. Otherwise fills err with all messages
 * (truncated with a count of the rest when they do not fit) and returns
 * false. Frees the messages either way. */
bool cv_diag_finish(struct cv_diag *d, struct cv_error *err);

void cv_diag_free(struct cv_diag *d);

#endif
