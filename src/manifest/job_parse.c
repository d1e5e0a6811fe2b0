/* job_parse.c: see job_parse.h. The valid-key lists here are what the
 * "unknown key" messages print and what cavalry-manifest(5) documents. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/limits.h"
#include "base/mem.h"
#include "manifest/job_parse.h"
#include "manifest/yaml_view.h"

static const char *const job_keys[] = {
    "name", "scene", "output", "formats", "resolution", "spp", "time_limit", "integrator",
    "max_depth", "seed", "color", "aovs", "exr", "png", "camera", "rlpath",
};
static const char *const color_keys[] = {"config", "display", "view", "look", "exposure"};
static const char *const exr_keys[] = {"half", "compression"};
static const char *const png_keys[] = {"bits"};
static const char *const camera_keys[] = {"fov", "lookat"};
static const char *const rlpath_keys[] = {"grid", "directions", "mix", "guide"};

static const char *const format_names[] = {"exr", "png"};
static const char *const aov_names[] = {"albedo", "normal", "depth"};
static const char *const integrator_names[] = {"path", "rlpath"};
static const char *const compression_names[] = {"none", "zip", "piz", "dwaa"};

#define MAX_RESOLUTION 65536

static struct cv_ypos pos(const yaml_node_t *n)
{
    return (struct cv_ypos){cv_yline(n), cv_ycol(n)};
}

static bool is_name_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '.' || c == '_' || c == '-';
}

static void set_string(char **dst, const char *src)
{
    free(*dst);
    *dst = cv_xstrdup(src);
}

static bool read_u32(yaml_node_t *n, struct cv_diag *d, const char *what, long long min,
                     long long max, uint32_t *out)
{
    long long v;
    if (!cv_yread_int(n, d, what, min, max, &v))
        return false;
    *out = (uint32_t)v;
    return true;
}

/* A list of names into bits; a lone scalar counts as a one-item list. */
static bool read_bits(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                      const char *what, const char *const *names, size_t count,
                      bool allow_empty, unsigned *out)
{
    unsigned bits = 0;
    bool ok = true;
    int idx;
    if (n->type == YAML_SCALAR_NODE) {
        if (!cv_yread_enum(n, d, what, names, count, &idx))
            return false;
        *out = 1u << idx;
        return true;
    }
    if (n->type != YAML_SEQUENCE_NODE) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected a list, got %s", what,
                    cv_ykind(n));
        return false;
    }
    for (yaml_node_item_t *it = n->data.sequence.items.start; it < n->data.sequence.items.top;
         it++) {
        yaml_node_t *item = yaml_document_get_node(doc, *it);
        if (item && cv_yread_enum(item, d, what, names, count, &idx))
            bits |= 1u << idx;
        else
            ok = false;
    }
    if (ok && !bits && !allow_empty) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected at least one entry", what);
        return false;
    }
    if (ok)
        *out = bits;
    return ok;
}

static bool read_resolution(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                            uint32_t *w, uint32_t *h)
{
    const char *exp = "[width, height] or \"WIDTHxHEIGHT\" with sides from 1 to 65536";
    if (n->type == YAML_SEQUENCE_NODE) {
        yaml_node_item_t *it = n->data.sequence.items.start;
        if (n->data.sequence.items.top - it != 2) {
            cv_diag_add(d, cv_yline(n), cv_ycol(n), "resolution: expected %s, got a list of %d",
                        exp, (int)(n->data.sequence.items.top - it));
            return false;
        }
        uint32_t v[2];
        bool ok = true;
        for (int i = 0; i < 2; i++)
            ok &= read_u32(yaml_document_get_node(doc, it[i]), d, "resolution", 1,
                           MAX_RESOLUTION, &v[i]);
        if (ok) {
            *w = v[0];
            *h = v[1];
        }
        return ok;
    }
    if (n->type == YAML_SCALAR_NODE) {
        const char *s = (const char *)n->data.scalar.value;
        char *x;
        unsigned long a = strtoul(s, &x, 10), b = 0;
        char *end = x;
        if (x != s && (*x == 'x' || *x == 'X') && x[1] >= '0' && x[1] <= '9')
            b = strtoul(x + 1, &end, 10);
        if (s[0] >= '0' && s[0] <= '9' && !*end && a >= 1 && a <= MAX_RESOLUTION && b >= 1 &&
            b <= MAX_RESOLUTION) {
            *w = (uint32_t)a;
            *h = (uint32_t)b;
            return true;
        }
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "resolution: expected %s, got \"%s\"", exp, s);
        return false;
    }
    cv_diag_add(d, cv_yline(n), cv_ycol(n), "resolution: expected %s, got %s", exp,
                cv_ykind(n));
    return false;
}

