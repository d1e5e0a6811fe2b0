// glsl/bvh/traverse.glsl: closest-hit and any-hit ray queries against the
// 4-wide BVH of glsl/shared/bvh.h. Include glsl/bvh/scene_buffers.glsl
// first. Stack-based, nearest child first, children entered beyond the
// current hit skipped (after Aila & Laine 2009's binary traversal);
// watertight triangles (triangle.glsl).
// A hit counts when tmin < t < tmax; among hits at the same t the lowest
// triangle index wins, so the result does not depend on the tree.
// The stack holds CV_BVH_STACK_SIZE entries (glsl/shared/bvh.h); a node
// pushes up to three. The build sizes it for the tree (the programs that
// trace a tree needing more than the default are compiled with more,
// cv_bvh_stack_define), so a valid tree never fills it; only a corrupt one
// can, and then what does not fit is dropped rather than written past the
// end.
// A corrupt or uninitialised tree must never hang the GPU (a reset kills
// every job on the device), so nothing here trusts the node words: inner
// children must lie in 1..length-1 (the root is nobody's child, which also
// rejects unused slots), leaf ranges are clipped to the leaf-ordered
// triangle buffer (whose records are valid by construction, leaf_tris.comp),
// and the loop stops after as many steps as there are nodes, which a valid
// tree never needs.
#ifndef CV_BVH_TRAVERSE_GLSL
#define CV_BVH_TRAVERSE_GLSL

#include "triangle.glsl"

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

#ifdef CV_HAS_CURVES
// Curves (prim CV_PRIM_CURVE | index, b1 = u, b2 = v) in their own tree,
// walked after the triangles' by the two queries below.
#include "curves.glsl"
#endif
// (Included files expand once, where first named, whatever #ifdef is
// around them: motion.glsl's own includes come first, outside it.)
#include "../lib/quaternion.glsl"
#ifdef CV_HAS_MOTION
// Moving shapes (prim: the triangle's index, as static ones) in trees of
// their own, walked after the static triangles' at the ray's time
// cv_trace_time.
#include "motion.glsl"
#endif

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
// ends are widened by `pad` (cv_bvh_pad): a few float epsilons / |d| times
// the L1 distance from the origin to the far corner of the root's box,
// which bounds that of every box below it. Without that, a box could be
// culled although a triangle in it reports a t at or below the hit. Once
// per ray rather than per box, which saves each box test its own sum of
// distances; the larger pad lets through only boxes within ~1e-6 of the
// scene's size of the ray.
float cv_bvh_pad(vec3 o, vec3 d)
{
    CvBvhNode4 root = cv_bvh_nodes[0];
    // The used slots' boxes only. Unused slots' (lo +CV_BVH_EMPTY, hi
    // -CV_BVH_EMPTY) would drop out of a plain min/max with the same
    // result, but this form traces faster (bench/RESULTS.md, "The 4-wide
    // tree, built on the GPU"): how the compiler allocates this function's
    // registers matters to the whole loop (see CV_BVH_STACK_SIZE).
    bvec4 ok = lessThanEqual(root.lox, root.hix);
    vec4 big = vec4(3.0e38);
    vec3 lo = vec3(min(min(mix(big.x, root.lox.x, ok.x), mix(big.x, root.lox.y, ok.y)),
                       min(mix(big.x, root.lox.z, ok.z), mix(big.x, root.lox.w, ok.w))),
                   min(min(mix(big.x, root.loy.x, ok.x), mix(big.x, root.loy.y, ok.y)),
                       min(mix(big.x, root.loy.z, ok.z), mix(big.x, root.loy.w, ok.w))),
                   min(min(mix(big.x, root.loz.x, ok.x), mix(big.x, root.loz.y, ok.y)),
                       min(mix(big.x, root.loz.z, ok.z), mix(big.x, root.loz.w, ok.w))));
    vec3 hi = vec3(max(max(mix(-big.x, root.hix.x, ok.x), mix(-big.x, root.hix.y, ok.y)),
                       max(mix(-big.x, root.hix.z, ok.z), mix(-big.x, root.hix.w, ok.w))),
                   max(max(mix(-big.x, root.hiy.x, ok.x), mix(-big.x, root.hiy.y, ok.y)),
                       max(mix(-big.x, root.hiy.z, ok.z), mix(-big.x, root.hiy.w, ok.w))),
                   max(max(mix(-big.x, root.hiz.x, ok.x), mix(-big.x, root.hiz.y, ok.y)),
                       max(mix(-big.x, root.hiz.z, ok.z), mix(-big.x, root.hiz.w, ok.w))));
    if (!any(ok)) {
        lo = vec3(0.0);
        hi = vec3(0.0);
    }
    vec3 m = max(abs(lo - o), abs(hi - o));
    return (m.x + m.y + m.z) * (1.0e-6 / max(length(d), 1.0e-30));
}

