/* log.c: see log.h. */
#include <stdarg.h>

#include "base/log.h"

static enum cv_log_level log_level = CV_LOG_INFO;
static FILE *log_stream;

void cv_log_set_level(enum cv_log_level level) { log_level = level; }
enum cv_log_level cv_log_get_level(void) { return log_level; }
void cv_log_set_stream(FILE *stream) { log_stream = stream; }

void cv_log(enum cv_log_level level, const char *fmt, ...)
{
    static const char *const prefix[] = {
        [CV_LOG_ERROR] = "error: ",
        [CV_LOG_WARN] = "warning: ",
        [CV_LOG_INFO] = "",
        [CV_LOG_DEBUG] = "debug: ",
    };
    if (level > log_level)
        return;
    FILE *out = log_stream ? log_stream : stderr;
    va_list ap;
    va_start(ap, fmt);
    fputs(prefix[level], out);
    vfprintf(out, fmt, ap);
    fputc('\n', out);
    va_end(ap);
}
