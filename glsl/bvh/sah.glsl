// glsl/bvh/sah.glsl: SAH cost bookkeeping shared by refit and treelet
// restructuring. Costs are not normalised by the root's area; a node's cost
// is the cheaper of splitting it and collapsing its subtree into one leaf
// (only when that leaf would be small enough). Needs a `nodes` buffer.
#ifndef CV_BVH_SAH_GLSL
#define CV_BVH_SAH_GLSL

float cv_half_area(vec3 lo, vec3 hi)
{
    vec3 e = max(hi - lo, vec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// Recomputes bounds, count and cost of inner node p from its children.
void cv_bvh_update_node(int p)
{
    ivec4 link = nodes[p].link;
    vec4 lmin = nodes[link.x].bmin, lmax = nodes[link.x].bmax;
    vec4 rmin = nodes[link.y].bmin, rmax = nodes[link.y].bmax;
    int count = (nodes[link.x].link.w & CV_BVH_COUNT_MASK) + (nodes[link.y].link.w & CV_BVH_COUNT_MASK);
    vec3 lo = min(lmin.xyz, rmin.xyz), hi = max(lmax.xyz, rmax.xyz);
    float area = cv_half_area(lo, hi);
    float split = float(CV_BVH_COST_INNER) * area + lmin.w + rmin.w;
    float leaf = float(CV_BVH_COST_TRI) * area * float(count);
#ifdef CV_BVH_NO_COLLAPSE
    bool collapse = false;
#else
    bool collapse = count <= CV_BVH_MAX_LEAF && leaf <= split && p != 0;
#endif
    nodes[p].bmin = vec4(lo, collapse ? leaf : split);
    nodes[p].bmax = vec4(hi, 0.0);
    nodes[p].link.w = count | (collapse ? CV_BVH_COLLAPSE : 0);
}

#endif
