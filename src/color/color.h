/* color.h: the colour stage. A cv_color_pass turns the renderer's
 * scene-linear RGBA into display-referred RGBA on the GPU with the
 * OpenColorIO processor for one job's config / display / view / look /
 * exposure (see color_params.h for the fallbacks when fields are NULL). */
#ifndef CV_COLOR_COLOR_H
#define CV_COLOR_COLOR_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "color/color_params.h"
#include "color/display_encoding.h"
#include "gpu/context.h"

struct cv_color_pass;

/* Opens the config, checks the names (errors list the valid ones), builds
 * glsl/color/display.comp with OpenColorIO's generated GLSL through gpu's
 * program cache and uploads its LUT textures. Needs the GL context of gpu
 * to be current. */
bool cv_color_pass_create(struct cv_gpu *gpu, const struct cv_color_params *p,
                          struct cv_color_pass **out, struct cv_error *err);

/* Runs the transform on `in` (a storage buffer of width*height vec4, 16
 * bytes a pixel, row-major, top row first; the renderer's resolved film)
 * into the pass's own output buffer, and reads that back into out_rgba
 * (width*height*4 floats). Sets the pass's uniforms first (its program may
 * be shared with other passes). Waits for the GPU. Uses binding points
 * CV_BIND_COLOR_IN and CV_BIND_COLOR_OUT and texture units from 0. */
struct cv_buf;
bool cv_color_pass_run(struct cv_color_pass *pass, const struct cv_buf *in, uint32_t width,
                       uint32_t height, float *out_rgba, struct cv_error *err);

/* "sRGB / ACES 1.0 - SDR Video" (plus look and exposure when set), for
 * image metadata; owned by the pass. */
const char *cv_color_pass_description(const struct cv_color_pass *pass);
/* The config's path, or "shipped cavalry.ocio"; owned by the pass. */
const char *cv_color_pass_config_source(const struct cv_color_pass *pass);
/* What the output encodes, for tagging images (color/display_encoding.h). */
enum cv_display_encoding cv_color_pass_encoding(const struct cv_color_pass *pass);

/* Accepts NULL; clears the pointer. Needs the context current. */
void cv_color_pass_destroy(struct cv_color_pass **pass);

/* Test oracle: the same transform on the CPU, in place on n RGBA pixels. */
bool cv_color_apply_cpu(const struct cv_color_pass *pass, float *rgba, size_t n,
                        struct cv_error *err);

#endif
