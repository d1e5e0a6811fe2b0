/* pass_size.h: how many samples per pixel the next progressive pass of a
 * job takes. Passes are sized to about CV_PASS_TARGET_SECONDS each, so that
 * progress, interruption and time limits stay responsive while passes are
 * long enough for path regeneration to keep the GPU's wave full (a pass
 * ends with a tail of few long paths). Shared by the batch and the
 * benchmark, so that the benchmark times what a job does. */
#ifndef CV_BATCH_PASS_SIZE_H
#define CV_BATCH_PASS_SIZE_H

#include <stdint.h>

/* Longer passes pay the tail less often (bench/RESULTS.md, "Longer
 * passes"); a signal still waits for one pass at most. */
#define CV_PASS_TARGET_SECONDS 2.0

/* The next pass after one of n spp that took seconds; time_left > 0 caps it
 * to the time a limit leaves (at least 1 spp). Grows at most 4x a pass. */
uint32_t cv_next_pass_spp(uint32_t n, double seconds, double time_left);

#endif
