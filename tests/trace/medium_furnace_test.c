/* medium_furnace_test.c: participating media (volpath) against exact
 * answers, in a uniform environment of radiance 1:
 * - furnace: a sphere of a chromatic medium of albedo 1 (sigma_s differs
 *   per channel, sigma_a 0) with a forward-scattering Henyey-Greenstein
 *   phase function, behind an index-matched "interface" boundary, reads 1
 *   in every channel: delta tracking with the channels' one-sample MIS,
 *   phase sampling, next-event estimation with transmittance through the
 *   boundary and MIS between the two neither lose nor gain energy;
 * - absorption: a cube of a chromatic, purely absorbing medium reads, per
 *   pixel, the transmittance exp(-sigma_a L) along each camera ray's chord
 *   L through the cube (averaged over the pixel here, exactly): the
 *   tracking's weights are the medium's transmittance, per channel;
 * - emission: the same cube emitting Le (Lescale 0.5) in an environment of
 *   0.5 reads 0.5 T + Le (1 - T) per channel (pbrt-v4's emission at
 *   collisions, sigma_a Le per unit length);
 * - the path integrator ignores media as pbrt-v4's does: both scenes read
 *   1 everywhere with it (the boundaries are invisible).
 * Each channel's image mean must lie within 4 standard errors (from the
 * pixels' spread about their exact values) and 1 % of the exact mean. */
#include "config.h"

#include "tests/trace/trace_test_util.h"

#define RES 16

static const char cube_scene[] =
    "LookAt 0 0 -4  0 0 0  0 1 0\n"
    "Camera \"perspective\" \"float fov\" [ 40 ]\n"
    "Integrator \"volpath\" \"integer maxdepth\" [ 5 ]\n"
    "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 16 ]\n"
    "PixelFilter \"box\"\n"
    "WorldBegin\n"
    "LightSource \"infinite\" \"rgb L\" [ 1 1 1 ]\n"
    "MakeNamedMedium \"ink\" \"string type\" \"homogeneous\"\n"
    "  \"rgb sigma_a\" [ 0.25 0.5 1 ] \"rgb sigma_s\" [ 0 0 0 ] \"float scale\" [ 2 ]\n"
    "AttributeBegin\n"
    "  MediumInterface \"ink\" \"\"\n"
    "  Material \"interface\"\n"
    "  Shape \"trianglemesh\" \"integer indices\" [ 0 1 2 0 2 3  4 5 6 4 6 7  8 9 10 8 10 11"
    "  12 13 14 12 14 15  16 17 18 16 18 19  20 21 22 20 22 23 ]\n"
    "    \"point3 P\" [ 1 -1 -1 1 1 -1 1 1 1 1 -1 1  -1 -1 -1 -1 -1 1 -1 1 1 -1 1 -1"
    "  -1 1 -1 -1 1 1 1 1 1 1 1 -1  -1 -1 -1 1 -1 -1 1 -1 1 -1 -1 1"
    "  -1 -1 1 1 -1 1 1 1 1 -1 1 1  -1 -1 -1 -1 1 -1 1 1 -1 1 -1 -1 ]\n"
    "    \"normal N\" [ 1 0 0 1 0 0 1 0 0 1 0 0  -1 0 0 -1 0 0 -1 0 0 -1 0 0"
    "  0 1 0 0 1 0 0 1 0 0 1 0  0 -1 0 0 -1 0 0 -1 0 0 -1 0"
    "  0 0 1 0 0 1 0 0 1 0 0 1  0 0 -1 0 0 -1 0 0 -1 0 0 -1 ]\n"
    "AttributeEnd\n";

/* sigma_a of the cube, scale applied */
static const double cube_sigma[3] = {0.5, 1, 2};

/* Length of the chord of the ray o + t d through the cube [-1, 1]^3. */
static double cube_chord(const double o[3], const double d[3])
{
    double t0 = 0, t1 = INFINITY;
    for (int a = 0; a < 3; a++) {
        double ta = (-1 - o[a]) / d[a], tb = (1 - o[a]) / d[a];
        t0 = fmax(t0, fmin(ta, tb));
        t1 = fmin(t1, fmax(ta, tb));
    }
    return t1 > t0 ? (t1 - t0) * sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) : 0;
}

/* The cube's exact image: each pixel's transmittance averaged over a
 * 32x32 grid in the pixel (box filter). The camera looks along +z from
 * z = -4 with a 40 degree field of view; the image is symmetric, so the
 * axes' orientation does not matter. */
static void cube_exact(double *img)
{
    double tf = tan(20.0 * M_PI / 180.0);
    const int sub = 32;
    for (int py = 0; py < RES; py++)
        for (int px = 0; px < RES; px++) {
            double acc[3] = {0, 0, 0};
            for (int j = 0; j < sub; j++)
                for (int i = 0; i < sub; i++) {
                    double sx = -1 + 2 * (px + (i + 0.5) / sub) / RES;
                    double sy = -1 + 2 * (py + (j + 0.5) / sub) / RES;
                    double o[3] = {0, 0, -4}, d[3] = {sx * tf, sy * tf, 1};
                    double L = cube_chord(o, d);
                    for (int c = 0; c < 3; c++)
                        acc[c] += exp(-cube_sigma[c] * L);
                }
            for (int c = 0; c < 3; c++)
                img[3 * (py * RES + px) + c] = acc[c] / (sub * sub);
        }
}

