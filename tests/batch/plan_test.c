/* plan_test.c: the render plan (batch/plan.h) and the film rules it shares
 * with the scene loader (scene/film.h), on the CPU: crop windows at their
 * edges, screen windows and resolution changes, a manifest fov and LookAt
 * against the same settings in a scene file, the fallbacks for spp, depth
 * and seed, the shorter time limit, a scene's integrator that Cavalry
 * substitutes (a warning, an error with --strict) and colour names checked
 * at the key that holds them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/limits.h"
#include "base/mem.h"
#include "batch/plan.h"
#include "glsl/shared/sdtree.h"
#include "manifest/manifest.h"
#include "scene/film.h"
#include "scene/scene.h"
#include "tests/tap.h"

static char dir[256];

static char *write_file(const char *name, const char *text)
{
    char *path = cv_xasprintf("%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

static struct cv_scene *scene_of(const char *text)
{
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    char *path = write_file("s.pbrt", text);
    if (!cv_scene_load(path, &lp, &s, &err))
        tap_diag("scene: %s", err.msg);
    free(path);
    return s;
}

static struct cv_manifest *manifest_of(const char *text)
{
    struct cv_manifest *m = NULL;
    struct cv_error err = {{0}};
    char *path = write_file("m.yaml", text);
    if (!cv_manifest_load(path, &m, &err))
        tap_diag("manifest: %s", err.msg);
    free(path);
    return m;
}

static bool crop_is(uint32_t w, uint32_t h, double x0, double x1, double y0, double y1,
                    uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    uint32_t px[4];
    cv_film_crop_pixels(w, h, (const double[4]){x0, x1, y0, y1}, px);
    if (px[0] == a && px[1] == b && px[2] == c && px[3] == d)
        return true;
    tap_diag("crop on %ux%u: got %u %u %u %u, want %u %u %u %u", w, h, px[0], px[1], px[2],
             px[3], a, b, c, d);
    return false;
}

static void test_film_rules(void)
{
    tap_ok(crop_is(40, 20, 0, 1, 0, 1, 0, 40, 0, 20), "full crop window: the whole film");
    tap_ok(crop_is(40, 20, 0.25, 0.75, 0, 0.5, 10, 30, 0, 10), "pbrt's ceil(res * crop)");
    tap_ok(crop_is(10, 10, 0.41, 0.42, 0, 1, 4, 5, 0, 10),
           "a window inside pixel 4 renders pixel 4");
    tap_ok(crop_is(10, 10, 0.95, 0.99, 0.95, 0.99, 9, 10, 9, 10),
           "a thin window at the far edge stays on the film (pixel 9 of 10)");
    tap_ok(crop_is(10, 10, 0, 0.01, 0, 0.01, 0, 1, 0, 1), "a thin window at the near edge");
    tap_ok(crop_is(3, 3, 1.0 / 3, 2.0 / 3, 0, 1, 1, 2, 0, 3), "edges on pixel boundaries");

    cv_vec4 wide = cv_film_default_screen(2), tall = cv_film_default_screen(0.5);
    tap_ok(wide.x == -2 && wide.y == 2 && wide.z == -1 && wide.w == 1 && tall.x == -1 &&
               tall.y == 1 && tall.z == -2 && tall.w == 2,
           "default screen window: the longer axis spans the aspect ratio");

    CvCamera c = {.screen = {-3, 3, -1.5f, 1.5f}, .film = {40, 20, 0, 0}, .crop = {40, 20, 0, 0}};
    const double half[4] = {0, 0.5, 0, 1};
    tap_ok(!cv_camera_fit_film(&c, half, 80, 40) && c.screen.x == -3 && c.film.x == 80 &&
               c.film.y == 40 && c.crop.x == 40 && c.crop.y == 40,
           "same aspect ratio: the screen window (an explicit one) is kept, the crop refit");
    tap_ok(cv_camera_fit_film(&c, half, 40, 40) && c.screen.x == -1 && c.screen.y == 1 &&
               c.screen.z == -1 && c.crop.x == 20,
           "a new aspect ratio gets its default screen window, and says so");
}

/* A manifest's fov and LookAt give the camera that the same settings in the
 * scene file give. */
