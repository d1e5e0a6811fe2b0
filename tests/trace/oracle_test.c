/* oracle_test.c: the scenes of tests/data/trace/oracle, each isolating one
 * feature (a material, a kind of light, textures, light order, a huge
 * plane, a deep BVH), rendered at 32x32 and compared with pbrt-v4's
 * references of the same files (README there: the exact pbrt command and
 * commit). Per scene, the channel-averaged mean of the whole image, of
 * each of its four quadrants and of a 10x10 square in the centre (inside
 * the sphere that carries the material under test) must lie within
 * ORACLE_TOL of the reference's (regions darker than a quarter of the
 * image mean are held to ORACLE_TOL times that quarter instead, so a black
 * sky cannot blow the ratio up). Also prints the whole-image ratio and
 * relMSE, and each region's ratio.
 *
 * The bound: the references are 4096-spp renders with a standard error
 * per region of about 0.05 % (at most 0.3 %); ours at ORACLE_SPP have
 * about 0.1 % (at most 0.3 %: spread between seeds, `oracle_test all
 * SEED`; figures in the README). ORACLE_TOL = 1.5 % is over 3.5 standard
 * errors of the difference in the noisiest region (over ten in a typical
 * one) and catches a bias of 2 %.
 *
 * Known bugs of issue 24 (the light order of environment lights, huge
 * planes, the layered coats) and the spectral difference of copper are
 * checks marked "# TODO issue 24 ..." with the worst region's ratio in
 * the message: when a fix lands they pass, the driver reports XPASS, and
 * the mark must go. */
#include "config.h"

#include <stdio.h>

#include "tests/trace/exr_ref.h"
#include "tests/trace/trace_test_util.h"

#define RES 32
#define ORACLE_SPP 1024
#define ORACLE_TOL 0.015

struct oracle_scene {
    const char *name;
    const char *todo; /* known bug: the checks are TODO with this reason */
};

static const struct oracle_scene scenes[] = {
    {"mat_diffuse", NULL},
    {"mat_conductor_smooth", NULL},
    {"mat_conductor_rough", NULL},
    /* not a bug of ours alone: pbrt-v4 renders copper's measured eta and k
     * per wavelength, Cavalry as RGB averages of them */
    {"mat_conductor_cu", "issue 24: spectral copper as RGB eta and k (spectral difference)"},
    {"mat_dielectric", NULL},
    {"mat_dielectric_rough", NULL},
    {"mat_thindielectric", NULL},
    {"mat_coateddiffuse", NULL},
    /* layered.glsl weighs a rough coat's two exits differently from
     * pbrt-v4 on purpose (cv_lay_exit_pdf): the centre is 1.9 % darker */
    {"mat_coateddiffuse_rough", "issue 24 bug 4: rough-coat exit weights differ from pbrt-v4"},
    {"mat_coatedconductor", NULL},
    {"mat_diffusetransmission", NULL},
    {"light_point", NULL},
    {"light_spot", NULL},
    {"light_distant", NULL},
    {"light_area", NULL},
    {"light_env_const", NULL},
    {"light_env_map", NULL},
    {"texture_image", NULL},
    {"lights_env_first", NULL},
    {"lights_env_last", NULL},
    {"huge_plane", NULL},
    {"deep_bvh", NULL},
    {"nee_area_env", NULL},
    /* coated diffuse in closed form: a white base, maxdepth 10 and 100 */
    {"mat_coateddiffuse_white_md10", NULL},
    {"mat_coateddiffuse_white_md100", NULL},
};

/* Channel-averaged mean of the pixels [x0, x1) x [y0, y1); stride: floats
 * per pixel. */
static double region_mean(const float *img, int stride, int x0, int y0, int x1, int y1)
{
    double s = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            const float *p = img + ((size_t)y * RES + x) * stride;
            s += (p[0] + p[1] + p[2]) / 3.0;
        }
    return s / ((double)(x1 - x0) * (y1 - y0));
}

