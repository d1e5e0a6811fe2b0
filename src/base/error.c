/* error.c: formatting of error messages (see error.h). */
#include <stdio.h>
#include <string.h>

#include "base/error.h"

bool cv_failv(struct cv_error *err, const char *fmt, va_list ap)
{
    if (err)
        vsnprintf(err->msg, sizeof(err->msg), fmt, ap);
    return false;
}

bool cv_fail(struct cv_error *err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    cv_failv(err, fmt, ap);
    va_end(ap);
    return false;
}

void cv_error_prefix(struct cv_error *err, const char *fmt, ...)
{
    if (!err)
        return;
    char buf[CV_ERROR_MAX];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof(buf) - 2, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    size_t p = strlen(buf);
    buf[p++] = ':';
    buf[p++] = ' ';
    size_t rest = strnlen(err->msg, sizeof(err->msg) - 1);
    if (rest > sizeof(buf) - 1 - p)
        rest = sizeof(buf) - 1 - p;
    memcpy(buf + p, err->msg, rest);
    buf[p + rest] = '\0';
    memcpy(err->msg, buf, p + rest + 1);
}

void cv_error_clear(struct cv_error *err)
{
    if (err)
        err->msg[0] = '\0';
}
