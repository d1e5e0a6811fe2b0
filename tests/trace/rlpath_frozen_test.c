/* rlpath_frozen_test.c: the programs of rlpath's sdtree passes after
 * training (trace/integrator.h: frozen_programs) hold no learning code, on
 * the GLSL that ships: the shade program built with CV_FROZEN, and the
 * shadow and escaped stages built without CV_RLPATH_SD (as render.c builds
 * them for those passes), use none of the training record and statistics
 * images that their learning builds use. Of the learning builds none
 * splats into the statistics: the shade bins and the escaped stage, which
 * would take longer to build with it, keep to the records, and
 * sd_flush.comp, run at the end of each training pass, splats. Code that
 * never runs still costs a kernel its registers (bench/RESULTS.md, "What
 * rlpath's passes after training pay for learning"), so its absence is
 * what the passes gain.
 * And a renderer asks the driver for those programs only where a pass will
 * run them: with rlpath.train 0 (learning in every pass), or a job whose
 * samples end within the training, no build starts that nothing uses;
 * with the default training and more samples every one is got but one:
 * the intersect stage's build of the way of starting misses anew that the
 * renderer did not choose (trace/render.c: request_all, set_misses). */
#include "config.h"

#include "base/limits.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/trace/rlpath_room.h"
#include "tests/trace/trace_test_util.h"

/* the learning images of glsl/trace/rlpath/sdtree.glsl: the records, then
 * the statistics (sd_flux where the driver has float atomics, sd_stats
 * where not) */
static const char *const learning_images[] = {"sd_verts", "sd_counts", "sd_stats", "sd_flux"};
#define N_IMAGES 4
#define N_RECORD_IMAGES 2

/* How many of the learning images program `file` built with `defines`
 * uses (-1: it did not build). */
static int images_used(struct cv_gpu *gpu, const char *file, const char *const *defines)
{
    return test_uniforms_read(gpu, file, defines, learning_images, N_IMAGES);
}

/* ... and how many of the statistics images alone. */
static int stats_used(struct cv_gpu *gpu, const char *file, const char *const *defines)
{
    return test_uniforms_read(gpu, file, defines, learning_images + N_RECORD_IMAGES,
                              N_IMAGES - N_RECORD_IMAGES);
}

/* Renders the room with sdtree, training for `train` (the render
 * parameter), in passes, in a fresh context (no program known before):
 * the context's build totals after it (requested: builds started ahead;
 * unused: those never got). false where it did not render. */
static bool requests(const struct cv_scene *s, uint32_t train, uint32_t spp,
                     const uint32_t *passes, const char *what,
                     struct cv_program_build_stats *st)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_render_params p = {.sampler = CV_SAMPLER_INDEPENDENT,
                                 .integrator = CV_INTEGRATOR_RLPATH,
                                 .rl_sdtree = true,
                                 .rl_mix = -1,
                                 .rl_train = train,
                                 .spp = spp};
    struct cv_error err = {{0}};
    struct test_image img = {0};
    bool ok = tap_ok(test_render(gpu, s, &p, passes, &img, &err), "%s: renders: %s", what,
                     err.msg);
    free(img.rgba);
    cv_program_build_stats(gpu, st);
    cv_gpu_destroy(&gpu);
    return ok;
}

int main(void)
{
    /* (the renders' contexts first: each is made current, then destroyed) */
    struct cv_error err = {{0}};
    struct cv_scene *s = NULL;
    struct cv_scene_load_params lp = {0};
    if (tap_ok(cv_scene_load_string("lobes.pbrt", rlpath_room_lobes, sizeof(rlpath_room_lobes) - 1,
                                    &lp, &s, &err),
               "load the room: %s", err.msg)) {
        /* the default training's passes after 16 spp get the frozen
         * programs, path's and the measure's of the guide's choice (its
         * sub-passes end within 64 spp: trace/guide_choice.h), and one of
         * the two ways of misses; with rlpath.train 0, or a job of 16 spp
         * (all within the default training), none is requested, so the
         * programs requested and never got (other stages' variants the
         * scene does not need) are the same in those two, and one more
         * with the default training */
        struct cv_program_build_stats always, trained, within;
        if (requests(s, CV_RL_TRAIN_ALWAYS, 0, (const uint32_t[]){1, 2, 4, 0},
                     "rlpath.train 0", &always) &&
            requests(s, 0, 80, (const uint32_t[]){16, 64, 0}, "the default training", &trained) &&
            requests(s, 0, 16, (const uint32_t[]){16, 0}, "a job of 16 spp", &within)) {
            if (!always.parallel) {
                tap_diag("no parallel compilation here: requests start no build");
            } else {
                tap_ok(trained.unused == always.unused + 1 &&
                           trained.requested > always.requested,
                       "rlpath.train 0 requests no program of the passes after training "
                       "(requested %u, unused %u; with the default training %u and %u)",
                       always.requested, always.unused, trained.requested, trained.unused);
                tap_ok(within.unused == always.unused && within.requested == always.requested,
                       "a job that ends within the training requests none either "
                       "(requested %u, unused %u)", within.requested, within.unused);
            }
        }
        cv_scene_destroy(&s);
    }
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    /* a scene of diffuse and mirror surfaces, as the Cornell box's */
#define SCENE "CV_BSDF_BASIC", "CV_NO_ENV", "CV_NO_TEXTURES", "CV_NO_HAIR", "CV_NO_LAYERED", \
              "CV_NO_COAT_CLOSED", "CV_NO_MEASURED"
    const char *shade[] = {SCENE, "CV_SHADE_BIN=0", NULL};
    const char *shade_frozen[] = {SCENE, "CV_SHADE_BIN=0", "CV_FROZEN", NULL};
    const char *stage[] = {SCENE, "CV_RLPATH_SD", NULL};
    const char *stage_frozen[] = {SCENE, NULL};
    const char *sd = "trace/rlpath/sd_shade.comp";

    int n = images_used(gpu, sd, shade), ns = stats_used(gpu, sd, shade);
    tap_ok(n == N_RECORD_IMAGES && ns == 0, "sd_shade.comp: the learning build uses the records "
           "(%d of the %d learning images), not the statistics (%d)", n, N_IMAGES, ns);
    n = images_used(gpu, sd, shade_frozen);
    tap_ok(n == 0, "sd_shade.comp with CV_FROZEN uses none of them (%d)", n);
    n = images_used(gpu, "trace/shadow.comp", stage);
    tap_ok(n > 0, "shadow.comp with CV_RLPATH_SD uses learning images (%d)", n);
    n = images_used(gpu, "trace/shadow.comp", stage_frozen);
    tap_ok(n == 0, "shadow.comp as the passes after training build it uses none (%d)", n);
    n = images_used(gpu, "trace/escaped.comp", stage);
    ns = stats_used(gpu, "trace/escaped.comp", stage);
    tap_ok(n > 0 && ns == 0, "escaped.comp with CV_RLPATH_SD uses learning images (%d), not the "
           "statistics (%d)", n, ns);
    n = images_used(gpu, "trace/escaped.comp", stage_frozen);
    tap_ok(n == 0, "escaped.comp as the passes after training build it uses none (%d)", n);
    n = images_used(gpu, "trace/rlpath/sd_flush.comp", NULL);
    ns = stats_used(gpu, "trace/rlpath/sd_flush.comp", NULL);
    tap_ok(n >= N_RECORD_IMAGES + 1 && ns >= 1, "sd_flush.comp uses the records and the "
           "statistics (%d of the %d learning images)", n, N_IMAGES);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
