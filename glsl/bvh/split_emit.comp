#version 450
// glsl/bvh/split_emit.comp: the references' boxes, one invocation per
// reference. A triangle with s extra references (the prefix sum of
// split_count.comp's shares gives where they go) has k = s + 1 of them and
// is cut s times: a piece holding k > 1 references is split by the most
// important grid plane crossing its box (split.glsl; the middle of its
// longest side when none does), and the two halves take shares of k by
// their longest sides, the left half references 0..kl-1 of the piece, the
// right half the rest. Reference j of a triangle follows its own path down
// these cuts from the whole triangle to its piece, so a triangle's cuts
// run in parallel, depth deep, instead of one after the other in one
// invocation: a few triangles with hundreds of extra references each (the
// killeroo scene's floor and walls) sit in the first workgroups, and one
// invocation doing all their cuts in turn held the whole pass
// (bench/RESULTS.md, "BVH build: wall time").
// Invocations of one triangle compute the same cuts from the same inputs
// with the same code, so they agree on every piece.
//
// A half's box is the box of the whole triangle's part on that side of the
// plane (its vertices there and its edges' crossings of the plane), rounded
// outward, clipped to the piece's box: the piece's part of the triangle is
// inside both, so the boxes always cover the triangle, and they never leave
// its box. Only the crossings are computed, from the original vertices,
// so errors do not build up from cut to cut; they stay within a few units
// in the last place of the coordinates' magnitude, and the rounding allows
// 2^-18 of it. A half that comes out empty holds none of the triangle; the
// other half then replaces the piece and the cut is tried again (at most
// RETRIES times on a path; after that, or when a box is too thin to cut,
// a piece's references share its box: duplicates, harmless).
//
// References 0..n-1 are the triangles' first pieces (reference 0 of each,
// in triangle order, so with no share this is the plain triangle box), the
// extra ones follow from n + offset. Writes each reference's box (min, max)
// and triangle.
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 64) in;
#include "../lib/index.glsl"
#include "split.glsl"

#include "mesh_buffers.glsl"
layout(std430, binding = CV_BIND_SPLIT_BOUNDS) readonly buffer Bounds { vec4 bounds[]; };
// Exclusive prefix sum of the fixed-point shares, n + 1 elements
// (split_count.comp says how to read it).
layout(std430, binding = CV_BIND_SPLIT_COUNTS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = CV_BIND_SPLIT_REF_TRIS) writeonly buffer RefTris { uint ref_tris[]; };
layout(std430, binding = CV_BIND_SPLIT_REF_BOXES) writeonly buffer RefBoxes { vec4 ref_boxes[]; };

uniform uint u_n;       // triangles
uniform uint u_n_refs;  // references
uniform uint u_shift;

#define RETRIES 16

vec3 g_v[3];
vec3 g_eps;

// The boxes of the triangle's parts on either side of plane x[axis] = pos,
// rounded outward and clipped to [lo, hi]; an empty part gives min > max.
void cut(int axis, float pos, vec3 lo, vec3 hi, out vec3 llo, out vec3 lhi, out vec3 rlo,
         out vec3 rhi)
{
    llo = vec3(3.0e38);
    rlo = llo;
    lhi = vec3(-3.0e38);
    rhi = lhi;
    for (int e = 0; e < 3; e++) {
        vec3 p = g_v[e], q = g_v[e == 2 ? 0 : e + 1];
        if (p[axis] <= pos) {
            llo = min(llo, p);
            lhi = max(lhi, p);
        }
        if (p[axis] >= pos) {
            rlo = min(rlo, p);
            rhi = max(rhi, p);
        }
        if ((p[axis] < pos && q[axis] > pos) || (p[axis] > pos && q[axis] < pos)) {
            vec3 x = p + (q - p) * ((pos - p[axis]) / (q[axis] - p[axis]));
            x[axis] = pos;
            llo = min(llo, x - g_eps);
            lhi = max(lhi, x + g_eps);
            rlo = min(rlo, x - g_eps);
            rhi = max(rhi, x + g_eps);
        }
    }
    llo = max(llo, lo);
    lhi = min(lhi, hi);
    rlo = max(rlo, lo);
    rhi = min(rhi, hi);
    lhi[axis] = min(lhi[axis], pos);
    rlo[axis] = max(rlo[axis], pos);
}

float longest(vec3 lo, vec3 hi)
{
    vec3 e = hi - lo;
    return max(e.x, max(e.y, e.z));
}

// The triangle whose extra references hold extra reference e: the first t
// with e < F[t + 1] (F: the offsets, shifted).
uint owner(uint e)
{
    uint lo = 0u, hi = u_n - 1u;
    while (lo < hi) {
        uint mid = (lo + hi) >> 1;
        if (e < (offsets[mid + 1u] >> u_shift))
            hi = mid;
        else
            lo = mid + 1u;
    }
    return lo;
}

void main()
{
    uint r = cv_global_index();
    if (r >= u_n_refs)
        return;
    uint t = r < u_n ? r : owner(r - u_n);
    uint first = offsets[t] >> u_shift;
    uint k = 1u + (offsets[t + 1u] >> u_shift) - first;
    uint j = r < u_n ? 0u : r - u_n - first + 1u;
    uvec4 idx = cv_triangles[t].idx;
    g_v[0] = cv_vertices[idx.x].pos_u.xyz;
    g_v[1] = cv_vertices[idx.y].pos_u.xyz;
    g_v[2] = cv_vertices[idx.z].pos_u.xyz;
    vec3 lo = cv_split_tri_lo(g_v[0], g_v[1], g_v[2]), hi = cv_split_tri_hi(g_v[0], g_v[1], g_v[2]);
    g_eps = max(abs(lo), abs(hi)) * (1.0 / 262144.0);
    vec3 s_lo = bounds[0].xyz, s_ext = bounds[1].xyz - s_lo;

    int retries = 0;
    while (k > 1u && retries < RETRIES) {
        int axis;
        float pos;
        if (cv_split_plane(lo, hi, s_lo, s_ext, axis, pos) < 0) {
            vec3 e = hi - lo;
            axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
            pos = 0.5 * (lo[axis] + hi[axis]);
            if (!(pos > lo[axis] && pos < hi[axis]))
                break;
        }
        vec3 llo, lhi, rlo, rhi;
        cut(axis, pos, lo, hi, llo, lhi, rlo, rhi);
        bool l_empty = any(greaterThan(llo, lhi)), r_empty = any(greaterThan(rlo, rhi));
        if (l_empty || r_empty) {
            retries++;
            if (l_empty && r_empty)
                break;
            lo = l_empty ? rlo : llo;
            hi = l_empty ? rhi : lhi;
            continue;
        }
        float el = longest(llo, lhi), er = longest(rlo, rhi);
        uint kl = uint(clamp(floor(float(k) * el / max(el + er, 1.0e-30)), 1.0, float(k - 1u)));
        bool left = j < kl;
        lo = left ? llo : rlo;
        hi = left ? lhi : rhi;
        k = left ? kl : k - kl;
        j = left ? j : j - kl;
    }
    ref_tris[r] = t;
    ref_boxes[2u * r] = vec4(lo, 0.0);
    ref_boxes[2u * r + 1u] = vec4(hi, 0.0);
}
