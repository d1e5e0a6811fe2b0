/* rlpath_sd_splat_test.c: every path that rlpath's sdtree method records
 * while it trains reaches the statistics of the tree, through
 * sd_flush.comp at the end of each training pass. Rendered with mix 0, so
 * that guiding changes no path, and one path slot a pixel: the renderer
 * runs a training pass of n samples as n passes of one path a slot
 * (integrator.h: learn_path_a_slot), each of which ends with the splat of
 * its paths. The records each training iteration counts (the `rlpath
 * sdtree N: R records` line of the log) are then in proportion to its
 * samples; a splat at the iteration's end alone would count one path a
 * slot: a nineteenth of them in the last iteration of 19 spp. In a closed
 * room and in one that camera rays leave (their misses end paths in the
 * escaped stage). The passes the renderer counts show the split, and that
 * passes after training are not split. */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "base/log.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/trace/rlpath_room.h"
#include "tests/trace/trace_test_util.h"

/* The training iterations' samples under rlpath.train 28 (1, 8, then the
 * rest: rlpath_sd.c, SECOND_ITERATION_SPP), and as many passes. */
static const uint32_t iterations[] = {1, 8, 19, 0};
#define N_ITERATIONS 3
#define TRAIN_ALL 28

static void check_room(struct cv_gpu *gpu, const char *name, const char *text, size_t len,
                       uint32_t train)
{
    struct cv_error err = {{0}};
    struct cv_scene *s = NULL;
    struct cv_scene_load_params lp = {0};
    if (!tap_ok(cv_scene_load_string(name, text, len, &lp, &s, &err), "%s: loads: %s", name,
                err.msg))
        return;
    struct cv_render_params p = {.sampler = CV_SAMPLER_INDEPENDENT,
                                 .integrator = CV_INTEGRATOR_RLPATH,
                                 .rl_sdtree = true,
                                 .rl_mix = 0,
                                 .rl_train = train,
                                 .paths_per_pixel = 1,
                                 .spp = TRAIN_ALL,
                                 /* passes after training as asked: no
                                  * sub-passes of the guide's choice */
                                 .rl_choice = CV_RL_CHOICE_GUIDED};
    FILE *log = tmpfile();
    enum cv_log_level level = cv_log_get_level();
    cv_log_set_stream(log);
    cv_log_set_level(CV_LOG_DEBUG);
    struct test_image img = {0};
    bool ok = test_render(gpu, s, &p, iterations, &img, &err);
    cv_log_set_stream(NULL);
    cv_log_set_level(level);
    free(img.rgba);
    cv_scene_destroy(&s);
    if (!tap_ok(ok && log, "%s: renders: %s", name, err.msg)) {
        if (log)
            fclose(log);
        return;
    }
    /* train 28: 28 learning passes of one sample; train 8: the 8-spp pass
     * splits at the training's end into 7 learning samples and one pass of
     * 1 after training, and the 19-spp pass is not split */
    uint64_t passes = train == TRAIN_ALL ? TRAIN_ALL : 1 + 7 + 1 + 1;
    tap_ok(img.counters.passes == passes,
           "%s, train %u: %llu passes of 1 8 19 spp at one slot a pixel (want %llu)", name,
           train, (unsigned long long)img.counters.passes, (unsigned long long)passes);
    if (train != TRAIN_ALL) {
        fclose(log);
        return;
    }
    unsigned long long records[N_ITERATIONS] = {0};
    int found = 0;
    char line[1024];
    rewind(log);
    while (fgets(line, sizeof(line), log)) {
        const char *at = strstr(line, "rlpath sdtree ");
        unsigned k;
        unsigned long long n;
        if (at && sscanf(at, "rlpath sdtree %u: %llu records", &k, &n) == 2 && k >= 1 &&
            k <= N_ITERATIONS) {
            records[k - 1] = n;
            found++;
        }
    }
    fclose(log);
    /* records a sample in each iteration, against the first's (one path a
     * slot: the iteration's end splats them all) */
    double first = (double)records[0] / iterations[0], worst = 1.0;
    for (int k = 1; k < N_ITERATIONS; k++) {
        double r = first > 0 ? (double)records[k] / iterations[k] / first : 0.0;
        if (fabs(r - 1.0) > fabs(worst - 1.0) || k == 1)
            worst = r;
    }
    tap_ok(found == N_ITERATIONS && records[0] > 0 && fabs(worst - 1.0) < 0.15,
           "%s: each iteration counts records in proportion to its samples (%llu %llu %llu "
           "over 1 8 19 spp; furthest from the first's rate: %.3f of it)",
           name, records[0], records[1], records[2], worst);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    check_room(gpu, "room.pbrt", rlpath_room, sizeof(rlpath_room) - 1, TRAIN_ALL);
    check_room(gpu, "open.pbrt", rlpath_room_open, sizeof(rlpath_room_open) - 1, TRAIN_ALL);
    check_room(gpu, "room.pbrt", rlpath_room, sizeof(rlpath_room) - 1, 8);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
