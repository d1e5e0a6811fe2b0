/* keys.c: the manifest key table (see keys.h). The defaults and ranges
 * written here are the only copies; cavalry-manifest(5) words them for
 * people, and tests/manifest/keys_test.c checks the rows against it. */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "base/limits.h"
#include "manifest/keys.h"
#include "manifest/manifest.h"

#define AT(field) offsetof(struct cv_job, field)

static bool is_name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '_' || c == '-';
}

static bool check_name(const void *value, char *msg, size_t n)
{
    const char *s = *(const char *const *)value;
    /* "." and ".." would make {name} outputs name the folder itself or its parent */
    if (strcmp(s, ".") == 0 || strcmp(s, "..") == 0) {
        snprintf(msg, n, "name: \"%s\" is not a job name: it names a folder", s);
        return false;
    }
    for (const char *p = s; *p; p++) {
        if (!is_name_char(*p)) {
            snprintf(msg, n,
                     "name: \"%s\" has '%c'; job names use only letters, digits, '.', '_' "
                     "and '-'", s, *p);
            return false;
        }
    }
    return true;
}

/* Only {name} and {KEY} of a key the matrix may vary appear in braces: a
 * typo such as {nmae} would otherwise silently become part of every file
 * name. Whether the job's matrix has the key is checked when the template
 * is expanded (manifest.c). */
static bool check_output(const void *value, char *msg, size_t n)
{
    const char *s = *(const char *const *)value;
    for (const char *p = strchr(s, '{'); p; p = strchr(p + 1, '{')) {
        const char *end = strchr(p, '}');
        char key[64] = "";
        if (end && (size_t)(end - p - 1) < sizeof(key))
            snprintf(key, sizeof(key), "%.*s", (int)(end - p - 1), p + 1);
        const struct cv_key *k = cv_key_find(key);
        if (strcmp(key, "name") != 0 && !(k && cv_key_in_matrix(k))) {
            snprintf(msg, n,
                     "output: \"%s\": only {name} and {KEY} of a key of the job's matrix may "
                     "be written in braces", s);
            return false;
        }
    }
    if (s[0] && s[strlen(s) - 1] == '/') {
        snprintf(msg, n,
                 "output: \"%s\" names a folder; expected a file name without extension, "
                 "e.g. \"%s{name}\"", s, s);
        return false;
    }
    return true;
}

static bool check_png_bits(const void *value, char *msg, size_t n)
{
    long long bits = *(const long long *)value;
    if (bits == 8 || bits == 16)
        return true;
    snprintf(msg, n, "png.bits: expected 8 or 16, got \"%lld\"", bits);
    return false;
}

static bool check_fov(const void *value, char *msg, size_t n)
{
    double f = *(const double *)value;
    if (f > 0 && f < 180)
        return true;
    snprintf(msg, n, "camera.fov: expected degrees between 0 and 180 (exclusive), got \"%g\"", f);
    return false;
}

#define OUTPUT_SETTING .merge = CV_MERGE_FROM_DEFAULTS, .fill_default = true
#define SECTION(n, h) {.name = n, .type = CV_KT_SECTION, .help = h}

