// glsl/bvh/motion.glsl: ray queries against the scene's moving shapes
// (src/scene/scene.h, cv_motion), walked beside the triangles' tree by
// traverse.glsl when the host defines CV_HAS_MOTION; and their transforms,
// for the surface of a hit (trace/geometry.glsl).
//
// As pbrt-v4's AnimatedPrimitive: a shape's triangles stay in its object
// space; a ray at time cv_trace_time is carried into that space by the
// inverse of the shape's transform at that time (pbrt-v4's
// AnimatedTransform::Interpolate: translation and scale-shear lerped, the
// rotation slerped, src/scene/animated.h) and meets the triangles there,
// with the same watertight test as static ones. The transform is affine,
// so a hit's t is the same along the world ray. A top tree over the
// shapes' motion boxes (world space: each holds its shape at every time)
// picks the shapes a ray may meet. A moving shape's curves (with
// CV_HAS_CURVES) are in its object space too, in a tree of their own in
// curves.glsl's buffer (cv_curve_shape), walked with the same object-space
// ray after its triangles; curves.glsl comes first where both are used.
//
// One buffer texture holds everything: vec4 0 is the header (shape count,
// first shape record, first triangle, the first moving triangle's index
// in cv_triangles), then binary nodes of 4 vec4 as curves.glsl's (the top
// tree from node 0: a leaf child's word is a shape, its count 1; then each
// shape's tree: a leaf child's word is its first triangle slot, its count
// the triangles), then the shape records, 11 vec4 each (for the start and
// then the end: T.xyz and the time; q; the 3 rows of S; then vec4 10:
// root node, first triangle index, triangle count), then the triangles, 3
// vec4 each (object-space v0, v1, v2; v0.w the triangle's index), in leaf
// order.
#ifndef CV_BVH_MOTION_GLSL
#define CV_BVH_MOTION_GLSL

#include "shared/bindings.h"
#include "../lib/quaternion.glsl"
#include "triangle.glsl"

// read with texelFetch: no storage block (a kernel may bind only 16)
layout(binding = CV_TEXUNIT_MOTION) uniform samplerBuffer cv_motion_tex;
vec4 cv_motion_at(uint i) { return texelFetch(cv_motion_tex, int(i)); }
uint cv_motion_len() { return uint(textureSize(cv_motion_tex)); }

#define CV_MOTION_STACK 32  // node stacks: median-split trees of < 2^32 items are shallower
#define CV_MOTION_RECORD 11u

// The time of the rays this invocation traces and the surfaces it builds:
// the stage sets it from the ray's path (trace/path_time.glsl) before it
// traces.
float cv_trace_time = 0.0;

uint cv_motion_count() { return floatBitsToUint(cv_motion_at(0).x); }
uint cv_motion_first_prim() { return floatBitsToUint(cv_motion_at(0).w); }

// World from object of shape g at `time`: w = m * x + T.
void cv_motion_xf(uint g, float time, out mat3 m, out vec3 T)
{
    uint b = floatBitsToUint(cv_motion_at(0).y) + CV_MOTION_RECORD * g;
    vec4 a0 = cv_motion_at(b), a1 = cv_motion_at(b + 5u);
    float t0 = a0.w, t1 = a1.w;
    float dt = time <= t0 ? 0.0 : time >= t1 ? 1.0 : (time - t0) / (t1 - t0);
    T = mix(a0.xyz, a1.xyz, dt);
    vec4 q = cv_quat_slerp(dt, cv_motion_at(b + 1u), cv_motion_at(b + 6u));
    // S's rows lerped; m's columns are R times S's columns
    mat3 s = transpose(mat3(mix(cv_motion_at(b + 2u).xyz, cv_motion_at(b + 7u).xyz, dt),
                            mix(cv_motion_at(b + 3u).xyz, cv_motion_at(b + 8u).xyz, dt),
                            mix(cv_motion_at(b + 4u).xyz, cv_motion_at(b + 9u).xyz, dt)));
    m = mat3(cv_quat_rotate(q, s[0]), cv_quat_rotate(q, s[1]), cv_quat_rotate(q, s[2]));
}

uvec4 cv_motion_info(uint g)
{
    return floatBitsToUint(cv_motion_at(floatBitsToUint(cv_motion_at(0).y) + CV_MOTION_RECORD * g + 10u));
}

// The shape that triangle `prim` (a moving one) belongs to: records are in
// triangle order.
uint cv_motion_of_prim(uint prim)
{
    uint lo = 0u, hi = cv_motion_count();
    while (hi - lo > 1u) {
        uint mid = (lo + hi) / 2u;
        if (cv_motion_info(mid).y <= prim)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

bool cv_motion_slab(vec3 o, vec3 inv, float pad, vec3 lo, vec3 hi, float tmin, float tmax)
{
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    float a = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), tmin));
    float b = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), tmax));
    a -= abs(a) * 2.0e-6 + pad;
    b += abs(b) * 2.0e-6 + pad;
    return a <= b && all(lessThanEqual(lo, hi));
}

