#version 450
// glsl/bvh/treelet.comp: one round of treelet restructuring (Karras & Aila
// 2013). Invocations climb from the leaves like refit.comp; the second
// arrival at an inner node whose subtree holds at least u_gamma primitives
// grows a treelet of up to TREELET_SIZE leaves below it (always opening the
// leaf of largest area), finds the SAH-optimal binary tree over those leaves
// by dynamic programming over all subsets, and rewires the treelet's inner
// nodes when that is cheaper. Smaller nodes only have their cost refreshed.
// One invocation handles one treelet; the DP tables live in its registers /
// local memory (3 * 2^TREELET_SIZE words).
#include "shared/bvh.h"
#include "shared/bindings.h"

#ifndef TREELET_SIZE
#define TREELET_SIZE 7
#endif
#define N_SUBSETS (1 << TREELET_SIZE)

layout(local_size_x = 64) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0 + 1) coherent buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) coherent buffer Counters { uint counters[]; };

uniform uint u_n;
uniform uint u_gamma;

#include "sah.glsl"

void restructure(int root)
{
    // The subtree below was refreshed this round; compare against that.
    cv_bvh_update_node(root);
    int n_inner = int(u_n) - 1;
    int leaves[TREELET_SIZE];
    int inner[TREELET_SIZE - 1];
    int nl = 2, ni = 1;
    inner[0] = root;
    leaves[0] = nodes[root].link.x;
    leaves[1] = nodes[root].link.y;
    while (nl < TREELET_SIZE) {
        int best = -1;
        float best_area = -1.0;
        for (int k = 0; k < nl; k++) {
            int c = leaves[k];
            if (c < n_inner) {
                float a = cv_half_area(nodes[c].bmin.xyz, nodes[c].bmax.xyz);
                if (a > best_area) {
                    best_area = a;
                    best = k;
                }
            }
        }
        if (best < 0)
            break;
        int c = leaves[best];
        inner[ni++] = c;
        leaves[best] = nodes[c].link.x;
        leaves[nl++] = nodes[c].link.y;
    }

    vec3 llo[TREELET_SIZE], lhi[TREELET_SIZE];
    float lcost[TREELET_SIZE];
    int lcount[TREELET_SIZE];
    for (int k = 0; k < nl; k++) {
        vec4 a = nodes[leaves[k]].bmin;
        llo[k] = a.xyz;
        lcost[k] = a.w;
        lhi[k] = nodes[leaves[k]].bmax.xyz;
        lcount[k] = nodes[leaves[k]].link.w & CV_BVH_COUNT_MASK;
    }
    float copt[N_SUBSETS];
    uint popt[N_SUBSETS];
    uint full = (1u << nl) - 1u;
    for (uint s = 1u; s <= full; s++) {
        if (bitCount(s) == 1) {
            copt[s] = lcost[findLSB(s)];
            continue;
        }
        vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
        int count = 0;
        for (int k = 0; k < nl; k++) {
            if ((s & (1u << k)) != 0u) {
                lo = min(lo, llo[k]);
                hi = max(hi, lhi[k]);
                count += lcount[k];
            }
        }
        float area = cv_half_area(lo, hi);
        uint delta = (s - 1u) & s;
        uint p = (~delta + 1u) & s;
        float best = 3.0e38;
        uint bp = p;
        do {
            float c = copt[p] + copt[s ^ p];
            if (c < best) {
                best = c;
                bp = p;
            }
            p = (p - delta) & s;
        } while (p != 0u);
        float split = float(CV_BVH_COST_INNER) * area + best;
        float leaf = float(CV_BVH_COST_TRI) * area * float(count);
#ifdef CV_BVH_NO_COLLAPSE
        bool collapse = false;
#else
        bool collapse = count <= CV_BVH_MAX_LEAF && leaf <= split && (s != full || root != 0);
#endif
        copt[s] = collapse ? leaf : split;
        popt[s] = bp;
    }
    // Keep the treelet unless the optimum is strictly cheaper.
    if (!(copt[full] < nodes[root].bmin.w * 0.99999))
        return;
    uint stack_s[TREELET_SIZE];
    int stack_node[TREELET_SIZE];
    int order[TREELET_SIZE - 1];
    int sp = 0, used = 1;
    order[0] = root;
    stack_s[sp] = full;
    stack_node[sp++] = root;
    while (sp > 0) {
        sp--;
        uint s = stack_s[sp];
        int node = stack_node[sp];
        uint part[2] = uint[2](popt[s], s ^ popt[s]);
        int child[2];
        for (int k = 0; k < 2; k++) {
            if (bitCount(part[k]) == 1) {
                child[k] = leaves[findLSB(part[k])];
            } else {
                child[k] = inner[used];
                order[used++] = child[k];
                stack_s[sp] = part[k];
                stack_node[sp++] = child[k];
            }
            nodes[child[k]].link.z = node;
        }
        nodes[node].link.xy = ivec2(child[0], child[1]);
    }
    for (int k = used - 1; k >= 0; k--)
        cv_bvh_update_node(order[k]);
}

void main()
{
    uint i = cv_global_index();
    if (i >= u_n)
        return;
    int p = nodes[int(u_n) - 1 + int(i)].link.z;
    while (p >= 0) {
        if (atomicAdd(counters[p], 1u) == 0u)
            return;
        memoryBarrierBuffer();
        int count = (nodes[nodes[p].link.x].link.w & CV_BVH_COUNT_MASK) +
                    (nodes[nodes[p].link.y].link.w & CV_BVH_COUNT_MASK);
        if (uint(count) >= u_gamma)
            restructure(p);
        else
            cv_bvh_update_node(p);
        memoryBarrierBuffer();
        p = nodes[p].link.z;
    }
}
