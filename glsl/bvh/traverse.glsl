// glsl/bvh/traverse.glsl: closest-hit and any-hit ray queries against the
// BVH of glsl/shared/bvh.h. Include glsl/bvh/scene_buffers.glsl first.
// Stack-based, nearer child first, children entered beyond the current hit
// skipped (Aila & Laine 2009); watertight triangles (triangle.glsl).
// A hit counts when tmin < t < tmax; among hits at the same t the lowest
// triangle index wins, so the result does not depend on the tree.
// Define CV_BVH_STACK_SIZE before including to change the stack (default
// 64 entries; the tree depth must stay below it).
#ifndef CV_BVH_TRAVERSE_GLSL
#define CV_BVH_TRAVERSE_GLSL

#include "triangle.glsl"

#ifndef CV_BVH_STACK_SIZE
#define CV_BVH_STACK_SIZE 64
#endif

struct CvHit {
    float t;
    uint prim;  // index into cv_triangles
    float b1;   // barycentric weight of v1
    float b2;   // barycentric weight of v2
};

// Zero direction components become tiny ones of the same sign, so slabs
// never compute 0 * inf.
vec3 cv_bvh_safe_inv(vec3 d)
{
    vec3 s = mix(vec3(1.0), vec3(-1.0), lessThan(d, vec3(0.0)));
    vec3 m = mix(d, s * 1.0e-30, lessThan(abs(d), vec3(1.0e-30)));
    return 1.0 / m;
}

// Conservative slab test. The watertight triangle test's t is only as exact
// as the vertices' distance from the origin allows (a ray starting just off
// a plane of large triangles gets t errors far above an ulp of t), so both
// ends are widened by err_k * (L1 distance of the box's far corner): err_k =
// a few float epsilons / |d|, from cv_bvh_err_k. Without that, a box could
// be culled although a triangle in it reports a t at or below the hit.
float cv_bvh_err_k(vec3 d)
{
    return 1.0e-6 / max(length(d), 1.0e-30);
}

bool cv_bvh_slab(vec3 o, vec3 inv, float err_k, vec3 lo, vec3 hi, float tmin, float tmax,
                 out float tnear)
{
    vec3 lo_o = lo - o, hi_o = hi - o;
    vec3 t0 = lo_o * inv, t1 = hi_o * inv;
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    vec3 m = max(abs(lo_o), abs(hi_o));
    float pad = (m.x + m.y + m.z) * err_k;
    float a = max(max(tn.x, tn.y), max(tn.z, tmin));
    float b = min(min(tf.x, tf.y), min(tf.z, tmax));
    a -= abs(a) * 2.0e-6 + pad;
    b += abs(b) * 2.0e-6 + pad;
    tnear = a;
    return a <= b;
}

bool cv_bvh_tri(CvRayTri r, uint prim, out float t, out float b1, out float b2)
{
    uvec4 idx = cv_triangles[prim].idx;
    return cv_ray_tri(r, cv_vertices[idx.x].pos_u.xyz, cv_vertices[idx.y].pos_u.xyz,
                      cv_vertices[idx.z].pos_u.xyz, t, b1, b2);
}

// Updates hit when prims[first..first+count) holds a better one.
void cv_bvh_leaf_closest(CvRayTri r, int first, int count, float tmin, inout CvHit hit)
{
    for (int k = 0; k < count; k++) {
        uint prim = cv_bvh_prims[first + k];
        float t, b1, b2;
        if (cv_bvh_tri(r, prim, t, b1, b2) && t > tmin &&
            (t < hit.t || (t == hit.t && prim < hit.prim && hit.prim != 0xffffffffu))) {
            hit = CvHit(t, prim, b1, b2);
        }
    }
}

bool cv_bvh_leaf_any(CvRayTri r, int first, int count, float tmin, float tmax)
{
    for (int k = 0; k < count; k++) {
        float t, b1, b2;
        if (cv_bvh_tri(r, cv_bvh_prims[first + k], t, b1, b2) && t > tmin && t < tmax)
            return true;
    }
    return false;
}