static void test_camera_overrides(void)
{
    struct cv_scene *moved = scene_of("LookAt 1 2 3  0 0 1  0 1 0\n"
                                      "Camera \"perspective\" \"float fov\" 22\n"
                                      "Film \"rgb\" \"integer xresolution\" 32 "
                                      "\"integer yresolution\" 16\nWorldBegin\n");
    struct cv_scene *plain = scene_of("Camera \"perspective\" \"float fov\" 60\n"
                                      "Film \"rgb\" \"integer xresolution\" 64 "
                                      "\"integer yresolution\" 32\nWorldBegin\n");
    struct cv_manifest *m = manifest_of(
        "version: 1\njobs:\n"
        "  - {name: a, scene: s.pbrt, resolution: [32, 16], camera: {fov: 22, "
        "lookat: [[1, 2, 3], [0, 0, 1], [0, 1, 0]]}}\n"
        "  - {name: b, scene: s.pbrt, camera: {lookat: [[0, 0, 0], [0, 0, 1], [0, 0, 2]]}}\n"
        "  - {name: c, scene: s.pbrt, resolution: [32, 8], camera: {lookat: [1, 0, 0, 1, 0, 1, "
        "0, 1, 0]}}\n");
    if (!tap_ok(moved && plain && m, "scenes and manifest load")) {
        cv_scene_destroy(&moved);
        cv_scene_destroy(&plain);
        cv_manifest_destroy(&m);
        return;
    }
    struct cv_plan_options o = {.manifest_path = m->path};
    struct cv_render_plan p;
    struct cv_error err = {{0}};
    bool ok = cv_plan_make(&m->jobs[0], plain, &o, &p, &err);
    tap_ok(ok && memcmp(&p.camera, &moved->camera, sizeof(CvCamera)) == 0,
           "fov 22, LookAt and 32x16 from the manifest: the scene file's camera, bit for bit %s",
           err.msg);
    tap_ok(ok && p.width == 32 && p.height == 16, "the plan's film is 32x16");
    cv_error_clear(&err);
    tap_ok(!cv_plan_make(&m->jobs[1], plain, &o, &p, &err) &&
               strstr(err.msg, "m.yaml:4:") && strstr(err.msg, "camera.lookat") &&
               strstr(err.msg, "parallel"),
           "an up vector along the view direction fails at the job: %s", err.msg);
    cv_error_clear(&err);
    /* a spherical camera sees every direction: no fov to set; a new aspect
     * ratio changes no screen window of it */
    struct cv_scene *sph = scene_of("Camera \"spherical\"\nWorldBegin\n");
    tap_ok(sph && !cv_plan_make(&m->jobs[0], sph, &o, &p, &err) && strstr(err.msg, "m.yaml:3:66:") &&
               strstr(err.msg, "camera.fov: the scene's camera is spherical"),
           "camera.fov on a spherical camera fails at the key: %s", err.msg);
    cv_error_clear(&err);
    tap_ok(sph && cv_plan_make(&m->jobs[2], sph, &o, &p, &err) &&
               p.camera.type == CV_CAMERA_EQUAL_AREA && p.width == 32 && p.height == 8 &&
               p.camera.to_world[0].w == 1,
           "camera.lookat and a resolution of another aspect on a spherical camera %s", err.msg);
    cv_scene_destroy(&sph);
    cv_scene_destroy(&moved);
    cv_scene_destroy(&plain);
    cv_manifest_destroy(&m);
}

