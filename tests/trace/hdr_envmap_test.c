/* hdr_envmap_test.c: environment maps brighter than half floats hold
 * (65504), written as float EXRs and loaded through the scene loader.
 * - A uniform map of 70000 over a diffuse plane (reflectance 0.5) seen
 *   from above: the plane's radiance is 0.5 * 70000 for any mapping.
 * - A map of 1 with a "sun" of 70000 against the same map divided by 100
 *   with L 100: the same image (the same samples; the importance
 *   distribution is the same up to scale when it sees the true values).
 * - The loaded texel and the map's average (the light's selection power)
 *   read back exactly. */
#include "config.h"

#include "output/exr_write.h"
#include "tests/output/output_helpers.h"
#include "tests/trace/trace_test_util.h"

enum { MAP_W = 16, MAP_H = 8, SUN_X = 5, SUN_Y = 2 };
#define SUN 70000.0f

/* A lat-long map of `sky` with, where sun > 0, a 2x1 block of `sun` at
 * (SUN_X, SUN_Y): upper hemisphere, away from the seam and the poles. */
static bool write_map(const char *path, float sky, float sun, struct cv_error *err)
{
    float rgba[MAP_W * MAP_H * 4];
    for (int i = 0; i < MAP_W * MAP_H; i++) {
        int x = i % MAP_W, y = i / MAP_W;
        float v = sun > 0 && y == SUN_Y && (x == SUN_X || x == SUN_X + 1) ? sun : sky;
        for (int c = 0; c < 3; c++)
            rgba[4 * i + c] = v;
        rgba[4 * i + 3] = 1;
    }
    struct cv_exr_params p = {.rgba = rgba, .width = MAP_W, .height = MAP_H, .use_float = true,
                              .compression = CV_EXR_ZIP};
    return cv_exr_write(path, &p, err);
}

static struct cv_scene *plane_under(const char *dir, const char *map, float L)
{
    char *name = cv_xasprintf("%s/scene.pbrt", dir);
    char *text = cv_xasprintf(
        "LookAt 0 0 5  0 0 0  0 1 0\n"
        "Camera \"perspective\" \"float fov\" [ 20 ]\n"
        "Film \"rgb\" \"integer xresolution\" [ 8 ] \"integer yresolution\" [ 8 ]\n"
        "Integrator \"path\" \"integer maxdepth\" [ 1 ]\n"
        "WorldBegin\n"
        "LightSource \"infinite\" \"string mapname\" \"%s\" \"rgb L\" [ %g %g %g ]\n"
        "Material \"diffuse\" \"rgb reflectance\" [ 0.5 0.5 0.5 ]\n"
        "Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3 ]\n"
        "  \"point3 P\" [ -10 -10 0  10 -10 0  10 10 0  -10 10 0 ]\n",
        map, L, L, L);
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    tap_ok(cv_scene_load_string(name, text, strlen(text), &lp, &s, &err), "load with %s: %s",
           map, s ? "yes" : err.msg);
    free(name);
    free(text);
    return s;
}

static bool render(struct cv_gpu *gpu, const struct cv_scene *s, struct test_image *img)
{
    struct cv_error err = {{0}};
    struct cv_render_params p = {.seed = 11};
    const uint32_t passes[] = {64, 0};
    return tap_ok(s && test_render(gpu, s, &p, passes, img, &err), "render: %s",
                  s ? err.msg : "no scene");
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    char *dir = scratch_dir("hdr");
    struct cv_error err = {{0}};
    char *uniform = cv_xasprintf("%s/uniform.exr", dir), *sun = cv_xasprintf("%s/sun.exr", dir),
         *sun100 = cv_xasprintf("%s/sun100.exr", dir);
    if (!tap_ok(write_map(uniform, SUN, 0, &err) && write_map(sun, 1, SUN, &err) &&
                    write_map(sun100, 0.01f, SUN / 100, &err),
                "float EXR maps written: %s", err.msg))
        goto out;

    struct cv_scene *s = plane_under(dir, "uniform.exr", 1);
    struct test_image img = {0};
    if (render(gpu, s, &img)) {
        double dev, mean = test_mean(&img, 0.5 * SUN, &dev);
        tap_ok(fabs(mean / (0.5 * SUN) - 1) < 0.01,
               "uniform map of %g: the plane's radiance %.1f is %g within 1%%", SUN, mean,
               0.5 * SUN);
        tap_ok(dev < 0.02 * 0.5 * SUN, "uniform map: every pixel within 2%% (largest deviation %.1f)",
               dev);
    }
    free(img.rgba);
    cv_scene_destroy(&s);

    s = plane_under(dir, "sun.exr", 1);
    struct cv_scene *s100 = plane_under(dir, "sun100.exr", 100);
    if (s && s100 && s->n_textures == 1) {
        /* what the renderer and the light's sampling read */
        float t[4], avg[4];
        const CvTexture *tx = &s->textures[0];
        cv_scene_texel(s, tx, (uint64_t)SUN_Y * MAP_W + SUN_X, t);
        uint64_t last = 0;
        for (uint32_t w = tx->width, h = tx->height; w > 1 || h > 1;) {
            last += (uint64_t)w * h;
            w = w > 1 ? w / 2 : 1;
            h = h > 1 ? h / 2 : 1;
        }
        cv_scene_texel(s, tx, last, avg);
        double want = (2.0 * SUN + (MAP_W * MAP_H - 2)) / (MAP_W * MAP_H);
        tap_ok(t[0] == SUN && t[1] == SUN && t[2] == SUN,
               "the sun texel loads as %g (got %g %g %g)", SUN, t[0], t[1], t[2]);
        tap_ok(fabs(avg[0] / want - 1) < 1e-5, "the map's average %g is %g", avg[0], want);
    }
    struct test_image a = {0}, b = {0};
    if (render(gpu, s, &a) && render(gpu, s100, &b)) {
        double ma = test_mean(&a, 0, NULL), mb = test_mean(&b, 0, NULL);
        tap_ok(isfinite(ma) && fabs(ma / mb - 1) < 0.005,
               "sun of %g: mean radiance %.2f equals that of the map / 100 with L 100 (%.2f) "
               "within 0.5%%", SUN, ma, mb);
        /* a floor: the sun alone must light the plane far above the sky */
        tap_ok(ma > 100, "the sun lights the plane (mean %.2f, sky alone 0.5)", ma);
    }
    free(a.rgba);
    free(b.rgba);
    cv_scene_destroy(&s);
    cv_scene_destroy(&s100);
out:
    free(uniform);
    free(sun);
    free(sun100);
    remove_scratch(dir);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
