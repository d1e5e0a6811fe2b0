/* bdpt_test.c: the bdpt integrator (glsl/trace/bdpt) against references.
 * 1. pbrt-v4's own renders of the oracle scenes (tests/data/trace/oracle,
 *    made by its path integrator; an unbiased bdpt converges to the same
 *    image) that bdpt renders: diffuse, glossy, specular and coated
 *    materials, area, point, spot, distant, constant and image infinite
 *    lights; and bdpt_caustic, a glass sphere's caustic under a lamp, whose reference
 *    pbrt-v4's bdpt made (README there); the same spheres through an
 *    orthographic camera (bdpt_ortho: pbrt-v4's bdpt takes none, its path
 *    made the reference) and through a moving camera while the glass
 *    slides (bdpt_motion, by pbrt-v4's bdpt); participating media: the
 *    bdpt_vol scenes (references by pbrt-v4's bdpt: a lamp inside fog, a
 *    volumetric caustic, the camera and a point light in chromatic fog)
 *    and the vol scenes (by pbrt-v4's volpath: grids, cloud, nanovdb,
 *    glass, emission). Whole image, quadrants and centre within
 *    BDPT_TOL, as oracle_test.c measures them.
 * 2. Each strategy (s, t) of one path length alone, unweighted: the same
 *    image mean (strategies()).
 * 3. bdpt's AOVs are path's (aovs()).
 * 4. Unbiasedness against our own path integrator on bdpt_caustic_gaussian
 *    (light tracing's splats under a filter wider than a pixel) and
 *    bdpt_ortho_lens (light tracing into an orthographic thin lens), and
 *    against volpath on vol_cube: the regions' means agree within
 *    BDPT_TOL_PATH; and next-event estimation against light tracing,
 *    alone, on bdpt_vol_lamp (strategies_media()).
 * 5. The vertex store holds one wave of path slots (waves()): a film whose
 *    slots pass bdpt_slots, or whose store would pass the driver's
 *    per-buffer limit, renders in several dispatches a round, with the
 *    image of one dispatch a round.
 * The bound: at BDPT_SPP a region's standard error is below 0.5 % (seeds
 * 24 and 1; bdpt_caustic's lower-left quadrant, where the lamp is seen
 * through the glass, 0.8 %); BDPT_TOL = 2 % is over two and a half of
 * those and catches a bias of 2.5 %. bdpt_caustic's centre is 1 % darker
 * than pbrt-v4's with path as with bdpt (README). */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "glsl/shared/bdpt.h"
#include "gpu/context.h"
#include "tests/trace/exr_ref.h"
#include "tests/trace/trace_test_util.h"

#define RES 32
#define BDPT_SPP 512
#define BDPT_TOL 0.02
#define BDPT_TOL_STRATEGY 0.03
/* bdpt against path, both noisy: in the quadrant where the lamp is seen
 * through the glass (found by s = 0 alone, by both integrators alike)
 * each region mean has about 0.8 % standard error, their difference 1.1 % */
#define BDPT_TOL_PATH 0.03
/* waves(): few samples (the images are compared with each other, not with
 * a reference); the full image's bound, relative to its largest value:
 * a few float roundings, over ten times what the splats' order changes */
#define WAVE_SPP 8
#define WAVE_TOL 1e-6

static const int regions[6][4] = {{0, 0, RES, RES},           {0, 0, RES / 2, RES / 2},
                                  {RES / 2, 0, RES, RES / 2}, {0, RES / 2, RES / 2, RES},
                                  {RES / 2, RES / 2, RES, RES}, {11, 10, 21, 20}};

/* Renders scene `name` (tests/data/trace/oracle) with integrator `in`;
 * with bdpt and t > 0 strategy (s, t) alone, unweighted. */
static bool render_st(struct cv_gpu *gpu, const char *name, enum cv_integrator in, uint64_t seed,
                      uint32_t spp, uint32_t s_only, uint32_t t_only, struct test_image *img)
{
    char path[256];
    snprintf(path, sizeof(path), "oracle/%s.pbrt", name);
    struct cv_scene *s = test_scene(path);
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = seed, .camera = &cam, .integrator = in,
                                 .bdpt_s = s_only, .bdpt_t = t_only};
    const uint32_t passes[] = {spp / 2, spp / 2, 0};
    struct cv_error err = {{0}};
    memset(img, 0, sizeof(*img));
    bool ok = test_render(gpu, s, &p, passes, img, &err);
    cv_scene_destroy(&s);
    return tap_ok(ok && img->w == RES && img->h == RES, "%s renders with %s (%u, %u): %s", name,
                  cv_integrator_name(in), s_only, t_only, err.msg);
}

