// glsl/bvh/curves.glsl: ray queries against the scene's curves
// (glsl/shared/scene.h, CvCurve): their own binary BVH, built on the host
// (src/bvh/curve_bvh.c) and walked beside the triangles' tree by
// traverse.glsl when the host defines CV_HAS_CURVES; and the surface
// frame of a curve hit.
//
// The intersection is pbrt-v4's Curve::IntersectRay: in a frame where the
// ray runs down +z, the piece is split recursively (to a depth from its
// curvature and width) into cubic segments whose boxes the ray may meet;
// at the last level the segment is a ribbon facing the ray, hit where the
// ray passes within half the width of the closest point of the segment's
// chord. u runs along the piece, v across the width (0.5 on the centre).
//
// One buffer texture holds everything (CV_TEXUNIT_CURVES, read with
// texelFetch: it uses no storage block, of which a kernel may bind few):
// vec4 0 is the header (node count, curve count, first curve's vec4,
// static curve count), then the nodes, 4 vec4 each as a binary CvBvhNode
// (glsl/shared/bvh.h: a leaf child's word is its first curve, its count
// the curves), then one record per moving shape (its tree's root node,
// first curve, curve count), then the curves, 7 vec4 each as CvCurve, in
// leaf order: the static ones (their tree from node 0) first, then each
// moving shape's, in its object space (walked by motion.glsl with the ray
// carried there; CvCurve.info.w = 1 + the shape); then the transforms of
// curves kept in their own object space, 6 vec4 each as CvCurveXform.
#ifndef CV_BVH_CURVES_GLSL
#define CV_BVH_CURVES_GLSL

#include "shared/scene.h"
#include "shared/bvh.h"
#include "shared/bindings.h"

layout(binding = CV_TEXUNIT_CURVES) uniform samplerBuffer cv_curve_tex;
vec4 cv_curve_word(uint i) { return texelFetch(cv_curve_tex, int(i)); }

#define CV_CURVE_STACK 32  // node stack: the host builds trees at most this deep
#define CV_CURVE_SPLIT_STACK 12

uint cv_curve_count() { return floatBitsToUint(cv_curve_word(0).y); }

// Moving shape g's curves: (root node, first curve, count); count 0 when
// it has none.
uvec4 cv_curve_shape(uint g)
{
    return floatBitsToUint(cv_curve_word(1u + 4u * floatBitsToUint(cv_curve_word(0).x) + g));
}

CvCurve cv_curve_at(uint i)
{
    uint b = floatBitsToUint(cv_curve_word(0).z) + 7u * i;
    CvCurve c;
    for (uint k = 0u; k < 4u; k++)
        c.cp[k] = cv_curve_word(b + k);
    c.n0 = cv_curve_word(b + 4u);
    c.n1 = cv_curve_word(b + 5u);
    c.info = floatBitsToUint(cv_curve_word(b + 6u));
    return c;
}

uint cv_curve_type(CvCurve c) { return c.info.y & CV_CURVE_TYPE_MASK; }

// The transform of curve c kept in its object space (CvCurveXform), as
// the vec4 where its six rows start; 0 for a curve in the tree's space.
// They follow the curves: header.z + 7 * the curve count.
uint cv_curve_xform_base(CvCurve c)
{
    uint xf = c.info.y >> CV_CURVE_XF_SHIFT;
    if (xf == 0u)
        return 0u;
    return floatBitsToUint(cv_curve_word(0).z) + 7u * cv_curve_count() + 6u * (xf - 1u);
}

// The 3x4 transform whose rows (3x3 row, translation) start at vec4 b,
// applied to point p or direction v.
vec3 cv_curve_xf_point(uint b, vec3 p)
{
    return vec3(dot(cv_curve_word(b).xyz, p) + cv_curve_word(b).w,
                dot(cv_curve_word(b + 1u).xyz, p) + cv_curve_word(b + 1u).w,
                dot(cv_curve_word(b + 2u).xyz, p) + cv_curve_word(b + 2u).w);
}
vec3 cv_curve_xf_dir(uint b, vec3 v)
{
    return vec3(dot(cv_curve_word(b).xyz, v), dot(cv_curve_word(b + 1u).xyz, v), dot(cv_curve_word(b + 2u).xyz, v));
}

