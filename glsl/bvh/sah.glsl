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

// Inner node p from its children's bmin (box low, cost), bmax.xyz and
// link.w (count, flags): writes its bounds, count and cost, returns its
// bmin and sets hi and w to its bmax.xyz and link.w.
vec4 cv_bvh_combine(int p, vec4 lmin, vec3 lmax, int lw, vec4 rmin, vec3 rmax, int rw,
                    out vec3 hi, out int w)
{
    int count = (lw & CV_BVH_COUNT_MASK) + (rw & CV_BVH_COUNT_MASK);
    vec3 lo = min(lmin.xyz, rmin.xyz);
    hi = max(lmax, rmax);
    float area = cv_half_area(lo, hi);
    float split = float(CV_BVH_COST_INNER) * area + lmin.w + rmin.w;
    float leaf = float(CV_BVH_COST_TRI) * area * float(count);
#ifdef CV_BVH_NO_COLLAPSE
    bool collapse = false;
#else
    bool collapse = count <= CV_BVH_MAX_LEAF && leaf <= split && p != 0;
#endif
    vec4 bmin = vec4(lo, collapse ? leaf : split);
    w = count | (collapse ? CV_BVH_COLLAPSE : 0);
    nodes[p].bmin = bmin;
    nodes[p].bmax = vec4(hi, 0.0);
    nodes[p].link.w = w;
    return bmin;
}

// Recomputes bounds, count and cost of inner node p from its children.
void cv_bvh_update_node(int p)
{
    ivec4 link = nodes[p].link;
    vec3 hi;
    int w;
    cv_bvh_combine(p, nodes[link.x].bmin, nodes[link.x].bmax.xyz, nodes[link.x].link.w,
                   nodes[link.y].bmin, nodes[link.y].bmax.xyz, nodes[link.y].link.w, hi, w);
}

#endif