static bool render(struct cv_gpu *gpu, const char *name, enum cv_integrator in, uint64_t seed,
                   uint32_t spp, struct test_image *img)
{
    return render_st(gpu, name, in, seed, spp, 0, 0, img);
}

/* The worst region's deviation of a from b (stride floats a pixel). */
static double worst_dev(const char *name, const float *a, int sa, const float *b, int sb)
{
    double all_b = exr_ref_region_mean(b, RES, sb, 0, 0, RES, RES), worst = 0;
    for (int k = 0; k < 6; k++) {
        const int *r = regions[k];
        double x = exr_ref_region_mean(a, RES, sa, r[0], r[1], r[2], r[3]);
        double y = exr_ref_region_mean(b, RES, sb, r[0], r[1], r[2], r[3]);
        double dev = fabs(x - y) / fmax(y, 0.25 * all_b);
        tap_diag("  %-20s region %d mean %.5f reference %.5f ratio %.4f", name, k, x, y, x / y);
        if (!(dev <= worst))
            worst = dev;
    }
    return worst;
}

/* Reads scene name's pbrt-v4 reference (RES x RES, RGB) into *ref: one
 * TAP check. */
static bool oracle_ref(const char *name, float **ref)
{
    char why[4400] = "";
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/oracle/%s.exr", dir ? dir : "tests/data", name);
    uint32_t rw = 0, rh = 0;
    bool read = exr_ref_read_rgb(path, ref, &rw, &rh, why, sizeof(why));
    free(path);
    return tap_ok(read && rw == RES && rh == RES, "%s: reference read %s", name, why);
}

static void against_pbrt(struct cv_gpu *gpu, const char *name, uint64_t seed)
{
    float *ref = NULL;
    struct test_image img = {0};
    if (oracle_ref(name, &ref) &&
        render(gpu, name, CV_INTEGRATOR_BDPT, seed, BDPT_SPP, &img)) {
        double dev = worst_dev(name, img.rgba, 4, ref, 3);
        tap_ok(dev <= BDPT_TOL, "%s: bdpt within %.0f%% of pbrt-v4 (worst region off by %.4f)",
               name, 100 * BDPT_TOL, dev);
        tap_ok(img.counters.nonfinite_samples == 0, "%s: no non-finite samples", name);
    }
    free(img.rgba);
    free(ref);
}

/* bdpt_vol_caustic: the glass sphere in the middle shows the caustic in
 * the fog behind it, by paths few strategies find: at BDPT_SPP its 4x4
 * blocks scatter by up to 14 % around pbrt-v4's (whose own reference is
 * noisy there), both ways, so the regions cannot be held to BDPT_TOL; its
 * image mean, at CAUSTIC_SPP, is (within 0.4 % at seed 5). Not in make
 * check: minutes on llvmpipe. */
#define CAUSTIC_SPP 2048
static void caustic_mean(struct cv_gpu *gpu, uint64_t seed)
{
    const char *name = "bdpt_vol_caustic";
    float *ref = NULL;
    struct test_image img = {0};
    if (oracle_ref(name, &ref) &&
        render(gpu, name, CV_INTEGRATOR_BDPT, seed, CAUSTIC_SPP, &img)) {
        worst_dev(name, img.rgba, 4, ref, 3);  /* the regions, for the log */
        double a = exr_ref_region_mean(img.rgba, RES, 4, 0, 0, RES, RES);
        double b = exr_ref_region_mean(ref, RES, 3, 0, 0, RES, RES);
        tap_ok(fabs(a - b) <= BDPT_TOL * b, "%s: image mean within %.0f%% of pbrt-v4's (ratio %.4f)",
               name, 100 * BDPT_TOL, a / b);
    }
    free(img.rgba);
    free(ref);
}

/* bdpt and path (volpath in a scene with media) converge to the same
 * image. */
static void against_path(struct cv_gpu *gpu, const char *name, enum cv_integrator in, uint64_t seed)
{
    struct test_image a, b;
    if (render(gpu, name, CV_INTEGRATOR_BDPT, seed, BDPT_SPP, &a) &&
        render(gpu, name, in, seed + 1, 2 * BDPT_SPP, &b)) {
        double dev = worst_dev(name, a.rgba, 4, b.rgba, 4);
        tap_ok(dev <= BDPT_TOL_PATH, "%s: bdpt within %.0f%% of %s (worst region off by %.4f)",
               name, 100 * BDPT_TOL_PATH, cv_integrator_name(in), dev);
    }
    free(a.rgba);
    free(b.rgba);
}