static void test_fallbacks(void)
{
    struct cv_scene *bare = scene_of("Camera \"perspective\"\nWorldBegin\n");
    struct cv_scene *set = scene_of("Sampler \"halton\" \"integer pixelsamples\" 7\n"
                                    "Integrator \"path\" \"integer maxdepth\" 3\n"
                                    "Camera \"perspective\"\nWorldBegin\n");
    struct cv_manifest *m = manifest_of("version: 1\njobs:\n"
                                        "  - {name: a, scene: s.pbrt}\n"
                                        "  - {name: b, scene: s.pbrt, spp: 5, max_depth: 9, "
                                        "seed: 4, time_limit: 60}\n");
    if (!tap_ok(bare && set && m, "scenes and manifest load")) {
        cv_scene_destroy(&bare);
        cv_scene_destroy(&set);
        cv_manifest_destroy(&m);
        return;
    }
    struct cv_plan_options o = {.manifest_path = m->path};
    struct cv_render_plan p;
    struct cv_error err = {{0}};
    bool ok = cv_plan_make(&m->jobs[0], bare, &o, &p, &err);
    tap_ok(ok && p.spp == CV_DEFAULT_SPP && p.max_depth == CV_DEFAULT_MAX_DEPTH && p.seed == 0 &&
               p.time_limit == 0 && p.integrator == CV_INTEGRATOR_PATH && !p.substituted,
           "nothing set anywhere: pbrt's 16 spp and depth 5, seed 0, no limit, path");
    tap_ok(ok && p.width == 1280 && p.height == 720 && p.camera.crop.x == 1280,
           "pbrt's default film 1280x720");
    ok = cv_plan_make(&m->jobs[0], set, &o, &p, &err);
    tap_ok(ok && p.spp == 7 && p.max_depth == 3, "the scene's spp and depth");
    o.time_limit = 90;
    ok = cv_plan_make(&m->jobs[1], set, &o, &p, &err);
    tap_ok(ok && p.spp == 5 && p.max_depth == 9 && p.seed == 4 && p.time_limit == 60,
           "the job's spp, depth, seed; its time limit under a longer --time-limit");
    o.time_limit = 30;
    ok = cv_plan_make(&m->jobs[1], set, &o, &p, &err);
    tap_ok(ok && p.time_limit == 30, "a shorter --time-limit wins");
    struct cv_render_params rp = cv_plan_render_params(&p);
    tap_ok(rp.camera == &p.camera && rp.max_depth == 9 && rp.seed == 4 &&
               rp.integrator == CV_INTEGRATOR_PATH,
           "the renderer's parameters come from the plan");
    cv_scene_destroy(&bare);
    cv_scene_destroy(&set);
    cv_manifest_destroy(&m);
}

/* Issue 24, bug 9: a scene's bdpt was rendered with path, said only while
 * rendering. Issue 27: bdpt renders it now; sppm is rendered with bdpt,
 * substituted. */
static void test_substituted_integrator(void)
{
    struct cv_scene *s = scene_of("Camera \"perspective\"\n\n  Integrator \"sppm\"\nWorldBegin\n");
    struct cv_manifest *m = manifest_of("version: 1\njobs:\n"
                                        "  - {name: a, scene: s.pbrt}\n"
                                        "  - {name: b, scene: s.pbrt, integrator: rlpath}\n");
    if (!tap_ok(s && m, "scene and manifest load")) {
        cv_scene_destroy(&s);
        cv_manifest_destroy(&m);
        return;
    }
    struct cv_plan_options o = {.manifest_path = m->path};
    struct cv_render_plan p;
    struct cv_error err = {{0}};
    tap_ok(cv_plan_make(&m->jobs[0], s, &o, &p, &err) && p.substituted &&
               !strcmp(p.substituted, "sppm") && p.integrator == CV_INTEGRATOR_BDPT,
           "sppm is rendered with bdpt, and the plan says so");
    o.strict = true;
    tap_ok(!cv_plan_make(&m->jobs[0], s, &o, &p, &err) && strstr(err.msg, "s.pbrt:3:3: ") &&
               strstr(err.msg, "\"sppm\"") && strstr(err.msg, "--strict"),
           "--strict: an error at the scene's Integrator: %s", err.msg);
    cv_error_clear(&err);
    o.strict = false;
    struct cv_scene *b = scene_of("Camera \"perspective\"\n\n  Integrator \"bdpt\"\nWorldBegin\n");
    struct cv_scene *env = scene_of("Camera \"perspective\"\nIntegrator \"bdpt\"\nWorldBegin\n"
                                    "LightSource \"distant\" \"rgb L\" [ 1 1 1 ]\n");
    struct cv_scene *ortho = scene_of("Camera \"orthographic\"\nIntegrator \"bdpt\"\nWorldBegin\n");
    tap_ok(b && cv_plan_make(&m->jobs[0], b, &o, &p, &err) && !p.substituted &&
               p.integrator == CV_INTEGRATOR_BDPT,
           "bdpt is rendered with bdpt, not substituted");
    tap_ok(env && cv_plan_make(&m->jobs[0], env, &o, &p, &err) && !p.substituted &&
               p.integrator == CV_INTEGRATOR_BDPT,
           "bdpt with a distant light is rendered with bdpt");
    tap_ok(ortho && cv_plan_make(&m->jobs[0], ortho, &o, &p, &err) && !p.substituted &&
               p.integrator == CV_INTEGRATOR_BDPT,
           "bdpt with an orthographic camera is rendered with bdpt");
    cv_scene_destroy(&b);
    cv_scene_destroy(&env);
    cv_scene_destroy(&ortho);
    cv_error_clear(&err);
    tap_ok(cv_plan_make(&m->jobs[1], s, &o, &p, &err) && !p.substituted &&
               p.integrator == CV_INTEGRATOR_RLPATH,
           "a job that names its integrator substitutes nothing, even with --strict %s",
           err.msg);
    cv_scene_destroy(&s);
    cv_manifest_destroy(&m);
}