static bool read_vec3(yaml_document_t *doc, yaml_node_item_t *items, struct cv_diag *d,
                      float *out)
{
    bool ok = true;
    for (int i = 0; i < 3; i++) {
        double v = 0;
        ok &= cv_yread_float(yaml_document_get_node(doc, items[i]), d, "camera.lookat", -1e30,
                             1e30, &v);
        out[i] = (float)v;
    }
    return ok;
}

/* [[eye], [at], [up]] or the nine numbers flat, as pbrt writes LookAt. */
static bool read_lookat(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                        struct cv_job_camera *cam)
{
    const char *exp = "[[ex, ey, ez], [ax, ay, az], [ux, uy, uz]] or nine numbers";
    if (n->type != YAML_SEQUENCE_NODE) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "camera.lookat: expected %s, got %s", exp,
                    cv_ykind(n));
        return false;
    }
    yaml_node_item_t *it = n->data.sequence.items.start;
    ptrdiff_t count = n->data.sequence.items.top - it;
    float v[9];
    bool ok = true;
    if (count == 9) {
        ok = read_vec3(doc, it, d, v) & read_vec3(doc, it + 3, d, v + 3) &
             read_vec3(doc, it + 6, d, v + 6);
    } else if (count == 3) {
        for (int i = 0; i < 3; i++) {
            yaml_node_t *row = yaml_document_get_node(doc, it[i]);
            if (row->type != YAML_SEQUENCE_NODE ||
                row->data.sequence.items.top - row->data.sequence.items.start != 3) {
                cv_diag_add(d, cv_yline(row), cv_ycol(row),
                            "camera.lookat: expected a list of 3 numbers, got %s",
                            cv_ykind(row));
                ok = false;
                continue;
            }
            ok &= read_vec3(doc, row->data.sequence.items.start, d, v + 3 * i);
        }
    } else {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "camera.lookat: expected %s", exp);
        return false;
    }
    if (!ok)
        return false;
    if (v[0] == v[3] && v[1] == v[4] && v[2] == v[5]) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "camera.lookat: eye and target are the same point");
        return false;
    }
    if (v[6] == 0 && v[7] == 0 && v[8] == 0) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "camera.lookat: up vector is zero");
        return false;
    }
    memcpy(cam->eye, v, sizeof(cam->eye));
    memcpy(cam->at, v + 3, sizeof(cam->at));
    memcpy(cam->up, v + 6, sizeof(cam->up));
    return true;
}

/* The pairs of a nested mapping such as `color:`, or NULL after reporting. */
static size_t sub_pairs(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                        const char *what, struct cv_ypair **pairs)
{
    *pairs = NULL;
    if (n->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected a mapping, got %s", what,
                    cv_ykind(n));
        return 0;
    }
    return cv_ymap_pairs(doc, n, d, pairs);
}

static void parse_color(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                        struct cv_job_draft *out)
{
    struct cv_job_color *c = &out->job.color;
    struct cv_ypair *pairs;
    size_t np = sub_pairs(doc, n, d, "color", &pairs);
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        yaml_node_t *v = pairs[i].value;
        const char *s;
        double f;
        if (!strcmp(k, "config")) {
            if (cv_yread_string(v, d, "color.config", &s)) {
                set_string(&c->config, s);
                out->config_at = pos(v);
            }
        } else if (!strcmp(k, "display")) {
            if (cv_yread_string(v, d, "color.display", &s))
                set_string(&c->display, s);
        } else if (!strcmp(k, "view")) {
            if (cv_yread_string(v, d, "color.view", &s))
                set_string(&c->view, s);
        } else if (!strcmp(k, "look")) {
            if (cv_yread_string(v, d, "color.look", &s))
                set_string(&c->look, s);
        } else if (!strcmp(k, "exposure")) {
            if (cv_yread_float(v, d, "color.exposure", -64, 64, &f)) {
                c->exposure = (float)f;
                c->has_exposure = true;
            }
        } else {
            cv_yunknown_key(&pairs[i], d, "color", color_keys, CV_ARRAY_SIZE(color_keys));
        }
    }
    free(pairs);
}

