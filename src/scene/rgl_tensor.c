/* rgl_tensor.c: see rgl_tensor.h. Every read is checked against the
 * file's length, so a truncated or corrupt file is an error, never a read
 * past the buffer. */
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/rgl_tensor.h"

static const struct {
    const char *name;
    size_t size;
} types[CV_TENSOR_TYPES] = {
    {"invalid", 0}, {"uint8", 1},  {"int8", 1},    {"uint16", 2},  {"int16", 2},   {"uint32", 4},
    {"int32", 4},   {"uint64", 8}, {"int64", 8},   {"float16", 2}, {"float32", 4}, {"float64", 8},
};

size_t cv_tensor_type_size(enum cv_tensor_type type)
{
    return (unsigned)type < CV_TENSOR_TYPES ? types[type].size : 0;
}

const char *cv_tensor_type_name(enum cv_tensor_type type)
{
    return (unsigned)type < CV_TENSOR_TYPES ? types[type].name : "unknown";
}

/* a little-endian reader over the bytes */
struct reader {
    const unsigned char *p;
    size_t len, at;
};

static bool take(struct reader *r, size_t n, const unsigned char **out)
{
    if (n > r->len - r->at)
        return false;
    *out = r->p + r->at;
    r->at += n;
    return true;
}

static bool get_u(struct reader *r, size_t n, uint64_t *v)
{
    const unsigned char *b;
    if (!take(r, n, &b))
        return false;
    *v = 0;
    for (size_t i = n; i-- > 0;)
        *v = (*v << 8) | b[i];
    return true;
}

void cv_tensor_free(struct cv_tensor_file *t)
{
    for (size_t i = 0; i < t->n_fields; i++)
        free(t->fields[i].name);
    free(t->fields);
    free(t->bytes);
    memset(t, 0, sizeof(*t));
}

static bool parse(const char *name, struct cv_tensor_file *t, struct cv_error *err)
{
    static const unsigned char magic[12] = "tensor_file";
    struct reader r = {(const unsigned char *)t->bytes, t->len, 0};
    const unsigned char *b;
    uint64_t n_fields;
    if (!take(&r, 12, &b) || memcmp(b, magic, sizeof(magic)) != 0)
        return cv_fail(err, "%s: not a tensor file (no \"tensor_file\" header)", name);
    if (!take(&r, 2, &b))
        return cv_fail(err, "%s: truncated in the header (%zu bytes)", name, t->len);
    if (b[0] != 1 || b[1] != 0)
        return cv_fail(err, "%s: tensor file version %u.%u; only 1.0 is known", name, b[0], b[1]);
    if (!get_u(&r, 4, &n_fields))
        return cv_fail(err, "%s: truncated in the header (%zu bytes)", name, t->len);
    /* each field takes at least 13 bytes of table */
    if (n_fields > (t->len - r.at) / 13)
        return cv_fail(err, "%s: %llu fields cannot fit the file (%zu bytes): truncated?", name,
                       (unsigned long long)n_fields, t->len);
    t->fields = cv_xcalloc(n_fields ? n_fields : 1, sizeof(*t->fields));
    for (uint64_t i = 0; i < n_fields; i++) {
        struct cv_tensor_field *f = &t->fields[i];
        uint64_t name_len, ndim, type;
        if (!get_u(&r, 2, &name_len) || !take(&r, name_len, &b))
            return cv_fail(err, "%s: field %llu: truncated in its name (file of %zu bytes)", name,
                           (unsigned long long)i, t->len);
        f->name = cv_xmalloc(name_len + 1);
        memcpy(f->name, b, name_len);
        f->name[name_len] = '\0';
        t->n_fields = i + 1;
        if (!get_u(&r, 2, &ndim) || !get_u(&r, 1, &type) || !get_u(&r, 8, &f->offset))
            return cv_fail(err, "%s: field %llu \"%s\": truncated in its description", name,
                           (unsigned long long)i, f->name);
        if (type == CV_TENSOR_INVALID || type >= CV_TENSOR_TYPES)
            return cv_fail(err, "%s: field \"%s\": unknown type code %llu", name, f->name,
                           (unsigned long long)type);
        if (ndim > CV_TENSOR_MAX_DIMS)
            return cv_fail(err, "%s: field \"%s\": %llu dimensions (at most %d)", name, f->name,
                           (unsigned long long)ndim, CV_TENSOR_MAX_DIMS);
        f->type = (enum cv_tensor_type)type;
        f->ndim = (uint32_t)ndim;
        f->count = 1;
        for (uint32_t d = 0; d < f->ndim; d++) {
            if (!get_u(&r, 8, &f->shape[d]))
                return cv_fail(err, "%s: field \"%s\": truncated in its shape", name, f->name);
            /* no product past the file's size, so no overflow either */
            if (f->shape[d] != 0 && f->count > t->len / f->shape[d])
                return cv_fail(err, "%s: field \"%s\": shape larger than the file", name, f->name);
            f->count *= f->shape[d];
        }
        uint64_t bytes = f->count * types[f->type].size;
        if (f->offset > t->len || bytes > t->len - f->offset)
            return cv_fail(err,
                           "%s: field \"%s\": data at %llu (+%llu bytes) past the end of the "
                           "file (%zu bytes): truncated?",
                           name, f->name, (unsigned long long)f->offset, (unsigned long long)bytes,
                           t->len);
        f->data = (const unsigned char *)t->bytes + f->offset;
        for (uint64_t j = 0; j < i; j++)
            if (strcmp(t->fields[j].name, f->name) == 0)
                return cv_fail(err, "%s: field \"%s\" appears twice", name, f->name);
    }
    return true;
}

bool cv_tensor_parse(const char *name, const void *bytes, size_t len, struct cv_tensor_file *out,
                     struct cv_error *err)
{
    struct cv_tensor_file t = {0};
    t.bytes = cv_xmalloc(len ? len : 1);
    memcpy(t.bytes, bytes, len);
    t.len = len;
    if (!parse(name, &t, err)) {
        cv_tensor_free(&t);
        return false;
    }
    *out = t;
    return true;
}

bool cv_tensor_load(const char *path, struct cv_tensor_file *out, struct cv_error *err)
{
    struct cv_tensor_file t = {0};
    if (!cv_read_file(path, &t.bytes, &t.len, err))
        return false;
    if (!parse(path, &t, err)) {
        cv_tensor_free(&t);
        return false;
    }
    *out = t;
    return true;
}

const struct cv_tensor_field *cv_tensor_field(const struct cv_tensor_file *t, const char *name)
{
    for (size_t i = 0; i < t->n_fields; i++)
        if (strcmp(t->fields[i].name, name) == 0)
            return &t->fields[i];
    return NULL;
}

float cv_tensor_f32(const struct cv_tensor_field *f, uint64_t i)
{
    float v;
    memcpy(&v, f->data + 4 * i, 4);
    return v;
}