/* Issue 27: bdpt renders a moving camera and a job's alpha and ID mattes:
 * neither a scene that asks for bdpt nor a job that names it falls back. */
static void test_bdpt_camera_mattes(void)
{
    struct cv_scene *moving = scene_of("LookAt 0 0 -5  0 0 0  0 1 0\nActiveTransform EndTime\n"
                                       "Translate 0.3 0 0\nActiveTransform All\n"
                                       "Camera \"perspective\"\nIntegrator \"bdpt\"\nWorldBegin\n");
    struct cv_manifest *m = manifest_of("version: 1\njobs:\n"
                                        "  - {name: a, scene: s.pbrt}\n"
                                        "  - {name: b, scene: s.pbrt, integrator: bdpt, alpha: true, "
                                        "formats: [exr], aovs: [object_id, material_id, "
                                        "crypto_object, crypto_material]}\n");
    if (tap_ok(moving && m, "moving-camera scene and manifest load")) {
        struct cv_plan_options o = {.manifest_path = m->path, .strict = true};
        struct cv_render_plan p;
        struct cv_error err = {{0}};
        tap_ok(cv_plan_make(&m->jobs[0], moving, &o, &p, &err) && !p.substituted &&
                   p.integrator == CV_INTEGRATOR_BDPT,
               "bdpt with a moving camera is rendered with bdpt, even with --strict %s", err.msg);
        cv_error_clear(&err);
        tap_ok(cv_plan_make(&m->jobs[1], moving, &o, &p, &err) &&
                   p.integrator == CV_INTEGRATOR_BDPT,
               "a job naming bdpt with alpha, ID AOVs and Cryptomatte plans %s", err.msg);
    }
    cv_scene_destroy(&moving);
    cv_manifest_destroy(&m);
}

/* Issue 29: rlpath's settings reach the renderer. rlpath.train: unset is
 * the default count, 0 learns in every pass (CV_RL_TRAIN_ALWAYS), a count
 * is that count. rlpath.fallback: unset and true measure after training
 * whether to guide on (CV_RL_CHOICE_MEASURE), false keeps guiding
 * (CV_RL_CHOICE_GUIDED); a value not a boolean is an error at its place.
 * rlpath.filter reaches sdtree as its filter bits, unset as unset. */
