// glsl/color/lut_filter.glsl: linear interpolation of OpenColorIO's LUT
// textures in shader arithmetic. OCIO's generated GLSL samples 1D LUTs
// (sampler1D, or sampler2D when a long LUT is folded) and trilinear 3D LUTs
// with texture() and lets GL_LINEAR filtering interpolate. Hardware texture
// units blend with fixed-point weights (8 fractional bits on NVIDIA), which
// put a 9^3 LUT look ~9e-4 away from OCIO's CPU result; llvmpipe filters in
// float. display.comp renames texture() to these functions inside the
// generated code only, so every GPU interpolates alike, in float. Each
// behaves as GL_LINEAR with GL_CLAMP_TO_EDGE (how color_pass.c uploads the
// LUTs); OCIO's nearest lookups (tetrahedral 3D LUTs) sample texel centres,
// where the weights are 0 or 1 up to rounding.
#ifndef CV_COLOR_LUT_FILTER_GLSL
#define CV_COLOR_LUT_FILTER_GLSL

// Texel index below x (in texels, centres at +0.5) and the weight of the
// next one, clamped to the texture as GL_CLAMP_TO_EDGE clamps.
void cv_lut_axis(float x, int size, out int i0, out int i1, out float w)
{
    float f = x * float(size) - 0.5;
    float fl = floor(f);
    w = f - fl;
    i0 = clamp(int(fl), 0, size - 1);
    i1 = clamp(int(fl) + 1, 0, size - 1);
}

vec4 cv_lut_texture(sampler1D s, float x)
{
    int a, b;
    float w;
    cv_lut_axis(x, textureSize(s, 0), a, b, w);
    return mix(texelFetch(s, a, 0), texelFetch(s, b, 0), w);
}

vec4 cv_lut_texture(sampler2D s, vec2 p)
{
    ivec2 size = textureSize(s, 0);
    int x0, x1, y0, y1;
    float wx, wy;
    cv_lut_axis(p.x, size.x, x0, x1, wx);
    cv_lut_axis(p.y, size.y, y0, y1, wy);
    vec4 lo = mix(texelFetch(s, ivec2(x0, y0), 0), texelFetch(s, ivec2(x1, y0), 0), wx);
    vec4 hi = mix(texelFetch(s, ivec2(x0, y1), 0), texelFetch(s, ivec2(x1, y1), 0), wx);
    return mix(lo, hi, wy);
}

vec4 cv_lut_texture(sampler3D s, vec3 p)
{
    ivec3 size = textureSize(s, 0);
    int x0, x1, y0, y1, z0, z1;
    float wx, wy, wz;
    cv_lut_axis(p.x, size.x, x0, x1, wx);
    cv_lut_axis(p.y, size.y, y0, y1, wy);
    cv_lut_axis(p.z, size.z, z0, z1, wz);
    vec4 c00 = mix(texelFetch(s, ivec3(x0, y0, z0), 0), texelFetch(s, ivec3(x1, y0, z0), 0), wx);
    vec4 c10 = mix(texelFetch(s, ivec3(x0, y1, z0), 0), texelFetch(s, ivec3(x1, y1, z0), 0), wx);
    vec4 c01 = mix(texelFetch(s, ivec3(x0, y0, z1), 0), texelFetch(s, ivec3(x1, y0, z1), 0), wx);
    vec4 c11 = mix(texelFetch(s, ivec3(x0, y1, z1), 0), texelFetch(s, ivec3(x1, y1, z1), 0), wx);
    return mix(mix(c00, c10, wy), mix(c01, c11, wy), wz);
}

#endif
