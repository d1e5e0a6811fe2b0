#version 450
// glsl/bvh/treelet.comp: one round of treelet restructuring (Karras & Aila
// 2013). Invocations climb from the leaves like refit.comp (the second
// arrival at an inner node carries on); nodes whose subtree holds fewer than
// u_gamma primitives only have their cost refreshed on the way. An
// invocation that reaches a larger node stops there, and its workgroup of
// GROUP invocations then restructures the pending roots of all its members
// together, one after another: invocation 0 grows a treelet of up to
// TREELET_SIZE leaves (always opening the leaf of largest area), the group
// finds the SAH-optimal binary tree over those leaves by dynamic programming
// over all subsets in parallel (all subsets of one size at once, the
// partitions of large subsets split over several invocations), and
// invocation 0 rewires the treelet when that is cheaper. The group then
// climbs on. Nothing waits on another workgroup: the counters only decide
// who carries on, as in refit.
#include "shared/bvh.h"
#include "shared/bindings.h"

#ifndef TREELET_SIZE
#define TREELET_SIZE 7
#endif
#define N_SUBSETS (1 << TREELET_SIZE)
// One subgroup on NVIDIA, so the barriers are cheap.
#define GROUP 32
#define POPT_COLLAPSE 0x100u

layout(local_size_x = GROUP) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0 + 1) coherent buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) coherent buffer Counters { uint counters[]; };

uniform uint u_n;
uniform uint u_gamma;

#include "sah.glsl"

// Per subset of treelet leaves (bit k = leaf k; singletons are the leaves).
shared vec3 s_lo[N_SUBSETS], s_hi[N_SUBSETS];
shared float s_area[N_SUBSETS], s_copt[N_SUBSETS];
shared int s_count[N_SUBSETS];
shared uint s_popt[N_SUBSETS];  // best left part, | POPT_COLLAPSE
// The subsets ordered by size, then colexicographically within a size.
shared uint s_order[N_SUBSETS];
shared int s_leaf[TREELET_SIZE], s_inner[TREELET_SIZE];
shared ivec2 s_kids[TREELET_SIZE];
shared int s_nl;
shared float s_root_cost;
shared float s_red_c[GROUP];
shared uint s_red_p[GROUP];
shared int s_todo[GROUP];
shared uint s_ntodo;

int binom(int n, int k)
{
    if (k < 0 || k > n)
        return 0;
    int r = 1;
    for (int i = 0; i < k; i++)
        r = r * (n - i) / (i + 1);
    return r;
}

// Where the subsets of size k start in s_order for nl leaves.
int size_offset(int nl, int k)
{
    int o = 0;
    for (int j = 1; j < k; j++)
        o += binom(nl, j);
    return o;
}

// The bits of m placed, in order, on the set bits of mask.
uint deposit(uint m, uint mask)
{
    uint r = 0u;
    while (mask != 0u) {
        uint b = mask & (~mask + 1u);
        if ((m & 1u) != 0u)
            r |= b;
        m >>= 1;
        mask ^= b;
    }
    return r;
}

void load_leaf(int k, int c)
{
    vec4 a = nodes[c].bmin, b = nodes[c].bmax;
    ivec4 l = nodes[c].link;
    uint bit = 1u << k;
    s_leaf[k] = c;
    s_kids[k] = l.xy;
    s_lo[bit] = a.xyz;
    s_hi[bit] = b.xyz;
    s_copt[bit] = a.w;
    s_area[bit] = cv_half_area(a.xyz, b.xyz);
    s_count[bit] = l.w & CV_BVH_COUNT_MASK;
}

void form_treelet(int root)
{
    // The subtree below was refreshed this round; compare against that.
    cv_bvh_update_node(root);
    s_root_cost = nodes[root].bmin.w;
    int n_inner = int(u_n) - 1;
    ivec4 rlink = nodes[root].link;
    s_inner[0] = root;
    load_leaf(0, rlink.x);
    load_leaf(1, rlink.y);
    int nl = 2, ni = 1;
    while (nl < TREELET_SIZE) {
        int best = -1;
        float best_area = -1.0;
        for (int k = 0; k < nl; k++) {
            if (s_leaf[k] < n_inner && s_area[1u << k] > best_area) {
                best_area = s_area[1u << k];
                best = k;
            }
        }
        if (best < 0)
            break;
        s_inner[ni++] = s_leaf[best];
        ivec2 kids = s_kids[best];
        load_leaf(best, kids.x);
        load_leaf(nl++, kids.y);
    }
    s_nl = nl;
}

void finish_subset(uint s, float best, uint bp, uint full, int root)
{
    float area = s_area[s];
    int count = s_count[s];
    float split = float(CV_BVH_COST_INNER) * area + best;
    float leaf = float(CV_BVH_COST_TRI) * area * float(count);
#ifdef CV_BVH_NO_COLLAPSE
    bool collapse = false;
#else
    bool collapse = count <= CV_BVH_MAX_LEAF && leaf <= split && (s != full || root != 0);
#endif
    s_copt[s] = collapse ? leaf : split;
    s_popt[s] = bp | (collapse ? POPT_COLLAPSE : 0u);
}

