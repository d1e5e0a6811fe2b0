/* job_parse.c: see job_parse.h. Reading, merging and the "unknown key"
 * lists walk the key table (keys.h): no key is spelled here. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/job_parse.h"
#include "manifest/keys.h"
#include "manifest/yaml_view.h"

static struct cv_key_at pos(const yaml_node_t *n)
{
    return (struct cv_key_at){(unsigned)cv_yline(n), (unsigned)cv_ycol(n)};
}

static void set_string(char **dst, const char *src)
{
    free(*dst);
    *dst = cv_xstrdup(src);
}

static void *field(struct cv_job *j, const struct cv_key *k)
{
    return (char *)j + k->offset;
}

static bool *has_flag(struct cv_job *j, const struct cv_key *k)
{
    return k->has ? (bool *)((char *)j + k->has) : NULL;
}

/* A list of names into bits; a lone scalar counts as a one-item list. */
static bool read_bits(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                      const char *what, const struct cv_names *t, bool allow_empty,
                      unsigned *out)
{
    unsigned bits = 0;
    bool ok = true;
    int idx;
    if (n->type == YAML_SCALAR_NODE) {
        if (!cv_yread_enum(n, d, what, t->names, t->count, &idx))
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
        if (item && cv_yread_enum(item, d, what, t->names, t->count, &idx))
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

static bool read_u32(yaml_node_t *n, struct cv_diag *d, const char *what, long long min,
                     long long max, uint32_t *out)
{
    long long v;
    if (!cv_yread_int(n, d, what, min, max, &v))
        return false;
    *out = (uint32_t)v;
    return true;
}

static bool read_resolution(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d,
                            const struct cv_key *k, uint32_t *w, uint32_t *h)
{
    const long long max = (long long)k->max;
    char exp[96];
    snprintf(exp, sizeof(exp), "[width, height] or \"WIDTHxHEIGHT\" with sides from %.0f to %lld",
             k->min, max);
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
            ok &= read_u32(yaml_document_get_node(doc, it[i]), d, k->name, (long long)k->min,
                           max, &v[i]);
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
        if (s[0] >= '0' && s[0] <= '9' && !*end && a >= k->min && (long long)a <= max && b >= k->min &&
            (long long)b <= max) {
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
static bool read_lookat(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d, float *out)
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
    memcpy(out, v, sizeof(v));
    return true;
}

/* A sequence of four numbers in [lo, hi] into v; what a key of that shape
 * expects is said in the error ("[x0, x1, y0, y1] ..."). */
static bool read_four(yaml_document_t *doc, yaml_node_t *n, const char *key, const char *shape,
                      double lo, double hi, struct cv_diag *d, double v[4])
{
    if (n->type != YAML_SEQUENCE_NODE ||
        n->data.sequence.items.top - n->data.sequence.items.start != 4) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected %s, got %s", key, shape,
                    cv_ykind(n));
        return false;
    }
    yaml_node_item_t *it = n->data.sequence.items.start;
    bool ok = true;
    for (int i = 0; i < 4; i++)
        ok &= cv_yread_float(yaml_document_get_node(doc, it[i]), d, key, lo, hi, &v[i]);
    return ok;
}

/* crop: [x0, x1, y0, y1], fractions of the film as pbrt's cropwindow. */
static bool read_crop(yaml_document_t *doc, yaml_node_t *n, struct cv_diag *d, float *out)
{
    double v[4];
    if (!read_four(doc, n, "crop", "[x0, x1, y0, y1] (film fractions in [0, 1])", 0, 1, d, v))
        return false;
    if (!(v[0] < v[1] && v[2] < v[3])) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n),
                    "crop: empty window [%g, %g, %g, %g]: needs x0 < x1 and y0 < y1", v[0],
                    v[1], v[2], v[3]);
        return false;
    }
    for (int i = 0; i < 4; i++)
        out[i] = (float)v[i];
    return true;
}

/* env.rotate: [degrees, x, y, z], as pbrt's Rotate. */
static bool read_rotate(yaml_document_t *doc, yaml_node_t *n, const struct cv_key *k,
                        struct cv_diag *d, float *out)
{
    double v[4];
    if (!read_four(doc, n, k->name, "[degrees, x, y, z] (as pbrt's Rotate)", -1e6, 1e6, d, v))
        return false;
    if (v[1] == 0 && v[2] == 0 && v[3] == 0) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: the axis is zero", k->name);
        return false;
    }
    for (int i = 0; i < 4; i++)
        out[i] = (float)v[i];
    return true;
}