/* text with the first `from` replaced by `to`; newly allocated. */
static char *replace(const char *text, const char *from, const char *to)
{
    const char *at = strstr(text, from);
    if (!at)
        return cv_xstrdup(text);
    return cv_xasprintf("%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
}

/* The emitting cube: cube_scene in a dimmer environment, its medium
 * emitting. */
static char *emitting_cube(void)
{
    char *t = replace(cube_scene, "\"rgb L\" [ 1 1 1 ]", "\"rgb L\" [ 0.5 0.5 0.5 ]");
    char *out = replace(t, "\"float scale\" [ 2 ]",
                        "\"float scale\" [ 2 ] \"rgb Le\" [ 2 4 1 ] \"float Lescale\" [ 0.5 ]");
    free(t);
    return out;
}

/* Renders s with integrator integ and checks each channel's mean against
 * exact (3 per pixel; NULL: 1 everywhere). */
static void check(struct cv_gpu *gpu, const struct cv_scene *s, enum cv_integrator integ,
                  const char *name, const double *exact, uint32_t spp)
{
    struct cv_error err = {{0}};
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = 5, .camera = &cam, .integrator = integ};
    struct test_image img = {0};
    const uint32_t passes[] = {spp / 2, spp / 2, 0};
    if (!tap_ok(test_render(gpu, s, &p, passes, &img, &err), "%s renders: %s", name, err.msg))
        return;
    const size_t n = (size_t)RES * RES;
    bool ok = img.w == RES && img.h == RES;
    char msg[512] = "";
    for (int c = 0; c < 3 && ok; c++) {
        double mean = 0, want = 0, var = 0;
        for (size_t i = 0; i < n; i++) {
            double v = img.rgba[4 * i + c], e = exact ? exact[3 * i + c] : 1;
            mean += v / (double)n;
            want += e / (double)n;
            var += (v - e) * (v - e) / (double)n;
            if (!isfinite(v))
                ok = false;
        }
        double se = sqrt(var / (double)n);
        size_t l = strlen(msg);
        snprintf(msg + l, sizeof(msg) - l, " %c %.5f (exact %.5f, s.e. %.5f)", "RGB"[c], mean, want,
                 se);
        if (!(fabs(mean - want) <= fmax(4 * se, 1e-4) && fabs(mean - want) <= 0.01 * want))
            ok = false;
    }
    tap_ok(ok, "%s:%s", name, msg);
    free(img.rgba);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("medium_furnace.pbrt");
    tap_ok(s->n_media == 2 && s->media[1].type == CV_MEDIUM_HOMOGENEOUS &&
               fabsf(s->media[1].sigma_s.z - 6) < 1e-6f && fabsf(s->media[1].sigma_a.w - 0.6f) < 1e-6f,
           "the medium is read: sigma_s (%g %g %g), g %g", s->n_media > 1 ? s->media[1].sigma_s.x : 0,
           s->n_media > 1 ? s->media[1].sigma_s.y : 0, s->n_media > 1 ? s->media[1].sigma_s.z : 0,
           s->n_media > 1 ? s->media[1].sigma_a.w : 0);
    check(gpu, s, CV_INTEGRATOR_VOLPATH, "furnace, volpath", NULL, 512);
    check(gpu, s, CV_INTEGRATOR_PATH, "furnace, path (media ignored)", NULL, 16);
    cv_scene_destroy(&s);

    struct cv_scene_load_params lp = {0};
    struct cv_error err = {{0}};
    if (tap_ok(cv_scene_load_string("cube.pbrt", cube_scene, strlen(cube_scene), &lp, &s, &err),
               "load the absorbing cube: %s", err.msg)) {
        double *exact = cv_xmalloc(RES * RES * 3 * sizeof(double));
        cube_exact(exact);
        check(gpu, s, CV_INTEGRATOR_VOLPATH, "absorbing cube, volpath", exact, 256);
        check(gpu, s, CV_INTEGRATOR_PATH, "absorbing cube, path (media ignored)", NULL, 16);
        cv_scene_destroy(&s);
        char *text = emitting_cube();
        if (tap_ok(cv_scene_load_string("emit.pbrt", text, strlen(text), &lp, &s, &err),
                   "load the emitting cube: %s", err.msg)) {
            const double Le[3] = {1, 2, 0.5};
            for (int i = 0; i < RES * RES * 3; i++)
                exact[i] = 0.5 * exact[i] + Le[i % 3] * (1 - exact[i]);
            check(gpu, s, CV_INTEGRATOR_VOLPATH, "emitting cube, volpath", exact, 256);
            cv_scene_destroy(&s);
        }
        free(text);
        free(exact);
    }
    cv_gpu_destroy(&gpu);
    return tap_done();
}
