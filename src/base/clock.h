/* clock.h: the monotonic clock the stages time their host work with
 * [seconds, from an arbitrary start]. */
#ifndef CV_BASE_CLOCK_H
#define CV_BASE_CLOCK_H

#include <time.h>

static inline double cv_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

#endif