static void check_scene(struct cv_gpu *gpu, const struct oracle_scene *sc, uint64_t seed)
{
    char name[256], why[4400] = "";
    snprintf(name, sizeof(name), "oracle/%s.pbrt", sc->name);
    struct cv_scene *s = test_scene(name);
    const char *dir = getenv("CV_TEST_DATA");
    char *ref_path = cv_xasprintf("%s/trace/oracle/%s.exr", dir ? dir : "tests/data", sc->name);
    float *ref = NULL;
    uint32_t rw = 0, rh = 0;
    bool read = exr_ref_read_rgb(ref_path, &ref, &rw, &rh, why, sizeof(why));
    free(ref_path);
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = seed, .camera = &cam};
    const uint32_t passes[] = {ORACLE_SPP / 4, ORACLE_SPP / 4, ORACLE_SPP / 4, ORACLE_SPP / 4, 0};
    struct test_image img = {0};
    struct cv_error err = {{0}};
    bool ok = test_render(gpu, s, &p, passes, &img, &err);
    cv_scene_destroy(&s);
    if (!tap_ok(read && rw == RES && rh == RES, "%s: reference %ux%u read %s", sc->name, rw, rh,
                why) ||
        !tap_ok(ok && img.w == RES && img.h == RES, "%s renders: %s", sc->name, err.msg)) {
        free(ref);
        free(img.rgba);
        return;
    }
    double all = region_mean(img.rgba, 4, 0, 0, RES, RES);
    double all_ref = region_mean(ref, 3, 0, 0, RES, RES);
    double rel_mse = 0;
    for (int i = 0; i < RES * RES; i++)
        for (int c = 0; c < 3; c++) {
            double a = img.rgba[4 * i + c], b = ref[3 * i + c];
            rel_mse += (a - b) * (a - b) / (b * b + 0.01);
        }
    rel_mse /= RES * RES * 3;
    tap_diag("%-24s mean %.5f reference %.5f ratio %.4f relMSE %.5f", sc->name, all, all_ref,
             all / all_ref, rel_mse);
    /* the whole image, then the quadrants */
    /* the whole image, its quadrants, and a centre square inside the
     * sphere of the material scenes (radius about 7.7 pixels) */
    const int rg[6][4] = {{0, 0, RES, RES},
                          {0, 0, RES / 2, RES / 2},
                          {RES / 2, 0, RES, RES / 2},
                          {0, RES / 2, RES / 2, RES},
                          {RES / 2, RES / 2, RES, RES},
                          {11, 10, 21, 20}};
    static const char *const rname[6] = {"image", "top left", "top right", "bottom left",
                                         "bottom right", "centre"};
    bool pass = true;
    char worst[128] = "";
    double worst_dev = -1;
    for (int k = 0; k < 6; k++) {
        double a = region_mean(img.rgba, 4, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
        double b = region_mean(ref, 3, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
        double dev = fabs(a - b) / fmax(b, 0.25 * all_ref);
        if (!(dev <= ORACLE_TOL))
            pass = false;
        if (!(dev <= worst_dev)) {
            worst_dev = dev;
            snprintf(worst, sizeof(worst), "%s ratio %.4f", rname[k], a / b);
        }
        tap_diag("  %-12s mean %.5f pbrt-v4 %.5f ratio %.4f", rname[k], a, b, a / b);
    }
    /* one check per scene: a TODO scene whose regions pass only in part
     * must not report XPASS */
    if (sc->todo)
        tap_todo(pass, sc->todo, "%s: image, quadrants and centre within %.1f%% of pbrt-v4 (worst: %s)", sc->name,
                 100 * ORACLE_TOL, worst);
    else
        tap_ok(pass, "%s: image, quadrants and centre within %.1f%% of pbrt-v4 (worst: %s)", sc->name,
               100 * ORACLE_TOL, worst);
    free(ref);
    free(img.rgba);
}

/* oracle_test [SCENE|all [SEED]]: one scene, or another seed (to measure
 * the noise), by hand */
int main(int argc, char **argv)
{
    uint64_t seed = argc > 2 ? strtoull(argv[2], NULL, 10) : 24;
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    for (size_t i = 0; i < sizeof(scenes) / sizeof(scenes[0]); i++)
        if (argc < 2 || strcmp(argv[1], "all") == 0 || strcmp(argv[1], scenes[i].name) == 0)
            check_scene(gpu, &scenes[i], seed);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
