/* knobs.h: the tuning and diagnostic knobs that cavalry-batch and the bench
 * tools take from the environment (documented in cavalry-batch(1)). The
 * library reads no environment for them: these values are passed in as
 * parameters (struct cv_bvh_params, struct cv_render_params' stage_times,
 * bdpt_slots and misses). */
#ifndef CV_CLI_KNOBS_H
#define CV_CLI_KNOBS_H

#include <stdbool.h>

#include "bvh/bvh.h"
#include "trace/render.h"

struct cv_knobs {
    /* cv_bvh_default_params() with CAVALRY_BVH_ROUNDS (0 to 32) as
     * treelet_rounds and CAVALRY_BVH_SPLIT (0 to 4) as split_budget */
    struct cv_bvh_params bvh;
    bool stage_times;   /* CAVALRY_STAGE_TIMES set, not empty and not "0" */
    /* CAVALRY_PARALLEL_COMPILE=0: programs are compiled one at a time at
     * first use (gpu/program.h), which times each one's compile alone */
    bool serial_compile;
    /* CAVALRY_BDPT_SLOTS (0 to CV_MAX_PATHS; 0, the default: automatic):
     * render params' bdpt_slots, the path slots bdpt runs in one dispatch */
    uint32_t bdpt_slots;
    /* CAVALRY_MISSES (auto, intersect or stage; a diagnostic): render
     * params' misses */
    enum cv_misses misses;
};

/* Reads the knobs; a value that is not a number in its range is warned
 * about and the default kept. */
struct cv_knobs cv_knobs_from_environment(void);

#endif