bool cv_trace_closest(vec3 o, vec3 d, float tmin, float tmax, out CvHit hit)
{
    CvRayTri r = cv_ray_tri_setup(o, d);
    vec3 inv = cv_bvh_safe_inv(d);
    float err_k = cv_bvh_err_k(d);
    hit = CvHit(tmax, 0xffffffffu, 0.0, 0.0);
    int stack_node[CV_BVH_STACK_SIZE];
    float stack_t[CV_BVH_STACK_SIZE];
    int sp = 0;
    int node = 0;
    for (;;) {
        CvBvhNode nd = cv_bvh_nodes[node];
        int lw = floatBitsToInt(nd.lmin.w), lc = floatBitsToInt(nd.lmax.w);
        int rw = floatBitsToInt(nd.rmin.w), rc = floatBitsToInt(nd.rmax.w);
        float tl, tr;
        bool hl = cv_bvh_slab(o, inv, err_k, nd.lmin.xyz, nd.lmax.xyz, tmin, hit.t, tl);
        bool hr = cv_bvh_slab(o, inv, err_k, nd.rmin.xyz, nd.rmax.xyz, tmin, hit.t, tr);
        if (hl && lc > 0) {
            cv_bvh_leaf_closest(r, lw, lc, tmin, hit);
            hl = false;
        }
        if (hr && rc > 0) {
            cv_bvh_leaf_closest(r, rw, rc, tmin, hit);
            hr = false;
        }
        if (hl && hr) {
            bool left_first = tl <= tr;
            node = left_first ? lw : rw;
            if (sp < CV_BVH_STACK_SIZE) {
                stack_node[sp] = left_first ? rw : lw;
                stack_t[sp++] = left_first ? tr : tl;
            }
            continue;
        }
        if (hl || hr) {
            node = hl ? lw : rw;
            continue;
        }
        // Pop the next subtree still entered before the current hit.
        bool found = false;
        while (sp > 0) {
            sp--;
            float te = stack_t[sp];
            if (te <= hit.t) {
                node = stack_node[sp];
                found = true;
                break;
            }
        }
        if (!found)
            break;
    }
    return hit.prim != 0xffffffffu;
}

bool cv_trace_any(vec3 o, vec3 d, float tmin, float tmax)
{
    CvRayTri r = cv_ray_tri_setup(o, d);
    vec3 inv = cv_bvh_safe_inv(d);
    float err_k = cv_bvh_err_k(d);
    int stack_node[CV_BVH_STACK_SIZE];
    int sp = 0;
    int node = 0;
    for (;;) {
        CvBvhNode nd = cv_bvh_nodes[node];
        int lw = floatBitsToInt(nd.lmin.w), lc = floatBitsToInt(nd.lmax.w);
        int rw = floatBitsToInt(nd.rmin.w), rc = floatBitsToInt(nd.rmax.w);
        float tl, tr;
        bool hl = cv_bvh_slab(o, inv, err_k, nd.lmin.xyz, nd.lmax.xyz, tmin, tmax, tl);
        bool hr = cv_bvh_slab(o, inv, err_k, nd.rmin.xyz, nd.rmax.xyz, tmin, tmax, tr);
        if (hl && lc > 0) {
            if (cv_bvh_leaf_any(r, lw, lc, tmin, tmax))
                return true;
            hl = false;
        }
        if (hr && rc > 0) {
            if (cv_bvh_leaf_any(r, rw, rc, tmin, tmax))
                return true;
            hr = false;
        }
        if (hl && hr) {
            bool left_first = tl <= tr;
            node = left_first ? lw : rw;
            if (sp < CV_BVH_STACK_SIZE)
                stack_node[sp++] = left_first ? rw : lw;
            continue;
        }
        if (hl || hr) {
            node = hl ? lw : rw;
            continue;
        }
        if (sp == 0)
            break;
        node = stack_node[--sp];
    }
    return false;
}

#endif
