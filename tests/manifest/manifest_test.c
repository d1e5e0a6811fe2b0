/* manifest_test.c: a good manifest (defaults, overrides, anchors, merge
 * keys) resolves to the expected jobs; each kind of mistake gives its
 * message at the right file:line:col, and all mistakes of a manifest are
 * reported together. Data: tests/data/manifest. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

static const char *data_dir;

static char *data_path(const char *name)
{
    return cv_xasprintf("%s/manifest/%s", data_dir, name);
}

static bool str_is(const char *got, const char *want)
{
    return got && want && !strcmp(got, want);
}

static void check_good(void)
{
    char *path = data_path("good.yaml");
    struct cv_manifest *m = NULL;
    struct cv_error err = {0};
    if (!tap_ok(cv_manifest_load(path, &m, &err), "good.yaml loads")) {
        tap_diag("%s", err.msg);
        free(path);
        return;
    }
    TAP_EQ_INT(m->n_jobs, 3, "three jobs");
    char *scene = data_path("scenes/tiny.pbrt");
    char *other = data_path("scenes/other.pbrt");

    const struct cv_job *h = cv_manifest_find_job(m, "hero");
    const struct cv_job *p = cv_manifest_find_job(m, "preview");
    const struct cv_job *g = cv_manifest_find_job(m, "guided");
    tap_ok(h == &m->jobs[0] && p == &m->jobs[1] && g == &m->jobs[2], "jobs in manifest order");
    tap_ok(cv_manifest_find_job(m, "nope") == NULL, "unknown name finds nothing");
    if (!h || !p || !g)
        return;

    /* hero: defaults with own overrides; color merged key by key. */
    tap_ok(str_is(h->scene, scene), "hero scene from defaults, joined: %s", h->scene);
    tap_ok(str_is(h->scene_as_written, "scenes/tiny.pbrt"), "hero scene as written");
    TAP_EQ_INT(h->line, 26, "hero line");
    TAP_EQ_INT(h->col, 5, "hero col");
    tap_ok(h->has_spp && h->spp == 256, "hero spp overrides defaults");
    tap_ok(h->has_resolution && h->width == 640 && h->height == 360, "hero resolution list");
    tap_ok(h->formats == (CV_FORMAT_EXR | CV_FORMAT_PNG), "hero formats from defaults");
    tap_ok(h->color.has_exposure && h->color.exposure == -1.0f, "hero exposure overrides");
    tap_ok(str_is(h->color.display, "sRGB") && str_is(h->color.view, "ACES 1.0 - SDR Video"),
           "hero display and view merged from defaults' color");
    tap_ok(h->color.look == NULL && h->color.config == NULL, "hero look and config unset");
    tap_ok(h->aovs == (CV_AOV_ALBEDO | CV_AOV_NORMAL), "hero aovs");
    tap_ok(h->exr.compression == CV_EXR_PIZ && h->exr.half && !h->exr.has_half,
           "hero exr from defaults (half by default)");
    tap_ok(h->png.bits == 8 && !h->png.has_bits, "hero png bits default 8");
    tap_ok(!h->has_integrator && !h->has_max_depth && !h->has_time_limit &&
               !h->has_seed && !h->camera.has_fov && !h->camera.has_lookat,
           "hero leaves the rest to the scene");
    char *want = data_path("out/hero");
    tap_ok(str_is(h->output, want), "hero output templated: %s", h->output);
    free(want);
    char *png = cv_job_output_path(h, "png");
    want = data_path("out/hero.png");
    tap_ok(str_is(png, want), "cv_job_output_path adds the extension: %s", png);
    free(png);
    free(want);

    /* preview: a merge key, "WxH" resolution, minutes. */
    tap_ok(p->has_spp && p->spp == 16, "preview spp from the merged anchor");
    tap_ok(p->has_max_depth && p->max_depth == 4 && p->integrator == CV_INTEGRATOR_PATH,
           "preview max_depth and integrator merged");
    tap_ok(p->has_resolution && p->width == 320 && p->height == 180, "preview resolution WxH");
    tap_ok(p->formats == CV_FORMAT_PNG, "preview formats overrides");
    tap_ok(p->png.has_bits && p->png.bits == 16, "preview png bits");
    tap_ok(p->has_time_limit && fabs(p->time_limit - 90.0) < 1e-9, "1.5m is 90 s");
    tap_ok(p->color.has_exposure && p->color.exposure == 0.5f, "preview exposure from defaults");

    /* guided: a list of merges, own keys win. */
    tap_ok(g->has_spp && g->spp == 32, "guided own spp beats the merged one");
    tap_ok(g->has_max_depth && g->max_depth == 4, "guided max_depth from the first merge");
    tap_ok(g->integrator == CV_INTEGRATOR_RLPATH, "guided integrator");
    tap_ok(str_is(g->color.look, "Filmic") && str_is(g->color.display, "sRGB") &&
               g->color.exposure == 0.5f,
           "guided color: look merged from an anchor, the rest from defaults");
    tap_ok(g->rlpath.has_grid && g->rlpath.grid == 8 && g->rlpath.directions == 16 &&
               g->rlpath.mix == 0.5f && g->rlpath.has_guide && g->rlpath.guide == CV_RL_GUIDE_INDIRECT,
           "guided rlpath");
    tap_ok(!p->rlpath.has_guide && p->rlpath.guide == CV_RL_GUIDE_ALL, "rlpath guide: all by default");
    tap_ok(str_is(g->scene, other), "guided own scene");
    want = data_path("renders/guided_final");
    tap_ok(str_is(g->output, want), "guided output template: %s", g->output);
    free(want);
    tap_ok(g->has_seed && g->seed == 7, "guided seed");
    tap_ok(g->camera.has_fov && g->camera.fov == 45.0f, "guided fov");
    tap_ok(g->camera.has_lookat && g->camera.eye[1] == 1.0f && g->camera.eye[2] == 5.0f &&
               g->camera.up[1] == 1.0f,
           "guided lookat");
    tap_ok(g->exr.half && g->exr.compression == CV_EXR_PIZ, "guided exr merged key by key");
    tap_ok(g->has_time_limit && g->time_limit == 90.0, "guided time_limit seconds");
    tap_ok(h->settings_hash && strlen(h->settings_hash) == 16, "settings hash is 16 hex digits");
    tap_ok(strcmp(h->settings_hash, p->settings_hash) != 0, "different jobs, different hashes");

    cv_manifest_destroy(&m);
    tap_ok(m == NULL, "destroy clears the pointer");
    cv_manifest_destroy(&m);
    cv_manifest_destroy(NULL);
    free(scene);
    free(other);
    free(path);
}