const struct cv_key cv_manifest_keys[CV_K_COUNT] = {
    [CV_K_NAME] = {.name = "name", .type = CV_KT_STRING, .offset = AT(name),
                   .merge = CV_MERGE_JOB_ONLY, .check = check_name,
                   .help = "the job's name, unique in the manifest: [A-Za-z0-9._-]+"},
    [CV_K_SCENE] = {.name = "scene", .type = CV_KT_STRING, .offset = AT(scene_as_written),
                    .hash = CV_HASH_WITH_STAMP,
                    .help = "pbrt-v3/v4 scene file, relative to the manifest's folder"},
    [CV_K_OUTPUT] = {.name = "output", .type = CV_KT_STRING, .offset = AT(output),
                     .def_text = "{name}", .check = check_output,
                     .help = "output path without extension; {name} is the job's name"},
    [CV_K_FORMATS] = {.name = "formats", .type = CV_KT_BITS, .names = &cv_format_names,
                      .offset = AT(formats), .has = AT(has_formats), OUTPUT_SETTING,
                      .def = CV_FORMAT_EXR, .def_text = "[exr]",
                      .help = "files to write: exr (scene-linear), png (display-referred)"},
    [CV_K_RESOLUTION] = {.name = "resolution", .type = CV_KT_RESOLUTION, .min = 1,
                         .max = CV_MAX_FILM_SIDE, .offset = AT(width), .has = AT(has_resolution),
                         .hash = CV_HASH_YES, .def_text = "the scene's",
                         .help = "film size [width, height] or \"WIDTHxHEIGHT\""},
    [CV_K_CROP] = {.name = "crop", .type = CV_KT_CROP, .offset = AT(crop),
                   .has = AT(has_crop), .hash = CV_HASH_OFF_DEFAULT, .def_text = "[0, 1, 0, 1]",
                   .help = "film part to render [x0, x1, y0, y1] in [0, 1], as pbrt's cropwindow"},
    [CV_K_SPP] = {.name = "spp", .type = CV_KT_U32, .min = 1, .max = CV_MAX_SPP,
                  .offset = AT(spp), .has = AT(has_spp), .hash = CV_HASH_YES,
                  .def_text = "the scene's", .help = "samples per pixel"},
    [CV_K_TIME_LIMIT] = {.name = "time_limit", .type = CV_KT_DURATION,
                         .offset = AT(time_limit), .has = AT(has_time_limit),
                         .hash = CV_HASH_YES, .def_text = "none",
                         .help = "stop the job after this long (90, 90s, 1.5m, 2h)"},
    [CV_K_INTEGRATOR] = {.name = "integrator", .type = CV_KT_ENUM,
                         .names = &cv_integrator_names, .offset = AT(integrator),
                         .has = AT(has_integrator), .hash = CV_HASH_YES,
                         .def_text = "the scene's (path)", .help = "light transport algorithm"},
    [CV_K_MAX_DEPTH] = {.name = "max_depth", .type = CV_KT_U32, .min = 1, .max = 1024,
                        .offset = AT(max_depth), .has = AT(has_max_depth), .hash = CV_HASH_YES,
                        .def_text = "the scene's", .help = "most bounces of a path"},
    [CV_K_SEED] = {.name = "seed", .type = CV_KT_U32, .min = 0, .max = UINT32_MAX,
                   .offset = AT(seed), .has = AT(has_seed), .hash = CV_HASH_YES,
                   .def_text = "0", .help = "sampler seed: same seed, same image"},
    [CV_K_COLOR] = SECTION("color", "colour management of the png output (OpenColorIO)"),
    [CV_K_COLOR_CONFIG] = {.name = "color.config", .type = CV_KT_STRING,
                           .offset = AT(color.config), .hash = CV_HASH_YES,
                           .def_text = "$OCIO, else the shipped config",
                           .help = "OCIO config file (relative to the manifest) or ocio:// URI"},
    [CV_K_COLOR_DISPLAY] = {.name = "color.display", .type = CV_KT_STRING,
                            .offset = AT(color.display), .hash = CV_HASH_YES,
                            .def_text = "the config's default display", .help = "OCIO display"},
    [CV_K_COLOR_VIEW] = {.name = "color.view", .type = CV_KT_STRING, .offset = AT(color.view),
                         .hash = CV_HASH_YES, .def_text = "the display's default view",
                         .help = "OCIO view"},
    [CV_K_COLOR_LOOK] = {.name = "color.look", .type = CV_KT_STRING, .offset = AT(color.look),
                         .hash = CV_HASH_YES, .def_text = "the view's looks",
                         .help = "OCIO looks, comma-separated"},
    [CV_K_COLOR_EXPOSURE] = {.name = "color.exposure", .type = CV_KT_FLOAT, .min = -64,
                             .max = 64, .offset = AT(color.exposure),
                             .has = AT(color.has_exposure), .hash = CV_HASH_YES,
                             .def_text = "0", .help = "stops added to the scene's exposure"},
    [CV_K_AOVS] = {.name = "aovs", .type = CV_KT_BITS, .names = &cv_aov_names,
                   .offset = AT(aovs), .has = AT(has_aovs), OUTPUT_SETTING, .def = 0,
                   .def_text = "[]", .allow_empty = true, .hash = CV_HASH_YES,
                   .help = "extra EXR layers: albedo, normal, depth"},
    [CV_K_EXR] = SECTION("exr", "OpenEXR output"),
    [CV_K_EXR_HALF] = {.name = "exr.half", .type = CV_KT_BOOL, .offset = AT(exr.half),
                       .has = AT(exr.has_half), OUTPUT_SETTING, .def = 1,
                       .def_text = "true", .hash = CV_HASH_YES,
                       .help = "16-bit half channels (false: 32-bit float)"},
    [CV_K_EXR_COMPRESSION] = {.name = "exr.compression", .type = CV_KT_ENUM,
                              .names = &cv_manifest_compression_names,
                              .values = &cv_exr_compression_names,
                              .offset = AT(exr.compression), .has = AT(exr.has_compression),
                              OUTPUT_SETTING, .def = CV_EXR_ZIP, .def_text = "zip",
                              .hash = CV_HASH_YES, .help = "EXR compression"},
    [CV_K_PNG] = SECTION("png", "PNG output"),
    [CV_K_PNG_BITS] = {.name = "png.bits", .type = CV_KT_U32, .min = 8, .max = 16,
                       .offset = AT(png.bits), .has = AT(png.has_bits), OUTPUT_SETTING,
                       .def = 8, .def_text = "8", .hash = CV_HASH_YES, .check = check_png_bits,
                       .help = "bits per channel: 8 or 16"},
    [CV_K_CAMERA] = SECTION("camera", "camera overrides"),
    [CV_K_CAMERA_FOV] = {.name = "camera.fov", .type = CV_KT_FLOAT, .min = 0, .max = 180,
                         .offset = AT(camera.fov), .has = AT(camera.has_fov),
                         .hash = CV_HASH_YES, .check = check_fov, .def_text = "the scene's",
                         .help = "field of view [degrees] of the shorter image axis"},
    [CV_K_CAMERA_LOOKAT] = {.name = "camera.lookat", .type = CV_KT_LOOKAT,
                            .offset = AT(camera.eye), .has = AT(camera.has_lookat),
                            .hash = CV_HASH_YES, .def_text = "the scene's",
                            .help = "[[eye], [at], [up]] as pbrt's LookAt"},
    [CV_K_RLPATH] = SECTION("rlpath", "settings of the rlpath integrator"),
    [CV_K_RLPATH_GRID] = {.name = "rlpath.grid", .type = CV_KT_U32, .min = 1,
                          .max = CV_RL_MAX_GRID, .offset = AT(rlpath.grid),
                          .has = AT(rlpath.has_grid), .hash = CV_HASH_YES,
                          .def_text = "automatic", .help = "cells along the longest axis"},
    [CV_K_RLPATH_DIRECTIONS] = {.name = "rlpath.directions", .type = CV_KT_U32, .min = 1,
                                .max = CV_RL_MAX_DIRECTIONS, .offset = AT(rlpath.directions),
                                .has = AT(rlpath.has_directions), .hash = CV_HASH_YES,
                                .def_text = "automatic", .help = "direction bins per cell"},
    [CV_K_RLPATH_MIX] = {.name = "rlpath.mix", .type = CV_KT_FLOAT, .min = 0, .max = 1,
                         .offset = AT(rlpath.mix), .has = AT(rlpath.has_mix),
                         .hash = CV_HASH_YES, .def_text = "automatic",
                         .help = "share of guided against BSDF sampling"},
    [CV_K_RLPATH_GUIDE] = {.name = "rlpath.guide", .type = CV_KT_ENUM,
                           .names = &cv_rl_guide_names, .offset = AT(rlpath.guide),
                           .has = AT(rlpath.has_guide), .def = CV_RL_GUIDE_ALL,
                           .def_text = "all", .hash = CV_HASH_OFF_DEFAULT,
                           .help = "guide by all learned radiance or the indirect part"},
    [CV_K_RLPATH_TRAIN] = {.name = "rlpath.train", .type = CV_KT_U32, .min = 0,
                           .max = CV_MAX_SPP, .offset = AT(rlpath.train),
                           .has = AT(rlpath.has_train), .hash = CV_HASH_OFF_DEFAULT,
                           .def = CV_RL_DEFAULT_TRAIN, .fill_default = true, .def_text = "16",
                           .help = "spp the table learns in, then the guide is frozen "
                                   "(0: learns in every pass)"},
    [CV_K_MATRIX] = {.name = "matrix", .type = CV_KT_MATRIX, .offset = AT(has_matrix),
                     .has = AT(has_matrix), .merge = CV_MERGE_JOB_ONLY, .def_text = "none",
                     .help = "expand the job over lists of values of its keys (every combination)"},
    [CV_K_ENV] = SECTION("env", "overrides of the scene's environment light"),
    [CV_K_ENV_SCALE] = {.name = "env.scale", .type = CV_KT_FLOAT, .min = 0, .max = 1e9,
                        .offset = AT(env.scale), .has = AT(env.has_scale),
                        .hash = CV_HASH_OFF_DEFAULT, .def_text = "1",
                        .help = "factor on the environment's radiance"},
    [CV_K_ENV_ROTATE] = {.name = "env.rotate", .type = CV_KT_ROTATE, .offset = AT(env.rotate),
                         .has = AT(env.has_rotate), .hash = CV_HASH_OFF_DEFAULT,
                         .def_text = "none",
                         .help = "[degrees, x, y, z]: turns the environment about a world axis"},
    [CV_K_LIGHTS] = SECTION("lights", "overrides of the scene's lights"),
    [CV_K_LIGHTS_SCALE] = {.name = "lights.scale", .type = CV_KT_LIGHT_SCALES, .min = 0,
                           .max = 1e9, .offset = AT(lights.scale), .has = AT(lights.has_scale),
                           .hash = CV_HASH_OFF_DEFAULT, .def_text = "none",
                           .help = "{LIGHT: factor}: factors on lights named by their index"},
    [CV_K_ENV_FILE] = {.name = "env.file", .type = CV_KT_STRING, .offset = AT(env.file),
                       .hash = CV_HASH_OFF_DEFAULT, .def_text = "the scene's",
                       .help = "image the environment shows instead (relative to the manifest)"},
    [CV_K_ALPHA] = {.name = "alpha", .type = CV_KT_BOOL, .offset = AT(alpha),
                    .has = AT(has_alpha), OUTPUT_SETTING, .def = 0, .def_text = "false",
                    .hash = CV_HASH_OFF_DEFAULT,
                    .help = "alpha from coverage; the environment seen directly is transparent"},
    [CV_K_RLPATH_METHOD] = {.name = "rlpath.method", .type = CV_KT_ENUM,
                            .names = &cv_rl_method_names, .offset = AT(rlpath.method),
                            .has = AT(rlpath.has_method), .def = CV_RL_METHOD_QLEARN,
                            .def_text = "qlearn", .hash = CV_HASH_OFF_DEFAULT,
                            .help = "how the guide learns: a Q-table or spatial-directional trees"},
    [CV_K_RLPATH_FILTER] = {.name = "rlpath.filter", .type = CV_KT_ENUM,
                            .names = &cv_rl_filter_names, .offset = AT(rlpath.filter),
                            .has = AT(rlpath.has_filter), .def = CV_RL_FILTER_NONE,
                            .def_text = "none", .hash = CV_HASH_OFF_DEFAULT,
                            .help = "sdtree's training filters: none, spatial, directional, both"},
    [CV_K_RLPATH_FALLBACK] = {.name = "rlpath.fallback", .type = CV_KT_BOOL,
                              .offset = AT(rlpath.fallback), .has = AT(rlpath.has_fallback),
                              .def = 1, .def_text = "true", .hash = CV_HASH_OFF_DEFAULT,
                              .help = "after training, render on with path's programs where "
                                      "guiding costs more time than it saves"},
};

