/* exr_write.h: the scene-linear image as OpenEXR, through OpenEXR's C API:
 * RGBA in half (default) or float, a chosen compression, optional AOV
 * layers (albedo.R/G/B, N.X/Y/Z, Z), chromaticities (Rec.709 primaries, D65
 * white), "software" and the caller's metadata as attributes; a crop as a
 * data window inside its full image's display window. The file is written
 * atomically (output/atomic_file.h). */
#ifndef CV_OUTPUT_EXR_WRITE_H
#define CV_OUTPUT_EXR_WRITE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "manifest/enums.h"   /* enum cv_exr_compression and its names */
#include "output/metadata.h"


/* Channel storage of one layer. */
enum cv_exr_pixel {
    CV_EXR_PIXEL_AS_IMAGE = 0, /* whatever the RGBA channels use */
    CV_EXR_PIXEL_HALF,
    CV_EXR_PIXEL_FLOAT,        /* advisable for Z */
};

/* One extra layer (AOV). data holds width*height*n_channels floats,
 * interleaved, top row first, borrowed for the call. Channel names are
 * "name.channel" ("albedo.R", "N.X"), or just "channel" when name is NULL
 * or "" (the depth layer: name NULL, channels {"Z"}). */
struct cv_image_layer {
    const char *name;
    uint32_t n_channels; /* 1 to 4 */
    const char *channels[4];
    const float *data;
    enum cv_exr_pixel pixel;
};

struct cv_exr_params {
    const float *rgba;   /* width*height*4 floats, top row first, borrowed */
    uint32_t width, height;
    /* A crop: the pixels are the data window, at (x0, y0) of a display
     * window of full_width x full_height, so that compositors place them.
     * full_width 0: the display window is the image (x0, y0 ignored). */
    uint32_t full_width, full_height, x0, y0;
    bool use_float;      /* false: half (the default; magnitudes above 65504
                          * become infinity, NaN stays NaN), true: float32 */
    enum cv_exr_compression compression;
    const struct cv_image_layer *layers; /* n_layers of them, may be NULL */
    size_t n_layers;
    const struct cv_metadata *meta; /* may be NULL */
    const struct cv_metadata *meta_exr; /* more attributes, for the EXR alone (Cryptomatte's); may be NULL */
    struct cv_write_limit *write_limit; /* NULL; tests: a disk that fills up */
};

/* Whether the OpenEXR library linked at run time can write c. */
bool cv_exr_compression_supported(enum cv_exr_compression c);
/* Parses "none", "zip", "zips", "piz", "rle", "dwaa", "dwab"; fails for a
 * method this OpenEXR cannot write, saying so. */
bool cv_exr_compression_parse(const char *name, enum cv_exr_compression *out,
                              struct cv_error *err);

/* Ours of OpenEXR's compression value (exr_compression_t): zip for one we
 * do not name. */
enum cv_exr_compression cv_exr_compression_of(int openexr_value);

/* Writes path atomically. Metadata becomes attributes of the same name:
 * strings as string, integers as int (double when outside 32 bits), matrices
 * as m44f, floats
 * as float. The error names the path and the reason (e.g. "No space left
 * on device"); on failure nothing is left behind and an older file under
 * path is untouched. */
bool cv_exr_write(const char *path, const struct cv_exr_params *p, struct cv_error *err);

#endif
