/* medium_grid_store_test.c: the grid media's store on the GPU
 * (trace/scene_upload.c: four floats a texel of rgba32f buffer textures of
 * GL_MAX_TEXTURE_BUFFER_SIZE texels, in pages where one is too few, as many
 * as GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS leaves room for), through the
 * shipped lookups (glsl/trace/medium/grid.glsl, driven by
 * glsl/trace/test/grid_probe.comp); smaller drivers are simulated by
 * lowering those limits in gpu->info:
 * - a scene whose grids do not fit fails at upload, before anything
 *   renders, at the first medium beyond the store, with its statement's
 *   location, its size and the limit;
 * - stores in one page (one float in its last texel), two full pages and
 *   three pages (a medium across each boundary) read back every float:
 *   lookups and majorants of both media equal the host's;
 * - volpath renders the oracle's nanovdb scene in three pages as
 *   in one, bit for bit;
 * - a density grid of more than 2^26 samples (the old limit of nanovdb
 *   media; 270 MB) looks up as pbrt-v4's trilinear interpolation does at
 *   points whose samples lie on both sides of float 2^26 and at the grid's
 *   end. It is a probe, not a render: a render of that grid on llvmpipe
 *   would cost far more than make check allows, and the render path's
 *   lookups are this code. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/medium.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/trace/grid_probe.h"
#include "tests/trace/trace_test_util.h"
#include "trace/scene_upload.h"

/* Two uniformgrid media, "a" at line 2 and "b" at line 4 (col 1): 8 + 1 +
 * 4096 floats, then 27 + 1 + 4096 (each density grid, pbrt-v4's
 * one-sample Lescale grid and the majorants). */
static const char SCENE[] =
    "WorldBegin\n"
    "MakeNamedMedium \"a\" \"string type\" \"uniformgrid\" \"integer nx\" 2 \"integer ny\" 2 "
    "\"integer nz\" 2 \"float density\" [1 2 3 4 5 6 7 8]\n"
    "Translate 0 0 0\n"
    "MakeNamedMedium \"b\" \"string type\" \"uniformgrid\" \"integer nx\" 3 \"integer ny\" 3 "
    "\"integer nz\" 3 \"rgb sigma_a\" [1 1 1] \"rgb sigma_s\" [0 0 0] \"float density\" "
    "[0.5 1 1.5 2 2.5 3 3.5 4 4.5 5 5.5 6 6.5 7 7.5 8 8.5 9 9.5 10 10.5 11 11.5 12 12.5 13 "
    "13.5]\n";

#define FLOATS_A (8 + 1 + 4096)
#define FLOATS_B (27 + 1 + 4096)

static uint32_t lcg = 777;
static double rnd(void)
{
    return cv_test_lcg32(&lcg);
}

/* A density grid's samples, value(v, n, x, y, z) (grid_probe_ref_lookup). */
struct density {
    double (*value)(const float *, const int *, int, int, int);
    const float *v;
    const int *n;
};

static double density_at(const void *ctx, int x, int y, int z)
{
    const struct density *d = ctx;
    return d->value(d->v, d->n, x, y, z);
}

/* pbrt-v4's SampledGrid::Lookup at g in the unit cube, of a density grid of
 * n samples given by value(x, y, z). */
static double lookup(double (*value)(const float *, const int *, int, int, int), const float *v,
                     const int n[3], const double g[3])
{
    struct density d = {value, v, n};
    return grid_probe_ref_lookup(density_at, &d, n, g);
}

static double stored(const float *v, const int *n, int x, int y, int z)
{
    return v[((size_t)z * n[1] + y) * n[0] + x];
}

/* The large grid's density: every sample its own value, none zero. */
static double formula(const float *v, const int *n, int x, int y, int z)
{
    (void)v;
    (void)n;
    return (float)(1 + ((x * 7 + y * 13 + z * 29) % 101) / 16.0);
}

/* Mode 0 of the probe at unit-cube points g (n of them) of medium m, whose
 * bounds are the unit cube with an identity transform; out: 16 floats a
 * point. */
static bool probe_points(struct cv_program *prog, unsigned m, const double *g, size_t n,
                         float *out, struct cv_error *err)
{
    float *in = cv_xmalloc(n * 16);
    for (size_t i = 0; i < n; i++)
        memcpy(in + 4 * i, (float[4]){(float)g[3 * i], (float)g[3 * i + 1], (float)g[3 * i + 2], 0},
               16);
    bool ok = grid_probe_run(prog, 0, m, 1, in, n, n, out, 4 * n, err);
    free(in);
    return ok;
}