// The four child slabs of node nd at once, one child per vector component:
// which children the ray enters within [tmin, tmax] and their entry
// distances (tnear).
bvec4 cv_bvh_slab4(vec3 o, vec3 inv, float pad, CvBvhNode4 nd, float tmin, float tmax,
                   out vec4 tnear)
{
    vec4 tx0 = (nd.lox - o.x) * inv.x, tx1 = (nd.hix - o.x) * inv.x;
    vec4 ty0 = (nd.loy - o.y) * inv.y, ty1 = (nd.hiy - o.y) * inv.y;
    vec4 tz0 = (nd.loz - o.z) * inv.z, tz1 = (nd.hiz - o.z) * inv.z;
    vec4 a = max(max(min(tx0, tx1), min(ty0, ty1)), max(min(tz0, tz1), vec4(tmin)));
    vec4 b = min(min(max(tx0, tx1), max(ty0, ty1)), min(max(tz0, tz1), vec4(tmax)));
    a -= abs(a) * 2.0e-6 + pad;
    b += abs(b) * 2.0e-6 + pad;
    tnear = a;
    // min/max above would turn an inverted (unused) box inside out. The
    // vector ands are spelt as uint ands here and in cv_bvh_step: through
    // a bvec4 helper function they compile to slower code (bench/RESULTS.md,
    // "The 4-wide tree, built on the GPU").
    return bvec4(uvec4(lessThanEqual(a, b)) & uvec4(lessThanEqual(nd.lox, nd.hix)));
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

// A query's state: the ray's set-up, the node to visit next, the stack
// depth and the best hit so far (the stack entries are the invocation's,
// below). The same loops as one function each with local variables were
// a little slower (bench/RESULTS.md, "Figures behind the code"); the
// arithmetic and the order of visits are the same.
struct CvBvhWalk {
    CvRayTri r;  // r.o: the origin
    vec3 inv;
    float pad;
    float tmin;
    float tmax;  // any-hit only; closest-hit queries shrink hit.t instead
    CvHit hit;
    int node;
    int sp;
    int steps;   // nodes left before the query gives up (see the top)
};

int cv_bvh_stack[CV_BVH_STACK_SIZE];

// A full stack drops the entry (that subtree is skipped): only a corrupt
// tree gets here, the stack being sized for the tree (see the top).
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
    w.inv = cv_bvh_safe_inv(d);
    w.pad = cv_bvh_pad(o, d);
    w.tmin = tmin;
    w.tmax = tmax;
    w.hit = CvHit(tmax, 0xffffffffu, 0.0, 0.0);
    w.node = 0;
    w.sp = 0;
    w.steps = cv_bvh_nodes.length();
}

// Sorts two (entry distance, node) pairs, nearer first.
void cv_bvh_order(inout float da, inout int na, inout float db, inout int nb)
{
    bool swap = db < da;
    float t = da;
    int n = na;
    da = swap ? db : da;
    na = swap ? nb : na;
    db = swap ? t : db;
    nb = swap ? n : nb;
}

