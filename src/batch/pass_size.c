/* pass_size.c: see pass_size.h. */
#include <math.h>

#include "batch/pass_size.h"

uint32_t cv_next_pass_spp(uint32_t n, double seconds, double time_left)
{
    double per_spp = n > 0 ? seconds / n : 0;
    double want = per_spp > 0 ? CV_PASS_TARGET_SECONDS / per_spp : 4.0 * n;
    if (time_left > 0 && per_spp > 0)
        want = fmin(want, fmax(1.0, time_left / per_spp));
    return (uint32_t)fmax(1.0, fmin(want, 4.0 * n));
}