static void test_rlpath_settings(void)
{
    static const struct {
        const char *rlpath;
        uint32_t train;
        int choice;
        int filter;   /* sdtree's filter bits; -1: unset */
    } cases[] = {
        {"{}", CV_RL_DEFAULT_TRAIN, CV_RL_CHOICE_MEASURE, -1},
        {"{train: 0}", CV_RL_TRAIN_ALWAYS, CV_RL_CHOICE_MEASURE, -1},
        {"{train: 64, fallback: true}", 64, CV_RL_CHOICE_MEASURE, -1},
        {"{method: sdtree, fallback: false}", CV_RL_DEFAULT_TRAIN, CV_RL_CHOICE_GUIDED, -1},
        {"{method: sdtree, filter: none}", CV_RL_DEFAULT_TRAIN, CV_RL_CHOICE_MEASURE, 0},
        {"{method: sdtree, filter: spatial}", CV_RL_DEFAULT_TRAIN, CV_RL_CHOICE_MEASURE,
         CV_SD_FILTER_SPATIAL},
        {"{method: sdtree, filter: both}", CV_RL_DEFAULT_TRAIN, CV_RL_CHOICE_MEASURE,
         CV_SD_FILTER_SPATIAL | CV_SD_FILTER_DIRECTIONAL},
    };
    struct cv_scene *s = scene_of("WorldBegin\n");
    for (size_t j = 0; j < sizeof(cases) / sizeof(cases[0]); j++) {
        char text[256];
        snprintf(text, sizeof(text), "version: 1\njobs:\n  - {name: a, scene: s.pbrt, "
                 "integrator: rlpath, rlpath: %s}\n", cases[j].rlpath);
        struct cv_manifest *m = manifest_of(text);
        struct cv_render_plan p;
        struct cv_error err = {{0}};
        bool ok = s && m && cv_plan_make(&m->jobs[0], s,
                                         &(struct cv_plan_options){.manifest_path = m->path},
                                         &p, &err);
        struct cv_render_params rp = ok ? cv_plan_render_params(&p) : (struct cv_render_params){0};
        int filter = rp.rl_sd_filter_set ? (int)rp.rl_sd_filter : -1;
        tap_ok(ok && rp.rl_train == cases[j].train && (int)rp.rl_choice == cases[j].choice &&
                   filter == cases[j].filter,
               "rlpath: %s: rl_train %u (want %u), rl_choice %d (want %d), filter %d (want %d) %s",
               cases[j].rlpath, rp.rl_train, cases[j].train, (int)rp.rl_choice, cases[j].choice,
               filter, cases[j].filter, err.msg);
        cv_manifest_destroy(&m);
    }
    cv_scene_destroy(&s);
    struct cv_error err = {{0}};
    char *path = write_file("bad.yaml",
                            "version: 1\njobs:\n"
                            "  - {name: a, scene: s.pbrt, rlpath: {fallback: maybe}}\n");
    struct cv_manifest *mb = NULL;
    bool ok = cv_manifest_load(path, &mb, &err);
    tap_ok(!ok && strstr(err.msg, "bad.yaml:3:") && strstr(err.msg, "rlpath.fallback"),
           "rlpath.fallback: maybe is an error at its place: %s", err.msg);
    cv_manifest_destroy(&mb);
    free(path);
}

/* Issue 27: volpath and bdpt render media; a scene with media that asks
 * for nothing renders with volpath, one that asks for path ignores them
 * (pbrt-v4's path does too), and so does one that asks for sppm (pbrt-v4's
 * sppm ignores them: path, not bdpt). */