/* Uploads s with the driver's limits lowered to `texels` a buffer texture
 * and room for `pages` textures (0: the driver's own); the upload's
 * result, g uploaded where true. */
static bool upload_as(struct cv_gpu *gpu, struct cv_scene *s, long long texels, int pages,
                      struct cv_scene_gpu *g, struct cv_error *err)
{
    struct cv_gpu_info real = gpu->info;
    if (texels)
        gpu->info.max_texture_buffer_texels = texels;
    if (pages)
        gpu->info.max_compute_texture_units = CV_TEXUNIT_MEDIUM_GRID_PAGES + pages - 1;
    *err = (struct cv_error){{0}};
    *g = (struct cv_scene_gpu){0};
    bool ok = cv_scene_upload(gpu, s, NULL, g, err);
    gpu->info = real;
    return ok;
}

/* Lookups (sigma_a: the density, sigma_a 1) and majorants of media a and
 * b of the uploaded store g at random points and each one's last cell,
 * against the host's floats, through the probe built with g's page
 * defines. */
static void check_media(struct cv_gpu *gpu, const struct cv_scene *s, const struct cv_scene_gpu *g,
                        const char *what)
{
    struct cv_error err = {{0}};
    const char *defines[3] = {NULL, NULL, NULL};
    int nd = 0;
    if (g->grid_pages_define[0]) {
        defines[nd++] = g->grid_pages_define;
        defines[nd++] = g->grid_page_texels_define;
    }
    cv_scene_bind(g);
    struct cv_program *prog = cv_program_get(gpu, "trace/test/grid_probe.comp", defines, &err);
    if (!tap_ok(prog != NULL, "%s: grid_probe.comp compiles: %s", what, prog ? "" : err.msg))
        return;
    const unsigned R = CV_MAJORANT_RES;
    size_t np = 2000;
    double *pts = cv_xmalloc(np * 3 * sizeof(double));
    float *out = cv_xmalloc(np * 64);
    double worst = 0;
    size_t wrong_maj = 0;
    bool ran = true;
    for (unsigned m = 1; m <= 2 && ran; m++) {
        const int nm[3] = {m == 1 ? 2 : 3, m == 1 ? 2 : 3, m == 1 ? 2 : 3};
        const CvMedium *md = &s->media[m];
        for (size_t i = 0; i < np * 3; i++)
            pts[i] = 0.001 + 0.998 * rnd();
        pts[0] = pts[1] = pts[2] = 0.999;  /* the last cell */
        ran = probe_points(prog, m, pts, np, out, &err);
        for (size_t i = 0; ran && i < np; i++) {
            const float *o = out + 16 * i;
            double gg[3] = {o[12], o[13], o[14]};
            double want = lookup(stored, s->medium_grids + md->grids.x, nm, gg);
            worst = fmax(worst, fabs(o[0] - want) / (m == 1 ? 8 : 13.5));
            int c[3];
            for (int a = 0; a < 3; a++)
                c[a] = (int)fmin(floor(gg[a] * R), R - 1);
            wrong_maj += o[3] != s->medium_grids[md->res.w + ((size_t)c[2] * R + c[1]) * R + c[0]];
        }
    }
    if (tap_ok(ran, "%s: probe runs %s", what, err.msg))
        tap_ok(worst < 2e-6 && wrong_maj == 0,
               "%s: every float reads back: lookups of both media within %.2g of the largest "
               "value, %zu majorants differ", what, worst, wrong_maj);
    free(pts);
    free(out);
}

