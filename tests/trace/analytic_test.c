/* analytic_test.c: pbrt's analytic scene: inside a diffuse sphere
 * (reflectance 0.5) with a point light of intensity pi at its centre every
 * pixel has radiance 1. The sphere is an icosphere of 1280 flat triangles
 * with analytic shading normals; its faces lie between 0.99 and 1 of the
 * radius, so the irradiance departs from pi by up to about 2 %. Checks the
 * mean within 2 % and every pixel within 20 % (64 spp); with the depth cut
 * at 1 and 2 bounces the radiance is 0.5 and 0.75. */
#include "config.h"

#include "tests/trace/trace_test_util.h"

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("analytic.pbrt");
    struct cv_error err = {{0}};
    const uint32_t samplers[2] = {CV_SAMPLER_SOBOL, CV_SAMPLER_INDEPENDENT};
    for (int k = 0; k < 2; k++) {
        struct cv_render_params p = {.seed = 7, .sampler = samplers[k]};
        struct test_image img = {0};
        const uint32_t passes[] = {32, 32, 0};
        if (!tap_ok(test_render(gpu, s, &p, passes, &img, &err), "render (%s sampler): %s",
                    k ? "independent" : "sobol", err.msg))
            continue;
        double dev, mean = test_mean(&img, 1.0, &dev);
        tap_ok(fabs(mean - 1) < 0.02, "%s: mean radiance %.4f is 1 within 2%%",
               k ? "independent" : "sobol", mean);
        tap_ok(dev < 0.20, "%s: every pixel within 20%% of 1 (largest deviation %.4f)",
               k ? "independent" : "sobol", dev);
        free(img.rgba);
    }
    for (uint32_t depth = 1; depth <= 2; depth++) {
        struct cv_render_params p = {.seed = 3, .max_depth = depth};
        struct test_image img = {0};
        const uint32_t passes[] = {32, 0};
        if (!tap_ok(test_render(gpu, s, &p, passes, &img, &err), "render at max depth %u: %s",
                    depth, err.msg))
            continue;
        double expect = depth == 1 ? 0.5 : 0.75, mean = test_mean(&img, expect, NULL);
        tap_ok(fabs(mean / expect - 1) < 0.02, "max depth %u: mean %.4f is %.2f within 2%%", depth,
               mean, expect);
        free(img.rgba);
    }
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