static void parse_exr(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                      struct cv_job_exr *e)
{
    struct cv_ypair *pairs;
    size_t np = sub_pairs(doc, n, d, "exr", &pairs);
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        int idx;
        if (!strcmp(k, "half")) {
            e->has_half = cv_yread_bool(pairs[i].value, d, "exr.half", &e->half) || e->has_half;
        } else if (!strcmp(k, "compression")) {
            if (cv_yread_enum(pairs[i].value, d, "exr.compression", compression_names,
                              CV_ARRAY_SIZE(compression_names), &idx)) {
                e->compression = (enum cv_job_compression)idx;
                e->has_compression = true;
            }
        } else {
            cv_yunknown_key(&pairs[i], d, "exr", exr_keys, CV_ARRAY_SIZE(exr_keys));
        }
    }
    free(pairs);
}

static void parse_png(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                      struct cv_job_png *p)
{
    struct cv_ypair *pairs;
    size_t np = sub_pairs(doc, n, d, "png", &pairs);
    for (size_t i = 0; i < np; i++) {
        long long bits;
        if (!strcmp(cv_ykey(&pairs[i]), "bits")) {
            yaml_node_t *v = pairs[i].value;
            if (cv_yread_int(v, d, "png.bits", 8, 16, &bits)) {
                if (bits != 8 && bits != 16) {
                    cv_diag_add(d, cv_yline(v), cv_ycol(v),
                                "png.bits: expected 8 or 16, got \"%lld\"", bits);
                } else {
                    p->bits = (unsigned)bits;
                    p->has_bits = true;
                }
            }
        } else {
            cv_yunknown_key(&pairs[i], d, "png", png_keys, CV_ARRAY_SIZE(png_keys));
        }
    }
    free(pairs);
}

static void parse_camera(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                         struct cv_job_camera *cam)
{
    struct cv_ypair *pairs;
    size_t np = sub_pairs(doc, n, d, "camera", &pairs);
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        yaml_node_t *v = pairs[i].value;
        double f;
        if (!strcmp(k, "fov")) {
            if (cv_yread_float(v, d, "camera.fov", 0, 180, &f)) {
                if (f <= 0 || f >= 180) {
                    cv_diag_add(d, cv_yline(v), cv_ycol(v),
                                "camera.fov: expected degrees between 0 and 180 (exclusive), "
                                "got \"%g\"", f);
                } else {
                    cam->fov = (float)f;
                    cam->has_fov = true;
                }
            }
        } else if (!strcmp(k, "lookat")) {
            cam->has_lookat = read_lookat(doc, v, d, cam) || cam->has_lookat;
        } else {
            cv_yunknown_key(&pairs[i], d, "camera", camera_keys, CV_ARRAY_SIZE(camera_keys));
        }
    }
    free(pairs);
}

static void parse_rlpath(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                         struct cv_job_rlpath *r)
{
    struct cv_ypair *pairs;
    size_t np = sub_pairs(doc, n, d, "rlpath", &pairs);
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        yaml_node_t *v = pairs[i].value;
        double f;
        if (!strcmp(k, "grid")) {
            r->has_grid = read_u32(v, d, "rlpath.grid", 1, CV_RL_MAX_GRID, &r->grid) || r->has_grid;
        } else if (!strcmp(k, "directions")) {
            r->has_directions =
                read_u32(v, d, "rlpath.directions", 1, CV_RL_MAX_DIRECTIONS,
                         &r->directions) || r->has_directions;
        } else if (!strcmp(k, "mix")) {
            if (cv_yread_float(v, d, "rlpath.mix", 0, 1, &f)) {
                r->mix = (float)f;
                r->has_mix = true;
            }
        } else if (!strcmp(k, "guide")) {
            const char *s;
            if (!cv_yread_string(v, d, "rlpath.guide", &s))
                continue;
            if (strcmp(s, "all") && strcmp(s, "indirect")) {
                cv_diag_add(d, cv_yline(v), cv_ycol(v),
                            "rlpath.guide: expected one of all, indirect, got \"%s\"", s);
                continue;
            }
            r->guide_indirect = !strcmp(s, "indirect");
            r->has_guide = true;
        } else {
            cv_yunknown_key(&pairs[i], d, "rlpath", rlpath_keys, CV_ARRAY_SIZE(rlpath_keys));
        }
    }
    free(pairs);
}

