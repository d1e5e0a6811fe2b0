/* envmap_wrap_test.c: image infinite lights look their maps up with the
 * wrapping of the sphere they map, through the real path: the scene loader
 * reads a map from a file, the upload puts it on the GPU, the shipped
 * light code (trace/test/light_probe.comp, cv_env_Le) looks it up.
 * - pbrt-v4 equal-area maps: radiance is the nearest texel's, as pbrt-v4's
 *   (ImageLe), over the sphere and on either side of the square's edges
 *   (the half-circles y = 0 and x = 0 below the horizon, where the
 *   octahedral map folds).
 * - pbrt-v3 lat-long maps: continuous across longitude 0 (repeat in u),
 *   and at each pole the radiance of the rows next to that pole alone
 *   (clamp in v), not blended with the other pole's.
 * Random texels in [0.5, 1.5] (fixed seed); a jump over a seam above 0.02
 * fails, where a wrong neighbour gives jumps of the order of 1. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/scene/scene_helpers.h"
#include "trace/scene_upload.h"

#define PAIRS 256
#define EPS 1e-4
#define JUMP 0.02

static uint32_t rng_state = 12345;
static float rnd(void)
{
    return (float)cv_test_lcg32(&rng_state);
}

/* cv_env_Le at n directions (xyz of dirs, 4 floats each) of the loaded
 * scene s, into le (4 floats each: rgb, pdf). */
static bool probe(struct cv_gpu *gpu, struct cv_program *prog, const struct cv_scene *s,
                  const float *dirs, size_t n, float *le, struct cv_error *err)
{
    struct cv_scene_gpu g = {0};
    if (!cv_scene_upload(gpu, s, NULL, &g, err))
        return false;
    cv_scene_bind(&g);
    GLuint in = cv_buffer_create(n * 16, dirs, "probe directions", err);
    GLuint out = cv_buffer_create(n * 16, NULL, "probe radiance", err);
    bool ok = in && out;
    if (ok) {
        cv_buffer_bind(in, CV_BIND_PROBE_IN);
        cv_buffer_bind(out, CV_BIND_PROBE_OUT);
        glUseProgram(prog->id);
        glUniform1ui(glGetUniformLocation(prog->id, "u_mode"), 1);
        glUniform1ui(glGetUniformLocation(prog->id, "u_count"), (GLuint)n);
        cv_program_dispatch_1d(prog, n);
        ok = cv_buffer_read(out, 0, n * 16, le, err);
    }
    cv_buffer_destroy(&in);
    cv_buffer_destroy(&out);
    cv_scene_gpu_release(&g);
    return ok;
}

static struct cv_scene *load(const char *rel, const char *text)
{
    th_write_str(rel, text);
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    if (!tap_ok(cv_scene_load(th_path(rel), &lp, &s, &err), "load %s: %s", rel, err.msg))
        return NULL;
    return s;
}

static void put(float *d, double x, double y, double z)
{
    double l = sqrt(x * x + y * y + z * z);
    d[0] = (float)(x / l), d[1] = (float)(y / l), d[2] = (float)(z / l), d[3] = 0;
}

/* Largest channel difference between the radiance of directions 2i and
 * 2i + 1. */
static double largest_jump(const float *le, size_t pairs)
{
    double worst = 0;
    for (size_t i = 0; i < pairs; i++)
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(le[8 * i + c] - le[8 * i + 4 + c]));
    return worst;
}

/* pbrt-v4's EqualAreaSphereToSquare (as glsl/lib/sampling.glsl has it):
 * (u, v) in [0, 1]^2, v = 0 at the image's top row. */
static void sphere_to_square(const float *d, double uv[2])
{
    double x = fabs(d[0]), y = fabs(d[1]), z = fabs(d[2]);
    double r = sqrt(fmax(0.0, 1.0 - z));
    double a = fmax(x, y), b = fmin(x, y);
    b = a == 0 ? 0 : b / a;
    double phi = atan(b) * 2 / M_PI;
    if (x < y)
        phi = 1 - phi;
    double v = phi * r, u = r - v;
    if (d[2] < 0) {
        double t = u;
        u = 1 - v;
        v = 1 - t;
    }
    u = d[0] < 0 ? -u : u;
    v = d[1] < 0 ? -v : v;
    uv[0] = 0.5 * (u + 1);
    uv[1] = 0.5 * (v + 1);
}