// Blossom of the cubic Bezier p at (a, b, c): the control points of its
// piece over [a, b] are B(a,a,a), B(a,a,b), B(a,b,b), B(b,b,b).
vec3 cv_curve_blossom(vec3 p[4], float a, float b, float c)
{
    vec3 q0 = mix(p[0], p[1], a), q1 = mix(p[1], p[2], a), q2 = mix(p[2], p[3], a);
    return mix(mix(q0, q1, b), mix(q1, q2, b), c);
}

void cv_curve_piece(vec3 p[4], float u0, float u1, out vec3 q[4])
{
    q[0] = cv_curve_blossom(p, u0, u0, u0);
    q[1] = cv_curve_blossom(p, u0, u0, u1);
    q[2] = cv_curve_blossom(p, u0, u1, u1);
    q[3] = cv_curve_blossom(p, u1, u1, u1);
}

// Point and derivative at u (pbrt-v4's EvaluateCubicBezier).
vec3 cv_curve_eval(vec3 p[4], float u, out vec3 deriv)
{
    vec3 a0 = mix(p[0], p[1], u), a1 = mix(p[1], p[2], u), a2 = mix(p[2], p[3], u);
    vec3 b0 = mix(a0, a1, u), b1 = mix(a1, a2, u);
    deriv = dot(b1 - b0, b1 - b0) > 0.0 ? 3.0 * (b1 - b0) : p[3] - p[0];
    return mix(b0, b1, u);
}

float cv_curve_width(CvCurve c, float u) { return mix(c.cp[0].w, c.cp[1].w, u); }

// A ribbon's normal at u: n0 and n1 slerped.
vec3 cv_curve_ribbon_normal(CvCurve c, float u)
{
    if (c.n0.w == 0.0)
        return c.n0.xyz;
    return sin((1.0 - u) * c.n0.w) * c.n1.w * c.n0.xyz + sin(u * c.n0.w) * c.n1.w * c.n1.xyz;
}

// Whether the box of segment q, grown by half of width w, meets the ray's
// segment from 0 to zmax along +z.
bool cv_curve_box_hit(vec3 q[4], float w, float zmax)
{
    vec3 lo = min(min(q[0], q[1]), min(q[2], q[3])) - 0.5 * w;
    vec3 hi = max(max(q[0], q[1]), max(q[2], q[3])) + 0.5 * w;
    return lo.x <= 0.0 && hi.x >= 0.0 && lo.y <= 0.0 && hi.y >= 0.0 && hi.z >= 0.0 && lo.z <= zmax;
}

// pbrt-v4's round-to-nearest log2 of a positive float.
int cv_curve_log2_int(float x)
{
    return x < 1.0 ? -int(round(log2(1.0 / x))) : int(round(log2(x)));
}

