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
 * The camera and film scenes (filter_*, camera_dof, camera_motion: bright
 * emitters alone; camera_spherical_*) are checked on smaller regions where
 * the filter's shape, the lens's or the shutter's blur, or the spherical
 * mapping shows (enum oracle_regions), each within ORACLE_TOL of the
 * reference's brightest region (README: their noise).
 *
 * Known bugs of issue 24 (the light order of environment lights, huge
 * planes, the layered coats) are checks marked "# TODO issue 24 ..." with the worst region's ratio in
 * the message: when a fix lands they pass, the driver reports XPASS, and
 * the mark must go. */
#include "config.h"

#include <stdio.h>
#include <string.h>

#include "tests/trace/exr_ref.h"
#include "tests/trace/trace_test_util.h"

#define RES 32
#define ORACLE_SPP 1024
/* Scenes with media: their paths are several times longer; at this count
 * their regions' standard error is still about 0.3 % (README). */
#define ORACLE_SPP_MEDIA 512
#define ORACLE_TOL 0.015

/* Which regions a scene is checked on. */
enum oracle_regions {
    REGIONS_DEFAULT, /* the image, its quadrants and the centre */
    /* filter_*: the pixel strips beside make_oracle.py's two thin lines,
     * where a pixel is the filter's integral over a line: columns 6..17
     * (rows 16..31) about the vertical line over columns 11.2-12.2, rows
     * 4..15 (columns 20..31) about the horizontal one over rows 9.7-10.7 */
    REGIONS_LINES,
    REGIONS_GRID, /* camera_dof: the 64 blocks of 4 x 4 pixels (blur moves light between them) */
    /* camera_motion: the 16 blocks of 8 x 8 pixels (the time adds noise a
     * 4x4 block's mean feels at 1 % of the brightest) */
    REGIONS_GRID8,
};

struct oracle_scene {
    const char *name;
    const char *todo; /* known bug: the checks are TODO with this reason */
};

/* Scenes whose reference is made channel by channel: channel c from the
 * reference named by `channels` with %c as 'r', 'g', 'b' (grey scenes of
 * one channel's coefficients each, where pbrt-v4's spectral rendering of a
 * coloured medium is not what RGB rendering means: README). */
static const struct {
    const char *name, *channels;
} scene_channels[] = {
    {"sss_skin", "sss_skin_%c"},
};

static const char *channels_of(const char *name)
{
    for (size_t i = 0; i < sizeof(scene_channels) / sizeof(scene_channels[0]); i++)
        if (strcmp(scene_channels[i].name, name) == 0)
            return scene_channels[i].channels;
    return NULL;
}

/* Scenes whose colour is under test: each channel of each region is held
 * to the bound, not only their mean; and the samples per pixel they are
 * rendered with (0: ORACLE_SPP). mat_measured's centre is a glossy
 * highlight of the lamp whose channels spread by about 0.5 % between seeds
 * at ORACLE_SPP; at 4096 the bound keeps its margin for a 2 % bias
 * (README). */
static const struct {
    const char *name;
    uint32_t spp;
} per_channel_scenes[] = {{"mat_measured", 4096}, {"mat_conductor_cu", 0}};

static bool per_channel(const char *name, uint32_t *spp)
{
    for (size_t i = 0; i < sizeof(per_channel_scenes) / sizeof(per_channel_scenes[0]); i++)
        if (strcmp(per_channel_scenes[i].name, name) == 0) {
            if (spp && per_channel_scenes[i].spp)
                *spp = per_channel_scenes[i].spp;
            return true;
        }
    return false;
}

/* Scenes checked on regions of their own (the others: REGIONS_DEFAULT),
 * each held to ORACLE_TOL of the reference's brightest region: a region
 * near a line or an edge can be near 0, or negative under a filter's
 * lobe. */
static const struct {
    const char *name;
    enum oracle_regions regions;
} scene_regions[] = {
    {"filter_mitchell", REGIONS_LINES},
    {"filter_sinc", REGIONS_LINES},
    {"camera_dof", REGIONS_GRID},
    {"camera_motion", REGIONS_GRID8},
    /* object_motion: where the moving shapes' blur moves light between
     * blocks */
    {"object_motion", REGIONS_GRID8},
    /* curve_motion: the same for a moving curve and a moving instance of
     * a curve object */
    {"curve_motion", REGIONS_GRID8},
    /* instance_turn: where turning instances' blur moves light between
     * blocks */
    {"instance_turn", REGIONS_GRID8},
    /* curve_scale: where each strand's width lies (and the moving
     * instance's blur) */
    {"curve_scale", REGIONS_GRID8},
    /* the spherical cameras: a mapping that is mirrored, turned or
     * wrapped otherwise moves light between blocks */
    {"camera_spherical_equalarea", REGIONS_GRID8},
    {"camera_spherical_equirect", REGIONS_GRID8},
    /* texture_ply_quad, texture_bilinear_patch: a patch's texture
     * coordinates sheared on one of its triangles move the checker's
     * texels between blocks */
    {"texture_ply_quad", REGIONS_GRID8},
    {"texture_bilinear_patch", REGIONS_GRID8},
};

