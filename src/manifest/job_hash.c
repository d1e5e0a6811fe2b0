/* job_hash.c: see job_hash.h. The text walks the key table (keys.h): each
 * row's hash rule says whether and how it enters. Changing what goes into
 * the text changes every hash, which makes --resume redo all jobs once: bump the first line's
 * version when doing so on purpose. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/mem.h"
#include "manifest/job_hash.h"
#include "manifest/job_parse.h"
#include "manifest/keys.h"

#define FNV1A64_PRIME UINT64_C(0x100000001b3)

uint64_t cv_fnv1a64(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= FNV1A64_PRIME;
    }
    return h;
}

struct text {
    char *s;
    size_t len, cap;
};

static void add(struct text *t, const char *fmt, ...) CV_PRINTF(2, 3);
static void add(struct text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    t->s = cv_xgrow(t->s, &t->cap, t->len + (size_t)n + 1, 1);
    va_start(ap, fmt);
    vsnprintf(t->s + t->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    t->len += (size_t)n;
}

static void add_str(struct text *t, const char *key, const char *v)
{
    /* Length-prefixed so that a value holding a newline cannot mimic a key. */
    if (v)
        add(t, "%s=%zu:%s\n", key, strlen(v), v);
    else
        add(t, "%s=-\n", key);
}

static void add_u32(struct text *t, const char *key, bool has, uint32_t v)
{
    if (has)
        add(t, "%s=%u\n", key, (unsigned)v);
    else
        add(t, "%s=-\n", key);
}

static void add_float(struct text *t, const char *key, bool has, double v)
{
    if (has)
        add(t, "%s=%.9g\n", key, v);
    else
        add(t, "%s=-\n", key);
}

static void add_vec(struct text *t, const char *key, const float *v)
{
    add(t, "%s=%.9g,%.9g,%.9g\n", key, v[0], v[1], v[2]);
}

/* One row's lines of the canonical text. */
static void add_key(struct text *t, const struct cv_job *job, const struct cv_key *k,
                    long long scene_size, long long scene_mtime)
{
    const void *f = (const char *)job + k->offset;
    /* output settings always hold a value (keys.h: fill_default) */
    bool has = k->fill_default || cv_job_key_set(job, k);
    /* keys added later: absent when unset, so that older jobs keep their hashes */
    if (k->hash == CV_HASH_OFF_DEFAULT && !has)
        return;
    switch (k->type) {
    case CV_KT_SECTION:
    case CV_KT_MATRIX:   /* its values enter as the keys they set */
        return;
    case CV_KT_ROTATE: {
        const float *r = f;
        add(t, "%s=%.9g,%.9g,%.9g,%.9g\n", k->name, r[0], r[1], r[2], r[3]);
        break;
    }
    case CV_KT_LIGHT_SCALES: {
        const struct cv_light_scales *ls = f;
        add(t, "%s=", k->name);
        for (uint32_t i = 0; i < ls->n; i++)
            add(t, "%s%u:%.9g", i ? "," : "", (unsigned)ls->v[i].light, ls->v[i].scale);
        add(t, "\n");
        break;
    }
    case CV_KT_STRING:
        add_str(t, k->name, *(char *const *)f);
        break;
    case CV_KT_U32:
        add_u32(t, k->name, has, *(const uint32_t *)f);
        break;
    case CV_KT_FLOAT:
        add_float(t, k->name, has, *(const float *)f);
        break;
    case CV_KT_DURATION:
        add_float(t, k->name, has, *(const double *)f);
        break;
    case CV_KT_BOOL:
        if (k->hash == CV_HASH_OFF_DEFAULT && *(const bool *)f == (k->def != 0))
            break;
        if (has)
            add(t, "%s=%d\n", k->name, *(const bool *)f);
        else
            add(t, "%s=-\n", k->name);
        break;
    case CV_KT_ENUM: {
        unsigned v = *(const unsigned *)f;
        const struct cv_names *values = k->values ? k->values : k->names;
        if (k->hash == CV_HASH_OFF_DEFAULT && v == (unsigned)k->def)
            break;
        add(t, "%s=%s\n", k->name, has ? cv_name_of(values, v) : "-");
        break;
    }
    case CV_KT_BITS:
        add(t, "%s=%u\n", k->name, *(const unsigned *)f);
        break;
    case CV_KT_RESOLUTION: {
        const uint32_t *wh = f;
        if (has)
            add(t, "%s=%ux%u\n", k->name, (unsigned)wh[0], (unsigned)wh[1]);
        else
            add(t, "%s=-\n", k->name);
        break;
    }
    case CV_KT_CROP: {
        /* a key added later: absent from the hash when unset */
        const float *c = f;
        if (has)
            add(t, "%s=%.9g,%.9g,%.9g,%.9g\n", k->name, c[0], c[1], c[2], c[3]);
        break;
    }
    case CV_KT_LOOKAT: {
        /* eye, at, up, each under the key's section ("camera.eye") */
        static const char *const parts[] = {"eye", "at", "up"};
        size_t section = (size_t)(cv_key_leaf(k) - k->name);
        if (!has) {
            add(t, "%s=-\n", k->name);
            break;
        }
        for (int i = 0; i < 3; i++) {
            char name[64];
            snprintf(name, sizeof(name), "%.*s%s", (int)section, k->name, parts[i]);
            add_vec(t, name, (const float *)f + 3 * i);
        }
        break;
    }
    }
    if (k->hash == CV_HASH_WITH_STAMP)
        add(t, "%s.size=%lld\n%s.mtime=%lld\n", k->name, scene_size, k->name, scene_mtime);
}

char *cv_job_settings_text(const struct cv_job *job, long long scene_size,
                           long long scene_mtime)
{
    struct text t = {0};
    add(&t, "cavalry-job-settings 1\n");
    for (size_t i = 0; i < CV_K_COUNT; i++)
        if (cv_manifest_keys[i].hash != CV_HASH_NO)
            add_key(&t, job, &cv_manifest_keys[i], scene_size, scene_mtime);
    return t.s;
}

char *cv_job_settings_hash(const struct cv_job *job, long long scene_size,
                           long long scene_mtime)
{
    char *text = cv_job_settings_text(job, scene_size, scene_mtime);
    uint64_t h = cv_fnv1a64(CV_FNV1A64_BASIS, text, strlen(text));
    free(text);
    return cv_xasprintf("%016llx", (unsigned long long)h);
}

char *cv_job_settings_hash_stat(const struct cv_job *job, const struct stat *scene)
{
    return cv_job_settings_hash(job, (long long)scene->st_size, (long long)scene->st_mtim.tv_sec);
}
