/* glsl_source.h: where GLSL files come from. The files under glsl/ are
 * compiled into the binary (glsl_embedded.c, made by embed_glsl.sh), so a
 * copied cavalry-batch needs nothing beside it; CAVALRY_DATA_DIR points it at
 * a source tree's glsl/ instead, for development. */
#ifndef CV_GPU_GLSL_SOURCE_H
#define CV_GPU_GLSL_SOURCE_H

#include <stdbool.h>

#include "base/error.h"

struct cv_glsl_file {
    const char *path;     /* relative to glsl/, e.g. "bvh/morton.comp" */
    const char *text;
};

/* Ends with {NULL, NULL}. */
extern const struct cv_glsl_file cv_glsl_files[];

/* Reads glsl/<path>; *text is owned by the caller (free()). */
bool cv_glsl_read(const char *path, char **text, struct cv_error *err);

#endif
