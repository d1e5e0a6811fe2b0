/* knobs_test.c: cavalry-batch's knobs come from the environment in one
 * place (cli/knobs.c): CAVALRY_BVH_ROUNDS and CAVALRY_BVH_SPLIT set the BVH
 * build's treelet rounds and split budget, CAVALRY_STAGE_TIMES turns on the
 * stage timer, CAVALRY_PARALLEL_COMPILE=0 turns compiling ahead off,
 * CAVALRY_BDPT_SLOTS caps bdpt's slots a dispatch, CAVALRY_MISSES says
 * where misses start their slots' next samples; a bad
 * value is ignored (with a warning). The library's own defaults read no
 * environment. */
#include <stdlib.h>

#include "bvh/bvh.h"
#include "cli/knobs.h"
#include "tests/tap.h"

static void check_rounds(void)
{
    setenv("CAVALRY_BVH_ROUNDS", "1", 1);
    int one = cv_knobs_from_environment().bvh.treelet_rounds;
    int lib = cv_bvh_default_params().treelet_rounds;
    setenv("CAVALRY_BVH_ROUNDS", "33", 1);
    int past = cv_knobs_from_environment().bvh.treelet_rounds;
    setenv("CAVALRY_BVH_ROUNDS", "2x", 1);
    int junk = cv_knobs_from_environment().bvh.treelet_rounds;
    unsetenv("CAVALRY_BVH_ROUNDS");
    int dflt = cv_knobs_from_environment().bvh.treelet_rounds;
    tap_ok(one == 1 && past == 3 && junk == 3 && dflt == 3,
           "CAVALRY_BVH_ROUNDS: 1 -> %d, 33 -> %d, 2x -> %d, unset -> %d", one, past, junk, dflt);
    tap_ok(lib == 3, "the library's default ignores CAVALRY_BVH_ROUNDS=1: %d", lib);
}

static void check_split(void)
{
    float dflt = cv_knobs_from_environment().bvh.split_budget;
    setenv("CAVALRY_BVH_SPLIT", "0.5", 1);
    float half = cv_knobs_from_environment().bvh.split_budget;
    float lib = cv_bvh_default_params().split_budget;
    setenv("CAVALRY_BVH_SPLIT", "0", 1);
    float zero = cv_knobs_from_environment().bvh.split_budget;
    setenv("CAVALRY_BVH_SPLIT", "5", 1);
    float past = cv_knobs_from_environment().bvh.split_budget;
    setenv("CAVALRY_BVH_SPLIT", "0.3x", 1);
    float junk = cv_knobs_from_environment().bvh.split_budget;
    unsetenv("CAVALRY_BVH_SPLIT");
    tap_ok(half == 0.5f && zero == 0.0f && past == dflt && junk == dflt && dflt == 0.3f,
           "CAVALRY_BVH_SPLIT: 0.5 -> %g, 0 -> %g, 5 -> %g, 0.3x -> %g, unset -> %g", half, zero,
           past, junk, dflt);
    tap_ok(lib == 0.3f, "the library's default ignores CAVALRY_BVH_SPLIT=0.5: %g", lib);
}

static void check_stage_times(void)
{
    unsetenv("CAVALRY_STAGE_TIMES");
    bool unset = cv_knobs_from_environment().stage_times;
    setenv("CAVALRY_STAGE_TIMES", "", 1);
    bool empty = cv_knobs_from_environment().stage_times;
    setenv("CAVALRY_STAGE_TIMES", "0", 1);
    bool zero = cv_knobs_from_environment().stage_times;
    setenv("CAVALRY_STAGE_TIMES", "1", 1);
    bool one = cv_knobs_from_environment().stage_times;
    unsetenv("CAVALRY_STAGE_TIMES");
    tap_ok(!unset && !empty && !zero && one,
           "CAVALRY_STAGE_TIMES: unset %d, empty %d, 0 %d, 1 %d", unset, empty, zero, one);
}

static void check_parallel_compile(void)
{
    unsetenv("CAVALRY_PARALLEL_COMPILE");
    bool unset = cv_knobs_from_environment().serial_compile;
    setenv("CAVALRY_PARALLEL_COMPILE", "1", 1);
    bool one = cv_knobs_from_environment().serial_compile;
    setenv("CAVALRY_PARALLEL_COMPILE", "0", 1);
    bool zero = cv_knobs_from_environment().serial_compile;
    unsetenv("CAVALRY_PARALLEL_COMPILE");
    tap_ok(!unset && !one && zero, "CAVALRY_PARALLEL_COMPILE: serial when unset %d, 1 %d, 0 %d",
           unset, one, zero);
}

static void check_bdpt_slots(void)
{
    unsetenv("CAVALRY_BDPT_SLOTS");
    uint32_t unset = cv_knobs_from_environment().bdpt_slots;
    setenv("CAVALRY_BDPT_SLOTS", "1000", 1);
    uint32_t some = cv_knobs_from_environment().bdpt_slots;
    setenv("CAVALRY_BDPT_SLOTS", "-1", 1);
    uint32_t negative = cv_knobs_from_environment().bdpt_slots;
    setenv("CAVALRY_BDPT_SLOTS", "99999999", 1);
    uint32_t past = cv_knobs_from_environment().bdpt_slots;
    unsetenv("CAVALRY_BDPT_SLOTS");
    tap_ok(unset == 0 && some == 1000 && negative == 0 && past == 0,
           "CAVALRY_BDPT_SLOTS: unset -> %u, 1000 -> %u, -1 -> %u, 99999999 -> %u", unset, some,
           negative, past);
}

static void check_misses(void)
{
    unsetenv("CAVALRY_MISSES");
    enum cv_misses unset = cv_knobs_from_environment().misses;
    setenv("CAVALRY_MISSES", "stage", 1);
    enum cv_misses stage = cv_knobs_from_environment().misses;
    setenv("CAVALRY_MISSES", "intersect", 1);
    enum cv_misses isect = cv_knobs_from_environment().misses;
    setenv("CAVALRY_MISSES", "auto", 1);
    enum cv_misses aut = cv_knobs_from_environment().misses;
    setenv("CAVALRY_MISSES", "Stage", 1);
    enum cv_misses bad = cv_knobs_from_environment().misses;
    unsetenv("CAVALRY_MISSES");
    tap_ok(unset == CV_MISSES_AUTO && stage == CV_MISSES_STAGE && isect == CV_MISSES_INTERSECT &&
               aut == CV_MISSES_AUTO && bad == CV_MISSES_AUTO,
           "CAVALRY_MISSES: unset -> %s, stage -> %s, intersect -> %s, auto -> %s, Stage -> %s",
           cv_name_of(&cv_misses_names, unset), cv_name_of(&cv_misses_names, stage),
           cv_name_of(&cv_misses_names, isect), cv_name_of(&cv_misses_names, aut),
           cv_name_of(&cv_misses_names, bad));
}

int main(void)
{
    check_rounds();
    check_split();
    check_stage_times();
    check_parallel_compile();
    check_bdpt_slots();
    check_misses();
    return tap_done();
}