static void limits(struct cv_gpu *gpu, struct cv_scene *s)
{
    struct cv_error err;
    struct cv_scene_gpu g;
    size_t n = s->n_medium_grids;
    tap_ok(n == FLOATS_A + FLOATS_B, "the scene's grid store holds %zu floats (%d expected)", n,
           FLOATS_A + FLOATS_B);

    /* two pages of 1028 texels, 8224 floats: medium b ends beyond */
    bool ok = upload_as(gpu, s, 1028, 2, &g, &err);
    char want[256];
    snprintf(want, sizeof(want),
             "store.pbrt:4:1: medium \"b\": its grids take %d floats (0.0 MiB), floats %d to "
             "%zu of the scene's grid store; this GPU's holds 8224 floats",
             FLOATS_B, FLOATS_A, n);
    tap_ok(!ok && strstr(err.msg, want) &&
               strstr(err.msg, "2 buffer textures of GL_MAX_TEXTURE_BUFFER_SIZE 1028 texels, "
                               "GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS 17"),
           "a store 5 floats short fails at the medium beyond it, with its size and the "
           "limit: %s", err.msg);
    cv_scene_gpu_release(&g);

    /* medium a alone is too large for 2 pages of 500 texels */
    ok = upload_as(gpu, s, 500, 2, &g, &err);
    tap_ok(!ok && strstr(err.msg, "store.pbrt:2:1: medium \"a\": its grids take 4105 floats") &&
               strstr(err.msg, "holds 4000 floats"),
           "the first medium beyond the store is named: %s", err.msg);
    cv_scene_gpu_release(&g);

    /* one texture, an exact fit with one float in its last texel */
    ok = upload_as(gpu, s, (long long)(n + 3) / 4, 0, &g, &err);
    if (tap_ok(ok && g.n_grid_pages == 1 && !g.grid_pages_define[0],
               "a store that fits one texture exactly uploads as one page: %s", err.msg))
        check_media(gpu, s, &g, "one page");
    cv_scene_gpu_release(&g);

    /* two pages that fit exactly: 2 x 1029 texels */
    ok = upload_as(gpu, s, 1029, 2, &g, &err);
    if (tap_ok(ok && g.n_grid_pages == 2 &&
                   strcmp(g.grid_page_texels_define, "CV_MEDIUM_GRID_PAGE_TEXELS=1029u") == 0,
               "a store of two full pages uploads: %s", err.msg))
        check_media(gpu, s, &g, "two pages");
    cv_scene_gpu_release(&g);

    /* three pages of 1000, 1000 and 58 texels: medium a's majorants
     * and medium b each cross a page */
    ok = upload_as(gpu, s, 1000, 0, &g, &err);
    if (tap_ok(ok && g.n_grid_pages == 3 &&
                   strcmp(g.grid_pages_define, "CV_MEDIUM_GRID_PAGES=3") == 0,
               "with the driver's texture units, a store of 2058 texels takes 3 pages of "
               "1000: %s", err.msg))
        check_media(gpu, s, &g, "three pages");
    cv_scene_gpu_release(&g);
}

/* Medium a becomes a grid of nx x ny x nz samples (over 2^26) by hand: its
 * density by formula(), then its majorants (a constant: only the lookups
 * are checked). */
static void large(struct cv_gpu *gpu, struct cv_scene *s)
{
    const int n[3] = {512, 512, 257};
    size_t count = (size_t)n[0] * n[1] * n[2], R3 = (size_t)CV_MAJORANT_RES * CV_MAJORANT_RES *
                                                     CV_MAJORANT_RES;
    tap_ok(count > (1u << 26), "the large grid has %zu samples, over 2^26", count);
    float *v = cv_xmalloc((count + R3) * sizeof(float));
    for (int z = 0; z < n[2]; z++)
        for (int y = 0; y < n[1]; y++)
            for (int x = 0; x < n[0]; x++)
                v[((size_t)z * n[1] + y) * n[0] + x] = (float)formula(NULL, n, x, y, z);
    for (size_t i = 0; i < R3; i++)
        v[count + i] = 20;
    free(s->medium_grids);
    s->medium_grids = v;
    s->n_medium_grids = count + R3;
    CvMedium *m = &s->media[1];
    m->res = (cv_uvec4){(uint32_t)n[0], (uint32_t)n[1], (uint32_t)n[2], (uint32_t)count};
    m->grids = (cv_uvec4){0, 0, CV_NO_GRID, 0};
    m->emissive = 0;
    /* medium b's offsets now point into the new store: it is not probed */
    struct cv_error err = {{0}};
    struct cv_scene_gpu g = {0};
    if (!tap_ok(cv_scene_upload(gpu, s, NULL, &g, &err), "the large grid uploads: %s", err.msg))
        return;
    cv_scene_bind(&g);
    struct cv_program *prog = cv_program_get(gpu, "trace/test/grid_probe.comp", NULL, &err);
    /* points whose eight samples straddle float 2^26 (sample 2^26 - 1 is
     * (511, 511, 255), 2^26 is (0, 0, 256)) near both, in the last slab,
     * and anywhere */
    size_t np = 3000;
    double *pts = cv_xmalloc(np * 3 * sizeof(double));
    float *out = cv_xmalloc(np * 64);
    for (size_t i = 0; i < np; i++) {
        int which = (int)(i % 3);
        for (int a = 0; a < 3; a++)
            pts[3 * i + a] = 0.001 + 0.998 * rnd();
        if (which == 0) {  /* around sample (511, 511, 255) and (0, 0, 256) */
            pts[3 * i] = (i & 4) ? (510 + 1.5 * rnd()) / n[0] : (0.2 + 1.5 * rnd()) / n[0];
            pts[3 * i + 1] = (i & 4) ? (510 + 1.5 * rnd()) / n[1] : (0.2 + 1.5 * rnd()) / n[1];
            pts[3 * i + 2] = (254.6 + 2.0 * rnd()) / n[2];
        } else if (which == 1) {  /* the last slab, to the grid's last sample */
            pts[3 * i + 2] = (255.6 + 1.35 * rnd()) / n[2];
        }
    }
    pts[0] = 511.4 / n[0];  /* reads samples 2^26 - 1 and 2^26 */
    pts[1] = 511.4 / n[1];
    pts[2] = 255.9 / n[2];
    if (tap_ok(prog && probe_points(prog, 1, pts, np, out, &err), "probe runs %s", err.msg)) {
        double worst = 0;
        size_t straddle = 0;
        for (size_t i = 0; i < np; i++) {
            const float *o = out + 16 * i;
            double gg[3] = {o[12], o[13], o[14]};
            double want = lookup(formula, NULL, n, gg);
            worst = fmax(worst, fabs(o[0] - want) / 7.25);
            /* samples in slabs 255 (floats below 2^26) and 256 (from 2^26) */
            straddle += (int)floor(gg[2] * n[2] - 0.5) == 255;
        }
        /* the GPU's float sample position on a 512-sample axis moves the
         * weights by up to about 3e-5; a wrong address misses by 1/16 of
         * the largest value or more */
        tap_ok(worst < 5e-5 && straddle > 100,
               "a grid of %zu samples looks up as pbrt-v4 does across float 2^26 and to its end "
               "(worst %.2g of the largest value; %zu points read both sides of 2^26)", count,
               worst, straddle);
    }
    free(pts);
    free(out);
    cv_scene_gpu_release(&g);
}

