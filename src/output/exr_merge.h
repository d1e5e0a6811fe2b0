/* exr_merge.h: tiles of one image (crop renders, each an EXR whose data
 * window sits in the same display window) merged into one EXR of the whole
 * display window: `cavalry-batch --merge OUT.exr TILE.exr...`. */
#ifndef CV_OUTPUT_EXR_MERGE_H
#define CV_OUTPUT_EXR_MERGE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* Checks that the tiles share display window, channels (names and pixel
 * types) and compression, and that their data windows cover the display
 * window exactly once (no gap, no overlap), then writes out_path
 * atomically: every channel in its tiles' pixel type, so a pixel's bits are
 * those of the tile that holds it. Attributes come from the first tile,
 * except cavalry.settingsHash (a tile's, not the whole image's: --resume
 * must not take the merge for a render) and cavalry.status, which is
 * "partial" when any tile's is not "complete". Reads every tile whole:
 * memory grows with the full image. */
bool cv_exr_merge(const char *out_path, const char *const *tiles, size_t n_tiles,
                  struct cv_error *err);

#endif