_Static_assert(sizeof(enum cv_integrator) == sizeof(unsigned) &&
                   sizeof(enum cv_exr_compression) == sizeof(unsigned) &&
                   sizeof(enum cv_rl_guide) == sizeof(unsigned) &&
                   sizeof(enum cv_rl_method) == sizeof(unsigned) &&
                   sizeof(enum cv_rl_filter) == sizeof(unsigned),
               "ENUM keys are stored as unsigned");

const struct cv_key *cv_key_find(const char *dotted)
{
    for (size_t i = 0; i < CV_K_COUNT; i++)
        if (strcmp(cv_manifest_keys[i].name, dotted) == 0)
            return &cv_manifest_keys[i];
    return NULL;
}

const char *cv_key_leaf(const struct cv_key *k)
{
    const char *dot = strrchr(k->name, '.');
    return dot ? dot + 1 : k->name;
}

bool cv_key_in_matrix(const struct cv_key *k)
{
    size_t id = (size_t)(k - cv_manifest_keys);
    return k->type != CV_KT_SECTION && k->merge != CV_MERGE_JOB_ONLY && id != CV_K_OUTPUT;
}

bool cv_key_in(const struct cv_key *k, const struct cv_key *section)
{
    const char *dot = strrchr(k->name, '.');
    if (!section)
        return !dot;
    size_t n = strlen(section->name);
    return dot && (size_t)(dot - k->name) == n && strncmp(k->name, section->name, n) == 0;
}