static void equal_area(struct cv_gpu *gpu, struct cv_program *prog)
{
    enum { W = 8, N_DIRS = 1024 };
    float rgb[W * W * 3];
    for (int i = 0; i < W * W * 3; i++)
        rgb[i] = 0.5f + rnd();
    th_write_pfm("oct.pfm", W, W, rgb);
    struct cv_scene *s = load("oct.pbrt", "WorldBegin\nLightSource \"infinite\" \"string filename\" \"oct.pfm\"\n");
    if (!s)
        return;
    tap_ok(s->n_lights == 1 && s->lights[0].tex >= 0 &&
               (s->textures[s->lights[0].tex].flags & CV_TEXF_WRAP_OCTAHEDRAL),
           "equal-area map: the loader wraps it as an octahedral sphere");
    /* pbrt-v4 looks an equal-area map up at its nearest texel (ImageLe,
     * LookupNearestChannel): random directions, and pairs across the
     * folds of the square's edges below the horizon (y = 0 and x = 0),
     * each side its own texel */
    size_t n = N_DIRS + 2 * PAIRS;
    float *d = cv_xmalloc(n * 16), *le = cv_xmalloc(n * 16);
    for (int i = 0; i < N_DIRS; i++) {
        double z = 2 * rnd() - 1, ph = 2 * M_PI * rnd(), r = sqrt(fmax(0, 1 - z * z));
        put(d + 4 * i, r * cos(ph), r * sin(ph), z);
    }
    for (int i = 0; i < PAIRS; i++) {
        double b = 0.02 + 1.53 * (i / 4 + 0.5) / (PAIRS / 4), sb = sin(b), cb = cos(b);
        double side = (i & 1) ? 1 : -1;
        float *q = d + 4 * (N_DIRS + 2 * i);
        if (i & 2) {
            put(q, EPS, side * sb, -cb);
            put(q + 4, -EPS, side * sb, -cb);
        } else {
            put(q, side * sb, EPS, -cb);
            put(q + 4, side * sb, -EPS, -cb);
        }
    }
    struct cv_error err = {{0}};
    if (tap_ok(probe(gpu, prog, s, d, n, le, &err), "equal-area map: probe: %s", err.msg)) {
        size_t checked = 0, bad = 0;
        double worst = 0;
        for (size_t i = 0; i < n; i++) {
            double uv[2];
            sphere_to_square(d + 4 * i, uv);
            double px = uv[0] * W, py = uv[1] * W;
            /* the host's and the GPU's rounding may part on an edge
             * between texels (not on the square's: the folds' pairs) */
            double rx = round(px), ry = round(py);
            if ((fabs(px - rx) < 1e-3 && rx > 0 && rx < W) || (fabs(py - ry) < 1e-3 && ry > 0 && ry < W))
                continue;
            int x = (int)fmin(floor(px), W - 1), y = (int)fmin(floor(py), W - 1);
            double e = 0;
            for (int c = 0; c < 3; c++)
                e = fmax(e, fabs(le[4 * i + c] - rgb[(y * W + x) * 3 + c]));
            worst = fmax(worst, e);
            bad += e > 1e-5;
            checked++;
        }
        tap_ok(checked > n * 9 / 10 && bad == 0, "equal-area map: radiance is the nearest texel's, as "
               "pbrt-v4's (%zu of %zu directions differ, by up to %.3g)", bad, checked, worst);
    }
    free(d), free(le);
    cv_scene_destroy(&s);
}

static void lat_long(struct cv_gpu *gpu, struct cv_program *prog)
{
    enum { W = 16, H = 8 };
    float rgb[W * H * 3];
    /* the top half 1, the bottom half 3, times a random factor per column
     * (the same in every row of a half: a pole's value is then known) */
    float col[W];
    for (int x = 0; x < W; x++)
        col[x] = 0.5f + rnd();
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++)
                rgb[(y * W + x) * 3 + c] = (y < H / 2 ? 1.0f : 3.0f) * col[x];
    double mean = 0;
    for (int x = 0; x < W; x++)
        mean += col[x] / W;
    th_write_pfm("ll.pfm", W, H, rgb);
    struct cv_scene *s = load("ll.pbrt", "WorldBegin\nLightSource \"infinite\" \"string mapname\" \"ll.pfm\"\n");
    if (!s)
        return;
    tap_ok(s->n_lights == 1 && s->lights[0].tex >= 0 &&
               (s->textures[s->lights[0].tex].flags & CV_TEXF_WRAP_LATLONG),
           "lat-long map: the loader wraps it as a lat-long sphere");
    /* pairs across longitude 0 (x > 0, y = 0), then rings round each pole */
    enum { RING = 64 };
    size_t n = 2 * PAIRS + 2 * RING;
    float *d = cv_xmalloc(n * 16), *le = cv_xmalloc(n * 16);
    for (int i = 0; i < PAIRS; i++) {
        /* away from the poles, where EPS would be a large step in longitude */
        double t = 0.5 + 2.14 * (i + 0.5) / PAIRS;
        put(d + 8 * i, sin(t), EPS, cos(t));
        put(d + 8 * i + 4, sin(t), -EPS, cos(t));
    }
    for (int k = 0; k < 2 * RING; k++) {
        double phi = 2 * M_PI * (k % RING + 0.5) / RING, z = k < RING ? 1 : -1;
        put(d + 4 * (2 * PAIRS + k), 1e-4 * cos(phi), 1e-4 * sin(phi), z);
    }
    struct cv_error err = {{0}};
    if (tap_ok(probe(gpu, prog, s, d, n, le, &err), "lat-long map: probe: %s", err.msg)) {
        double j = largest_jump(le, PAIRS);
        tap_ok(j < JUMP, "lat-long map: continuous across longitude 0 (largest jump %.4f)", j);
        /* at each pole the ring averages that pole's rows over all columns */
        double ring[2] = {0, 0};
        for (int k = 0; k < 2 * RING; k++)
            ring[k / RING] += (le[4 * (2 * PAIRS + k)] + le[4 * (2 * PAIRS + k) + 1] +
                               le[4 * (2 * PAIRS + k) + 2]) / (3.0 * RING);
        tap_ok(fabs(ring[0] / mean - 1) < 0.01 && fabs(ring[1] / (3 * mean) - 1) < 0.01,
               "lat-long map: each pole sees its own rows: %.4f and %.4f for %.4f and %.4f", ring[0],
               ring[1], mean, 3 * mean);
    }
    free(d), free(le);
    cv_scene_destroy(&s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    th_init();
    struct cv_error err = {{0}};
    struct cv_program *prog = cv_program_get(gpu, "trace/test/light_probe.comp", NULL, &err);
    if (tap_ok(prog != NULL, "light_probe.comp compiles: %s", prog ? "" : err.msg)) {
        equal_area(gpu, prog);
        lat_long(gpu, prog);
    }
    th_cleanup();
    cv_gpu_destroy(&gpu);
    return tap_done();
}