/* lights.scale: {LIGHT: factor}, LIGHT the index of a light directive. */
static bool read_light_scales(yaml_document_t *doc, yaml_node_t *n, const struct cv_key *k,
                              struct cv_diag *d, struct cv_light_scales *out)
{
    if (n->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n),
                    "%s: expected a mapping of light index to factor ({0: 2}), got %s",
                    k->name, cv_ykind(n));
        return false;
    }
    struct cv_ypair *pairs;
    size_t np = cv_ymap_pairs(doc, n, d, &pairs);
    struct cv_light_scales v = {0};
    unsigned long first[CV_MAX_LIGHT_SCALES];  /* each pair's light, for duplicates */
    bool ok = true;
    if (np > CV_MAX_LIGHT_SCALES) {
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: %zu lights named; at most %u", k->name,
                    np, CV_MAX_LIGHT_SCALES);
        ok = false;
    }
    for (size_t i = 0; ok && i < np; i++) {
        const char *name = cv_ykey(&pairs[i]);
        char *end;
        unsigned long idx = strtoul(name, &end, 10);
        if (!(name[0] >= '0' && name[0] <= '9') || *end || idx > INT32_MAX) {
            cv_diag_add(d, cv_yline(pairs[i].key), cv_ycol(pairs[i].key),
                        "%s: \"%s\" is not a light: lights are named by their index among "
                        "the scene's LightSource and AreaLightSource directives (0, 1, ...)",
                        k->name, name);
            ok = false;
            continue;
        }
        /* "0" and "00" are two YAML keys but one light: a duplicate key,
         * as cavalry-manifest(5) has it, not two factors multiplied */
        size_t twice = 0;
        while (twice < i && first[twice] != idx)
            twice++;
        if (twice < i) {
            cv_diag_add(d, cv_yline(pairs[i].key), cv_ycol(pairs[i].key),
                        "%s: light %lu is named twice (first given as \"%s\" at line %zu)", k->name,
                        idx, cv_ykey(&pairs[twice]), cv_yline(pairs[twice].key));
            ok = false;
            continue;
        }
        first[i] = idx;
        double x;
        if (!cv_yread_float(pairs[i].value, d, k->name, k->min, k->max, &x)) {
            ok = false;
            continue;
        }
        /* kept sorted by light: one spelling for the settings hash */
        size_t at = v.n++;
        for (; at > 0 && v.v[at - 1].light > idx; at--)
            v.v[at] = v.v[at - 1];
        v.v[at] = (struct cv_light_scale){(uint32_t)idx, (float)x};
    }
    free(pairs);
    if (ok)
        *out = v;
    return ok;
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

/* Reads one value of row k into the job; true when it was valid. */
static bool read_value(yaml_document_t *doc, yaml_node_t *v, const struct cv_key *k,
                       struct cv_diag *d, struct cv_job *j)
{
    void *f = field(j, k);
    char msg[512];
    const char *s;
    long long i;
    double x;
    int idx;
    switch (k->type) {
    case CV_KT_SECTION:
        return false; /* read by read_mapping */
    case CV_KT_STRING:
        if (!cv_yread_string(v, d, k->name, &s))
            return false;
        if (k->check && !k->check(&s, msg, sizeof(msg)))
            break;
        set_string(f, s);
        return true;
    case CV_KT_U32:
        if (!cv_yread_int(v, d, k->name, (long long)k->min, (long long)k->max, &i))
            return false;
        if (k->check && !k->check(&i, msg, sizeof(msg)))
            break;
        *(uint32_t *)f = (uint32_t)i;
        return true;
    case CV_KT_FLOAT:
        if (!cv_yread_float(v, d, k->name, k->min, k->max, &x))
            return false;
        if (k->check && !k->check(&x, msg, sizeof(msg)))
            break;
        *(float *)f = (float)x;
        return true;
    case CV_KT_DURATION:
        return cv_yread_duration(v, d, k->name, f);
    case CV_KT_BOOL:
        return cv_yread_bool(v, d, k->name, f);
    case CV_KT_ENUM:
        if (!cv_yread_enum(v, d, k->name, k->names->names, k->names->count, &idx))
            return false;
        *(unsigned *)f = k->values ? (unsigned)cv_name_find(k->values, k->names->names[idx])
                                   : (unsigned)idx;
        return true;
    case CV_KT_BITS:
        return read_bits(doc, v, d, k->name, k->names, k->allow_empty, f);
    case CV_KT_RESOLUTION:
        return read_resolution(doc, v, d, k, f, (uint32_t *)f + 1);
    case CV_KT_LOOKAT:
        return read_lookat(doc, v, d, f);
    case CV_KT_CROP:
        return read_crop(doc, v, d, f);
    case CV_KT_MATRIX:
        return true; /* expanded by matrix.c */
    case CV_KT_ROTATE:
        return read_rotate(doc, v, k, d, f);
    case CV_KT_LIGHT_SCALES:
        return read_light_scales(doc, v, k, d, f);
    }
    cv_diag_add(d, cv_yline(v), cv_ycol(v), "%s", msg);
    return false;
}

