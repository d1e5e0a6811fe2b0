/* rlpath_frozen_test.c: the programs of rlpath's sdtree passes after
 * training (trace/integrator.h: frozen_programs) hold no learning code, on
 * the GLSL that ships: the shade program built with CV_FROZEN, and the
 * shadow and escaped stages built without CV_RLPATH_SD (as render.c builds
 * them for those passes), use none of the training record and statistics
 * images that their learning builds use. Code that never runs still costs
 * a kernel its registers (bench/RESULTS.md, "What rlpath's passes after
 * training pay for learning"), so its absence is what the passes gain. */
#include "config.h"

#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

/* the learning images of glsl/trace/rlpath/sdtree.glsl */
/* (sd_flux where the driver has float atomics, sd_stats where not) */
static const char *const learning_images[] = {"sd_verts", "sd_counts", "sd_stats", "sd_flux"};
#define N_IMAGES 4

/* How many of the learning images program `file` built with `defines`
 * uses (-1: it did not build). */
static int images_used(struct cv_gpu *gpu, const char *file, const char *const *defines)
{
    struct cv_error err = {{0}};
    struct cv_program *p = cv_program_get(gpu, file, defines, &err);
    if (!tap_ok(p != NULL, "%s builds: %s", file, err.msg))
        return -1;
    int n = 0;
    for (int i = 0; i < N_IMAGES; i++)
        n += glGetProgramResourceIndex(p->id, GL_UNIFORM, learning_images[i]) != GL_INVALID_INDEX;
    return n;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    /* a scene of diffuse and mirror surfaces, as the Cornell box's */
#define SCENE "CV_BSDF_BASIC", "CV_NO_ENV", "CV_NO_TEXTURES", "CV_NO_HAIR", "CV_NO_LAYERED", \
              "CV_NO_COAT_CLOSED", "CV_NO_MEASURED"
    const char *shade[] = {SCENE, "CV_SHADE_BIN=0", NULL};
    const char *shade_frozen[] = {SCENE, "CV_SHADE_BIN=0", "CV_FROZEN", NULL};
    const char *stage[] = {SCENE, "CV_RLPATH_SD", NULL};
    const char *stage_frozen[] = {SCENE, NULL};
    const char *sd = "trace/rlpath/sd_shade.comp";

    int n = images_used(gpu, sd, shade);
    tap_ok(n >= 3, "sd_shade.comp: the learning build uses the records and statistics (%d of "
           "the %d learning images)", n, N_IMAGES);
    n = images_used(gpu, sd, shade_frozen);
    tap_ok(n == 0, "sd_shade.comp with CV_FROZEN uses none of them (%d)", n);
    n = images_used(gpu, "trace/shadow.comp", stage);
    tap_ok(n > 0, "shadow.comp with CV_RLPATH_SD uses learning images (%d)", n);
    n = images_used(gpu, "trace/shadow.comp", stage_frozen);
    tap_ok(n == 0, "shadow.comp as the passes after training build it uses none (%d)", n);
    n = images_used(gpu, "trace/escaped.comp", stage);
    tap_ok(n > 0, "escaped.comp with CV_RLPATH_SD uses learning images (%d)", n);
    n = images_used(gpu, "trace/escaped.comp", stage_frozen);
    tap_ok(n == 0, "escaped.comp as the passes after training build it uses none (%d)", n);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
