// glsl/trace/medium/medium.glsl: participating media (glsl/shared/medium.h)
// as the volumetric stages use them: which medium a ray enters at a surface,
// collision distances, transmittance, and the Henyey-Greenstein phase
// function. A homogeneous medium's majorant is sigma_t itself, so delta
// tracking there never meets a null collision; grid media (grid.glsl,
// with CV_MEDIUM_GRIDS) walk a majorant grid.
//
// Colour is RGB, and sigma_t may differ per channel (a chromatic medium).
// As pbrt-v4 does over its wavelengths (the hero wavelength of
// SampleT_maj with the r_u ratios of VolPathIntegrator), distances are
// drawn with one channel's sigma_t, the path's hero channel, fixed for the
// path, and the path's throughput is divided by the average over the
// channels of the path's density as each channel would have drawn it:
// one-sample MIS over the channels with the balance heuristic, unbiased in
// every channel, and no channel's weight exceeds three times what its own
// sampling would give. A path carries the ratios r of the channels'
// densities to their mean (medium/track.glsl), its throughput is already
// divided by that mean, and surface vertices leave r alone (a BSDF's
// density is the same in every channel).
// Include after common.glsl and materials.glsl.
#ifndef CV_TRACE_MEDIUM_MEDIUM_GLSL
#define CV_TRACE_MEDIUM_MEDIUM_GLSL

#include "shared/medium.h"
#include "shared/bindings.h"
#include "../../lib/frame.glsl"

// The media table as a buffer texture (CV_TEXUNIT_MEDIA): texture units
// do not count against a kernel's 16 storage blocks, which bdpt's would
// pass (glsl/shared/bindings.h). Medium m, field by field (medium.h).
layout(binding = CV_TEXUNIT_MEDIA) uniform samplerBuffer cv_media_tex;
CvMedium cv_media(uint m)
{
    int b = int(m) * CV_MEDIUM_TEXELS;
    CvMedium r;
    r.sigma_a = texelFetch(cv_media_tex, b);
    r.sigma_s = texelFetch(cv_media_tex, b + 1);
    r.Le = texelFetch(cv_media_tex, b + 2);
    uvec4 w = floatBitsToUint(texelFetch(cv_media_tex, b + 3));
    r.type = w.x;
    r.emissive = w.y;
    r.pad0 = w.z;
    r.pad1 = w.w;
    for (int i = 0; i < 3; i++)
        r.to_grid[i] = texelFetch(cv_media_tex, b + 4 + i);
    r.res = floatBitsToUint(texelFetch(cv_media_tex, b + 7));
    r.grids = floatBitsToUint(texelFetch(cv_media_tex, b + 8));
    r.le_res = floatBitsToUint(texelFetch(cv_media_tex, b + 9));
    r.temperature_grids = floatBitsToUint(texelFetch(cv_media_tex, b + 10));
    r.temperature = texelFetch(cv_media_tex, b + 11);
    return r;
}

vec3 cv_medium_sigma_t(uint m) { return cv_media(m).sigma_a.rgb + cv_media(m).sigma_s.rgb; }

#ifdef CV_MEDIUM_GRIDS
#include "grid.glsl"
#else
bool cv_grid_medium(uint m) { return false; }
#endif

// sigma_a, sigma_s and emitted radiance of medium m at render-space point
// p: its constants, or a grid medium's lookups (grid.glsl).
void cv_medium_point(uint m, vec3 p, out vec3 sigma_a, out vec3 sigma_s, out vec3 Le)
{
#ifdef CV_MEDIUM_GRIDS
    if (cv_grid_medium(m)) {
        cv_grid_point(m, cv_grid_space(m, vec4(p, 1.0)), sigma_a, sigma_s, Le);
        return;
    }
#endif
    sigma_a = cv_media(m).sigma_a.rgb;
    sigma_s = cv_media(m).sigma_s.rgb;
    Le = cv_media(m).Le.rgb;
}

// The medium a ray in direction w is in after crossing (or leaving) the
// surface of top-level material `material` with geometric normal ng:
// pbrt-v4's GetMedium(w), or `current` where the surface is no transition.
uint cv_medium_across(uint material, vec3 ng, vec3 w, uint current)
{
    uint word = materials[material].media;
    if ((word & CV_MEDIA_TRANSITION) == 0u)
        return current;
    return dot(w, ng) > 0.0 ? (word >> 8) & 255u : word & 255u;
}

// Transmittance over a length len of medium m (exact for a homogeneous
// medium: the expectation that ratio tracking against the majorant
// estimates, without its noise).
vec3 cv_medium_transmittance(uint m, float len)
{
    return exp(-cv_medium_sigma_t(m) * len);
}

// Delta tracking over a segment of length len (1e30 for an unbounded one)
// in medium m, drawn in channel `hero` with u: true, a collision at t <
// len; false, the ray passes the segment. Either way the caller multiplies
// its throughput by weight, the segment's transmittance over the mean of
// r times the channels' densities of what happened (sigma_t T(t) for a
// collision, T(len) for a pass), and r is renormalised to mean 1. At a
// collision, sigma_s (scattering) or sigma_a Le (emission) follow.
bool cv_medium_sample_distance(uint m, float len, uint hero, float u, inout vec3 r,
                               out float t, out vec3 weight)
{
    vec3 st = cv_medium_sigma_t(m);
    float sc = st[hero];
    t = sc > 0.0 ? -log(1.0 - u) / sc : 3.0e38;
    bool collide = t < len;
    vec3 T = exp(-st * (collide ? t : len));
    vec3 p = collide ? st * T : T;
    float q = dot(r * p, vec3(1.0 / 3.0));
    if (!(q > 0.0)) {
        weight = vec3(0.0);
        return collide;
    }
    weight = T / q;
    r = r * p / q;
    return collide;
}

// Henyey-Greenstein, in pbrt-v4's convention: wo points back along the
// incoming ray, cos_theta = dot(wo, wi), so g > 0 scatters forward (wi
// near -wo). Density per solid angle.
float cv_hg_pdf(float cos_theta, float g)
{
    float d = 1.0 + g * g + 2.0 * g * cos_theta;
    return CV_INV_4PI * (1.0 - g * g) / (d * sqrt(max(d, 1e-12)));
}

// Draws wi from the Henyey-Greenstein lobe about -wo by inverting its CDF;
// pdf is its density (the phase function itself: f / pdf is 1).
vec3 cv_hg_sample(vec3 wo, float g, vec2 u, out float pdf)
{
    float c;  // cosine between wi and -wo
    if (abs(g) < 1e-3) {
        c = 1.0 - 2.0 * u.x;
    } else {
        float s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        c = (1.0 + g * g - s * s) / (2.0 * g);
    }
    c = clamp(c, -1.0, 1.0);
    float sin_t = sqrt(max(0.0, 1.0 - c * c));
    float phi = 2.0 * CV_PI * u.y;
    CvFrame f = cv_frame_from_z(-wo);
    vec3 wi = normalize(sin_t * cos(phi) * f.x + sin_t * sin(phi) * f.y + c * f.z);
    pdf = cv_hg_pdf(dot(wo, wi), g);
    return wi;
}

#endif