/* Reports an unknown key of a mapping with the keys valid there. */
static void unknown_key(const struct cv_ypair *p, const struct cv_key *section,
                        bool is_defaults, struct cv_diag *d)
{
    const char *valid[CV_K_COUNT];
    size_t n = 0;
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        if (cv_key_in(k, section) && !(is_defaults && k->merge == CV_MERGE_JOB_ONLY))
            valid[n++] = cv_key_leaf(k);
    }
    const char *where = section ? section->name : is_defaults ? "defaults" : "job";
    cv_yunknown_key(p, d, where, valid, n);
}

static void read_mapping(yaml_document_t *doc, struct cv_ypair *pairs, size_t np,
                         const struct cv_key *section, bool is_defaults, struct cv_diag *d,
                         struct cv_job *j)
{
    for (size_t i = 0; i < np; i++) {
        const char *leaf = cv_ykey(&pairs[i]);
        yaml_node_t *v = pairs[i].value;
        const struct cv_key *k = NULL;
        for (size_t r = 0; r < CV_K_COUNT && !k; r++)
            if (cv_key_in(&cv_manifest_keys[r], section) &&
                !strcmp(cv_key_leaf(&cv_manifest_keys[r]), leaf))
                k = &cv_manifest_keys[r];
        if (!k) {
            unknown_key(&pairs[i], section, is_defaults, d);
        } else if (is_defaults && k->merge == CV_MERGE_JOB_ONLY) {
            cv_diag_add(d, cv_yline(pairs[i].key), cv_ycol(pairs[i].key),
                        "\"%s\" cannot be given in defaults: every job needs its own", k->name);
        } else if (k->type == CV_KT_SECTION) {
            struct cv_ypair *sub;
            size_t ns = sub_pairs(doc, v, d, k->name, &sub);
            read_mapping(doc, sub, ns, k, is_defaults, d, j);
            free(sub);
        } else {
            size_t id = (size_t)(k - cv_manifest_keys);
            if (k->merge == CV_MERGE_JOB_ONLY)
                j->at[id] = pos(v); /* given, even if invalid: not "missing" */
            if (read_value(doc, v, k, d, j)) {
                j->at[id] = pos(v);
                if (has_flag(j, k))
                    *has_flag(j, k) = true;
            }
        }
    }
}

bool cv_job_read_value(yaml_document_t *doc, yaml_node_t *v, const struct cv_key *k,
                       struct cv_diag *d, struct cv_job *j)
{
    if (!read_value(doc, v, k, d, j))
        return false;
    j->at[k - cv_manifest_keys] = pos(v);
    if (has_flag(j, k))
        *has_flag(j, k) = true;
    return true;
}

void cv_job_parse(yaml_document_t *doc, yaml_node_t *map, bool is_defaults,
                  struct cv_diag *d, struct cv_job_draft *out)
{
    memset(out, 0, sizeof(*out));
    out->at.line = cv_yline(map);
    out->at.col = cv_ycol(map);
    out->job.line = (unsigned)out->at.line;
    out->job.col = (unsigned)out->at.col;
    if (map->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(map), cv_ycol(map), "%s: expected a mapping, got %s",
                    is_defaults ? "defaults" : "job", cv_ykind(map));
        return;
    }
    struct cv_ypair *pairs;
    size_t np = cv_ymap_pairs(doc, map, d, &pairs);
    read_mapping(doc, pairs, np, NULL, is_defaults, d, &out->job);
    for (size_t i = 0; i < np; i++)
        if (!is_defaults && cv_key_find(cv_ykey(&pairs[i])) == &cv_manifest_keys[CV_K_MATRIX])
            out->matrix = pairs[i].value;
    free(pairs);
}