// Ray o + t d against curve ci over tmin < t < tmax: t, u, v of the nearest
// hit (any hit when `any`).
bool cv_curve_intersect(uint ci, vec3 o, vec3 d, float tmin, float tmax, bool any, out float t_hit,
                        out float u_hit, out float v_hit)
{
    t_hit = tmax;
    u_hit = 0.0;
    v_hit = 0.0;
    CvCurve c = cv_curve_at(ci);
    uint xb = cv_curve_xform_base(c);
    if (xb != 0u) {
        // into the curve's object space, as pbrt-v4 intersects every
        // curve: an affine map keeps the ray's parameter t
        o = cv_curve_xf_point(xb + 3u, o);
        d = cv_curve_xf_dir(xb + 3u, d);
    }
    float umin = c.cp[2].w, umax = c.cp[3].w;
    vec3 pw[4] = vec3[4](c.cp[0].xyz, c.cp[1].xyz, c.cp[2].xyz, c.cp[3].xyz);
    vec3 seg[4];
    cv_curve_piece(pw, umin, umax, seg);
    // the ray's frame: pbrt-v4's LookAt with "up" across the piece's chord
    float len = length(d);
    vec3 dir = d / len;
    vec3 up = cross(d, seg[3] - seg[0]);
    if (!(dot(up, up) > 0.0))
        up = abs(dir.x) > abs(dir.y) ? vec3(-dir.z, 0.0, dir.x) : vec3(0.0, dir.z, -dir.y);
    vec3 right = normalize(cross(normalize(up), dir));
    vec3 nup = cross(dir, right);
    vec3 p[4];
    for (int k = 0; k < 4; k++) {
        vec3 r = pw[k] - o;
        p[k] = vec3(dot(r, right), dot(r, nup), dot(r, dir));
    }
    vec3 q[4];
    cv_curve_piece(p, umin, umax, q);
    float zmax = len * tmax;
    float wmax = max(cv_curve_width(c, umin), cv_curve_width(c, umax));
    if (!cv_curve_box_hit(q, wmax, zmax))
        return false;
    // refinement depth from the piece's flatness against its width
    float l0 = 0.0;
    for (int k = 0; k < 2; k++) {
        vec3 dd = abs(q[k] - 2.0 * q[k + 1] + q[k + 2]);
        l0 = max(l0, max(max(dd.x, dd.y), dd.z));
    }
    int max_depth = 0;
    if (l0 > 0.0) {
        float eps = max(c.cp[0].w, c.cp[1].w) * 0.05;
        float x = 1.41421356237 * 6.0 * l0 / (8.0 * eps);
        max_depth = x > 0.0 ? clamp(cv_curve_log2_int(x) / 2, 0, 10) : 0;
    }
    bool ribbon = cv_curve_type(c) == CV_CURVE_RIBBON;
    bool found = false;
    vec3 stack[CV_CURVE_SPLIT_STACK];  // (u0, u1, depth) of segments whose boxes the ray meets
    int sp = 0;
    stack[sp++] = vec3(umin, umax, float(max_depth));
    while (sp > 0) {
        vec3 e = stack[--sp];
        float u0 = e.x, u1 = e.y;
        int depth = int(e.z);
        if (depth > 0) {
            float um = 0.5 * (u0 + u1);
            vec3 a[4], b[4];
            cv_curve_piece(p, u0, um, a);
            cv_curve_piece(p, um, u1, b);
            float w0 = cv_curve_width(c, u0), wm = cv_curve_width(c, um), w1 = cv_curve_width(c, u1);
            float zm = len * t_hit;
            // the first half is tried first: pushed last
            if (cv_curve_box_hit(b, max(wm, w1), zm) && sp < CV_CURVE_SPLIT_STACK)
                stack[sp++] = vec3(um, u1, float(depth - 1));
            if (cv_curve_box_hit(a, max(w0, wm), zm) && sp < CV_CURVE_SPLIT_STACK)
                stack[sp++] = vec3(u0, um, float(depth - 1));
            continue;
        }
        vec3 s[4];
        cv_curve_piece(p, u0, u1, s);
        // the ray must pass between the segment's end perpendiculars
        if ((s[1].y - s[0].y) * -s[0].y + s[0].x * (s[0].x - s[1].x) < 0.0)
            continue;
        if ((s[2].y - s[3].y) * -s[3].y + s[3].x * (s[3].x - s[2].x) < 0.0)
            continue;
        vec2 chord = s[3].xy - s[0].xy;
        float denom = dot(chord, chord);
        if (denom == 0.0)
            continue;
        float w = dot(-s[0].xy, chord) / denom;
        float u = clamp(mix(u0, u1, w), u0, u1);
        float hw = cv_curve_width(c, u);
        if (ribbon)
            hw *= abs(dot(cv_curve_ribbon_normal(c, u), d)) / len;
        vec3 dpc;
        vec3 pc = cv_curve_eval(s, clamp(w, 0.0, 1.0), dpc);
        float dist2 = pc.x * pc.x + pc.y * pc.y;
        if (dist2 > hw * hw * 0.25)
            continue;
        float t = pc.z / len;
        if (pc.z < 0.0 || !(t > tmin) || !(t < t_hit))
            continue;
        float dist = sqrt(dist2);
        float edge = dpc.x * -pc.y + pc.x * dpc.y;
        t_hit = t;
        u_hit = u;
        v_hit = edge > 0.0 ? 0.5 + dist / hw : 0.5 - dist / hw;
        found = true;
        if (any)
            return true;
    }
    return found;
}

