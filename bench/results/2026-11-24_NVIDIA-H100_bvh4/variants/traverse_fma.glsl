// glsl/bvh/traverse.glsl: closest-hit and any-hit ray queries against the
// BVH of glsl/shared/bvh.h. Include glsl/bvh/scene_buffers.glsl first.
// Stack-based, nearer child first, children entered beyond the current hit
// skipped (Aila & Laine 2009); watertight triangles (triangle.glsl).
// A hit counts when tmin < t < tmax; among hits at the same t the lowest
// triangle index wins, so the result does not depend on the tree.
// Define CV_BVH_STACK_SIZE before including to change the stack (default
// 64 entries; the tree depth must stay below it, deeper subtrees are
// skipped rather than overflow it).
// A corrupt or uninitialised tree must never hang the GPU (a reset kills
// every job on the device), so nothing here trusts the node words: inner
// children must lie in 1..length-1 (the root is nobody's child, which also
// rejects the empty child of a tiny tree), leaf ranges are clipped to the
// leaf-ordered triangle buffer (whose records are valid by construction,
// leaf_tris.comp), and the loop stops after as many steps as there are
// nodes, which a valid tree never needs.
#ifndef CV_BVH_TRAVERSE_GLSL
#define CV_BVH_TRAVERSE_GLSL

#include "triangle.glsl"

#ifndef CV_BVH_STACK_SIZE
#define CV_BVH_STACK_SIZE 64
#endif

#ifdef CV_BVH_COUNT_STEPS
// Nodes visited by the queries of this invocation, for tests.
uint cv_bvh_steps = 0u;
#endif

struct CvHit {
    float t;
    uint prim;  // index into cv_triangles
    float b1;   // barycentric weight of v1
    float b2;   // barycentric weight of v2
};

// Zero direction components become tiny ones of the same sign, so slabs
// never compute 0 * inf; the floor grows with the origin's distance so that
// o * inv stays finite (the planes' t comes from it, cv_bvh_begin).
vec3 cv_bvh_safe_inv(vec3 o, vec3 d)
{
    vec3 s = mix(vec3(1.0), vec3(-1.0), lessThan(d, vec3(0.0)));
    vec3 f = max(vec3(1.0e-30), abs(o) * 1.0e-37);
    vec3 m = mix(d, s * f, lessThan(abs(d), f));
    return 1.0 / m;
}

// Conservative slab test. The watertight triangle test's t is only as exact
// as the vertices' distance from the origin allows (a ray starting just off
// a plane of large triangles gets t errors far above an ulp of t), so both
// ends are widened by `pad` (cv_bvh_pad): a few float epsilons / |d| times
// the L1 distance from the origin to the far corner of the root's box,
// which bounds that of every box below it. Without that, a box could be
// culled although a triangle in it reports a t at or below the hit. Once
// per ray rather than per box, which saves each box test its own sum of
// distances; the larger pad lets through only boxes within ~1e-6 of the
// scene's size of the ray.
float cv_bvh_pad(vec3 o, vec3 d)
{
    CvBvhNode root = cv_bvh_nodes[0];
    // An empty child's inverted box drops out of min/max.
    vec3 lo = min(root.lmin.xyz, root.rmin.xyz), hi = max(root.lmax.xyz, root.rmax.xyz);
    vec3 m = max(abs(lo - o), abs(hi - o));
    return (m.x + m.y + m.z) * (1.0e-6 / max(length(d), 1.0e-30));
}

bool cv_bvh_slab(vec3 inv, vec3 olo, vec3 ohi, vec3 lo, vec3 hi, float tmin, float tmax,
                 out float tnear)
{
    precise vec3 t0 = fma(lo, inv, olo), t1 = fma(hi, inv, ohi);
    vec3 tn = min(t0, t1), tf = max(t0, t1);
    float a = max(max(tn.x, tn.y), max(tn.z, tmin));
    float b = min(min(tf.x, tf.y), min(tf.z, tmax));
    a -= abs(a) * 2.0e-6;
    b += abs(b) * 2.0e-6;
    tnear = a;
    // min/max above would turn an inverted (empty) box inside out.
    return a <= b && lo.x <= hi.x;
}

// Triangle `prim` through the scene's index buffers (the brute force of the
// tests; traversal reads leaf slots with cv_bvh_leaf_tri).
bool cv_bvh_tri(CvRayTri r, uint prim, out float t, out float b1, out float b2)
{
    t = 0.0;
    b1 = 0.0;
    b2 = 0.0;
    if (prim >= uint(cv_triangles.length()))
        return false;
    uvec4 idx = cv_triangles[prim].idx;
    return cv_ray_tri(r, cv_vertices[idx.x].pos_u.xyz, cv_vertices[idx.y].pos_u.xyz,
                      cv_vertices[idx.z].pos_u.xyz, t, b1, b2);
}