static void parse_name(yaml_node_t *v, struct cv_diag *d, struct cv_job_draft *out)
{
    const char *s;
    out->name_at = pos(v);  /* given, even if invalid: not "missing" */
    if (!cv_yread_string(v, d, "name", &s))
        return;
    for (const char *p = s; *p; p++) {
        if (!is_name_char(*p)) {
            cv_diag_add(d, cv_yline(v), cv_ycol(v),
                        "name: \"%s\" has '%c'; job names use only letters, digits, '.', '_' "
                        "and '-'", s, *p);
            return;
        }
    }
    set_string(&out->job.name, s);
}

/* Only {name} may appear in braces: a typo such as {nmae} would otherwise
 * silently become part of every file name. */
static void parse_output(yaml_node_t *v, struct cv_diag *d, struct cv_job_draft *out)
{
    const char *s;
    if (!cv_yread_string(v, d, "output", &s))
        return;
    for (const char *p = strchr(s, '{'); p; p = strchr(p + 1, '{')) {
        if (strncmp(p, "{name}", 6) != 0) {
            cv_diag_add(d, cv_yline(v), cv_ycol(v),
                        "output: \"%s\": only {name} may be written in braces", s);
            return;
        }
    }
    if (s[strlen(s) - 1] == '/') {
        cv_diag_add(d, cv_yline(v), cv_ycol(v),
                    "output: \"%s\" names a folder; expected a file name without extension, "
                    "e.g. \"%s{name}\"", s, s);
        return;
    }
    set_string(&out->job.output, s);
    out->job.has_output = true;
    out->output_at = pos(v);
}

void cv_job_parse(yaml_document_t *doc, yaml_node_t *map, bool is_defaults,
                  struct cv_diag *d, struct cv_job_draft *out)
{
    memset(out, 0, sizeof(*out));
    out->at = pos(map);
    out->job.line = (unsigned)out->at.line;
    out->job.col = (unsigned)out->at.col;
    const char *where = is_defaults ? "defaults" : "job";
    if (map->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(map), cv_ycol(map), "%s: expected a mapping, got %s", where,
                    cv_ykind(map));
        return;
    }
    struct cv_job *j = &out->job;
    struct cv_ypair *pairs;
    size_t np = cv_ymap_pairs(doc, map, d, &pairs);
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        yaml_node_t *v = pairs[i].value;
        const char *s;
        int idx;
        if (!strcmp(k, "name") && !is_defaults) {
            parse_name(v, d, out);
        } else if (!strcmp(k, "scene")) {
            if (cv_yread_string(v, d, "scene", &s)) {
                set_string(&j->scene_as_written, s);
                out->scene_at = pos(v);
            }
        } else if (!strcmp(k, "output")) {
            parse_output(v, d, out);
        } else if (!strcmp(k, "formats")) {
            j->has_formats = read_bits(doc, v, d, "formats", format_names,
                                       CV_ARRAY_SIZE(format_names), false, &j->formats) ||
                             j->has_formats;
        } else if (!strcmp(k, "aovs")) {
            j->has_aovs = read_bits(doc, v, d, "aovs", aov_names, CV_ARRAY_SIZE(aov_names),
                                    true, &j->aovs) ||
                          j->has_aovs;
        } else if (!strcmp(k, "resolution")) {
            j->has_resolution = read_resolution(doc, v, d, &j->width, &j->height);
        } else if (!strcmp(k, "spp")) {
            j->has_spp = read_u32(v, d, "spp", 1, CV_MAX_SPP, &j->spp);
        } else if (!strcmp(k, "time_limit")) {
            j->has_time_limit = cv_yread_duration(v, d, "time_limit", &j->time_limit);
        } else if (!strcmp(k, "integrator")) {
            if (cv_yread_enum(v, d, "integrator", integrator_names,
                              CV_ARRAY_SIZE(integrator_names), &idx))
                j->integrator = (enum cv_integrator)(CV_INTEGRATOR_PATH + idx);
        } else if (!strcmp(k, "max_depth")) {
            j->has_max_depth = read_u32(v, d, "max_depth", 1, 1024, &j->max_depth);
        } else if (!strcmp(k, "seed")) {
            j->has_seed = read_u32(v, d, "seed", 0, UINT32_MAX, &j->seed);
        } else if (!strcmp(k, "color")) {
            parse_color(doc, v, d, out);
        } else if (!strcmp(k, "exr")) {
            parse_exr(doc, v, d, &j->exr);
        } else if (!strcmp(k, "png")) {
            parse_png(doc, v, d, &j->png);
        } else if (!strcmp(k, "camera")) {
            parse_camera(doc, v, d, &j->camera);
        } else if (!strcmp(k, "rlpath")) {
            parse_rlpath(doc, v, d, &j->rlpath);
        } else if (!strcmp(k, "name")) {
            cv_diag_add(d, cv_yline(pairs[i].key), cv_ycol(pairs[i].key),
                        "\"name\" cannot be given in defaults: every job needs its own");
        } else {
            /* Defaults take every job key but name. */
            cv_yunknown_key(&pairs[i], d, where, job_keys + is_defaults,
                            CV_ARRAY_SIZE(job_keys) - is_defaults);
        }
    }
    free(pairs);
}

