/* ocio.h: the C face of OpenColorIO (src/color/ocio_shim.cpp, with
 * ocio_spaces.cpp). A cv_ocio holds one config and the processor for one job's
 * display / view / look / exposure; it hands out the GLSL, LUT textures and
 * uniforms of the GPU processor, and applies the CPU processor (the test
 * oracle). No C++ exception crosses this header: every failure comes back
 * as a message in err. Strings and arrays returned stay owned by the
 * cv_ocio and live until it is destroyed. */
#ifndef CV_COLOR_OCIO_H
#define CV_COLOR_OCIO_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "color/color_params.h"
#include "color/display_encoding.h"

#ifdef __cplusplus
extern "C" {
#endif

struct cv_ocio;

/* Text of configs/cavalry.ocio compiled into the binary (NUL-terminated). */
extern const char cv_ocio_shipped_config[];

/* The config that a colour pass with config_path would open (color_params.h:
 * the path or ocio:// URI itself, else $OCIO, else the data folder's
 * cavalry.ocio), or NULL for the copy compiled in (cv_ocio_shipped_config).
 * The one home of that order; the string lives until the next call. */
const char *cv_ocio_config_file(const char *config_path);

/* Opens the config p names (see color_params.h for the fallbacks) and builds
 * the processor from the render's colour space (linear Rec.709) to p's
 * display / view, with exposure applied in the scene_linear role's space.
 * The render's space is found in the config by name, else through its
 * aces_interchange or cie_xyz_d65_interchange role (ocio_spaces.hpp); a
 * config where none applies fails, saying so. Unknown display, view or look
 * names fail with the valid names listed; $OCIO naming a missing file fails
 * naming the path. */
bool cv_ocio_create(const struct cv_color_params *p, struct cv_ocio **out, struct cv_error *err);
/* Accepts NULL; clears the pointer. */
void cv_ocio_destroy(struct cv_ocio **ocio);

/* "sRGB / ACES 1.0 - SDR Video", with " / look: L" and " / exposure +1 EV"
 * when set: for image metadata and logs. */
const char *cv_ocio_description(const struct cv_ocio *ocio);
/* Where the config came from: its path, or "shipped cavalry.ocio". */
const char *cv_ocio_config_source(const struct cv_ocio *ocio);
/* How the render's space was found: 'colour space "lin_rec709"', or
 * 'aces_interchange role ("ACES2065-1")'. */
const char *cv_ocio_render_space(const struct cv_ocio *ocio);
/* What the view's display colour space encodes (CV_DISPLAY_UNKNOWN for a
 * Raw view, a linear one, or one not recognised). */
enum cv_display_encoding cv_ocio_display_encoding(const struct cv_ocio *ocio);

/* Applies the CPU processor in place to n RGBA float pixels. */
bool cv_ocio_apply_cpu(const struct cv_ocio *ocio, float *rgba, size_t n, struct cv_error *err);

/* ---- GPU processor ------------------------------------------------------ */

struct cv_ocio_texture {
    const char *sampler;   /* the sampler uniform's name in the GLSL */
    unsigned dims;         /* 1, 2 (a long 1D LUT folded into rows) or 3 */
    unsigned width, height, depth;  /* texels; unused dimensions are 1 */
    unsigned channels;     /* 1 (red only) or 3 (RGB) */
    bool linear;           /* linear filtering, else nearest */
    const float *values;   /* width*height*depth*channels floats, x fastest */
};

enum cv_ocio_uniform_type {
    CV_OCIO_UNIFORM_FLOAT,       /* v[0] */
    CV_OCIO_UNIFORM_BOOL,        /* b */
    CV_OCIO_UNIFORM_FLOAT3,      /* v[0..2] */
    CV_OCIO_UNIFORM_FLOAT_ARRAY, /* fv[0..count) */
    CV_OCIO_UNIFORM_INT_ARRAY,   /* iv[0..count) */
};

struct cv_ocio_uniform {
    const char *name;
    enum cv_ocio_uniform_type type;
    float v[3];
    bool b;
    const float *fv;
    const int *iv;
    int count;
};

/* Generates the GLSL (4.0 dialect, valid in a #version 450 shader) of
 * `vec4 <function_name>(vec4)`, its resources prefixed with function_name.
 * Must be called before the getters below. */
bool cv_ocio_gpu_extract(struct cv_ocio *ocio, const char *function_name, struct cv_error *err);
const char *cv_ocio_gpu_source(const struct cv_ocio *ocio);
unsigned cv_ocio_gpu_texture_count(const struct cv_ocio *ocio);
bool cv_ocio_gpu_texture(const struct cv_ocio *ocio, unsigned i, struct cv_ocio_texture *t,
                         struct cv_error *err);
unsigned cv_ocio_gpu_uniform_count(const struct cv_ocio *ocio);
/* The uniform's current value (dynamic properties such as exposure). */
bool cv_ocio_gpu_uniform(const struct cv_ocio *ocio, unsigned i, struct cv_ocio_uniform *u,
                         struct cv_error *err);

/* ---- config inspection -------------------------------------------------- */

/* Every (display, view) pair of the config (config_path as in
 * cv_color_params): *names receives display0, view0, display1, view1, ...
 * NULL-terminated, owned by the caller (cv_ocio_free_names). */
bool cv_ocio_list_views(const char *config_path, char ***names, size_t *n_pairs,
                        struct cv_error *err);
void cv_ocio_free_names(char ***names);

#ifdef __cplusplus
}
#endif

#endif