/* s with every "@@" replaced by path (newly allocated). */
static char *with_path(const char *s, const char *path)
{
    char *out = cv_xstrdup("");
    for (const char *at; (at = strstr(s, "@@")); s = at + 2) {
        char *next = cv_xasprintf("%s%.*s%s", out, (int)(at - s), s, path);
        free(out);
        out = next;
    }
    char *next = cv_xasprintf("%s%s", out, s);
    free(out);
    return next;
}

/* Loads name, which must fail with exactly the lines in want (each a
 * "LINE:COL: message" to which the path is prefixed; "@@" in a message
 * stands for the manifest's folder). */
static void check_error(const char *name, const char *const *want, size_t n_want)
{
    char *path = data_path(name);
    char *dir = data_path("");
    dir[strlen(dir) - 1] = '\0';
    struct cv_manifest *m = NULL;
    struct cv_error err = {0};
    bool ok = cv_manifest_load(path, &m, &err);
    tap_ok(!ok && m == NULL, "%s is rejected", name);
    char *expect = cv_xstrdup("");
    for (size_t i = 0; i < n_want; i++) {
        char *line = with_path(want[i], dir);
        char *next = cv_xasprintf("%s%s%s:%s", expect, i ? "\n" : "", path, line);
        free(line);
        free(expect);
        expect = next;
    }
    if (!tap_ok(!strcmp(err.msg, expect), "%s: message", name)) {
        tap_diag("got:\n%s", err.msg);
        tap_diag("want:\n%s", expect);
    }
    free(expect);
    free(path);
    free(dir);
    cv_manifest_destroy(&m);
}

#define CHECK_ERROR(name, ...)                                   \
    do {                                                         \
        static const char *const w[] = {__VA_ARGS__};            \
        check_error(name, w, CV_ARRAY_SIZE(w));                  \
    } while (0)

#define JOB_KEYS                                                                      \
    "name, scene, output, formats, resolution, crop, spp, time_limit, integrator, max_depth, " \
    "seed, color, aovs, exr, png, camera, rlpath, matrix, env, lights, alpha"

int main(void)
{
    data_dir = getenv("CV_TEST_DATA");
    if (!data_dir)
        data_dir = CV_SRCDIR "/tests/data";
    check_good();

    CHECK_ERROR("err_unknown_key.yaml",
                "5:5: unknown key \"sp\" in job; valid keys: " JOB_KEYS " (did you mean \"spp\"?)");
    CHECK_ERROR("err_wrong_type.yaml",
                "5:10: spp: expected an integer from 1 to 16777216, got \"lots\"",
                "6:17: resolution: expected [width, height] or \"WIDTHxHEIGHT\" with sides "
                "from 1 to 65536, got a list of 1",
                "8:13: exr.half: expected true or false, got \"maybe\"");
    CHECK_ERROR("err_negative_spp.yaml",
                "5:10: spp: expected an integer from 1 to 16777216, got \"-4\"");
    CHECK_ERROR("err_missing_scene.yaml",
                "6:12: job \"b\" (line 5): scene file \"scenes/missing.pbrt\" not found "
                "(@@/scenes/missing.pbrt: No such file or directory)");
    CHECK_ERROR("err_duplicate_names.yaml",
                "7:11: duplicate job name \"shot\" (first defined at "
                "@@/err_duplicate_names.yaml:5:11)");
    CHECK_ERROR("err_missing_version.yaml",
                "1:1: missing required key \"version\" (write \"version: 1\" at the top)");
    CHECK_ERROR("err_syntax.yaml",
                "5:9: YAML syntax error: did not find expected ',' or ']' (while parsing a "
                "flow sequence at line 4, column 12)");
    CHECK_ERROR("err_many.yaml",
                "5:3: unknown key \"colour\" in defaults; valid keys: scene, output, formats, "
                "resolution, crop, spp, time_limit, integrator, max_depth, seed, color, aovs, exr, "
                "png, camera, rlpath, env, lights, alpha (did you mean \"color\"?)",
                "8:17: integrator: expected one of path, rlpath, volpath, bdpt, got \"bidir\"",
                "9:5: job 2: missing required key \"name\"",
                "10:11: name: \"b c\" has ' '; job names use only letters, digits, '.', '_' "
                "and '-'",
                "11:17: time_limit: expected a duration > 0 in seconds, or with a unit s, m or "
                "h (\"90\", \"1.5m\", \"2h\"), got \"-3\"",
                "12:19: rlpath.mix: expected a number from 0 to 1, got \"1.5\"",
                "12:31: rlpath.guide: expected one of all, indirect, got \"most\"");
    return tap_done();
}