// The triangle in leaf slot `slot`, and its index.
bool cv_bvh_leaf_tri(CvRayTri r, int slot, out uint prim, out float t, out float b1, out float b2)
{
    CvBvhTri tri = cv_bvh_tris[slot];
    prim = floatBitsToUint(tri.v0.w);
    return cv_ray_tri(r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, t, b1, b2);
}

// The part of slots first..first+count-1 that exists.
int cv_bvh_leaf_count(int first, int count)
{
    int n = cv_bvh_tris.length();
    return first < 0 || first >= n ? 0 : clamp(count, 0, n - first);
}

// True when a child word may be entered as an inner node.
bool cv_bvh_inner_ok(int node)
{
    return node > 0 && node < cv_bvh_nodes.length();
}

// The leaf children a node's slab tests let in, as one run of triangles:
// n0 slots from lw (left), then n1 from rw (right). One loop over both
// rather than a loop per child: a lane with one leaf child and a lane with
// two run in step, and the triangle test is compiled once. Measured on an
// H100 (veach-bidir, 256 spp, with the shear rows of triangle.glsl): closest
// 588 -> 560 ms, any-hit 669 -> 618 ms. The order of the tests decides no
// result (ties go to the lower triangle index).
void cv_bvh_leaf_runs(bool hl, bool hr, int lw, int lc, int rw, int rc, out int n0, out int n1)
{
    n0 = hl && lc > 0 ? cv_bvh_leaf_count(lw, lc) : 0;
    n1 = hr && rc > 0 ? cv_bvh_leaf_count(rw, rc) : 0;
}

// A query's state: the ray's set-up, the node to visit next, the stack
// depth and the best hit so far (the stack entries are the invocation's,
// below). The same loops as one function each with local variables were
// 1-2 % slower on an H100 (4 M-triangle scene, 1280x720, 64 spp, medians
// of 9: closest-hit stage 167.8 -> 165.5 ms, any-hit 114.5 -> 113.8 ms;
// veach-bidir 1024 spp, of 6: 2027 -> 1994 and 1550 -> 1536 ms); the
// arithmetic and the order of visits are the same.
struct CvBvhWalk {
    CvRayTri r;  // r.o: the origin
    vec3 inv;
    vec3 olo;    // plane t = fma(plane, inv, olo) for min planes, ohi for max
    vec3 ohi;
    float pad;
    float tmin;
    float tmax;  // any-hit only; closest-hit queries shrink hit.t instead
    CvHit hit;
    int node;
    int sp;
    int steps;   // nodes left before the query gives up (see the top)
};

int cv_bvh_stack[CV_BVH_STACK_SIZE];

// A full stack drops the entry: that subtree is skipped (a valid tree never
// gets that deep).
void cv_bvh_push(inout CvBvhWalk w, int node)
{
    if (w.sp >= CV_BVH_STACK_SIZE)
        return;
    cv_bvh_stack[w.sp] = node;
    w.sp++;
}

int cv_bvh_pop(inout CvBvhWalk w)
{
    w.sp--;
    return cv_bvh_stack[w.sp];
}

// Starts a query (closest or any hit) over tmin < t < tmax.
void cv_bvh_begin(vec3 o, vec3 d, float tmin, float tmax, out CvBvhWalk w)
{
    w.r = cv_ray_tri_setup(o, d);
    w.inv = cv_bvh_safe_inv(o, d);
    w.pad = cv_bvh_pad(o, d);
    vec3 oi = o * w.inv;
    vec3 e = (abs(oi) * 2.4e-7 + w.pad) * mix(vec3(1.0), vec3(-1.0), lessThan(w.inv, vec3(0.0)));
    w.olo = -oi - e;
    w.ohi = -oi + e;
    w.tmin = tmin;
    w.tmax = tmax;
    w.hit = CvHit(tmax, 0xffffffffu, 0.0, 0.0);
    w.node = 0;
    w.sp = 0;
    w.steps = cv_bvh_nodes.length();
}

// After a node whose inner children hl, hr (at lw, rw, entered at tl, tr)
// the ray enters: the next node, the nearer child first. False when the
// query has nothing left to visit.
bool cv_bvh_next(inout CvBvhWalk w, bool hl, bool hr, int lw, int rw, float tl, float tr)
{
    if (hl && hr) {
        bool left_first = tl <= tr;
        w.node = left_first ? lw : rw;
        cv_bvh_push(w, left_first ? rw : lw);
        return true;
    }
    if (hl || hr) {
        w.node = hl ? lw : rw;
        return true;
    }
    // The next subtree. Its entry distance is not kept: one more node
    // fetch (whose slab tests fail beyond the hit) for a subtree entered
    // beyond the current hit costs less than a second stack word per
    // entry (H100, veach-bidir: closest-hit stage 1.48 s -> 0.80 s at
    // 256 spp).
    if (w.sp == 0)
        return false;
    w.node = cv_bvh_pop(w);
    return true;
}