static enum oracle_regions regions_of(const char *name)
{
    for (size_t i = 0; i < sizeof(scene_regions) / sizeof(scene_regions[0]); i++)
        if (strcmp(scene_regions[i].name, name) == 0)
            return scene_regions[i].regions;
    return REGIONS_DEFAULT;
}

static const struct oracle_scene scenes[] = {
    {"mat_diffuse", NULL},
    {"mat_conductor_smooth", NULL},
    {"mat_conductor_rough", NULL},
    /* pbrt-v4's default copper, given by spectra: Fresnel per wavelength
     * (src/scene/conductor_fresnel.c) */
    {"mat_conductor_cu", NULL},
    {"mat_dielectric", NULL},
    {"mat_dielectric_rough", NULL},
    {"mat_thindielectric", NULL},
    {"mat_coateddiffuse", NULL},
    /* pbrt-v4's own images of a rough coat disagree: its path (light
     * sampling with MIS, through LayeredBxDF::f) is brighter than its
     * BSDF sampling alone (the layered walk) by 1.8 % in the centre, and
     * by 1.0 % with its "power" light sampler in place of "bvh" (README).
     * LayeredBxDF::f weighs its exits through a rough coat with the
     * density of wi from the exit direction where the other strategy's
     * density of that direction belongs, so its weights do not sum to 1
     * and f overshoots (bsdf_layered_test: 6 to 8 % in albedo with them);
     * layered.glsl weighs them consistently (cv_lay_exit_pdf). Cavalry
     * matches the walk's image (mat_coateddiffuse_rough_bsdf); this one
     * stays TODO: matching it would mean copying the bias and pbrt-v4's
     * light sampler. */
    {"mat_coateddiffuse_rough", "issue 24 bug 4: pbrt-v4's rough-coat exit MIS weights are biased"},
    /* the same scene, pbrt-v4 by BSDF sampling alone (simplepath without
     * light sampling), Cavalry by its path */
    {"mat_coateddiffuse_rough_bsdf", NULL},
    {"mat_coatedconductor", NULL},
    {"mat_diffusetransmission", NULL},
    {"light_point", NULL},
    {"light_spot", NULL},
    {"light_distant", NULL},
    {"light_area", NULL},
    {"light_env_const", NULL},
    {"light_env_map", NULL},
    {"texture_image", NULL},
    /* the same floor as a PLY quad and as a bilinearmesh, without uv:
     * pbrt-v4's bilinear patch and its (u, v) */
    {"texture_ply_quad", NULL},
    {"texture_bilinear_patch", NULL},
    {"lights_env_first", NULL},
    {"lights_env_last", NULL},
    {"huge_plane", NULL},
    {"deep_bvh", NULL},
    {"nee_area_env", NULL},
    {"filter_mitchell", NULL},
    {"filter_sinc", NULL},
    {"camera_dof", NULL},
    {"camera_motion", NULL},
    /* issue 27: shapes under an animated transform (object motion blur) */
    {"object_motion", NULL},
    /* issue 27: curve shapes (flat, cylinder, ribbon) and the hair BSDF */
    {"curve_diffuse", NULL},
    {"curve_hair", NULL},
    /* issue 27: curves in an ObjectBegin definition, instanced three
     * times; a moving curve and a moving instance of them */
    {"curve_instance", NULL},
    {"curve_motion", NULL},
    /* issue 27: moving instances that turn, interpolated about the
     * camera's position as pbrt-v4 does */
    {"instance_turn", NULL},
    /* issue 27: curves under non-uniform scales and a shear, widths and
     * ribbon normals in object space as pbrt-v4's */
    {"curve_scale", NULL},
    /* participating media, rendered with volpath */
    {"vol_cube", NULL},
    {"vol_chromatic", NULL},
    {"vol_fog_room", NULL},
    {"vol_glass", NULL},
    /* grid media: uniformgrid under a transform, rgbgrid, emission from
     * an Lescale grid and from a temperature grid */
    {"vol_grid_gradient", NULL},
    {"vol_grid_rgb", NULL},
    {"vol_grid_emission", NULL},
    {"vol_grid_blackbody", NULL},
    /* pbrt-v4's nanovdb medium: density and temperature grids of a
     * NanoVDB file (ZIP-compressed, make_nanovdb.py) */
    {"vol_nanovdb", NULL},
    /* coated diffuse in closed form: a white base, maxdepth 10 and 100 */
    {"mat_coateddiffuse_white_md10", NULL},
    {"mat_coateddiffuse_white_md100", NULL},
    /* issue 27: pbrt-v4's subsurface material (BSSRDF probes), volpath */
    {"sss_grey", NULL},
    {"sss_reflectance", NULL},
    {"sss_texture", NULL},
    /* Skin1: against pbrt-v4's grey renders of each channel (README: its
     * spectral render, sss_skin.exr, differs by the upsampling) */
    {"sss_skin", NULL},
    /* a measured BRDF (RGL tensor file of make_measured.py) */
    {"mat_measured", NULL},
    /* issue 27: a homogeneous medium from a measured preset, and pbrt-v4's
     * procedural cloud */
    {"vol_preset", NULL},
    {"vol_cloud", NULL},
    /* pbrt-v4's spherical camera, both mappings (every direction: floor,
     * spheres and sky) */
    {"camera_spherical_equalarea", NULL},
    {"camera_spherical_equirect", NULL},
    /* a cut-out emitter (pbrt-v4's DiffuseAreaLight::AlphaMasked): a
     * checker of alpha 1 and 0 */
    {"light_alpha_checker", NULL},
    /* alpha 0.5: pbrt-v4 keeps half of the lamp's light samples but a
     * quarter of the rays that hit it (half the rays pass through, half
     * of the hit points are masked), so the floor's light is a blend of
     * the two weighed by the MIS weights, which depend on the light
     * sampler's probabilities: pbrt-v4's "bvh" sampler makes the floor
     * brighter than Cavalry's power-proportional choice, and its "power"
     * sampler comes much nearer (README). Matching it would mean copying
     * pbrt-v4's light sampler for an estimator that depends on it; the
     * mask itself is checked by light_alpha_checker. */
    {"light_alpha_half", "pbrt-v4's alpha 0.5 emitter depends on its bvh light sampler"},
};

