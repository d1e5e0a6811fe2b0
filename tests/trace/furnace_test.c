/* furnace_test.c: white furnace: a diffuse sphere of reflectance 1 inside a
 * uniform environment of radiance 1 reads 1 everywhere, background
 * included, with environment light reached both by light sampling and by
 * BSDF sampling (MIS). Gaussian pixel filter. */
#include "config.h"

#include "tests/trace/trace_test_util.h"

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("furnace.pbrt");
    struct cv_error err = {{0}};
    CvCamera cam = test_camera(s, 24, 24);
    struct cv_render_params p = {.seed = 11, .camera = &cam};
    struct test_image img = {0};
    const uint32_t passes[] = {16, 16, 0};
    if (tap_ok(test_render(gpu, s, &p, passes, &img, &err), "render: %s", err.msg)) {
        double dev, mean = test_mean(&img, 1.0, &dev);
        tap_ok(fabs(mean - 1) < 0.01, "mean %.5f is 1 within 1%%", mean);
        tap_ok(dev < 0.10, "every pixel within 10%% of 1 (largest deviation %.4f)", dev);
        /* the sphere must be there: the centre pixel's ray hits it */
        TAP_EQ_INT(img.counters.primary_rays, 24 * 24 * 32, "one primary ray per pixel sample");
        tap_ok(img.counters.secondary_rays > 0 && img.counters.shadow_rays > 0,
               "secondary (%llu) and shadow (%llu) rays traced",
               (unsigned long long)img.counters.secondary_rays,
               (unsigned long long)img.counters.shadow_rays);
        free(img.rgba);
    }
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
