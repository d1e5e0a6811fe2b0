/* nee_test.c: next-event estimation off against on. The scene
 * (tests/data/trace/oracle/nee_area_env.pbrt: a large lamp and a constant
 * environment over a grey floor and a rough conductor sphere) has only
 * lights that BSDF sampling can find, so the path tracer without light
 * sampling (render params no_nee: every emission hit at full weight) must
 * give the same image as with it and MIS. The means of the whole image and
 * of its four quadrants must agree within NEE_TOL.
 *
 * The bound: over seeds 1-4 (`nee_test SEED`) the region ratios of the two
 * renders at NEE_SPP spread by about 0.15 % (standard deviation; all within
 * 0.9977-1.0033), so NEE_TOL = 1 % is six of those and a bias of 2 % in
 * either technique fails. Keeping the MIS weight of the lamp's emission
 * hits when light sampling is off makes the bottom quadrants 0.52 of the
 * image with it. */
#include "config.h"

#include <stdio.h>

#include "tests/trace/trace_test_util.h"

#define RES 32
#define NEE_SPP 1024
#define NEE_TOL 0.01

static double region_mean(const float *img, int x0, int y0, int x1, int y1)
{
    double s = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            const float *p = img + ((size_t)y * RES + x) * 4;
            s += (p[0] + p[1] + p[2]) / 3.0;
        }
    return s / ((double)(x1 - x0) * (y1 - y0));
}

int main(int argc, char **argv)
{
    uint64_t seed = argc > 1 ? strtoull(argv[1], NULL, 10) : 7;
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("oracle/nee_area_env.pbrt");
    const uint32_t passes[] = {NEE_SPP / 2, NEE_SPP / 2, 0};
    struct test_image on = {0}, off = {0};
    struct cv_error err = {{0}};
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = seed, .camera = &cam};
    bool ok_on = tap_ok(test_render(gpu, s, &p, passes, &on, &err), "renders with light sampling: %s",
                        err.msg);
    p.no_nee = true;
    bool ok_off = tap_ok(test_render(gpu, s, &p, passes, &off, &err),
                         "renders without light sampling: %s", err.msg);
    cv_scene_destroy(&s);
    if (ok_on && ok_off) {
        tap_ok(on.counters.shadow_rays > 0 && off.counters.shadow_rays == 0,
               "shadow rays: %llu with light sampling, %llu without",
               (unsigned long long)on.counters.shadow_rays, (unsigned long long)off.counters.shadow_rays);
        const int rg[5][4] = {{0, 0, RES, RES},
                              {0, 0, RES / 2, RES / 2},
                              {RES / 2, 0, RES, RES / 2},
                              {0, RES / 2, RES / 2, RES},
                              {RES / 2, RES / 2, RES, RES}};
        static const char *const rname[5] = {"image", "top left", "top right", "bottom left",
                                             "bottom right"};
        for (int k = 0; k < 5; k++) {
            double a = region_mean(off.rgba, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
            double b = region_mean(on.rgba, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
            tap_ok(fabs(a - b) <= NEE_TOL * b && b > 0,
                   "%s: mean %.5f without light sampling, %.5f with (ratio %.4f) within %.0f%%",
                   rname[k], a, b, a / b, 100 * NEE_TOL);
        }
    }
    free(on.rgba);
    free(off.rgba);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
