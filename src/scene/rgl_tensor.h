/* rgl_tensor.h: reads the tensor files of the EPFL RGL material database
 * (the format pbrt-v4's `measured` material and Mitsuba read): a header
 * "tensor_file\0", version 1.0, then a table of named fields, each an
 * n-dimensional array of one type stored at an offset in the file. All
 * numbers are little-endian. The file is read whole; fields point into it. */
#ifndef CV_SCENE_RGL_TENSOR_H
#define CV_SCENE_RGL_TENSOR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

/* the format's type codes */
enum cv_tensor_type {
    CV_TENSOR_INVALID = 0,
    CV_TENSOR_U8, CV_TENSOR_I8, CV_TENSOR_U16, CV_TENSOR_I16, CV_TENSOR_U32, CV_TENSOR_I32,
    CV_TENSOR_U64, CV_TENSOR_I64, CV_TENSOR_F16, CV_TENSOR_F32, CV_TENSOR_F64,
    CV_TENSOR_TYPES
};

#define CV_TENSOR_MAX_DIMS 8

struct cv_tensor_field {
    char *name;
    enum cv_tensor_type type;
    uint32_t ndim;                      /* <= CV_TENSOR_MAX_DIMS */
    uint64_t shape[CV_TENSOR_MAX_DIMS];
    uint64_t offset;                    /* in the file [bytes] */
    uint64_t count;                     /* product of shape */
    const unsigned char *data;          /* into the file's bytes, count values */
};

struct cv_tensor_file {
    char *bytes;                        /* the whole file (owned) */
    size_t len;
    struct cv_tensor_field *fields;
    size_t n_fields;
};

/* Reads and checks path: header, version, a field table that fits the
 * file and data that lies inside it. Errors name the file and what is
 * wrong ("x.bsdf: field 3 \"vndf\": data at 812 (+4096 bytes) past the end
 * of the file (2048 bytes)"). */
bool cv_tensor_load(const char *path, struct cv_tensor_file *out, struct cv_error *err);
/* The same on bytes in memory (copied); name stands for the file in
 * messages. */
bool cv_tensor_parse(const char *name, const void *bytes, size_t len, struct cv_tensor_file *out,
                     struct cv_error *err);
/* The field called name, or NULL. */
const struct cv_tensor_field *cv_tensor_field(const struct cv_tensor_file *t, const char *name);
/* Bytes per value of a type; 0 for invalid codes. */
size_t cv_tensor_type_size(enum cv_tensor_type type);
/* The format's name of a type ("float32"). */
const char *cv_tensor_type_name(enum cv_tensor_type type);
/* Value i of a float32 field (host is little-endian, as the format). */
float cv_tensor_f32(const struct cv_tensor_field *f, uint64_t i);
/* Accepts a zeroed struct; zeroes it. */
void cv_tensor_free(struct cv_tensor_file *t);

#endif