/* Bytes of a row's value in struct cv_job. */
static size_t value_size(const struct cv_key *k)
{
    switch (k->type) {
    case CV_KT_U32: return sizeof(uint32_t);
    case CV_KT_FLOAT: return sizeof(float);
    case CV_KT_DURATION: return sizeof(double);
    case CV_KT_BOOL: return sizeof(bool);
    case CV_KT_ENUM:
    case CV_KT_BITS: return sizeof(unsigned);
    case CV_KT_RESOLUTION: return 2 * sizeof(uint32_t);
    case CV_KT_LOOKAT: return 9 * sizeof(float);
    case CV_KT_CROP: return 4 * sizeof(float);
    case CV_KT_ROTATE: return 4 * sizeof(float);
    case CV_KT_LIGHT_SCALES: return sizeof(struct cv_light_scales);
    case CV_KT_MATRIX: return sizeof(bool);
    case CV_KT_SECTION:
    case CV_KT_STRING: break;
    }
    return 0;
}

bool cv_job_key_set(const struct cv_job *job, const struct cv_key *k)
{
    if (k->type == CV_KT_SECTION)
        return false;
    if (k->type == CV_KT_STRING)
        return *(char *const *)((const char *)job + k->offset) != NULL;
    return *(const bool *)((const char *)job + k->has);
}

void cv_job_merge(struct cv_job_draft *job, const struct cv_job_draft *defaults)
{
    struct cv_job *j = &job->job;
    const struct cv_job *dj = &defaults->job;
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        if (k->type == CV_KT_SECTION || k->merge == CV_MERGE_JOB_ONLY ||
            cv_job_key_set(j, k) || !cv_job_key_set(dj, k))
            continue;
        const void *from = (const char *)dj + k->offset;
        if (k->type == CV_KT_STRING) {
            *(char **)field(j, k) = cv_xstrdup(*(char *const *)from);
        } else {
            memcpy(field(j, k), from, value_size(k));
            *has_flag(j, k) = true;
        }
        j->at[i] = dj->at[i];
    }
}

void cv_job_fill_defaults(struct cv_job *job)
{
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        if (!k->fill_default || cv_job_key_set(job, k))
            continue;
        void *f = field(job, k);
        switch (k->type) {
        case CV_KT_U32: *(uint32_t *)f = (uint32_t)k->def; break;
        case CV_KT_BOOL: *(bool *)f = k->def != 0; break;
        case CV_KT_ENUM:
        case CV_KT_BITS: *(unsigned *)f = (unsigned)k->def; break;
        default: break; /* no other type has a filled default */
        }
    }
}

void cv_job_copy(struct cv_job *dst, const struct cv_job *src)
{
    *dst = *src;
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        char **f = field(dst, k);
        if (k->type == CV_KT_STRING && *f)
            *f = cv_xstrdup(*f);
    }
    dst->scene = src->scene ? cv_xstrdup(src->scene) : NULL;
    dst->settings_hash = src->settings_hash ? cv_xstrdup(src->settings_hash) : NULL;
    dst->matrix_of = src->matrix_of ? cv_xstrdup(src->matrix_of) : NULL;
    dst->axes = src->n_axes ? cv_xcalloc(src->n_axes, sizeof(*dst->axes)) : NULL;
    for (size_t i = 0; i < src->n_axes; i++)
        dst->axes[i] = (struct cv_job_axis){src->axes[i].key, cv_xstrdup(src->axes[i].label)};
}

void cv_job_free(struct cv_job *job)
{
    for (size_t i = 0; i < CV_K_COUNT; i++)
        if (cv_manifest_keys[i].type == CV_KT_STRING)
            free(*(char **)field(job, &cv_manifest_keys[i]));
    free(job->scene);
    free(job->settings_hash);
    free(job->matrix_of);
    for (size_t i = 0; i < job->n_axes; i++)
        free(job->axes[i].label);
    free(job->axes);
    memset(job, 0, sizeof(*job));
}