// Visits node w.node of a query whose hits count below tfar: the leaf
// children its slab tests let in, as one run of triangles (first slots f,
// counts c, in slot order: cv_bvh_run_slot), and the next node. False when
// the query has no node left to visit.
// One run for all four children rather than a loop per child: lanes with
// different numbers of leaf children run in step, and the triangle test is
// compiled once, which makes both stages faster. The order of the tests
// decides no result (ties go to the lower triangle index).
// The nearest entered inner child is visited next and the others pushed,
// farthest first, so the stack pops near subtrees before far ones. The
// sort (a 5-exchange network) runs only when two or more are entered,
// which beat sorting always and beat an unsorted push order by more
// (bench/RESULTS.md, "The 4-wide tree, measured first").
bool cv_bvh_step(inout CvBvhWalk w, float tfar, out ivec4 f, out ivec4 c)
{
    w.steps--;
#ifdef CV_BVH_COUNT_STEPS
    cv_bvh_steps++;
#endif
    CvBvhNode4 nd = cv_bvh_nodes[w.node];
    vec4 tn;
    bvec4 h = cv_bvh_slab4(w.r.o, w.inv, w.pad, nd, w.tmin, tfar, tn);
    int nt = cv_bvh_tris.length(), nn = cv_bvh_nodes.length();
    f = nd.word;
    // Leaf runs clipped to the leaf-ordered triangles, inner children
    // inside 1..nn-1 (see the top).
    ivec4 cnt = clamp(nd.count, ivec4(0), ivec4(nt) - max(f, ivec4(0)));
    bvec4 leaf = bvec4(uvec4(h) & uvec4(greaterThan(nd.count, ivec4(0))) &
                       uvec4(greaterThanEqual(f, ivec4(0))) & uvec4(lessThan(f, ivec4(nt))));
    c = mix(ivec4(0), cnt, leaf);
    bvec4 inner = bvec4(uvec4(h) & uvec4(equal(nd.count, ivec4(0))) &
                        uvec4(greaterThan(f, ivec4(0))) & uvec4(lessThan(f, ivec4(nn))));
    vec4 d = mix(vec4(3.0e38), tn, inner);
    float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
    int n0 = inner.x ? f.x : -1, n1 = inner.y ? f.y : -1, n2 = inner.z ? f.z : -1,
        n3 = inner.w ? f.w : -1;
    if (int(inner.x) + int(inner.y) + int(inner.z) + int(inner.w) > 1) {
        cv_bvh_order(d0, n0, d1, n1);
        cv_bvh_order(d2, n2, d3, n3);
        cv_bvh_order(d0, n0, d2, n2);
        cv_bvh_order(d1, n1, d3, n3);
        cv_bvh_order(d1, n1, d2, n2);
        if (n3 >= 0)
            cv_bvh_push(w, n3);
        if (n2 >= 0)
            cv_bvh_push(w, n2);
        cv_bvh_push(w, n1);
        w.node = n0;
        return true;
    }
    int only = max(max(n0, n1), max(n2, n3));
    if (only >= 0) {
        w.node = only;
        return true;
    }
    // The next subtree. Its entry distance is not kept: one more node
    // fetch (whose slab tests fail beyond the hit) for a subtree entered
    // beyond the current hit costs less than a second stack word per
    // entry, which halves what each stack entry costs in local memory.
    if (w.sp == 0)
        return false;
    w.node = cv_bvh_pop(w);
    return true;
}

// The slot of triangle k of a node's leaf run (first slots f, counts c).
int cv_bvh_run_slot(int k, ivec4 f, ivec4 c)
{
    int p1 = c.x, p2 = p1 + c.y, p3 = p2 + c.z;
    return k < p1 ? f.x + k : k < p2 ? f.y + (k - p1) : k < p3 ? f.z + (k - p2) : f.w + (k - p3);
}