/* The oracle's nanovdb scene (a density and a temperature lattice, its
 * blackbody table) rendered by volpath with its grid store in one page and
 * in three: the same image bit for bit, the page defines reaching every
 * kernel that looks grids up. (bdpt passes the same check, but its kernel
 * built once more costs make check minutes on llvmpipe.) */
static void render_pages(struct cv_gpu *gpu)
{
    struct cv_scene *s = test_scene("oracle/vol_nanovdb.pbrt");
    size_t texels = (s->n_medium_grids + 3) / 4;
    CvCamera cam = test_camera(s, 16, 16);
    const uint32_t passes[] = {2, 0};
    const enum cv_integrator which[1] = {CV_INTEGRATOR_VOLPATH};
    const char *names[1] = {"volpath"};
    for (int k = 0; k < 1; k++) {
        struct cv_render_params p = {.seed = 7, .camera = &cam, .integrator = which[k]};
        struct test_image one = {0}, three = {0};
        struct cv_error err = {{0}};
        bool ok = test_render(gpu, s, &p, passes, &one, &err);
        long long real = gpu->info.max_texture_buffer_texels;
        gpu->info.max_texture_buffer_texels = (long long)(texels + 2) / 3;
        ok = ok && test_render(gpu, s, &p, passes, &three, &err);
        gpu->info.max_texture_buffer_texels = real;
        size_t differ = 0;
        double sum = 0;
        for (size_t i = 0; ok && i < (size_t)16 * 16 * 4; i++) {
            differ += memcmp(&one.rgba[i], &three.rgba[i], sizeof(float)) != 0;
            sum += one.rgba[i];
        }
        tap_ok(ok && differ == 0 && sum > 0,
               "%s renders vol_nanovdb (%zu floats of grids) in three pages as in one, bit for "
               "bit (%zu of %d floats differ): %s", names[k], s->n_medium_grids, differ,
               16 * 16 * 4, err.msg);
        free(one.rgba);
        free(three.rgba);
    }
    cv_scene_destroy(&s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {.strict = true};
    struct cv_scene *s = NULL;
    tap_diag("GL_MAX_TEXTURE_BUFFER_SIZE %lld texels: the grid store reaches %lld floats",
             gpu->info.max_texture_buffer_texels, 4 * gpu->info.max_texture_buffer_texels);
    if (tap_ok(cv_scene_load_string("store.pbrt", SCENE, sizeof(SCENE) - 1, &lp, &s, &err) &&
                   s->n_media == 3,
               "the scene loads: %s", err.msg)) {
        limits(gpu, s);
        large(gpu, s);
    }
    render_pages(gpu);
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