/* Every strategy (s, t) of one path length, alone and unweighted, makes
 * the same image (all paths of that length, in a scene of diffuse
 * surfaces and a lamp, which each strategy can sample): a check of each
 * strategy's contribution apart from the MIS weights, against s = 1, on
 * the image mean (unweighted, s = 0 is far too noisy per region). */
static void strategies(struct cv_gpu *gpu, const char *name, uint32_t depth, uint64_t seed)
{
    struct test_image ref;
    if (!render_st(gpu, name, CV_INTEGRATOR_BDPT, seed, BDPT_SPP, 1, depth + 1, &ref))
        return;
    for (uint32_t s = 0; s <= depth + 1; s++) {
        uint32_t t = depth + 2 - s;
        struct test_image img;
        if (s == 1 || !render_st(gpu, name, CV_INTEGRATOR_BDPT, seed + s, BDPT_SPP, s, t, &img))
            continue;
        char what[64];
        snprintf(what, sizeof(what), "%s (%u,%u)", name, s, t);
        worst_dev(what, img.rgba, 4, ref.rgba, 4);  /* the regions, for the log */
        double a = exr_ref_region_mean(img.rgba, RES, 4, 0, 0, RES, RES);
        double b = exr_ref_region_mean(ref.rgba, RES, 4, 0, 0, RES, RES);
        tap_ok(fabs(a - b) <= BDPT_TOL_STRATEGY * b,
               "%s: strategy (%u, %u) alone: image mean within %.0f%% of (1, %u)'s (ratio %.4f)",
               name, s, t, 100 * BDPT_TOL_STRATEGY, depth + 1, a / b);
        free(img.rgba);
    }
    free(ref.rgba);
}

/* In media, the two strategies that join a subpath vertex to a sampled
 * end, unweighted: next-event estimation (1, depth + 1) and light tracing
 * (depth + 1, 1), each joining medium vertices to the lamp or the lens,
 * make the same image mean. The others are left out here: joining two
 * medium vertices (2, 2) weighs by 1 / d^2 with no cosine to tame it, an
 * estimate of infinite variance alone (its mean came out 16 % high at
 * BDPT_SPP), and s = 0 through fog onto a small lamp is too noisy alone. */
static void strategies_media(struct cv_gpu *gpu, const char *name, uint32_t depth, uint64_t seed)
{
    struct test_image a, b;
    if (render_st(gpu, name, CV_INTEGRATOR_BDPT, seed, BDPT_SPP, 1, depth + 1, &a) &&
        render_st(gpu, name, CV_INTEGRATOR_BDPT, seed + depth + 1, BDPT_SPP, depth + 1, 1, &b)) {
        double x = exr_ref_region_mean(b.rgba, RES, 4, 0, 0, RES, RES);
        double y = exr_ref_region_mean(a.rgba, RES, 4, 0, 0, RES, RES);
        tap_ok(fabs(x - y) <= BDPT_TOL_STRATEGY * y,
               "%s: strategy (%u, 1) alone: image mean within %.0f%% of (1, %u)'s (ratio %.4f)",
               name, depth + 1, 100 * BDPT_TOL_STRATEGY, depth + 1, x / y);
    }
    free(a.rgba);
    free(b.rgba);
}

/* the oracle scenes of lights and materials that bdpt renders */
static const char *const oracle_scenes[] = {
    "light_area", "light_point", "light_spot", "light_distant", "light_env_const", "light_env_map",
    "mat_diffuse", "mat_conductor_rough", "mat_dielectric", "mat_coateddiffuse",
    "bdpt_caustic", "bdpt_caustic_sun", "bdpt_ortho", "bdpt_motion",
    /* participating media: pbrt-v4's bdpt made the references of the
     * bdpt_vol scenes, its volpath those of the vol scenes */
    "bdpt_vol_lamp", "bdpt_vol_chromatic",
    "vol_cube", "vol_chromatic", "vol_fog_room", "vol_glass", "vol_grid_gradient", "vol_grid_rgb",
    "vol_grid_emission", "vol_cloud", "vol_nanovdb",
};

/* the scenes without a reference, held to our path integrator: light
 * tracing's splats under a filter wider than a pixel; an orthographic
 * thin lens (pbrt-v4's renders its rays from the lens about the camera's
 * origin, not about the film point: README) */
static const char *const path_scenes[] = {"bdpt_caustic_gaussian", "bdpt_ortho_lens"};

/* bdpt's camera subpaths take the path integrator's random numbers, so
 * its AOVs (albedo at the first non-specular hit, normal and depth at the
 * first) are path's, up to rounding, in a scene where path's Russian
 * roulette cannot end a camera path before its first non-specular hit
 * (behind glass it can: bdpt has no roulette). */