// Writes the optimal tree of the treelet, top down; every node's bounds,
// count and cost come from the subset tables, so nothing is read back.
void rewire(int root, uint full)
{
    uint stack_s[TREELET_SIZE];
    int stack_node[TREELET_SIZE];
    int sp = 0, used = 1;
    stack_s[sp] = full;
    stack_node[sp++] = root;
    while (sp > 0) {
        sp--;
        uint s = stack_s[sp];
        int node = stack_node[sp];
        uint pp = s_popt[s];
        uint part[2] = uint[2](pp & (POPT_COLLAPSE - 1u), s ^ (pp & (POPT_COLLAPSE - 1u)));
        int child[2];
        for (int k = 0; k < 2; k++) {
            if (bitCount(part[k]) == 1) {
                child[k] = s_leaf[findLSB(part[k])];
            } else {
                child[k] = s_inner[used++];
                stack_s[sp] = part[k];
                stack_node[sp++] = child[k];
            }
            nodes[child[k]].link.z = node;
        }
        nodes[node].bmin = vec4(s_lo[s], s_copt[s]);
        nodes[node].bmax = vec4(s_hi[s], 0.0);
        nodes[node].link.xy = ivec2(child[0], child[1]);
        nodes[node].link.w = s_count[s] | ((pp & POPT_COLLAPSE) != 0u ? CV_BVH_COLLAPSE : 0);
    }
}

// Called by the whole workgroup (uniform control flow).
void restructure(int root)
{
    uint lid = gl_LocalInvocationID.x;
    if (lid == 0u)
        form_treelet(root);
    barrier();
    int nl = s_nl;
    uint full = (1u << nl) - 1u;

    // Bounds, counts and areas of all subsets; their order by size.
    for (uint s = lid + 1u; s <= full; s += uint(GROUP)) {
        int k = bitCount(s);
        if (k > 1) {
            vec3 lo = vec3(3.0e38), hi = vec3(-3.0e38);
            int count = 0;
            for (int b = 0; b < TREELET_SIZE; b++) {
                if ((s & (1u << b)) != 0u) {
                    lo = min(lo, s_lo[1u << b]);
                    hi = max(hi, s_hi[1u << b]);
                    count += s_count[1u << b];
                }
            }
            s_lo[s] = lo;
            s_hi[s] = hi;
            s_count[s] = count;
            s_area[s] = cv_half_area(lo, hi);
        }
        int rank = 0, j = 0;
        for (int b = 0; b < TREELET_SIZE; b++) {
            if ((s & (1u << b)) != 0u)
                rank += binom(b, ++j);
        }
        s_order[size_offset(nl, k) + rank] = s;
    }
    barrier();

    // The DP, one subset size at a time. L invocations share a subset's
    // partitions when there are few subsets of that size.
    for (int k = 2; k <= nl; k++) {
        int base = size_offset(nl, k);
        int n_sub = binom(nl, k);
        int n_part = (1 << (k - 1)) - 1;
        int lanes = 1;
        while (lanes * 2 * n_sub <= GROUP && lanes * 2 <= n_part)
            lanes *= 2;
        int per_pass = GROUP / lanes;
        int lane = int(lid) % lanes;
        for (int j0 = 0; j0 < n_sub; j0 += per_pass) {
            int j = j0 + int(lid) / lanes;
            uint s = 0u;
            float best = 3.0e38;
            uint bp = 0u;
            if (j < n_sub) {
                s = s_order[base + j];
                uint low = s & (~s + 1u);
                uint rest = s ^ low;
                // m == n_part would be s itself; each split is seen once
                // because the lowest leaf always goes left.
                for (int m = lane; m < n_part; m += lanes) {
                    uint p = low | deposit(uint(m), rest);
                    float c = s_copt[p] + s_copt[s ^ p];
                    if (c < best) {
                        best = c;
                        bp = p;
                    }
                }
            }
            if (lanes == 1) {
                if (j < n_sub)
                    finish_subset(s, best, bp, full, root);
            } else {
                s_red_c[lid] = best;
                s_red_p[lid] = bp;
                barrier();
                if (j < n_sub && lane == 0) {
                    for (int q = 1; q < lanes; q++) {
                        if (s_red_c[lid + uint(q)] < best) {
                            best = s_red_c[lid + uint(q)];
                            bp = s_red_p[lid + uint(q)];
                        }
                    }
                    finish_subset(s, best, bp, full, root);
                }
                barrier();
            }
        }
        barrier();
    }

    // Keep the treelet unless the optimum is strictly cheaper.
    if (lid == 0u && s_copt[full] < s_root_cost * 0.99999)
        rewire(root, full);
    memoryBarrierBuffer();
    barrier();
}

void main()
{
    uint lid = gl_LocalInvocationID.x;
    uint i = cv_global_index();
    // Invocations past the end take part in the group's work only.
    int p = i < u_n ? nodes[int(u_n) - 1 + int(i)].link.z : -1;
    if (lid == 0u)
        s_ntodo = 0u;
    barrier();
    for (;;) {
        bool pending = false;
        while (p >= 0) {
            if (atomicAdd(counters[p], 1u) == 0u) {
                p = -1;
                break;
            }
            memoryBarrierBuffer();
            int count = (nodes[nodes[p].link.x].link.w & CV_BVH_COUNT_MASK) +
                        (nodes[nodes[p].link.y].link.w & CV_BVH_COUNT_MASK);
            if (uint(count) >= u_gamma) {
                pending = true;
                break;
            }
            cv_bvh_update_node(p);
            memoryBarrierBuffer();
            p = nodes[p].link.z;
        }
        if (pending)
            s_todo[atomicAdd(s_ntodo, 1u)] = p;
        barrier();
        // Every member either waits on a root here or has stopped for good.
        uint n_todo = s_ntodo;
        if (n_todo == 0u)
            break;
        for (uint t = 0u; t < n_todo; t++)
            restructure(s_todo[t]);
        if (lid == 0u)
            s_ntodo = 0u;
        if (pending)
            p = nodes[p].link.z;
        barrier();
    }
}