// Walks a closest-hit query to its end: the hit is w.hit, its prim
// 0xffffffff on a miss. Each turn of the loop either tests one triangle of
// the last node's leaf children or visits a node, so lanes of a warp that
// are testing leaves and lanes that are descending share the turn, rather
// than the descending lanes waiting on the longest leaf run of the warp
// (Aila & Laine 2009's if-if form). Faster than testing a node's leaf run
// whole on large scenes, slower on scenes of a few large leaves, which pay
// the extra loop turns (bench/RESULTS.md, "If-if traversal loop"). Hits
// below the current one still count, so visiting the next node before the
// triangles are done changes no result.
void cv_bvh_closest_run(inout CvBvhWalk w)
{
    int k = 0, n = 0;
    ivec4 f = ivec4(0), c = ivec4(0);
    bool more = true;
    for (;;) {
        if (k < n) {
            uint prim;
            float t, b1, b2;
            if (cv_bvh_leaf_tri(w.r, cv_bvh_run_slot(k, f, c), prim, t, b1, b2) &&
                t > w.tmin &&
                (t < w.hit.t || (t == w.hit.t && prim < w.hit.prim && w.hit.prim != 0xffffffffu)))
                w.hit = CvHit(t, prim, b1, b2);
            k++;
            continue;
        }
        if (!more || w.steps <= 0)
            return;
        more = cv_bvh_step(w, w.hit.t, f, c);
        n = c.x + c.y + c.z + c.w;
        k = 0;
    }
}

// The any-hit form, with the same loop: w.hit.prim ends 0 when an occluder
// was found, 0xffffffff when none. One loop form for both queries: the
// any-hit stage alone is a little slower in it than with a loop of its own,
// whole renders of small scenes faster (bench/RESULTS.md, "If-if traversal
// loop").
// Nearest child first here too: visiting the child with the larger box
// first (likelier to hold an occluder) was slower (bench/RESULTS.md,
// "Figures behind the code").
void cv_bvh_any_run(inout CvBvhWalk w)
{
    int k = 0, n = 0;
    ivec4 f = ivec4(0), c = ivec4(0);
    bool more = true;
    for (;;) {
        if (k < n) {
            CvBvhTri tri = cv_bvh_tris[cv_bvh_run_slot(k, f, c)];
            if (cv_ray_tri_any(w.r, tri.v0.xyz, tri.v1.xyz, tri.v2.xyz, w.tmin, w.tmax)) {
                w.hit.prim = 0u;
                return;
            }
            k++;
            continue;
        }
        if (!more || w.steps <= 0)
            return;
        more = cv_bvh_step(w, w.tmax, f, c);
        n = c.x + c.y + c.z + c.w;
        k = 0;
    }
}

bool cv_trace_closest(vec3 o, vec3 d, float tmin, float tmax, out CvHit hit)
{
    CvBvhWalk w;
#ifdef CV_NO_TRIANGLES
    // a scene of curves alone has no triangle tree bound
    w.hit = CvHit(tmax, 0xffffffffu, 0.0, 0.0);
#else
    cv_bvh_begin(o, d, tmin, tmax, w);
    cv_bvh_closest_run(w);
#endif
#ifdef CV_HAS_CURVES
    cv_curves_walk(o, d, tmin, false, w.hit.t, w.hit.prim, w.hit.b1, w.hit.b2);
#endif
#ifdef CV_HAS_MOTION
    cv_motion_walk(o, d, tmin, false, w.hit.t, w.hit.prim, w.hit.b1, w.hit.b2);
#endif
    hit = w.hit;
    return hit.prim != 0xffffffffu;
}

bool cv_trace_any(vec3 o, vec3 d, float tmin, float tmax)
{
    CvBvhWalk w;
#ifdef CV_NO_TRIANGLES
    w.hit = CvHit(tmax, 0xffffffffu, 0.0, 0.0);
#else
    cv_bvh_begin(o, d, tmin, tmax, w);
    cv_bvh_any_run(w);
#endif
#ifdef CV_HAS_CURVES
    if (w.hit.prim == 0xffffffffu)
        cv_curves_walk(o, d, tmin, true, w.hit.t, w.hit.prim, w.hit.b1, w.hit.b2);
#endif
#ifdef CV_HAS_MOTION
    if (w.hit.prim == 0xffffffffu)
        cv_motion_walk(o, d, tmin, true, w.hit.t, w.hit.prim, w.hit.b1, w.hit.b2);
#endif
    return w.hit.prim != 0xffffffffu;
}

#endif