static void aovs(struct cv_gpu *gpu, const char *name, uint64_t seed)
{
    char path[256];
    snprintf(path, sizeof(path), "oracle/%s.pbrt", name);
    struct cv_scene *s = test_scene(path);
    CvCamera cam = test_camera(s, RES, RES);
    float *aov[2][3];
    bool ok = true;
    struct cv_error err = {{0}};
    for (int k = 0; k < 2; k++) {
        struct cv_render_params p = {.seed = seed, .camera = &cam, .aovs = true,
                                     .integrator = k ? CV_INTEGRATOR_BDPT : CV_INTEGRATOR_PATH};
        struct cv_renderer *r = NULL;
        for (int a = 0; a < 3; a++)
            aov[k][a] = cv_xcalloc(RES * RES * 3, sizeof(float));
        ok = ok && cv_renderer_create(gpu, s, &p, &r, &err) && cv_renderer_pass(r, 4, &err) &&
             cv_renderer_read(r, NULL, aov[k][0], aov[k][1], aov[k][2], &err);
        cv_renderer_destroy(&r);
    }
    double worst = 0;
    for (int a = 0; ok && a < 3; a++)
        for (int i = 0; i < RES * RES * (a == 2 ? 1 : 3); i++)
            worst = fmax(worst, fabs(aov[0][a][i] - aov[1][a][i]) / fmax(1.0, fabs(aov[0][a][i])));
    tap_ok(ok && worst < 1e-4, "%s: bdpt's albedo, normal and depth AOVs are path's (worst "
           "difference %.2g) %s", name, worst, err.msg);
    for (int k = 0; k < 2; k++)
        for (int a = 0; a < 3; a++)
            free(aov[k][a]);
    cv_scene_destroy(&s);
}

/* Renders light_area at RES with K = 2 path slots a pixel (given, so that
 * a lowered storage limit cannot change the order in which a pixel's
 * samples add up), at most `slots` a dispatch (0: automatic); with t > 0
 * strategy (s, t) alone. */
static bool render_waves(struct cv_gpu *gpu, uint64_t seed, uint32_t slots, uint32_t s_only,
                         uint32_t t_only, const char *what, struct test_image *img)
{
    struct cv_scene *s = test_scene("oracle/light_area.pbrt");
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = seed, .camera = &cam, .integrator = CV_INTEGRATOR_BDPT,
                                 .paths_per_pixel = 2, .bdpt_slots = slots,
                                 .bdpt_s = s_only, .bdpt_t = t_only};
    const uint32_t passes[] = {WAVE_SPP / 2, WAVE_SPP / 2, 0};
    struct cv_error err = {{0}};
    memset(img, 0, sizeof(*img));
    bool ok = test_render(gpu, s, &p, passes, img, &err);
    cv_scene_destroy(&s);
    return tap_ok(ok && img->w == RES && img->h == RES, "waves: %s renders: %s", what, err.msg);
}

/* The largest difference of a's pixels from b's, relative to the image's
 * largest value: light tracing's splats add up with atomics in an order
 * that the waves change, so those sums may differ in their last bits. */
static double worst_rel(const struct test_image *a, const struct test_image *b)
{
    double worst = 0, top = 0;
    for (size_t i = 0; i < (size_t)RES * RES * 4; i++)
        top = fmax(top, fabs(b->rgba[i]));
    for (size_t i = 0; i < (size_t)RES * RES * 4; i++) {
        double d = fabs(a->rgba[i] - b->rgba[i]) / fmax(top, 1e-30);
        if (!(d <= worst))
            worst = d;
    }
    return worst;
}

/* The vertex store holds one wave of path slots (src/trace/integrator.h):
 * bdpt_slots below the film's slots, or a driver whose per-buffer limit
 * the film's whole store would pass (as an H100 with a 1024x1024 film at
 * maximum depth 7), split each round into several dispatches. The samples
 * do not change: a strategy without splats (2, 2) gives the same image bit
 * for bit; the full image within WAVE_TOL of the largest value (the
 * splats' summation order). */
