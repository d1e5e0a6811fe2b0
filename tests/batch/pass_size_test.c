/* pass_size_test.c: the progressive passes' sizes (batch/pass_size.h) on
 * the CPU: a pass is sized to about CV_PASS_TARGET_SECONDS from the last
 * one's time a sample, grows at most 4x, takes at least 1 spp, and is
 * capped by a time limit's time left, so that a job with a time limit
 * overruns it by one pass at most (cavalry-batch(1), --time-limit). */
#include <stdint.h>

#include "batch/pass_size.h"
#include "tests/tap.h"

/* A job of constant cost c seconds a sample and limit L seconds, driven
 * as run_job.c drives it (first pass 1 spp); the overrun past L and the
 * passes it took. */
static double overrun(double c, double L, int *passes)
{
    double t = 0;
    uint32_t n = 1;
    *passes = 0;
    for (;;) {
        t += n * c;
        ++*passes;
        if (t >= L || *passes > 100000)
            return t - L;
        n = cv_next_pass_spp(n, n * c, L - t);
    }
}

int main(void)
{
    /* a pass of 64 spp at a hundredth of the target a sample: the next
     * takes 100 spp, the target's time */
    double t64 = 64 * (CV_PASS_TARGET_SECONDS / 100);
    tap_ok(cv_next_pass_spp(64, t64, 0) == 100, "64 spp at 1/100 of the target a sample: next %u (100)",
           cv_next_pass_spp(64, t64, 0));
    tap_ok(cv_next_pass_spp(8, 1e-6, 0) == 32, "a fast pass grows 4x at most (%u)",
           cv_next_pass_spp(8, 1e-6, 0));
    tap_ok(cv_next_pass_spp(8, 0, 0) == 32, "a pass of no measured time grows 4x (%u)",
           cv_next_pass_spp(8, 0, 0));
    tap_ok(cv_next_pass_spp(64, 64 * CV_PASS_TARGET_SECONDS, 0) == 1,
           "a pass of a target's time a sample: 1 spp next (%u)",
           cv_next_pass_spp(64, 64 * CV_PASS_TARGET_SECONDS, 0));
    tap_ok(cv_next_pass_spp(4, 1000, 0) == 1, "a very slow pass: at least 1 spp (%u)",
           cv_next_pass_spp(4, 1000, 0));
    tap_ok(cv_next_pass_spp(16, 0.016, 0.005) == 5, "time left 5 ms at 1 ms a sample: 5 spp (%u)",
           cv_next_pass_spp(16, 0.016, 0.005));
    tap_ok(cv_next_pass_spp(16, 0.016, 1e-9) == 1, "no time left: still 1 spp (%u)",
           cv_next_pass_spp(16, 0.016, 1e-9));
    /* the time limit's promise over whole jobs of many speeds */
    double worst = 0;
    int bad = 0, most = 0;
    for (double c = 1e-4; c < 3; c *= 1.7)
        for (double L = 0.05; L < 60; L *= 2.3) {
            int passes;
            double o = overrun(c, L, &passes);
            /* the first pass always runs; after it, a pass fits the time left */
            double allowed = (passes == 1 ? c : 0) + c;
            if (o > allowed + 1e-9)
                bad++;
            worst = o / c > worst ? o / c : worst;
            most = passes > most ? passes : most;
        }
    tap_ok(bad == 0, "time limits overrun by at most one sample's time (%d jobs over; worst %.2f samples)",
           bad, worst);
    tap_ok(most < 64, "a job takes few passes (at most %d)", most);
    return tap_done();
}