static void take_string(char **dst, const char *src)
{
    if (!*dst && src)
        *dst = cv_xstrdup(src);
}

#define TAKE(flag, field)                  \
    do {                                   \
        if (!j->flag && dj->flag) {        \
            j->flag = true;                \
            j->field = dj->field;          \
        }                                  \
    } while (0)

void cv_job_merge(struct cv_job_draft *job, const struct cv_job_draft *defaults)
{
    struct cv_job *j = &job->job;
    const struct cv_job *dj = &defaults->job;
    if (!j->scene_as_written && dj->scene_as_written) {
        j->scene_as_written = cv_xstrdup(dj->scene_as_written);
        job->scene_at = defaults->scene_at;
    }
    if (!j->has_output && dj->has_output) {
        j->output = cv_xstrdup(dj->output);
        j->has_output = true;
        job->output_at = defaults->output_at;
    }
    TAKE(has_formats, formats);
    TAKE(has_aovs, aovs);
    if (!j->has_resolution && dj->has_resolution) {
        j->has_resolution = true;
        j->width = dj->width;
        j->height = dj->height;
    }
    TAKE(has_spp, spp);
    TAKE(has_time_limit, time_limit);
    if (j->integrator == CV_INTEGRATOR_UNSET)
        j->integrator = dj->integrator;
    TAKE(has_max_depth, max_depth);
    TAKE(has_seed, seed);

    if (!j->color.config && dj->color.config) {
        j->color.config = cv_xstrdup(dj->color.config);
        job->config_at = defaults->config_at;
    }
    take_string(&j->color.display, dj->color.display);
    take_string(&j->color.view, dj->color.view);
    take_string(&j->color.look, dj->color.look);
    TAKE(color.has_exposure, color.exposure);

    TAKE(exr.has_half, exr.half);
    TAKE(exr.has_compression, exr.compression);
    TAKE(png.has_bits, png.bits);
    TAKE(camera.has_fov, camera.fov);
    if (!j->camera.has_lookat && dj->camera.has_lookat) {
        j->camera.has_lookat = true;
        memcpy(j->camera.eye, dj->camera.eye, sizeof(j->camera.eye));
        memcpy(j->camera.at, dj->camera.at, sizeof(j->camera.at));
        memcpy(j->camera.up, dj->camera.up, sizeof(j->camera.up));
    }
    TAKE(rlpath.has_grid, rlpath.grid);
    TAKE(rlpath.has_directions, rlpath.directions);
    TAKE(rlpath.has_mix, rlpath.mix);
    TAKE(rlpath.has_guide, rlpath.guide_indirect);
}

void cv_job_free(struct cv_job *job)
{
    free(job->name);
    free(job->scene);
    free(job->scene_as_written);
    free(job->output);
    free(job->color.config);
    free(job->color.display);
    free(job->color.view);
    free(job->color.look);
    free(job->settings_hash);
    memset(job, 0, sizeof(*job));
}
