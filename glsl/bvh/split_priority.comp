#version 450
// glsl/bvh/split_priority.comp: each triangle's splitting priority
// (Karras & Aila 2013, section 5):
//   p = (2^i * (A_box - A_ideal))^(1/3)
// with i the Morton bit of the most important grid plane crossing the
// triangle's box (split.glsl), A_box the box's surface area and A_ideal the
// limit of its pieces' total area as the triangle is split ever finer: the
// sum of the triangle's projected areas on the three axis planes. The
// difference is what splitting can win; the plane level weighs it by how
// much of the tree the box spreads over; the cube root spreads the budget
// over more triangles than a straight share would. Areas are in units of
// the scene box's (only ratios of priorities matter) and 2^i is taken
// relative to the coarsest level, to keep it all in float range.
//
// One change from the paper: what splitting can win is taken as
// A_box - 3 A_ideal, not A_box - A_ideal, so that only triangles whose box
// is more than 3 times their ideal area get any. Half of a rectangle lying
// in an axis plane (walls, floors, every box-shaped mesh) wastes exactly its
// own area, and the paper's measure spent the budget on those: veach-bidir's
// 10 wall and floor triangles took 41 references each, which then spread
// over the whole tree (SAH 16.3 -> 24.6 and shadow rays visiting 50 % more
// nodes, by CPU traversal of the GPU-built tree). A ray that enters such a
// flat box crosses the triangle's plane there, so it tests at most one
// needless triangle, the quad's other half; split, it walks a path of more
// nodes instead. Long thin triangles, the cones of lamp shades, waste many
// times their area and keep nearly all their priority. Of the thresholds
// tried (flat boxes left out, 2, 3 and 3.5 A_ideal), 3 rendered veach-bidir
// fastest (bench/RESULTS.md, "Figures behind the code").
// Writes p (float bits) to prio[i] and each workgroup's sum to sums[].
#include "shared/scene.h"
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"
#include "split.glsl"

#include "mesh_buffers.glsl"
layout(std430, binding = CV_BIND_SPLIT_BOUNDS) readonly buffer Bounds { vec4 bounds[]; };
layout(std430, binding = CV_BIND_SPLIT_COUNTS) writeonly buffer Prio { float prio[]; };
layout(std430, binding = CV_BIND_SPLIT_SUMS) writeonly buffer Sums { float sums[]; };

uniform uint u_n;

shared float s_sum[256];

void main()
{
    uint i = cv_global_index();
    float p = 0.0;
    if (i < u_n) {
        uvec4 t = cv_triangles[i].idx;
        vec3 a = cv_vertices[t.x].pos_u.xyz, b = cv_vertices[t.y].pos_u.xyz, c = cv_vertices[t.z].pos_u.xyz;
        vec3 lo = cv_split_tri_lo(a, b, c), hi = cv_split_tri_hi(a, b, c);
        vec3 s_lo = bounds[0].xyz, s_ext = bounds[1].xyz - s_lo;
        int axis;
        float pos;
        int bit = cv_split_plane(lo, hi, s_lo, s_ext, axis, pos);
        vec3 n = cross(b - a, c - a);
        float ideal = 0.5 * (abs(n.x) + abs(n.y) + abs(n.z));
        float waste = cv_split_half_area(lo, hi) - 3.0 * ideal;
        float scene = max(cv_split_half_area(s_lo, s_lo + s_ext), 1.0e-30);
        if (bit >= 0 && waste > 0.0)
            p = exp2((float(bit - CV_SPLIT_TOP_BIT) + log2(waste / scene)) * (1.0 / 3.0));
        prio[i] = p;
    }
    uint l = gl_LocalInvocationID.x;
    s_sum[l] = p;
    barrier();
    for (uint s = 128; s > 0; s >>= 1) {
        if (l < s)
            s_sum[l] += s_sum[l + s];
        barrier();
    }
    if (l == 0)
        sums[i / 256u] = s_sum[0];
}
