/* all_features_test.c: a scene with every feature that adds a buffer,
 * texture or define to the trace kernels (tests/data/trace/all_features.pbrt:
 * grid, cloud and homogeneous media, curves, moving shapes, alpha,
 * subsurface, measured, coated and spectral conductor materials, an
 * environment map) gets a renderer with every integrator, with and without
 * alpha and ID mattes: every stage program compiles and links. A kernel may use only so many storage blocks
 * (16 on Mesa), and features add their tables one by one: a scene that
 * uses them all together must still link, not fail with "too many storage
 * blocks". No pass is rendered: llvmpipe generates each kernel's code at
 * its first dispatch, minutes for all of these, and what the images should
 * look like is each feature's own test's job. */
#include "config.h"

#include "tests/trace/trace_test_util.h"

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("all_features.pbrt");
    tap_ok(s->warnings == 0, "the scene loads without warnings (%u)", s->warnings);
    static const struct {
        enum cv_integrator id;
        bool sdtree;   /* rlpath.method: sdtree (its own stages and images) */
        const char *name;
    } integrators[] = {{CV_INTEGRATOR_PATH, false, "path"},
                       {CV_INTEGRATOR_VOLPATH, false, "volpath"},
                       {CV_INTEGRATOR_RLPATH, false, "rlpath"},
                       {CV_INTEGRATOR_RLPATH, true, "rlpath sdtree"},
                       {CV_INTEGRATOR_BDPT, false, "bdpt"}};
    for (size_t i = 0; i < CV_ARRAY_SIZE(integrators); i++) {
        struct cv_render_params p = {.seed = 1, .integrator = integrators[i].id, .rl_mix = -1,
                                     .rl_sdtree = integrators[i].sdtree};
        struct cv_renderer *r = NULL;
        struct cv_error err = {{0}};
        tap_ok(cv_renderer_create(gpu, s, &p, &r, &err), "%s: every stage program links: %s",
               integrators[i].name, err.msg);
        cv_renderer_destroy(&r);
        /* a job's alpha, ID mattes, Cryptomatte and AOVs add the matte
         * buffers (to bdpt's own kernel: issue 27) */
        p.alpha = p.id_mattes = p.cryptomatte = p.aovs = true;
        tap_ok(cv_renderer_create(gpu, s, &p, &r, &err),
               "%s with alpha, ID mattes, Cryptomatte and AOVs: every stage program links: %s",
               integrators[i].name, err.msg);
        cv_renderer_destroy(&r);
    }
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