static const char *type_name(const struct cv_key *k, char *buf, size_t n)
{
    switch (k->type) {
    case CV_KT_SECTION: return "mapping";
    case CV_KT_STRING: return "string";
    case CV_KT_U32:
        snprintf(buf, n, "integer %.0f..%.0f", k->min, k->max);
        return buf;
    case CV_KT_FLOAT:
        snprintf(buf, n, "number %g..%g", k->min, k->max);
        return buf;
    case CV_KT_DURATION: return "duration";
    case CV_KT_BOOL: return "boolean";
    case CV_KT_RESOLUTION: return "resolution";
    case CV_KT_LOOKAT: return "lookat";
    case CV_KT_CROP: return "crop";
    case CV_KT_MATRIX: return "mapping of key: list";
    case CV_KT_ROTATE: return "rotation";
    case CV_KT_LIGHT_SCALES: return "mapping of light: number";
    case CV_KT_ENUM:
    case CV_KT_BITS: {
        size_t len = 0;
        buf[0] = '\0';
        for (size_t i = 0; i < k->names->count && len < n; i++)
            len += (size_t)snprintf(buf + len, n - len, "%s%s", i ? "|" : "",
                                    k->names->names[i]);
        return buf;
    }
    }
    return "?";
}

void cv_keys_print(FILE *out)
{
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        char buf[128];
        const char *type = type_name(k, buf, sizeof(buf));
        fprintf(out, "%s\t%s%s\t%s\t%s\n", k->name, k->type == CV_KT_BITS ? "list of " : "",
                type, k->def_text ? k->def_text : "-", k->help);
    }
}
