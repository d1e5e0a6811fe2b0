#version 450
// glsl/bvh/split_count.comp: each triangle's share of the split budget,
// x = B * p / P extra references for priority p of total P (at most
// CV_SPLIT_MAX_EXTRA), in fixed point with u_shift fraction bits, in place
// over the priorities. Element u_n (one past the last triangle) is set to 0.
// The host's exclusive prefix sum F of these then says everything: triangle
// t's extra references start at F[t] >> u_shift and number
// (F[t + 1] >> u_shift) - (F[t] >> u_shift), which is floor(x) or
// ceil(x), and they total F[n] >> u_shift <= B. Plain floor(x) per
// triangle would waste the budget wherever shares are spread thin (60
// cones of equal slivers at 0.3 per triangle: no split at all). The shares
// are scaled down by 1e-4 so that float rounding in P and in each quotient
// cannot take the total past B; the host picks u_shift so that B << u_shift
// fits in 31 bits.
#include "shared/bindings.h"

layout(local_size_x = 256) in;
#include "../lib/index.glsl"
#include "split.glsl"

layout(std430, binding = CV_BIND_SPLIT_COUNTS) buffer Counts { uint counts[]; };
layout(std430, binding = CV_BIND_SPLIT_SUMS) readonly buffer Sums { float sums[]; };

uniform uint u_n;
uniform float u_budget;   // B: the most extra references, over all triangles
uniform uint u_shift;

void main()
{
    uint i = cv_global_index();
    if (i > u_n)
        return;
    uint f = 0u;
    float total = sums[0];
    if (i < u_n && total > 0.0) {
        float x = u_budget * 0.9999 * (uintBitsToFloat(counts[i]) / total);
        f = uint(floor(min(x, float(CV_SPLIT_MAX_EXTRA)) * float(1u << u_shift)));
    }
    counts[i] = f;
}
