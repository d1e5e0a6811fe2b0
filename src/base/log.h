/* log.h: the program's log. Messages go to stderr (or a set stream) with a
 * level; -q and -v move the threshold. */
#ifndef CV_BASE_LOG_H
#define CV_BASE_LOG_H

#include <stdio.h>

#include "base/error.h"

enum cv_log_level {
    CV_LOG_ERROR = 0,
    CV_LOG_WARN,
    CV_LOG_INFO,
    CV_LOG_DEBUG,
};

void cv_log_set_level(enum cv_log_level level);
enum cv_log_level cv_log_get_level(void);
/* stream NULL restores stderr. */
void cv_log_set_stream(FILE *stream);
void cv_log(enum cv_log_level level, const char *fmt, ...) CV_PRINTF(2, 3);

#define cv_error_log(...) cv_log(CV_LOG_ERROR, __VA_ARGS__)
#define cv_warn(...) cv_log(CV_LOG_WARN, __VA_ARGS__)
#define cv_info(...) cv_log(CV_LOG_INFO, __VA_ARGS__)
#define cv_debug(...) cv_log(CV_LOG_DEBUG, __VA_ARGS__)

#endif
