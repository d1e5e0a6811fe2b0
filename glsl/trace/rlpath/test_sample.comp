#version 450
// glsl/trace/rlpath/test_sample.comp: exercises guide.glsl for
// tests/trace/rlpath_sample_test.c on the key of cell 0 and TEST_NORMAL's
// class, in a table the test filled and built with rebuild.comp.
// TEST_MODE 0: draw directions from the learned distribution (w, pdf at
// sampling; pdf evaluated again at w, the key's weight and irradiance). TEST_MODE 1: draw from the mixture of
// guiding (weight m) and a Lambertian lobe about TEST_NORMAL, the way
// rlpath/shade.comp does, with the key's guiding weight m (w, mixture pdf;
// pdf of each part, m). TEST_MODE 2: evaluate the learned and mixture pdfs
// at the directions of the input.
layout(local_size_x = 64) in;
#include "../../lib/index.glsl"
#include "guide.glsl"

layout(std430, binding = CV_BIND_RL_PROBE_OUT) writeonly buffer CvOut { vec4 outv[]; };
layout(std430, binding = CV_BIND_RL_PROBE_IN) readonly buffer CvIn { vec4 inv[]; };
layout(location = 0) uniform uint u_n;
layout(location = 1) uniform uint u_seed;

const vec3 TEST_NORMAL = vec3(0.3, -0.5, 0.812404);  // unit length

uint hash_u(uint x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

float unit(uint x) { return float(x >> 8) * (1.0 / 16777216.0); }

float lambert_pdf(vec3 w) { return max(dot(w, TEST_NORMAL), 0.0) / CV_RL_PI; }

vec3 lambert_sample(vec2 u)
{
    vec3 n = TEST_NORMAL;
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
    vec3 bt = cross(n, t);
    float r = sqrt(u.x), phi = 2.0 * CV_RL_PI * u.y;
    return normalize(r * cos(phi) * t + r * sin(phi) * bt + sqrt(max(0.0, 1.0 - u.x)) * n);
}

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    uint key = cv_rl_orient(TEST_NORMAL);   // cell 0
    float m = cv_rl_key_mix(key);
    float irr = cv_rl_key_load(key).irr;
#if TEST_MODE == 2
    vec3 w = inv[i].xyz;
    float pq = cv_rl_pdf(key, w);
    outv[2u * i] = vec4(pq, cv_rl_mix_pdf(m, pq, lambert_pdf(w)), 0.0, 0.0);
    outv[2u * i + 1u] = vec4(0.0);
#else
    uint h = hash_u(i ^ hash_u(u_seed));
    vec2 u = vec2(unit(h), unit(hash_u(h ^ 0x68bc21ebu)));
    vec3 w;
    float pdf;
#if TEST_MODE == 0
    cv_rl_sample(key, u, w, pdf);
    outv[2u * i] = vec4(w, pdf);
    outv[2u * i + 1u] = vec4(cv_rl_pdf(key, w), 0.0, m, irr);
#else
    if (u.x < m)
        cv_rl_sample(key, vec2(min(u.x / m, 0.99999994), u.y), w, pdf);
    else
        w = lambert_sample(vec2(min((u.x - m) / (1.0 - m), 0.99999994), u.y));
    float pq = cv_rl_pdf(key, w), pb = lambert_pdf(w);
    outv[2u * i] = vec4(w, cv_rl_mix_pdf(m, pq, pb));
    outv[2u * i + 1u] = vec4(pq, pb, m, 0.0);
#endif
#endif
}