vec3 cv_motion_inv(vec3 d)
{
    return 1.0 / mix(d, mix(vec3(1e-30), vec3(-1e-30), lessThan(d, vec3(0.0))), lessThan(abs(d), vec3(1e-30)));
}

// Node `node`'s two children: boxes, words and counts.
void cv_motion_node(int node, out vec4 lo0, out vec4 hi0, out vec4 lo1, out vec4 hi1)
{
    uint b = 1u + 4u * uint(node);
    lo0 = cv_motion_at(b);
    hi0 = cv_motion_at(b + 1u);
    lo1 = cv_motion_at(b + 2u);
    hi1 = cv_motion_at(b + 3u);
}

// The triangle test's t is only as exact as the vertices' distance from
// the ray origin allows (traverse.glsl, cv_bvh_pad): boxes are widened by
// this much along the ray, from the shape's root box.
float cv_motion_pad(int root, vec3 o, vec3 d)
{
    vec4 lo0, hi0, lo1, hi1;
    cv_motion_node(root, lo0, hi0, lo1, hi1);
    vec3 lo = lo0.xyz, hi = hi0.xyz;
    if (all(lessThanEqual(lo1.xyz, hi1.xyz))) {
        lo = min(lo, lo1.xyz);
        hi = max(hi, hi1.xyz);
    }
    vec3 m = max(abs(lo - o), abs(hi - o));
    return (m.x + m.y + m.z) * (1.0e-6 / max(length(d), 1.0e-30));
}

// Triangles in slots first..last-1 against the object-space ray: the
// nearest hit below hit_t (ties to the lower triangle index) replaces the
// hit; with any, the first ends the search.
bool cv_motion_tris(uint first, uint last, CvRayTri r, float tmin, bool any, inout float hit_t,
                    inout uint hit_prim, inout float hit_b1, inout float hit_b2)
{
    uint tb = floatBitsToUint(cv_motion_at(0).z);
    bool found = false;
    for (uint k = first; k < last; k++) {
        uint v = tb + 3u * k;
        vec4 v0 = cv_motion_at(v);
        float t, b1, b2;
        if (!cv_ray_tri(r, v0.xyz, cv_motion_at(v + 1u).xyz, cv_motion_at(v + 2u).xyz, t, b1, b2) ||
            !(t > tmin))
            continue;
        uint prim = floatBitsToUint(v0.w);
        if (t < hit_t || (t == hit_t && prim < hit_prim && hit_prim != 0xffffffffu)) {
            hit_t = t;
            hit_prim = prim;
            hit_b1 = b1;
            hit_b2 = b2;
            found = true;
            if (any)
                break;
        }
    }
    return found;
}

// World ray o + t d in shape g's object space at `time` (the same t).
// One function, its results precise, so that the walk and the brute force
// carry a ray into object space bit for bit alike.
void cv_motion_ray(uint g, float time, vec3 o, vec3 d, out vec3 oo, out vec3 od)
{
    mat3 m;
    vec3 T;
    cv_motion_xf(g, time, m, T);
    mat3 mi = inverse(m);
    precise vec3 po = mi * (o - T), pd = mi * d;
    oo = po;
    od = pd;
}

// Shape g against world ray o + t d at `time`.
bool cv_motion_shape(uint g, vec3 o, vec3 d, float time, float tmin, bool any, inout float hit_t,
                     inout uint hit_prim, inout float hit_b1, inout float hit_b2)
{
    vec3 oo, od;
    cv_motion_ray(g, time, o, d, oo, od);
    uvec4 info = cv_motion_info(g);
    int root = int(info.x);
    CvRayTri r = cv_ray_tri_setup(oo, od);
    vec3 inv = cv_motion_inv(od);
    float pad = cv_motion_pad(root, oo, od);
    int stack[CV_MOTION_STACK];
    int sp = 0;
    int node = root;
    bool found = false;
    uint n_nodes = (floatBitsToUint(cv_motion_at(0).y) - 1u) / 4u;
    uint slot_end = (cv_motion_len() - floatBitsToUint(cv_motion_at(0).z)) / 3u;
    for (uint steps = 0u; steps <= n_nodes; steps++) {
        vec4 lo[2], hi[2];
        cv_motion_node(node, lo[0], hi[0], lo[1], hi[1]);
        int next[2] = int[2](-1, -1);
        for (int side = 0; side < 2; side++) {
            if (!cv_motion_slab(oo, inv, pad, lo[side].xyz, hi[side].xyz, tmin, hit_t))
                continue;
            int word = floatBitsToInt(lo[side].w), count = floatBitsToInt(hi[side].w);
            if (count == 0) {
                if (word > 0 && uint(word) < n_nodes)
                    next[side] = word;
                continue;
            }
            uint first = uint(max(word, 0)), last = min(first + uint(max(count, 0)), slot_end);
            if (cv_motion_tris(first, last, r, tmin, any, hit_t, hit_prim, hit_b1, hit_b2))
                found = true;
        }
        if (any && found)
            break;
        if (next[0] >= 0 && next[1] >= 0) {
            if (sp < CV_MOTION_STACK)
                stack[sp++] = next[1];
            node = next[0];
        } else if (next[0] >= 0 || next[1] >= 0) {
            node = max(next[0], next[1]);
        } else if (sp > 0) {
            node = stack[--sp];
        } else {
            break;
        }
    }
#ifdef CV_HAS_CURVES
    uvec4 cs = cv_curve_shape(g);
    if (!(any && found) && cs.z > 0u &&
        cv_curves_walk_from(int(cs.x), oo, od, tmin, any, hit_t, hit_prim, hit_b1, hit_b2))
        found = true;
#endif
    return found;
}

