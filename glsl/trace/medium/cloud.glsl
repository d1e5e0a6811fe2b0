// glsl/trace/medium/cloud.glsl: pbrt-v4's procedural "cloud" medium
// (CV_MEDIUM_CLOUD; glsl/shared/medium.h): a density in [0, 1] from
// Perlin noise (lib/noise.glsl) scaling sigma_a and sigma_s, vacuum
// outside its bounds. Its lookups and majorant walk are the grid media's
// (grid.glsl: the host fills its majorant grid with a bound on sigma_t,
// src/scene/media_cloud.c). Compiled only with CV_MEDIUM_CLOUDS; grid.glsl
// includes it after the grid buffer.
#ifndef CV_TRACE_MEDIUM_CLOUD_GLSL
#define CV_TRACE_MEDIUM_CLOUD_GLSL

#include "../../lib/noise.glsl"

// pbrt-v4's CloudMedium::Density at p in medium space: the point warped
// by two octaves of the noise's differences (wispiness), five octaves of
// noise summed (fractional Brownian motion, lacunarity 1.99, gain 0.5),
// fading with height, plus a floor of density below y 0.5.
float cv_cloud_density(vec3 p, float density, float wispiness, float frequency)
{
    vec3 pp = frequency * p;
    if (wispiness > 0.0) {
        float vomega = 0.05 * wispiness, vlambda = 10.0;
        for (int i = 0; i < 2; i++) {
            pp += vomega * cv_dnoise(vlambda * pp);
            vomega *= 0.5;
            vlambda *= 1.99;
        }
    }
    float d = 0.0, omega = 0.5, lambda = 1.0;
    for (int i = 0; i < 5; i++) {
        d += omega * cv_noise(lambda * pp);
        omega *= 0.5;
        lambda *= 1.99;
    }
    d = clamp((1.0 - p.y) * 4.5 * density * d, 0.0, 1.0);
    d += 2.0 * max(0.0, 0.5 - p.y);
    return clamp(d, 0.0, 1.0);
}

// The density of cloud medium m at g in its unit cube: its parameters
// (density, wispiness, frequency, the bounds' low corner and size in
// medium space) lie in the grid buffer at grids.x.
float cv_cloud_density_at(uint m, vec3 g)
{
    uint k = cv_media(m).grids.x;
    vec3 lo = vec3(cv_grid_float(k + 3u), cv_grid_float(k + 4u), cv_grid_float(k + 5u));
    vec3 size = vec3(cv_grid_float(k + 6u), cv_grid_float(k + 7u), cv_grid_float(k + 8u));
    return cv_cloud_density(lo + g * size, cv_grid_float(k), cv_grid_float(k + 1u),
                            cv_grid_float(k + 2u));
}

#endif