/* Mean of channel c of the pixels [x0, x1) x [y0, y1); stride: floats per
 * pixel. */
static double region_channel_mean(const float *img, int stride, int c, int x0, int y0, int x1, int y1)
{
    double s = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            s += img[((size_t)y * RES + x) * stride + c];
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
    const char *channels = channels_of(sc->name);
    for (int c = 0; channels && read && c < 3; c++) {
        char one[256];
        float *ch = NULL;
        uint32_t cw = 0, chh = 0;
        snprintf(one, sizeof(one), channels, "rgb"[c]);
        char *path = cv_xasprintf("%s/trace/oracle/%s.exr", dir ? dir : "tests/data", one);
        read = exr_ref_read_rgb(path, &ch, &cw, &chh, why, sizeof(why)) && cw == rw && chh == rh;
        for (uint32_t i = 0; read && i < rw * rh; i++)
            ref[3 * i + c] = ch[3 * i + c];
        free(ch);
        free(path);
    }
    CvCamera cam = test_camera(s, RES, RES);
    /* scenes with media or subsurface ask for volpath, which renders them
     * (Cavalry's path renders subsurface alike) */
    bool volume = s->n_media || s->n_bssrdf;
    struct cv_render_params p = {.seed = seed, .camera = &cam,
                                 .integrator = volume ? CV_INTEGRATOR_VOLPATH : CV_INTEGRATOR_PATH};
    uint32_t spp = s->n_media ? ORACLE_SPP_MEDIA : ORACLE_SPP;
    per_channel(sc->name, &spp);
    const uint32_t passes[] = {spp / 4, spp / 4, spp / 4, spp / 4, 0};
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
    double all = exr_ref_region_mean(img.rgba, RES, 4, 0, 0, RES, RES);
    double all_ref = exr_ref_region_mean(ref, RES, 3, 0, 0, RES, RES);
    double rel_mse = 0;
    for (int i = 0; i < RES * RES; i++)
        for (int c = 0; c < 3; c++) {
            double a = img.rgba[4 * i + c], b = ref[3 * i + c];
            rel_mse += (a - b) * (a - b) / (b * b + 0.01);
        }
    rel_mse /= RES * RES * 3;
    tap_diag("%-24s mean %.5f reference %.5f ratio %.4f relMSE %.5f", sc->name, all, all_ref,
             all / all_ref, rel_mse);
    /* the centre per channel, for colour differences (spectral or not) */
    double c_rgb[3] = {0, 0, 0}, c_ref[3] = {0, 0, 0};
    for (int y = 10; y < 20; y++)
        for (int x = 11; x < 21; x++)
            for (int c = 0; c < 3; c++) {
                c_rgb[c] += img.rgba[4 * (y * RES + x) + c] / 100;
                c_ref[c] += ref[3 * (y * RES + x) + c] / 100;
            }
    tap_diag("  centre rgb   %.5f %.5f %.5f pbrt-v4 %.5f %.5f %.5f", c_rgb[0], c_rgb[1], c_rgb[2], c_ref[0],
             c_ref[1], c_ref[2]);
    /* the whole image, its quadrants, and a centre square inside the
     * sphere of the material scenes (radius about 7.7 pixels) */
    int rg[64][4] = {{0, 0, RES, RES},
                     {0, 0, RES / 2, RES / 2},
                     {RES / 2, 0, RES, RES / 2},
                     {0, RES / 2, RES / 2, RES},
                     {RES / 2, RES / 2, RES, RES},
                     {11, 10, 21, 20}};
    char rname[64][16] = {"image", "top left", "top right", "bottom left", "bottom right", "centre"};
    int n_rg = 6;
    enum oracle_regions kind = regions_of(sc->name);
    if (kind == REGIONS_LINES) {
        for (n_rg = 0; n_rg < 12; n_rg++) {
            memcpy(rg[n_rg], (int[4]){6 + n_rg, 16, 7 + n_rg, RES}, sizeof(rg[0]));
            snprintf(rname[n_rg], sizeof(rname[0]), "column %d", 6 + n_rg);
        }
        for (int y = 4; y < 16; y++, n_rg++) {
            memcpy(rg[n_rg], (int[4]){20, y, RES, y + 1}, sizeof(rg[0]));
            snprintf(rname[n_rg], sizeof(rname[0]), "row %d", y);
        }
    } else if (kind == REGIONS_GRID || kind == REGIONS_GRID8) {
        int side = kind == REGIONS_GRID ? 4 : 8, per_row = RES / side;
        for (n_rg = 0; n_rg < per_row * per_row; n_rg++) {
            int x = side * (n_rg % per_row), y = side * (n_rg / per_row);
            memcpy(rg[n_rg], (int[4]){x, y, x + side, y + side}, sizeof(rg[0]));
            snprintf(rname[n_rg], sizeof(rname[0]), "block %d,%d", x, y);
        }
    }
    double scale = 0; /* the brightest reference region (REGIONS_LINES, _GRID) */
    for (int k = 0; k < n_rg; k++)
        scale = fmax(scale,
                     exr_ref_region_mean(ref, RES, 3, rg[k][0], rg[k][1], rg[k][2], rg[k][3]));
    bool pass = true;
    char worst[128] = "";
    double worst_dev = -1;
    for (int k = 0; k < n_rg; k++) {
        double a = exr_ref_region_mean(img.rgba, RES, 4, rg[k][0], rg[k][1], rg[k][2],
                                       rg[k][3]);
        double b = exr_ref_region_mean(ref, RES, 3, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
        double dev = kind == REGIONS_DEFAULT ? fabs(a - b) / fmax(b, 0.25 * all_ref)
                                                    : fabs(a - b) / scale;
        if (!(dev <= ORACLE_TOL))
            pass = false;
        if (!(dev <= worst_dev)) {
            worst_dev = dev;
            if (kind == REGIONS_DEFAULT)
                snprintf(worst, sizeof(worst), "%.15s ratio %.4f", rname[k], a / b);
            else
                snprintf(worst, sizeof(worst), "%.15s off by %.4f of the brightest", rname[k], dev);
        }
        tap_diag("  %-12s mean %.5f pbrt-v4 %.5f ratio %.4f", rname[k], a, b, a / b);
        for (int c = 0; per_channel(sc->name, NULL) && c < 3; c++) {
            double ac = region_channel_mean(img.rgba, 4, c, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
            double bc = region_channel_mean(ref, 3, c, rg[k][0], rg[k][1], rg[k][2], rg[k][3]);
            double dc = fabs(ac - bc) / fmax(bc, 0.25 * all_ref);
            if (!(dc <= ORACLE_TOL))
                pass = false;
            if (!(dc <= worst_dev)) {
                worst_dev = dc;
                snprintf(worst, sizeof(worst), "%.15s %c ratio %.4f", rname[k], "RGB"[c], ac / bc);
            }
            tap_diag("  %-12s %c    %.5f pbrt-v4 %.5f ratio %.4f", "", "RGB"[c], ac, bc, ac / bc);
        }
    }
    /* one check per scene: a TODO scene whose regions pass only in part
     * must not report XPASS */
    const char *what = per_channel(sc->name, NULL) ? "image, quadrants and centre, per channel"
                       : kind == REGIONS_DEFAULT ? "image, quadrants and centre"
                       : kind == REGIONS_LINES ? "strips beside the lines"
                       : kind == REGIONS_GRID   ? "4x4 blocks"
                                                : "8x8 blocks";
    if (sc->todo)
        tap_todo(pass, sc->todo, "%s: %s within %.1f%% of pbrt-v4 (worst: %s)", sc->name, what,
                 100 * ORACLE_TOL, worst);
    else
        tap_ok(pass, "%s: %s within %.1f%% of pbrt-v4 (worst: %s)", sc->name, what,
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
