/* hdr_check.h: a structural check of Radiance .hdr files before stb_image
 * decodes them. Debian's stb_image loops forever on a run-length count of
 * 0 (a truncated file reads zeros past its end), so every scanline's runs
 * are walked here first, bounded by the file's length. */
#ifndef CV_SCENE_HDR_CHECK_H
#define CV_SCENE_HDR_CHECK_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* True when stb_image's Radiance decoder reads data[0..len) to its end
 * without meeting a run of length 0 or one past the scanline, and without
 * running out of data; otherwise false with a message naming path. */
bool cv_hdr_check(const char *path, const unsigned char *data, size_t len, struct cv_error *err);

#endif