static void waves(struct cv_gpu *gpu, uint64_t seed)
{
    const uint32_t slots = 2 * RES * RES, cap = 300;  /* 7 waves, the last one partial */
    struct test_image one, split, one22, split22, limited;
    if (!render_waves(gpu, seed, 0, 0, 0, "one dispatch a round", &one))
        return;
    if (render_waves(gpu, seed, cap, 0, 0, "bdpt_slots 300", &split)) {
        tap_ok(one.counters.wave_slots == slots && split.counters.wave_slots == cap &&
                   split.counters.path_slots == slots,
               "waves: %llu slots in one dispatch, %llu a dispatch with bdpt_slots %u",
               (unsigned long long)one.counters.wave_slots,
               (unsigned long long)split.counters.wave_slots, cap);
        double d = worst_rel(&split, &one);
        tap_ok(d <= WAVE_TOL, "waves: bdpt_slots %u gives the image of one dispatch (worst "
               "difference %.3g of the largest value)", cap, d);
        free(split.rgba);
    }
    if (render_waves(gpu, seed, 0, 2, 2, "(2, 2) alone", &one22) &&
        render_waves(gpu, seed, cap, 2, 2, "(2, 2) alone, bdpt_slots 300", &split22))
        tap_ok(memcmp(one22.rgba, split22.rgba, sizeof(float) * RES * RES * 4) == 0,
               "waves: strategy (2, 2) alone: bit-identical with bdpt_slots %u", cap);
    free(one22.rgba);
    free(split22.rgba);
    /* a driver whose storage buffers hold 1 MiB at most, and which cannot
     * address more (a probe past the limit is taken to have failed): the
     * film's whole store, 2048 slots of CV_BDPT_VERTS(5) vertices, would
     * need 3.3 MiB */
    struct cv_gpu_info info = gpu->info;
    struct cv_gpu_storage storage = gpu->storage;
    const uint64_t limit = 1u << 20, per_slot = CV_BDPT_VERTS(5u) * sizeof(CvBdptVertex);
    gpu->info.max_ssbo_bytes = (long long)limit;
    gpu->storage.works = 0;
    gpu->storage.fails = limit + 4;
    bool ok = render_waves(gpu, seed, 0, 0, 0, "a film's store over a 1 MiB storage limit",
                           &limited);
    gpu->info = info;
    gpu->storage = storage;
    if (ok) {
        uint64_t w = limited.counters.wave_slots;
        tap_ok(w < slots && w * per_slot <= limit && (w + 1) * per_slot > limit,
               "waves: under a 1 MiB limit, %llu slots a dispatch (%llu bytes of store)",
               (unsigned long long)w, (unsigned long long)(w * per_slot));
        double d = worst_rel(&limited, &one);
        tap_ok(d <= WAVE_TOL, "waves: under a 1 MiB limit, the image of one dispatch (worst "
               "difference %.3g of the largest value)", d);
        free(limited.rgba);
    }
    free(one.rgba);
}

/* The oracle scenes `make check` renders: every one is a kernel of its
 * own to build on llvmpipe, minutes for the whole list; `bdpt_test all`
 * renders them all (as on the GPU machine). */
static bool in_check(const char *name)
{
    return strcmp(name, "light_area") == 0 || strcmp(name, "light_distant") == 0 ||
           strcmp(name, "bdpt_caustic") == 0 || strcmp(name, "bdpt_ortho") == 0 ||
           strcmp(name, "bdpt_motion") == 0 || strcmp(name, "bdpt_vol_lamp") == 0 ||
           strcmp(name, "bdpt_vol_chromatic") == 0;
}

/* bdpt_test [all | SCENE [SEED]] */
int main(int argc, char **argv)
{
    uint64_t seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 24;
    const char *only = argc > 1 && strcmp(argv[1], "all") != 0 ? argv[1] : NULL;
    bool all = argc > 1;
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    for (size_t i = 0; i < sizeof(oracle_scenes) / sizeof(oracle_scenes[0]); i++)
        if (only ? strcmp(only, oracle_scenes[i]) == 0 : all || in_check(oracle_scenes[i]))
            against_pbrt(gpu, oracle_scenes[i], seed);
    if (!only || strcmp(only, "aovs") == 0)
        aovs(gpu, "light_area", seed);
    if (!only || strcmp(only, "strategies") == 0)
        strategies(gpu, "light_area", 2, seed);
    for (size_t i = 0; i < sizeof(path_scenes) / sizeof(path_scenes[0]); i++)
        if (!only || strcmp(only, "path") == 0 || strcmp(only, path_scenes[i]) == 0)
            against_path(gpu, path_scenes[i], CV_INTEGRATOR_PATH, seed);
    if (!only || strcmp(only, "volpath") == 0)
        against_path(gpu, "vol_cube", CV_INTEGRATOR_VOLPATH, seed);
    if (all && (!only || strcmp(only, "bdpt_vol_caustic") == 0))
        caustic_mean(gpu, seed);
    if (!only || strcmp(only, "strategies_media") == 0)
        strategies_media(gpu, "bdpt_vol_lamp", 2, seed);
    if (!only || strcmp(only, "waves") == 0)
        waves(gpu, seed);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
