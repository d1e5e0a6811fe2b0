// glsl/bvh/split.glsl: what split_priority.comp and split_emit.comp share
// for triangle splitting (src/bvh/split.h): the scene box's Morton grid and
// its most important plane across a box. The grid is the spatial median
// hierarchy that the LBVH's Morton codes follow, here refined to 2^20 cells
// per axis: a plane at a coarse level separates large subtrees, so a box
// crossing it costs every ray that visits them.
#ifndef CV_BVH_SPLIT_GLSL
#define CV_BVH_SPLIT_GLSL

#define CV_SPLIT_GRID_BITS 20
// The most extra references one triangle gets.
#define CV_SPLIT_MAX_EXTRA 255
// Morton bit of the finest grid plane of axis 0 is 2, of the coarsest 59.
#define CV_SPLIT_TOP_BIT (3 * CV_SPLIT_GRID_BITS - 1)

vec3 cv_split_tri_lo(vec3 a, vec3 b, vec3 c) { return min(a, min(b, c)); }
vec3 cv_split_tri_hi(vec3 a, vec3 b, vec3 c) { return max(a, max(b, c)); }

float cv_split_half_area(vec3 lo, vec3 hi)
{
    vec3 e = max(hi - lo, vec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// The grid plane strictly inside [lo, hi] whose bit in the interleaved
// Morton code (x above y above z at each level) is highest: for each axis
// the highest bit where the cells of lo and hi differ; the plane lies where
// that bit turns to 1. Returns that bit (the plane's importance) and sets
// axis and pos, or returns -1 when no grid plane lies strictly inside.
int cv_split_plane(vec3 lo, vec3 hi, vec3 s_lo, vec3 s_ext, out int axis, out float pos)
{
    const float cells = float(1u << CV_SPLIT_GRID_BITS);
    int best = -1;
    axis = 0;
    pos = 0.0;
    for (int a = 0; a < 3; a++) {
        if (!(s_ext[a] > 0.0))
            continue;
        float scale = cells / s_ext[a];
        uint qlo = uint(clamp((lo[a] - s_lo[a]) * scale, 0.0, cells - 1.0));
        uint qhi = uint(clamp((hi[a] - s_lo[a]) * scale, 0.0, cells - 1.0));
        if (qlo == qhi)
            continue;
        int level = findMSB(qlo ^ qhi);
        int bit = 3 * level + 2 - a;
        float p = s_lo[a] + float((qhi >> level) << level) * (s_ext[a] / cells);
        // Rounding may put the plane on or outside the box: not a split.
        if (bit > best && p > lo[a] && p < hi[a]) {
            best = bit;
            axis = a;
            pos = p;
        }
    }
    return best;
}

#endif
