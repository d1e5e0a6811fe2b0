/* spherical_camera_test.c: pbrt-v4's spherical camera and pbrt-v3's
 * environment camera, rendered through the real path (scene loader,
 * upload, glsl/trace/camera.glsl):
 * - Equal area: the camera sees an equal-area environment map (pbrt-v4's
 *   infinite light, looked up at its nearest texel) through the same
 *   square, so that with a box filter of radius 0.5 every sample of pixel
 *   (x, y) finds texel (x, y) and the image is the map, texel for texel.
 *   The camera is turned (Rotate before Camera) and the light by the same
 *   rotation, so the camera's transform is applied too. The map's random
 *   texels make a pixel that takes a neighbour's texel in one sample of
 *   16 miss by several per cent. Under pbrt-v4's default Gaussian filter
 *   (radius 1.5) the border pixels' samples leave the square and are
 *   mirrored back (WrapEqualAreaSquare); without it they read 0.1 off.
 * - Equirectangular (pbrt-v3's environment camera beside a pbrt-v3
 *   lat-long map in the same orientation): a pixel is the mean over its
 *   area of the map's bilinear interpolation, 3/4 of its texel and 1/8 of
 *   each neighbour along each axis (longitude wraps, the poles clamp).
 * - Inside a closed, emitting diffuse box (a furnace: radiance
 *   Le (1 - rho^(d + 1)) / (1 - rho) everywhere), path and bdpt see that
 *   radiance in every direction: bdpt joins no light vertex to a spherical
 *   camera, and its MIS weights must count no such strategy. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "manifest/enums.h"
#include "tests/rng.h"
#include "tests/scene/scene_helpers.h"
#include "tests/trace/trace_test_util.h"

enum { EA = 16, LL_W = 32, LL_H = 16 };

static uint32_t rng_state = 4242;
static float rnd(void)
{
    return (float)cv_test_lcg32(&rng_state);
}

static float *random_map(int w, int h)
{
    float *rgb = cv_xmalloc((size_t)w * h * 3 * sizeof(float));
    for (int i = 0; i < w * h * 3; i++)
        rgb[i] = 0.5f + rnd();
    return rgb;
}

static bool render(struct cv_gpu *gpu, const char *text, enum cv_integrator integrator,
                   uint32_t spp, struct test_image *img)
{
    struct cv_error err = {{0}};
    struct cv_scene *s = th_load(text, false, &err);
    struct cv_render_params p = {.seed = 7, .integrator = integrator};
    const uint32_t passes[] = {spp, 0};
    bool ok = tap_ok(s && test_render(gpu, s, &p, passes, img, &err), "%s render: %s",
                     cv_integrator_name(integrator), err.msg);
    cv_scene_destroy(&s);
    return ok;
}

/* The swap of y and z (its own inverse): camera space to the map's space. */
#define SWAP_YZ "ConcatTransform [1 0 0 0  0 0 1 0  0 1 0 0  0 0 0 1]\n"