// Entry and exit of the ray into box [lo, hi] overlap [tmin, tmax].
bool cv_curve_slab(vec3 o, vec3 inv, vec3 lo, vec3 hi, float tmin, float tmax)
{
    vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
    float a = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), max(min(t0.z, t1.z), tmin));
    float b = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), min(max(t0.z, t1.z), tmax));
    a -= abs(a) * 2.0e-6;
    b += abs(b) * 2.0e-6;
    return a <= b && all(lessThanEqual(lo, hi));
}

// Curves first..last-1 against o + t d over (tmin, hit_t): the nearest
// hit replaces (hit_t, hit_prim, hit_u, hit_v); with any, the first ends
// the search. True when one was found. The tree walk's leaves and the
// tests' brute force over every curve.
bool cv_curves_in_range(uint first, uint last, vec3 o, vec3 d, float tmin, bool any,
                        inout float hit_t, inout uint hit_prim, inout float hit_u, inout float hit_v)
{
    bool found = false;
    for (uint ci = first; ci < last; ci++) {
        float t, u, v;
        if (cv_curve_intersect(ci, o, d, tmin, hit_t, any, t, u, v) && t < hit_t) {
            hit_t = t;
            hit_prim = CV_PRIM_CURVE | ci;
            hit_u = u;
            hit_v = v;
            found = true;
            if (any)
                return true;
        }
    }
    return found;
}

