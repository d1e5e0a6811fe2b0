/* metadata.c: see metadata.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "output/metadata.h"

struct cv_metadata *cv_metadata_new(void)
{
    return cv_xcalloc(1, sizeof(struct cv_metadata));
}

static void clear_value(struct cv_meta_entry *e)
{
    if (e->type == CV_META_STRING)
        free(e->v.s);
}

void cv_metadata_destroy(struct cv_metadata **m)
{
    if (!m || !*m)
        return;
    for (size_t i = 0; i < (*m)->len; i++) {
        clear_value(&(*m)->entries[i]);
        free((*m)->entries[i].key);
    }
    free((*m)->entries);
    free(*m);
    *m = NULL;
}

/* The entry for key, emptied of its old value, or a new one at the end. */
static struct cv_meta_entry *slot(struct cv_metadata *m, const char *key)
{
    for (size_t i = 0; i < m->len; i++) {
        if (strcmp(m->entries[i].key, key) == 0) {
            clear_value(&m->entries[i]);
            return &m->entries[i];
        }
    }
    struct cv_meta_entry e = { .key = cv_xstrdup(key) };
    CV_PUSH(m->entries, m->len, m->cap, e);
    return &m->entries[m->len - 1];
}

void cv_metadata_set_string(struct cv_metadata *m, const char *key, const char *value)
{
    struct cv_meta_entry *e = slot(m, key);
    e->type = CV_META_STRING;
    e->v.s = cv_xstrdup(value);
}

void cv_metadata_set_int(struct cv_metadata *m, const char *key, int64_t value)
{
    struct cv_meta_entry *e = slot(m, key);
    e->type = CV_META_INT;
    e->v.i = value;
}

void cv_metadata_set_float(struct cv_metadata *m, const char *key, double value)
{
    struct cv_meta_entry *e = slot(m, key);
    e->type = CV_META_FLOAT;
    e->v.f = value;
}

void cv_metadata_set_bool(struct cv_metadata *m, const char *key, bool value)
{
    cv_metadata_set_int(m, key, value ? 1 : 0);
}

void cv_metadata_set_m44f(struct cv_metadata *m, const char *key, const float value[16])
{
    struct cv_meta_entry *e = slot(m, key);
    e->type = CV_META_M44F;
    memcpy(e->v.m, value, sizeof(e->v.m));
}

const struct cv_meta_entry *cv_metadata_get(const struct cv_metadata *m, const char *key)
{
    for (size_t i = 0; m && i < m->len; i++)
        if (strcmp(m->entries[i].key, key) == 0)
            return &m->entries[i];
    return NULL;
}

char *cv_meta_value_text(const struct cv_meta_entry *e)
{
    switch (e->type) {
    case CV_META_STRING:
        return cv_xstrdup(e->v.s);
    case CV_META_INT:
        return cv_xasprintf("%lld", (long long)e->v.i);
    case CV_META_FLOAT:
        return cv_xasprintf("%.9g", e->v.f);
    case CV_META_M44F: {
        char buf[16 * 18] = "";
        for (int i = 0; i < 16; i++)
            snprintf(buf + strlen(buf), sizeof(buf) - strlen(buf), "%s%.9g", i ? " " : "",
                     (double)e->v.m[i]);
        return cv_xstrdup(buf);
    }
    }
    return cv_xstrdup("");
}