static void test_equal_area(struct cv_gpu *gpu)
{
    float *map = random_map(EA, EA);
    th_write_pfm("ea.pfm", EA, EA, map);
    char *text = cv_xasprintf(
        "Rotate -30 1 2 3\nTranslate 0.5 0 0\n"
        "Camera \"spherical\"\n"
        "Film \"rgb\" \"integer xresolution\" %d \"integer yresolution\" %d\n"
        "PixelFilter \"box\"\nIntegrator \"path\" \"integer maxdepth\" 1\n"
        "WorldBegin\nAttributeBegin\nRotate 30 1 2 3\n" SWAP_YZ
        "LightSource \"infinite\" \"string filename\" \"ea.pfm\"\nAttributeEnd\n",
        EA, EA);
    struct test_image img = {0};
    if (render(gpu, text, CV_INTEGRATOR_PATH, 16, &img)) {
        double worst = 0;
        int wx = 0, wy = 0, off = 0;
        for (int y = 0; y < EA; y++)
            for (int x = 0; x < EA; x++)
                for (int c = 0; c < 3; c++) {
                    float want = map[3 * (y * EA + x) + c], got = img.rgba[4 * (y * EA + x) + c];
                    double d = fabs(got / want - 1);
                    off += d > 1e-4;
                    if (d > worst || isnan(got)) {
                        worst = isnan(got) ? INFINITY : d;
                        wx = x;
                        wy = y;
                    }
                }
        tap_ok(worst < 1e-4, "equal area: the image is the map texel for texel (worst %.3g "
               "at pixel %d %d; %d channels off by more than 1e-4)", worst, wx, wy, off);
    }
    free(img.rgba);
    free(text);
    /* pbrt-v4's default filter, a Gaussian of radius 1.5: a pixel is the
     * filter-weighted mean of its texel and its eight neighbours, those
     * beyond the square's edges mirrored back into it as pbrt-v4's
     * WrapEqualAreaSquare does (whole texels map to texels) */
    text = cv_xasprintf(
        "Camera \"spherical\"\n"
        "Film \"rgb\" \"integer xresolution\" %d \"integer yresolution\" %d\n"
        "Integrator \"path\" \"integer maxdepth\" 1\n"
        "WorldBegin\nAttributeBegin\n" SWAP_YZ
        "LightSource \"infinite\" \"string filename\" \"ea.pfm\"\nAttributeEnd\n",
        EA, EA);
    double w[3] = {0, 0, 0};
    const double sigma = 0.5, radius = 1.5;
    for (int k = 0; k < 3000; k++) {  /* midpoint rule over [-1.5, 1.5] */
        double x = -radius + (k + 0.5) * (2 * radius / 3000);
        double g = exp(-x * x / (2 * sigma * sigma)) - exp(-radius * radius / (2 * sigma * sigma));
        w[x < -0.5 ? 0 : x < 0.5 ? 1 : 2] += g;
    }
    double wsum = w[0] + w[1] + w[2];
    if (render(gpu, text, CV_INTEGRATOR_PATH, 1024, &img)) {
        double worst = 0, edge_worst = 0, sumd = 0;
        for (int y = 0; y < EA; y++)
            for (int x = 0; x < EA; x++)
                for (int c = 0; c < 3; c++) {
                    double want = 0;
                    for (int j = -1; j <= 1; j++)
                        for (int i = -1; i <= 1; i++) {
                            int tx = x + i, ty = y + j;
                            if (tx < 0 || tx >= EA) {
                                tx = tx < 0 ? -1 - tx : 2 * EA - 1 - tx;
                                ty = EA - 1 - ty;
                            }
                            if (ty < 0 || ty >= EA) {
                                ty = ty < 0 ? -1 - ty : 2 * EA - 1 - ty;
                                tx = EA - 1 - tx;
                            }
                            want += w[i + 1] * w[j + 1] * map[3 * (ty * EA + tx) + c];
                        }
                    want /= wsum * wsum;
                    double d = fabs(img.rgba[4 * (y * EA + x) + c] - want);
                    d = isnan(d) ? INFINITY : d;
                    worst = d > worst ? d : worst;
                    sumd += d;
                    if (x == 0 || y == 0 || x == EA - 1 || y == EA - 1)
                        edge_worst = d > edge_worst ? d : edge_worst;
                }
        tap_ok(worst < 0.01, "equal area, Gaussian filter: each pixel is the filter's mean of "
               "the texels about it, mirrored across the square's edges (worst %.4f, on the "
               "border %.4f, mean %.5f)", worst, edge_worst, sumd / (3 * EA * EA));
    }
    free(img.rgba);
    free(text);
    free(map);
}

