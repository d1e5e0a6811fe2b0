#version 450
// glsl/color/display.comp: the display transform pass. Reads the renderer's
// scene-linear RGBA (vec4 per pixel, row-major, top row first) and writes the
// display-referred RGBA of the same layout. The colour maths is the function
// OpenColorIO generates for the job's processor: src/color/color_pass.c puts
// its text where the marker line below stands (with #line directives, so
// compiler messages inside it name "color/ocio-generated"). Inside that
// text texture() means cv_lut_texture (lut_filter.glsl): LUTs interpolate in
// float on every GPU.
layout(local_size_x = 64) in;

#include "../lib/index.glsl"
#include "shared/bindings.h"
#include "lut_filter.glsl"

layout(std430, binding = CV_BIND_COLOR_IN) readonly buffer ColorIn { vec4 color_in[]; };
layout(std430, binding = CV_BIND_COLOR_OUT) writeonly buffer ColorOut { vec4 color_out[]; };

uniform uint u_count;   // pixels

#define texture cv_lut_texture
//@cavalry-ocio-function
#undef texture

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    color_out[i] = cv_ocio_display(color_in[i]);
}