// Walks the curve tree from node `root` (0: the static curves'; a moving
// shape's, cv_curve_shape) for hits below hit_t (closest, or any hit);
// replaces the hit (prim CV_PRIM_CURVE | curve, b1 = u, b2 = v) by a
// nearer one. Ties keep the earlier hit (triangles, then lower curves).
// Never trusts the node words (see traverse.glsl's top): children and
// leaf ranges are clipped and the walk stops after as many steps as nodes.
bool cv_curves_walk_from(int root, vec3 o, vec3 d, float tmin, bool any, inout float hit_t,
                         inout uint hit_prim, inout float hit_u, inout float hit_v)
{
    uint n_nodes = floatBitsToUint(cv_curve_word(0).x), n_curves = cv_curve_count();
    if (n_nodes == 0u || uint(root) >= n_nodes)
        return false;
    vec3 inv = 1.0 / mix(d, mix(vec3(1e-30), vec3(-1e-30), lessThan(d, vec3(0.0))), lessThan(abs(d), vec3(1e-30)));
    int stack[CV_CURVE_STACK];
    int sp = 0;
    int node = root;
    bool found = false;
    for (uint steps = 0u; steps <= n_nodes; steps++) {
        uint b = 1u + 4u * uint(node);
        vec4 lmin = cv_curve_word(b), lmax = cv_curve_word(b + 1u);
        vec4 rmin = cv_curve_word(b + 2u), rmax = cv_curve_word(b + 3u);
        int next[2] = int[2](-1, -1);
        for (int side = 0; side < 2; side++) {
            vec4 lo = side == 0 ? lmin : rmin, hi = side == 0 ? lmax : rmax;
            if (!cv_curve_slab(o, inv, lo.xyz, hi.xyz, tmin, hit_t))
                continue;
            int word = floatBitsToInt(lo.w), count = floatBitsToInt(hi.w);
            if (count == 0) {
                if (word > 0 && uint(word) < n_nodes)
                    next[side] = word;
                continue;
            }
            uint first = uint(max(word, 0)), last = min(first + uint(max(count, 0)), n_curves);
            if (cv_curves_in_range(first, last, o, d, tmin, any, hit_t, hit_prim, hit_u, hit_v)) {
                found = true;
                if (any)
                    return true;
            }
        }
        if (next[0] >= 0 && next[1] >= 0) {
            if (sp < CV_CURVE_STACK)
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

// The static curves' tree.
bool cv_curves_walk(vec3 o, vec3 d, float tmin, bool any, inout float hit_t, inout uint hit_prim,
                    inout float hit_u, inout float hit_v)
{
    return cv_curves_walk_from(0, o, d, tmin, any, hit_t, hit_prim, hit_u, hit_v);
}

// Brute force over every static curve, for the tests.
bool cv_curves_brute(vec3 o, vec3 d, float tmin, bool any, inout float hit_t, inout uint hit_prim,
                     inout float hit_u, inout float hit_v)
{
    return cv_curves_in_range(0u, floatBitsToUint(cv_curve_word(0).w), o, d, tmin, any, hit_t, hit_prim, hit_u,
                              hit_v);
}

// The surface at a curve hit (u, v) of ray o + t d, as pbrt-v4 builds its
// SurfaceInteraction: dp/du along the piece; dp/dv across the width,
// perpendicular to the ray (flat), turned about dp/du by up to 90 degrees
// towards the edges (cylinder), or across the ribbon's normal; the normal
// dp/du x dp/dv, flipped by ReverseOrientation and handedness. p_err as
// pbrt-v4's: the width, along each axis. A curve kept in its object space
// builds the frame there with the ray's direction taken there, then takes
// dp/du, the normal (by the inverse transpose) and the error bounds out,
// as pbrt-v4 transforms its SurfaceInteraction.
void cv_curve_frame(uint ci, float u, float v, vec3 d, out vec3 dpdu, out vec3 n, out float p_err,
                    out uint word)
{
    CvCurve c = cv_curve_at(ci);
    uint xb = cv_curve_xform_base(c);
    if (xb != 0u)
        d = cv_curve_xf_dir(xb + 3u, d);
    vec3 pw[4] = vec3[4](c.cp[0].xyz, c.cp[1].xyz, c.cp[2].xyz, c.cp[3].xyz);
    cv_curve_eval(pw, u, dpdu);
    float hw = cv_curve_width(c, u);
    vec3 dpdv;
    if (cv_curve_type(c) == CV_CURVE_RIBBON) {
        vec3 nh = cv_curve_ribbon_normal(c, u);
        hw *= abs(dot(nh, d)) / length(d);
        dpdv = normalize(cross(nh, dpdu)) * hw;
    } else {
        dpdv = normalize(cross(normalize(d), dpdu)) * hw;
        if (cv_curve_type(c) == CV_CURVE_CYLINDER) {
            float phi = -radians(mix(-90.0, 90.0, v));
            vec3 k = normalize(dpdu);
            dpdv = dpdv * cos(phi) + cross(k, dpdv) * sin(phi);
        }
    }
    n = normalize(cross(dpdu, dpdv));
    word = c.info.x;
    if ((word & CV_TRI_REVERSE) != 0u)
        n = -n;
    vec3 err = vec3(hw);
    if (xb != 0u) {
        dpdu = cv_curve_xf_dir(xb, dpdu);
        n = normalize(n.x * cv_curve_word(xb + 3u).xyz + n.y * cv_curve_word(xb + 4u).xyz +
                      n.z * cv_curve_word(xb + 5u).xyz);
        err = hw * vec3(dot(abs(cv_curve_word(xb).xyz), vec3(1.0)), dot(abs(cv_curve_word(xb + 1u).xyz), vec3(1.0)),
                        dot(abs(cv_curve_word(xb + 2u).xyz), vec3(1.0)));
    }
    p_err = dot(abs(n), err);
}

#endif
