/* knobs.c: see knobs.h. */
#include <stdlib.h>
#include <string.h>

#include "base/limits.h"
#include "base/log.h"
#include "cli/knobs.h"

/* Sets *out from environment variable `name` when it holds a number in
 * lo..hi (a whole one when `whole`); warns and leaves *out otherwise. */
static void env_number(const char *name, bool whole, double lo, double hi, double *out)
{
    const char *v = getenv(name);
    if (!v || !*v)
        return;
    char *end;
    double f = whole ? (double)strtol(v, &end, 10) : strtod(v, &end);
    if (*end == '\0' && f >= lo && f <= hi)
        *out = f;
    else
        cv_warn("%s=\"%s\" is not a number from %g to %g; ignored", name, v, lo, hi);
}

struct cv_knobs cv_knobs_from_environment(void)
{
    struct cv_knobs k = {.bvh = cv_bvh_default_params()};
    double split = k.bvh.split_budget, rounds = k.bvh.treelet_rounds;
    env_number("CAVALRY_BVH_SPLIT", false, 0, 4, &split);
    env_number("CAVALRY_BVH_ROUNDS", true, 0, 32, &rounds);
    k.bvh.split_budget = (float)split;
    k.bvh.treelet_rounds = (int)rounds;
    const char *times = getenv("CAVALRY_STAGE_TIMES");
    k.stage_times = times && *times && strcmp(times, "0") != 0;
    const char *parallel = getenv("CAVALRY_PARALLEL_COMPILE");
    k.serial_compile = parallel && strcmp(parallel, "0") == 0;
    double slots = 0;
    env_number("CAVALRY_BDPT_SLOTS", true, 0, CV_MAX_PATHS, &slots);
    k.bdpt_slots = (uint32_t)slots;
    const char *misses = getenv("CAVALRY_MISSES");
    if (misses && *misses) {
        int m = cv_name_find(&cv_misses_names, misses);
        if (m >= 0)
            k.misses = (enum cv_misses)m;
        else
            cv_warn("CAVALRY_MISSES=\"%s\" is not auto, intersect or stage; ignored", misses);
    }
    return k;
}
