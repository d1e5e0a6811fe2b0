/* parse.h: reads pbrt-v3/v4 directives from a file (following Include and
 * Import) and hands each one to the builder. */
#ifndef CV_SCENE_PARSE_H
#define CV_SCENE_PARSE_H

#include <stdbool.h>

#include "base/error.h"
#include "scene/builder.h"

bool cv_parse_file(struct cv_builder *b, const char *path, struct cv_error *err);
/* Parses text as if it were the file `name` (tests, fuzzing). Includes are
 * resolved relative to name's folder. */
bool cv_parse_string(struct cv_builder *b, const char *name, const char *text, size_t len,
                     struct cv_error *err);

#endif
