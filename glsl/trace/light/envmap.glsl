// glsl/trace/light/envmap.glsl: image infinite lights: radiance lookup and
// importance sampling of the piecewise-constant distribution laid out in
// glsl/shared/envmap.h. Needs light_buffers.glsl.
#ifndef CV_LIGHT_ENVMAP_GLSL
#define CV_LIGHT_ENVMAP_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/sampling.glsl"
#include "../bsdf/texture.glsl"

vec3 cv_light_to_local(CvLight l, vec3 d)
{
    return vec3(dot(l.to_light[0].xyz, d), dot(l.to_light[1].xyz, d), dot(l.to_light[2].xyz, d));
}

vec3 cv_light_to_world(CvLight l, vec3 d)
{
    return l.to_light[0].xyz * d.x + l.to_light[1].xyz * d.y + l.to_light[2].xyz * d.z;
}

bool cv_env_equal_area(CvLight l) { return (l.flags & CV_LIGHTF_EQUAL_AREA) != 0u; }

// Light-space direction <-> image (u, v), v = 0 at the top row.
vec2 cv_env_dir_to_uv(CvLight l, vec3 dl)
{
    if (cv_env_equal_area(l))
        return cv_equal_area_sphere_to_square(dl);
    return vec2(cv_spherical_phi(dl) * CV_INV_2PI, cv_spherical_theta(dl) * CV_INV_PI);
}

vec3 cv_env_uv_to_dir(CvLight l, vec2 uv)
{
    if (cv_env_equal_area(l))
        return cv_equal_area_square_to_sphere(uv);
    float theta = uv.y * CV_PI, phi = uv.x * 2.0 * CV_PI;
    return vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}

// A pbrt-v4 equal-area map is looked up at its nearest texel, as pbrt-v4's
// ImageInfiniteLight::ImageLe does (its radiance is then constant over each
// texel, as the sampling distribution is); a pbrt-v3 lat-long map
// bilinearly, as pbrt-v3's MIPMap lookup.
vec3 cv_env_map_Le(CvLight l, vec3 dir)
{
    if (l.tex < 0)
        return l.L.rgb;
    CvTexture tx = textures[l.tex];
    vec2 uv = cv_env_dir_to_uv(l, cv_light_to_local(l, normalize(dir)));
    vec4 v;
    if (cv_env_equal_area(l)) {
        uint w = max(tx.width, 1u), h = max(tx.height, 1u);
        v = cv_texel_fetch(tx.offset, w, h, ivec2(floor(uv * vec2(w, h))), tx.flags);
    } else {
        v = cv_image_lookup(tx, uv, 0.0);
    }
    return l.L.rgb * cv_tex_finish(tx, v).rgb;
}

// Index i in [0, n) with cdf[base + i] <= u < cdf[base + i + 1].
uint cv_env_find(uint base, uint n, float u)
{
    uint lo = 0u, hi = n;
    while (lo + 1u < hi) {
        uint mid = (lo + hi) / 2u;
        if (env_dist[base + mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

// Density in (u, v) of the map's distribution.
float cv_env_uv_pdf(uint o, vec2 uv)
{
    uint w = floatBitsToUint(env_dist[o]), h = floatBitsToUint(env_dist[o + 1u]);
    float integral = env_dist[o + 2u];
    if (!(integral > 0.0))
        return 0.0;
    uint x = min(uint(uv.x * float(w)), w - 1u), y = min(uint(uv.y * float(h)), h - 1u);
    return env_dist[CV_ENV_FUNC(o) + y * w + x] / integral;
}

float cv_env_map_pdf(CvLight l, vec3 dir)
{
    vec3 dl = cv_light_to_local(l, normalize(dir));
    vec2 uv = cv_env_dir_to_uv(l, dl);
    float p = cv_env_uv_pdf(l.prim, uv);
    if (cv_env_equal_area(l))
        return p * CV_INV_4PI;
    float s = sqrt(max(0.0, 1.0 - dl.z * dl.z));
    return s > 0.0 ? p / (2.0 * CV_PI * CV_PI * s) : 0.0;
}

// Samples a world direction; pdf per solid angle (0: failed).
vec3 cv_env_map_sample(CvLight l, vec2 u, out float pdf)
{
    uint o = l.prim;
    uint w = floatBitsToUint(env_dist[o]), h = floatBitsToUint(env_dist[o + 1u]);
    uint marg = CV_ENV_MARG(o, w, h);
    uint y = cv_env_find(marg, h + 1u, u.y);
    float c0 = env_dist[marg + y], c1 = env_dist[marg + y + 1u];
    float dv = c1 > c0 ? (u.y - c0) / (c1 - c0) : 0.5;
    uint cond = CV_ENV_COND(o, w, h) + y * (w + 1u);
    uint x = cv_env_find(cond, w + 1u, u.x);
    float d0 = env_dist[cond + x], d1 = env_dist[cond + x + 1u];
    float du = d1 > d0 ? (u.x - d0) / (d1 - d0) : 0.5;
    vec2 uv = vec2((float(x) + clamp(du, 0.0, 1.0)) / float(w), (float(y) + clamp(dv, 0.0, 1.0)) / float(h));
    vec3 dl = cv_env_uv_to_dir(l, uv);
    float integral = env_dist[o + 2u];
    float p = integral > 0.0 ? env_dist[CV_ENV_FUNC(o) + y * w + x] / integral : 0.0;
    if (cv_env_equal_area(l)) {
        pdf = p * CV_INV_4PI;
    } else {
        float s = sqrt(max(0.0, 1.0 - dl.z * dl.z));
        pdf = s > 0.0 ? p / (2.0 * CV_PI * CV_PI * s) : 0.0;
    }
    return normalize(cv_light_to_world(l, dl));
}

#endif
