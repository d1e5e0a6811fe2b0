/* exr_read.h: reading back what exr_write wrote, for --resume (a string
 * attribute such as the job settings hash) and for tests (channels as
 * floats). Part 0 of scanline files (what exr_write writes; tiled files are
 * refused), with the data window anywhere; pixels come back in data-window
 * order, top row first. */
#ifndef CV_OUTPUT_EXR_READ_H
#define CV_OUTPUT_EXR_READ_H

#include <stdbool.h>
#include <stdint.h>

#include <openexr.h>

#include "base/error.h"

/* Starts reading `path` with OpenEXR's core API, its own messages quiet
 * (the error names the path); the caller ends with exr_finish(ctxt). */
bool cv_exr_open_read(const char *path, exr_context_t *ctxt, struct cv_error *err);

/* *value is a newly allocated copy (free()). Fails, naming the path, when
 * the file cannot be read, or the attribute is missing or not a string. */
bool cv_exr_read_attribute_string(const char *path, const char *name, char **value,
                                  struct cv_error *err);

/* Reads one channel ("R", "albedo.G", "Z") of part 0 as float32 (halves are
 * converted). *data holds width*height floats, newly allocated (free()). */
bool cv_exr_read_channel(const char *path, const char *channel, float **data,
                         uint32_t *width, uint32_t *height, struct cv_error *err);

/* R, G, B, A interleaved: width*height*4 floats (free()). A missing A reads
 * as 1; a missing R, G or B is an error. */
bool cv_exr_read_rgba(const char *path, float **rgba, uint32_t *width, uint32_t *height,
                      struct cv_error *err);

/* Linear RGB for comparisons with images from other renderers: width*height*3
 * floats (free()). Channels are matched by the name after the last '.',
 * in either case ("R", "r", "beauty.R"), unprefixed names first; a
 * luminance-only image ("Y") and a missing G or B read as copies of the
 * first channel. Fails when there is neither R nor Y. */
bool cv_exr_read_rgb_any(const char *path, float **rgb, uint32_t *width, uint32_t *height,
                         struct cv_error *err);

#endif
