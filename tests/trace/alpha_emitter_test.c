/* alpha_emitter_test.c: a cut-out ("alpha") emitter lights the scene only
 * where it is not cut out, as pbrt-v4's DiffuseAreaLight::AlphaMasked
 * masks its light samples and its emission, through the real path (scene
 * loader, upload, the shipped light code) for path and bdpt (whose s = 1
 * strategy runs whether or not the light subpath began: where it ran
 * only then, as in pbrt-v4, the checker below gave 0.32, not 0.5).
 * A black 1x1 lamp faces down over a diffuse floor (a lamp that reflected
 * would light the floor again from its own opaque part alone); the
 * camera, between them, looks straight down and sees the floor alone.
 * - alpha 0: the lamp is wholly cut out: the floor is black (before the
 *   mask, light samples lit it as if whole).
 * - a 2x2 checker of alpha 1 and 0 over the lamp: the floor gets half the
 *   whole lamp's light. The view is symmetric about x = 0, which maps the
 *   checker's opaque squares onto its cut ones, so each half lights the
 *   image alike: half, in expectation, exactly.
 * - alpha 0.5: pbrt-v4 masks a point by a hash of it (half of the light
 *   samples) and passes half of the rays, whose hits it masks again: the
 *   floor gets between a quarter and a half of the whole lamp's light,
 *   by the MIS weights of the two strategies. */
#include "config.h"

#include <math.h>
#include <stdio.h>

#include "manifest/enums.h"
#include "tests/scene/scene_helpers.h"
#include "tests/trace/trace_test_util.h"

static double render_mean(struct cv_gpu *gpu, enum cv_integrator id, const char *alpha)
{
    char *text = cv_xasprintf(
        "LookAt 0 0.5 0  0 0 0  0 0 1\n"
        "Camera \"perspective\" \"float fov\" 90\n"
        "Film \"rgb\" \"integer xresolution\" 32 \"integer yresolution\" 32\n"
        "WorldBegin\n"
        "Texture \"checks\" \"float\" \"checkerboard\" \"float uscale\" 2 \"float vscale\" 2\n"
        "  \"float tex1\" 1 \"float tex2\" 0\n"
        "Texture \"ones\" \"float\" \"checkerboard\" \"float tex1\" 1 \"float tex2\" 1\n"
        "AttributeBegin\n"
        "Material \"diffuse\" \"rgb reflectance\" [0 0 0]\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [4 4 4]\n"
        "Shape \"trianglemesh\" \"point3 P\" [-0.5 1 -0.5  0.5 1 -0.5  0.5 1 0.5  -0.5 1 0.5]\n"
        "  \"point2 uv\" [0 0 1 0 1 1 0 1] \"integer indices\" [0 1 2 0 2 3] %s\n"
        "AttributeEnd\n"
        "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n"
        "Shape \"trianglemesh\" \"point3 P\" [-3 0 -3  3 0 -3  3 0 3  -3 0 3]\n"
        "  \"integer indices\" [0 1 2 0 2 3]\n",
        alpha);
    struct cv_error err = {{0}};
    struct cv_scene *s = th_load(text, false, &err);
    struct cv_render_params p = {.seed = 3, .integrator = id};
    const uint32_t passes[] = {256, 0};
    struct test_image img = {0};
    double mean = NAN;
    if (tap_ok(s && test_render(gpu, s, &p, passes, &img, &err), "%s, lamp with %s: render %s",
               cv_integrator_name(id), *alpha ? alpha : "no alpha", err.msg))
        mean = test_mean(&img, 0, NULL);
    free(img.rgba);
    cv_scene_destroy(&s);
    free(text);
    return mean;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    th_init();
    static const enum cv_integrator ids[] = {CV_INTEGRATOR_PATH, CV_INTEGRATOR_BDPT};
    for (size_t i = 0; i < sizeof(ids) / sizeof(ids[0]); i++) {
        const char *name = cv_integrator_name(ids[i]);
        /* a cut-out of ones: the same programs as the others (llvmpipe
         * builds each set once), and nothing masked */
        double whole = render_mean(gpu, ids[i], "\"texture alpha\" \"ones\"");
        double none = render_mean(gpu, ids[i], "\"float alpha\" 0");
        double checks = render_mean(gpu, ids[i], "\"texture alpha\" \"checks\"");
        double half = render_mean(gpu, ids[i], "\"float alpha\" 0.5");
        tap_ok(whole > 0.05, "%s: the whole lamp lights the floor (mean %.4f)", name, whole);
        tap_ok(none == 0, "%s: a lamp wholly cut out lights nothing (mean %.3g)", name, none);
        tap_ok(fabs(checks / whole - 0.5) < 0.01,
               "%s: a lamp half cut out in a checker gives half the light (%.4f of the whole)",
               name, checks / whole);
        tap_ok(half / whole > 0.25 && half / whole < 0.5,
               "%s: a lamp of alpha 0.5 gives between a quarter and a half (%.4f)", name,
               half / whole);
    }
    th_cleanup();
    cv_gpu_destroy(&gpu);
    return tap_done();
}
