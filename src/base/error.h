/* error.h: errors are values. A failing function fills a cv_error with a
 * message that names where it happened ("scene.pbrt:42:7: unknown material
 * \"foo\"") and returns false or NULL; only main decides to exit. */
#ifndef CV_BASE_ERROR_H
#define CV_BASE_ERROR_H

#include <stdarg.h>
#include <stdbool.h>

#if defined(__GNUC__)
#define CV_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define CV_PRINTF(f, a)
#endif

#define CV_ERROR_MAX 4096

struct cv_error {
    char msg[CV_ERROR_MAX];
};

/* Sets the message (err may be NULL) and returns false, so that a failing
 * path reads `return cv_fail(err, "...")`. */
bool cv_fail(struct cv_error *err, const char *fmt, ...) CV_PRINTF(2, 3);
bool cv_failv(struct cv_error *err, const char *fmt, va_list ap);

/* Puts context in front of an existing message: "loading x.ply: <msg>". */
void cv_error_prefix(struct cv_error *err, const char *fmt, ...) CV_PRINTF(2, 3);

void cv_error_clear(struct cv_error *err);

#endif
