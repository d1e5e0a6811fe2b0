// glsl/lib/noise.glsl: Perlin's gradient noise as pbrt-v4 defines it
// (Noise, DNoise): Ken Perlin's permutation (glsl/shared/perlin.h), his
// twelve edge gradients hashed from the lattice corner (padded to sixteen),
// the quintic fade 6t^5 - 15t^4 + 10t^3, and coordinates first reduced
// modulo 2^30 as C's fmod does (towards zero) so that the lattice cell fits
// an int. Float arithmetic, as pbrt-v4's. The permutation is a constant
// array indexed at run time: include only where noise is evaluated.
#ifndef CV_LIB_NOISE_GLSL
#define CV_LIB_NOISE_GLSL

#include "../shared/perlin.h"

const int cv_perlin_perm[256] = int[256](CV_PERLIN_PERM);

// The gradient of lattice corner (x, y, z) (each in 0..256) dotted with
// the offset d from it.
float cv_noise_grad(int x, int y, int z, vec3 d)
{
    int h = cv_perlin_perm[(cv_perlin_perm[(cv_perlin_perm[x & 255] + y) & 255] + z) & 255] & 15;
    float u = h < 8 || h == 12 || h == 13 ? d.x : d.y;
    float v = h < 4 || h == 12 || h == 13 ? d.y : d.z;
    return ((h & 1) != 0 ? -u : u) + ((h & 2) != 0 ? -v : v);
}

float cv_noise_weight(float t)
{
    float t3 = t * t * t;
    return t3 * (t * (t * 6.0 - 15.0) + 10.0);
}

// pbrt-v4's Noise(p), in about [-1, 1].
float cv_noise(vec3 p)
{
    const float period = 1073741824.0;  // 2^30
    p -= period * trunc(p / period);
    vec3 f = floor(p);
    ivec3 i = ivec3(f) & 255;
    vec3 d = p - f;
    float w000 = cv_noise_grad(i.x, i.y, i.z, d);
    float w100 = cv_noise_grad(i.x + 1, i.y, i.z, d - vec3(1, 0, 0));
    float w010 = cv_noise_grad(i.x, i.y + 1, i.z, d - vec3(0, 1, 0));
    float w110 = cv_noise_grad(i.x + 1, i.y + 1, i.z, d - vec3(1, 1, 0));
    float w001 = cv_noise_grad(i.x, i.y, i.z + 1, d - vec3(0, 0, 1));
    float w101 = cv_noise_grad(i.x + 1, i.y, i.z + 1, d - vec3(1, 0, 1));
    float w011 = cv_noise_grad(i.x, i.y + 1, i.z + 1, d - vec3(0, 1, 1));
    float w111 = cv_noise_grad(i.x + 1, i.y + 1, i.z + 1, d - vec3(1, 1, 1));
    float wx = cv_noise_weight(d.x), wy = cv_noise_weight(d.y), wz = cv_noise_weight(d.z);
    float x00 = mix(w000, w100, wx), x10 = mix(w010, w110, wx);
    float x01 = mix(w001, w101, wx), x11 = mix(w011, w111, wx);
    return mix(mix(x00, x10, wy), mix(x01, x11, wy), wz);
}

// pbrt-v4's DNoise(p): the noise's forward differences over 0.01 per axis.
vec3 cv_dnoise(vec3 p)
{
    const float delta = 0.01;
    float n = cv_noise(p);
    return (vec3(cv_noise(p + vec3(delta, 0, 0)), cv_noise(p + vec3(0, delta, 0)),
                 cv_noise(p + vec3(0, 0, delta))) - n) / delta;
}

#endif