static void test_media_integrator(void)
{
    const char *media = "WorldBegin\nMakeNamedMedium \"fog\" \"string type\" \"homogeneous\"\n";
    char text[512];
    struct cv_scene *sc[5];
    const char *asked[5] = {"volpath", "bdpt", NULL, "path", "sppm"};
    for (int i = 0; i < 5; i++) {
        snprintf(text, sizeof(text), "Camera \"perspective\"\n%s%s%s%s", asked[i] ? "Integrator \"" : "",
                 asked[i] ? asked[i] : "", asked[i] ? "\"\n" : "", media);
        sc[i] = scene_of(text);
    }
    struct cv_manifest *m = manifest_of("version: 1\njobs:\n  - {name: a, scene: s.pbrt}\n");
    if (tap_ok(sc[0] && sc[1] && sc[2] && sc[3] && sc[4] && m, "media scenes and manifest load")) {
        struct cv_plan_options o = {.manifest_path = m->path};
        struct cv_render_plan p;
        struct cv_error err = {{0}};
        tap_ok(cv_plan_make(&m->jobs[0], sc[0], &o, &p, &err) && !p.substituted &&
                   p.integrator == CV_INTEGRATOR_VOLPATH,
               "volpath is rendered with volpath, not substituted");
        tap_ok(cv_plan_make(&m->jobs[0], sc[1], &o, &p, &err) && !p.substituted &&
                   p.integrator == CV_INTEGRATOR_BDPT,
               "bdpt in a scene with media is rendered with bdpt, not substituted");
        tap_ok(cv_plan_make(&m->jobs[0], sc[4], &o, &p, &err) && p.substituted &&
                   p.integrator == CV_INTEGRATOR_PATH,
               "sppm in a scene with media is rendered with path (pbrt-v4's sppm ignores media)");
        tap_ok(cv_plan_make(&m->jobs[0], sc[2], &o, &p, &err) && !p.substituted &&
                   p.integrator == CV_INTEGRATOR_VOLPATH,
               "no integrator in a scene with media: volpath (pbrt-v4's default)");
        tap_ok(cv_plan_make(&m->jobs[0], sc[3], &o, &p, &err) && !p.substituted &&
                   p.integrator == CV_INTEGRATOR_PATH,
               "path stays path (media ignored with a warning, as pbrt-v4's path)");
        o.strict = true;
        tap_ok(cv_plan_make(&m->jobs[0], sc[0], &o, &p, &err),
               "--strict accepts volpath: %s", err.msg);
    }
    for (int i = 0; i < 5; i++)
        cv_scene_destroy(&sc[i]);
    cv_manifest_destroy(&m);
}

/* Colour names fail at the manifest key that holds them, before any render. */
static void test_color(void)
{
    struct cv_scene *s = scene_of("Camera \"perspective\"\nWorldBegin\n");
    char *not_ocio = write_file("not.ocio", "this is not an OCIO config\n");
    free(not_ocio);
    struct cv_manifest *m = manifest_of(
        "version: 1\ndefaults: {scene: s.pbrt, formats: [png]}\njobs:\n"
        "  - name: good\n    color: {view: Un-tone-mapped}\n"
        "  - name: view\n    color:\n      view: No Such View\n"
        "  - name: display\n    color: {display: Nowhere}\n"
        "  - name: config\n    color: {config: not.ocio}\n"
        "  - name: look\n    color: {look: NoLook}\n"
        "  - {name: exr, formats: [exr], color: {view: No Such View}}\n");
    if (!tap_ok(s && m, "scene and manifest load")) {
        cv_scene_destroy(&s);
        cv_manifest_destroy(&m);
        return;
    }
    struct cv_plan_options o = {.manifest_path = m->path, .check_color = true};
    struct cv_render_plan p;
    struct cv_error err = {{0}};
    static const struct {
        const char *at, *what;
    } bad[] = {
        {"m.yaml:8:13: ", "No Such View"},
        {"m.yaml:10:22: ", "Nowhere"},
        {"m.yaml:12:21: ", "not.ocio"},
        {"m.yaml:14:19: ", "NoLook"},
    };
    tap_ok(cv_plan_make(&m->jobs[0], s, &o, &p, &err), "a view of the config passes %s",
           err.msg);
    for (size_t i = 0; i < 4; i++) {
        cv_error_clear(&err);
        tap_ok(!cv_plan_make(&m->jobs[1 + i], s, &o, &p, &err) && strstr(err.msg, bad[i].at) &&
                   strstr(err.msg, bad[i].what),
               "job %s fails at %s: %s", m->jobs[1 + i].name, bad[i].at, err.msg);
    }
    cv_error_clear(&err);
    tap_ok(cv_plan_make(&m->jobs[5], s, &o, &p, &err),
           "a job without png output does not open the colour config %s", err.msg);
    cv_scene_destroy(&s);
    cv_manifest_destroy(&m);
}

int main(void)
{
    snprintf(dir, sizeof(dir), "%s/cavalry-plan-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir))
        return tap_skip_all("cannot make a temporary folder");
    test_film_rules();
    test_camera_overrides();
    test_fallbacks();
    test_substituted_integrator();
    test_media_integrator();
    test_rlpath_settings();
    test_color();
    test_bdpt_camera_mattes();
    char *cmd = cv_xasprintf("rm -rf '%s'", dir);
    if (system(cmd) != 0)
        tap_diag("could not remove %s", dir);
    free(cmd);
    return tap_done();
}