// Visits node w.node of a query whose hits count below tfar: the leaf
// triangles its slab tests let in (n0 slots from lw, then n1 from rw) and
// the next node. False when the query has no node left to visit.
bool cv_bvh_step(inout CvBvhWalk w, float tfar, out int lw, out int rw, out int n0, out int n1)
{
    w.steps--;
#ifdef CV_BVH_COUNT_STEPS
    cv_bvh_steps++;
#endif
    CvBvhNode nd = cv_bvh_nodes[w.node];
    lw = floatBitsToInt(nd.lmin.w);
    rw = floatBitsToInt(nd.rmin.w);
    int lc = floatBitsToInt(nd.lmax.w), rc = floatBitsToInt(nd.rmax.w);
    float tl, tr;
    float tlo = w.tmin - w.pad, thi = tfar + w.pad;
    bool hl = cv_bvh_slab(w.inv, w.olo, w.ohi, nd.lmin.xyz, nd.lmax.xyz, tlo, thi, tl);
    bool hr = cv_bvh_slab(w.inv, w.olo, w.ohi, nd.rmin.xyz, nd.rmax.xyz, tlo, thi, tr);
    cv_bvh_leaf_runs(hl, hr, lw, lc, rw, rc, n0, n1);
    hl = hl && lc == 0 && cv_bvh_inner_ok(lw);
    hr = hr && rc == 0 && cv_bvh_inner_ok(rw);
    return cv_bvh_next(w, hl, hr, lw, rw, tl, tr);
}

// Walks a closest-hit query to its end: the hit is w.hit, its prim
// 0xffffffff on a miss. Each turn of the loop either tests one triangle of
// the last node's leaf children or visits a node, so lanes of a warp that
// are testing leaves and lanes that are descending share the turn, rather
// than the descending lanes waiting on the longest leaf run of the warp
// (Aila & Laine 2009's if-if form). H100, medians of two interleaved rounds
// against testing a node's leaf run whole: bounce rays of a full wave on
// the 4 M-triangle scene 1.015 -> 1.058 G rays/s; veach-bidir 1024 spp
// 3392 -> 3245 ms; but cornell-box, whose few large leaves pay the extra
// loop turns, 1837 -> 1904 ms (bench/results/2026-11-24_NVIDIA-H100_if-if).
// Hits below the current one still count, so visiting the next node before
// the triangles are done changes no result.
void cv_bvh_closest_run(inout CvBvhWalk w)
{
    int k = 0, n0 = 0, n1 = 0, lw = 0, rw = 0;
    bool more = true;
    for (;;) {
        if (k < n0 + n1) {
            uint prim;
            float t, b1, b2;
            if (cv_bvh_leaf_tri(w.r, k < n0 ? lw + k : rw + (k - n0), prim, t, b1, b2) &&
                t > w.tmin &&
                (t < w.hit.t || (t == w.hit.t && prim < w.hit.prim && w.hit.prim != 0xffffffffu)))
                w.hit = CvHit(t, prim, b1, b2);
            k++;
            continue;
        }
        if (!more || w.steps <= 0)
            return;
        more = cv_bvh_step(w, w.hit.t, lw, rw, n0, n1);
        k = 0;
    }
}

// The any-hit form, with the same loop: w.hit.prim ends 0 when an occluder
// was found, 0xffffffff when none. In this form the any-hit stage alone ran
// 3 % slower on the 4 M scene (0.677 -> 0.658 G rays/s), cornell-box 1 %
// (1881 -> 1904 ms), but veach-bidir 4 % faster as a whole than with the
// old loop here (3340 -> 3214 ms).
// Nearer child first here too: visiting the child with the larger box first
// (likelier to hold an occluder) was slower on an H100 (veach-bidir, 256
// spp: shadow stage 918 -> 977 ms).
void cv_bvh_any_run(inout CvBvhWalk w)
{
    int k = 0, n0 = 0, n1 = 0, lw = 0, rw = 0;
    bool more = true;
    for (;;) {
        if (k < n0 + n1) {
            CvBvhTri tri = cv_bvh_tris[k < n0 ? lw + k : rw + (k - n0)];
            if (cv_ray_tri_any(w.r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, w.tmin, w.tmax)) {
                w.hit.prim = 0u;
                return;
            }
            k++;
            continue;
        }
        if (!more || w.steps <= 0)
            return;
        more = cv_bvh_step(w, w.tmax, lw, rw, n0, n1);
        k = 0;
    }
}

bool cv_trace_closest(vec3 o, vec3 d, float tmin, float tmax, out CvHit hit)
{
    CvBvhWalk w;
    cv_bvh_begin(o, d, tmin, tmax, w);
    cv_bvh_closest_run(w);
    hit = w.hit;
    return hit.prim != 0xffffffffu;
}

bool cv_trace_any(vec3 o, vec3 d, float tmin, float tmax)
{
    CvBvhWalk w;
    cv_bvh_begin(o, d, tmin, tmax, w);
    cv_bvh_any_run(w);
    return w.hit.prim != 0xffffffffu;
}

#endif
