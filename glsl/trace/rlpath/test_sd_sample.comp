#version 450
// glsl/trace/rlpath/test_sd_sample.comp: exercises sdtree.glsl for
// tests/trace/rlpath_sd_sample_test.c at the quadtree of u_point and
// TEST_NORMAL's orientation class, in a
// tree the test built and uploaded. TEST_MODE 0: draw directions from the
// leaf's quadtree (w, pdf at sampling; pdf evaluated again at w, the
// leaf's weight m, its root). TEST_MODE 1: draw from the mixture of the
// guide (weight m) and a Lambertian lobe about TEST_NORMAL, the way
// sd_shade.comp does (w, mixture pdf; guide and lobe pdfs at w, m).
// TEST_MODE 2: the guide's pdf at the directions of the input. TEST_MODE
// 3: the class texel (class i % CV_SD_CLASSES) of the input's points
// through the grid block and by the full descent.
layout(local_size_x = 64) in;
#include "../../lib/index.glsl"
#include "sdtree.glsl"

layout(std430, binding = CV_BIND_RL_PROBE_OUT) writeonly buffer CvOut { vec4 outv[]; };
layout(std430, binding = CV_BIND_RL_PROBE_IN) readonly buffer CvIn { vec4 inv[]; };
layout(location = 0) uniform uint u_n;
layout(location = 1) uniform uint u_seed;
layout(location = 2) uniform vec3 u_point;

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

float lambert_pdf(vec3 w) { return max(dot(w, TEST_NORMAL), 0.0) / CV_SD_PI; }

vec3 lambert_sample(vec2 u)
{
    vec3 n = TEST_NORMAL;
    vec3 t = normalize(abs(n.x) > 0.5 ? cross(n, vec3(0, 1, 0)) : cross(n, vec3(1, 0, 0)));
    vec3 bt = cross(n, t);
    float r = sqrt(u.x), phi = 2.0 * CV_SD_PI * u.y;
    return normalize(r * cos(phi) * t + r * sin(phi) * bt + sqrt(max(0.0, 1.0 - u.x)) * n);
}

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
#if TEST_MODE == 3
    vec3 lo, size;
    uint cls = i % CV_SD_CLASSES;
    outv[2u * i] = vec4(float(cv_sd_class_texel(inv[i].xyz, cls)),
                        float(cv_sd_class_texel_box(inv[i].xyz, cls, lo, size)), 0.0, 0.0);
    outv[2u * i + 1u] = vec4(0.0);
    return;
#endif
    vec4 leaf = cv_sd_leaf(u_point, cv_sd_class(TEST_NORMAL));
    int root = int(leaf.x);
    float m = leaf.y;
#if TEST_MODE == 2
    outv[2u * i] = vec4(cv_sd_pdf(root, inv[i].xyz), 0.0, 0.0, 0.0);
    outv[2u * i + 1u] = vec4(0.0);
#else
    uint h = hash_u(i ^ hash_u(u_seed));
    vec2 u = vec2(unit(h), unit(hash_u(h ^ 0x68bc21ebu)));
    vec3 w;
    float pdf;
#if TEST_MODE == 0
    w = cv_sd_sample(root, u, pdf);
    outv[2u * i] = vec4(w, pdf);
    outv[2u * i + 1u] = vec4(cv_sd_pdf(root, w), m, float(root), cv_sd_light(leaf));
#else
    if (u.x < m)
        w = cv_sd_sample(root, vec2(min(u.x / m, CV_SD_ONE_MINUS_EPS), u.y), pdf);
    else
        w = lambert_sample(vec2(min((u.x - m) / (1.0 - m), CV_SD_ONE_MINUS_EPS), u.y));
    float pq = cv_sd_pdf(root, w), pb = lambert_pdf(w);
    outv[2u * i] = vec4(w, m * pq + (1.0 - m) * pb);
    outv[2u * i + 1u] = vec4(pq, pb, m, 0.0);
#endif
#endif
}
