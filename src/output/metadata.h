/* metadata.h: the key/value facts written into image headers (EXR
 * attributes, PNG text chunks): scene file, integrator, spp, seed, render
 * time, GPU, job name, settings hash, partial flag. Keys are kept in the
 * order first set; setting a key again replaces its value in place. */
#ifndef CV_OUTPUT_METADATA_H
#define CV_OUTPUT_METADATA_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

enum cv_meta_type {
    CV_META_STRING,
    CV_META_INT,
    CV_META_FLOAT,
    CV_META_M44F,   /* 4x4 float matrix, OpenEXR's m44f (row-vector convention) */
};

struct cv_meta_entry {
    char *key;
    enum cv_meta_type type;
    union {
        char *s;    /* UTF-8, owned by the list */
        int64_t i;  /* booleans are stored as 0/1 */
        double f;
        float m[16]; /* row-major m[4 * row + col], as Imath::M44f */
    } v;
};

struct cv_metadata {
    struct cv_meta_entry *entries;
    size_t len, cap;
};

/* An empty list; free with cv_metadata_destroy. */
struct cv_metadata *cv_metadata_new(void);
void cv_metadata_destroy(struct cv_metadata **m);

/* Keys and string values are copied. */
void cv_metadata_set_string(struct cv_metadata *m, const char *key, const char *value);
void cv_metadata_set_int(struct cv_metadata *m, const char *key, int64_t value);
void cv_metadata_set_float(struct cv_metadata *m, const char *key, double value);
void cv_metadata_set_bool(struct cv_metadata *m, const char *key, bool value);
/* m: 16 floats, row-major in OpenEXR's convention (a point p maps to p * M,
 * translation in the last row); copied. */
void cv_metadata_set_m44f(struct cv_metadata *m, const char *key, const float value[16]);

/* NULL when the key is absent; the pointer lives until the list changes. */
const struct cv_meta_entry *cv_metadata_get(const struct cv_metadata *m, const char *key);

/* The value as text, as PNG text chunks carry it: integers in decimal,
 * floats with enough digits ("%.9g") to read back the same float32 value,
 * matrices as their 16 floats so, space-separated, row by row.
 * Newly allocated. */
char *cv_meta_value_text(const struct cv_meta_entry *e);

#endif