static void test_equirect(struct cv_gpu *gpu)
{
    float *map = random_map(LL_W, LL_H);
    th_write_pfm("ll.pfm", LL_W, LL_H, map);
    char *text = cv_xasprintf(
        "Camera \"environment\"\n"
        "Film \"image\" \"integer xresolution\" %d \"integer yresolution\" %d\n"
        "PixelFilter \"box\"\nIntegrator \"path\" \"integer maxdepth\" 1\n"
        "WorldBegin\nAttributeBegin\n" SWAP_YZ
        "LightSource \"infinite\" \"string mapname\" \"ll.pfm\"\nAttributeEnd\n",
        LL_W, LL_H);
    static const float w[3] = {0.125f, 0.75f, 0.125f};
    struct test_image img = {0};
    if (render(gpu, text, CV_INTEGRATOR_PATH, 256, &img)) {
        double worst = 0, sum = 0;
        int wx = 0, wy = 0;
        for (int y = 0; y < LL_H; y++)
            for (int x = 0; x < LL_W; x++)
                for (int c = 0; c < 3; c++) {
                    double want = 0;
                    for (int j = 0; j < 3; j++)
                        for (int i = 0; i < 3; i++) {
                            int ty = y + j - 1 < 0 ? 0 : y + j - 1 >= LL_H ? LL_H - 1 : y + j - 1;
                            int tx = (x + i - 1 + LL_W) % LL_W;
                            want += w[j] * w[i] * map[3 * (ty * LL_W + tx) + c];
                        }
                    double d = fabs(img.rgba[4 * (y * LL_W + x) + c] - want);
                    sum += d;
                    if (d > worst || isnan(d)) {
                        worst = isnan(d) ? INFINITY : d;
                        wx = x;
                        wy = y;
                    }
                }
        double mean = sum / (3.0 * LL_W * LL_H);
        tap_ok(worst < 0.01 && mean < 0.002,
               "equirectangular: each pixel is its area's mean of the bilinear map (worst "
               "%.4f at pixel %d %d, mean %.5f; a texel's shift moves pixels by 0.1 or more)",
               worst, wx, wy, mean);
    }
    free(img.rgba);
    free(text);
    free(map);
}

/* Six inward faces of the box [-1, 1]^3, each emitting Le on both sides
 * and reflecting rho. */
static void test_furnace(struct cv_gpu *gpu, enum cv_integrator id, const char *mapping)
{
    const char *integrator = cv_integrator_name(id);
    const double le = 0.25, rho = 0.5;
    const int depth = 12;
    char *text = cv_xasprintf(
        "Translate 0.2 -0.3 0.1\n"
        "Camera \"spherical\" \"string mapping\" \"%s\"\n"
        "Film \"rgb\" \"integer xresolution\" 16 \"integer yresolution\" 16\n"
        "Integrator \"%s\" \"integer maxdepth\" %d\n"
        "WorldBegin\n"
        "AreaLightSource \"diffuse\" \"rgb L\" [%g %g %g] \"bool twosided\" true\n"
        "Material \"diffuse\" \"rgb reflectance\" [%g %g %g]\n"
        "Shape \"trianglemesh\" \"point3 P\" [-1 -1 -1  1 -1 -1  1 1 -1  -1 1 -1"
        "  -1 -1 1  1 -1 1  1 1 1  -1 1 1]\n"
        "  \"integer indices\" [0 1 2 0 2 3  4 6 5 4 7 6  0 4 5 0 5 1  3 2 6 3 6 7"
        "  0 3 7 0 7 4  1 5 6 1 6 2]\n",
        mapping, integrator, depth, le, le, le, rho, rho, rho);
    struct test_image img = {0};
    if (render(gpu, text, id, 256, &img)) {
        double want = le * (1 - pow(rho, depth + 1)) / (1 - rho), dev;
        double mean = test_mean(&img, want, &dev);
        tap_ok(fabs(mean / want - 1) < 0.005 && dev < 0.05 * want,
               "%s, %s camera in a furnace: radiance %.5f everywhere (mean %.5f, worst pixel "
               "off by %.4f)", integrator, mapping, want, mean, dev);
    }
    free(img.rgba);
    free(text);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    th_init();
    test_equal_area(gpu);
    test_equirect(gpu);
    test_furnace(gpu, CV_INTEGRATOR_PATH, "equalarea");
    test_furnace(gpu, CV_INTEGRATOR_BDPT, "equalarea");
    test_furnace(gpu, CV_INTEGRATOR_BDPT, "equirectangular");
    th_cleanup();
    cv_gpu_destroy(&gpu);
    return tap_done();
}
