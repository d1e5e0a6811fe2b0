/* tap.h: a tiny TAP producer for the C tests. Each check prints one "ok" or
 * "not ok" line; tap_done() prints the plan and returns the exit status.
 * A test that cannot run here (no GPU context) calls tap_skip_all(), which
 * prints "1..0 # SKIP reason": automake's TAP driver counts any non-zero exit,
 * 77 included, as an error. */
#ifndef CV_TESTS_TAP_H
#define CV_TESTS_TAP_H

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>

static int tap_count, tap_failed;

static inline bool tap_ok(bool cond, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
static inline bool tap_ok(bool cond, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("%sok %d - ", cond ? "" : "not ", ++tap_count);
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
    fflush(stdout);
    if (!cond)
        tap_failed++;
    return cond;
}

/* A check of a known bug: "# TODO reason" makes the TAP driver count a
 * failure as expected (XFAIL) and a pass as unexpected (XPASS, an error: the
 * TODO must go once the bug is fixed). */
static inline bool tap_todo(bool cond, const char *reason, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static inline bool tap_todo(bool cond, const char *reason, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("%sok %d - ", cond ? "" : "not ", ++tap_count);
    vprintf(fmt, ap);
    printf(" # TODO %s\n", reason);
    va_end(ap);
    fflush(stdout);
    return cond;
}

static inline void tap_diag(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static inline void tap_diag(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("# ");
    vprintf(fmt, ap);
    printf("\n");
    va_end(ap);
    fflush(stdout);
}

static inline int tap_done(void)
{
    printf("1..%d\n", tap_count);
    return tap_failed ? 1 : 0;
}

static inline int tap_skip_all(const char *reason)
{
    printf("1..0 # SKIP %s\n", reason);
    return 0;
}

#define TAP_EQ_INT(a, b, what) \
    tap_ok((long long)(a) == (long long)(b), "%s (%lld == %lld)", what, (long long)(a), (long long)(b))

#endif