// Walks the moving shapes for hits below hit_t at cv_trace_time (closest,
// or any hit), replacing the hit by a nearer one (ties to the lower
// triangle index). Never trusts the node words (see traverse.glsl's top).
bool cv_motion_walk(vec3 o, vec3 d, float tmin, bool any, inout float hit_t, inout uint hit_prim,
                    inout float hit_b1, inout float hit_b2)
{
    uint ng = cv_motion_count();
    if (ng == 0u)
        return false;
    uint n_nodes = (floatBitsToUint(cv_motion_at(0).y) - 1u) / 4u;
    vec3 inv = cv_motion_inv(d);
    float pad = cv_motion_pad(0, o, d);
    int stack[CV_MOTION_STACK];
    int sp = 0;
    int node = 0;
    bool found = false;
    for (uint steps = 0u; steps <= n_nodes; steps++) {
        vec4 lo[2], hi[2];
        cv_motion_node(node, lo[0], hi[0], lo[1], hi[1]);
        int next[2] = int[2](-1, -1);
        for (int side = 0; side < 2; side++) {
            if (!cv_motion_slab(o, inv, pad, lo[side].xyz, hi[side].xyz, tmin, hit_t))
                continue;
            int word = floatBitsToInt(lo[side].w), count = floatBitsToInt(hi[side].w);
            if (count == 0) {
                if (word > 0 && uint(word) < n_nodes)
                    next[side] = word;
                continue;
            }
            if (word < 0 || uint(word) >= ng)
                continue;
            if (cv_motion_shape(uint(word), o, d, cv_trace_time, tmin, any, hit_t, hit_prim, hit_b1,
                                hit_b2))
                found = true;
        }
        if (any && found)
            break;
        if (next[0] >= 0 && next[1] >= 0) {
            if (sp < CV_MOTION_STACK)
                stack[sp++] = next[1];
            node = next[0];
        } else if (next[0] >= 0 || next[1] >= 0) {
            node = max(next[0], next[1]);
        } else if (sp > 0) {
            node = stack[--sp];
        } else {
            break;
        }
    }
    return found;
}

// Brute force for the tests: every moving triangle (and curve), each
// shape's transform at `time`, no tree.
bool cv_motion_brute(vec3 o, vec3 d, float time, float tmin, bool any, inout float hit_t,
                     inout uint hit_prim, inout float hit_b1, inout float hit_b2)
{
    bool found = false;
    uint slot = 0u, tb = floatBitsToUint(cv_motion_at(0).z);
    for (uint g = 0u; g < cv_motion_count(); g++) {
        vec3 oo, od;
        cv_motion_ray(g, time, o, d, oo, od);
        CvRayTri r = cv_ray_tri_setup(oo, od);
        uint n = cv_motion_info(g).z;
        for (uint k = slot; k < slot + n; k++) {
            uint v = tb + 3u * k;
            vec4 v0 = cv_motion_at(v);
            float t, b1, b2;
            if (!cv_ray_tri(r, v0.xyz, cv_motion_at(v + 1u).xyz, cv_motion_at(v + 2u).xyz, t, b1, b2) ||
                !(t > tmin))
                continue;
            uint prim = floatBitsToUint(v0.w);
            if (t < hit_t || (t == hit_t && prim < hit_prim && hit_prim != 0xffffffffu)) {
                hit_t = t;
                hit_prim = prim;
                hit_b1 = b1;
                hit_b2 = b2;
                found = true;
                if (any)
                    break;
            }
        }
#ifdef CV_HAS_CURVES
        uvec4 cs = cv_curve_shape(g);
        if (!(any && found) && cv_curves_in_range(cs.y, cs.y + cs.z, oo, od, tmin, any, hit_t, hit_prim, hit_b1, hit_b2))
            found = true;
#endif
        if (any && found)
            break;
        slot += n;
    }
    return found;
}

#endif
