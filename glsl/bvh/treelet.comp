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
// over all subsets in parallel (all subsets of one size at once, their
// partitions spread evenly over the group), and
// invocation 0 rewires the treelet when that is cheaper. The group then
// climbs on. Nothing waits on another workgroup: the counters only decide
// who carries on, as in refit.
// Rounds after the first skip treelets whose subtree changed neither in the
// previous round nor so far in this one: their optimisation would see the
// very same input and keep it, so the tree is the same as without skipping.
// stamps[p] is the last round (1-based) in which inner node p or anything
// below it changed (0: never); a rewired treelet stamps all its inner nodes.
#include "shared/bvh.h"
#include "shared/bindings.h"

#ifndef TREELET_SIZE
#define TREELET_SIZE 7
#endif
#define N_SUBSETS (1 << TREELET_SIZE)
// Four subgroups on NVIDIA: with the DP's pairs spread over the whole
// group, 128 invocations beat 32 and 64 (H100, 1 M triangles: treelet
// 14.6 ms against 19.5 and 15.3; not profiled: presumably more climbs
// share a group's latency and each treelet's DP chain is shorter).
#define GROUP 128
#define POPT_COLLAPSE 0x100u

layout(local_size_x = GROUP) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_STAGE0 + 1) coherent buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_STAGE0 + 2) coherent buffer Counters { uint counters[]; };
layout(std430, binding = CV_BIND_STAGE0 + 3) coherent buffer Stamps { uint stamps[]; };

uniform uint u_n;
uniform uint u_gamma;
uniform uint u_round;  // 1-based

#include "sah.glsl"

// Per subset of treelet leaves (bit k = leaf k; singletons are the leaves).
shared vec3 s_lo[N_SUBSETS], s_hi[N_SUBSETS];
shared float s_copt[N_SUBSETS];
shared float s_larea[TREELET_SIZE];  // leaf areas, to pick the leaf to open
shared int s_count[N_SUBSETS];
shared uint s_popt[N_SUBSETS];  // best left part, | POPT_COLLAPSE
// The subsets ordered by size, then colexicographically within a size.
shared uint s_order[N_SUBSETS];
shared int s_leaf[TREELET_SIZE], s_inner[TREELET_SIZE];
shared ivec2 s_kids[TREELET_SIZE];
shared int s_nl;
shared float s_root_cost;
// Most subsets of one size: C(8, 4), for the largest treelet (8 leaves,
// src/bvh/bvh.c checks the size).
#define MAX_SUBSETS_OF_A_SIZE 70
// Per subset of the current size: best cost bits | partition number.
shared uint s_best[MAX_SUBSETS_OF_A_SIZE];
shared int s_todo[GROUP];
shared uint s_ntodo;

// C(n, k) for n, k <= 8, at [n * 9 + k].
const int BINOM[81] = int[](
    1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1, 2, 1, 0, 0, 0, 0, 0, 0,
    1, 3, 3, 1, 0, 0, 0, 0, 0, 1, 4, 6, 4, 1, 0, 0, 0, 0, 1, 5, 10, 10, 5, 1, 0, 0, 0,
    1, 6, 15, 20, 15, 6, 1, 0, 0, 1, 7, 21, 35, 35, 21, 7, 1, 0, 1, 8, 28, 56, 70, 56, 28, 8, 1);

// The leaf count s_order was built for (0: not yet).
shared int s_order_nl;

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

// SAH cost of a node of the given area and primitive count whose children
// cost `children` together: split, or one leaf when that is allowed and
// no dearer (the rule of cv_bvh_update_node).
float node_cost(float area, int count, float children, bool may_collapse, out bool collapse)
{
    float split = float(CV_BVH_COST_INNER) * area + children;
    float leaf = float(CV_BVH_COST_TRI) * area * float(count);
#ifdef CV_BVH_NO_COLLAPSE
    collapse = false;
#else
    collapse = may_collapse && count <= CV_BVH_MAX_LEAF && leaf <= split;
#endif
    return collapse ? leaf : split;
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
    s_larea[k] = cv_half_area(a.xyz, b.xyz);
    s_count[bit] = l.w & CV_BVH_COUNT_MASK;
}

void form_treelet(int root)
{
    int n_inner = int(u_n) - 1;
    ivec4 rlink = nodes[root].link;
    s_inner[0] = root;
    load_leaf(0, rlink.x);
    load_leaf(1, rlink.y);
    // The subtree below was refreshed this round: refresh the root from its
    // children, and compare the optimum against that.
    vec3 lo = min(s_lo[1], s_lo[2]), hi = max(s_hi[1], s_hi[2]);
    int count = s_count[1] + s_count[2];
    bool collapse;
    float cost = node_cost(cv_half_area(lo, hi), count, s_copt[1] + s_copt[2], root != 0, collapse);
    nodes[root].bmin = vec4(lo, cost);
    nodes[root].bmax = vec4(hi, 0.0);
    nodes[root].link.w = count | (collapse ? CV_BVH_COLLAPSE : 0);
    s_root_cost = cost;
    int nl = 2, ni = 1;
    while (nl < TREELET_SIZE) {
        int best = -1;
        float best_area = -1.0;
        for (int k = 0; k < nl; k++) {
            if (s_leaf[k] < n_inner && s_larea[k] > best_area) {
                best_area = s_larea[k];
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

// Subset s (of two or more leaves) takes its bounds from its lowest leaf
// and the rest, both final, and its cost from the best split found.
void finish_subset(uint s, float best, uint bp, uint full, int root)
{
    uint low = s & (~s + 1u), rest = s ^ low;
    vec3 lo = min(s_lo[low], s_lo[rest]), hi = max(s_hi[low], s_hi[rest]);
    int count = s_count[low] + s_count[rest];
    float area = cv_half_area(lo, hi);
    bool collapse;
    s_lo[s] = lo;
    s_hi[s] = hi;
    s_count[s] = count;
    s_copt[s] = node_cost(area, count, best, s != full || root != 0, collapse);
    s_popt[s] = bp | (collapse ? POPT_COLLAPSE : 0u);
}

// Writes the optimal tree of the treelet, top down; every node's bounds,
// count and cost come from the subset tables, so nothing is read back.
void rewire(int root, uint full)
{
    uint stack_s[TREELET_SIZE];
    int stack_node[TREELET_SIZE];
    int sp = 0, used = 1;
    for (int k = 0; k < s_nl - 1; k++)
        stamps[s_inner[k]] = u_round;
    stack_s[sp] = full;
    stack_node[sp++] = root;
    while (sp > 0) {
        sp--;
        uint s = stack_s[sp];
        int node = stack_node[sp];
        uint pp = s_popt[s];
        uint left = pp & (POPT_COLLAPSE - 1u);
        uint part[2] = uint[2](left, s ^ left);
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

    // The subsets ordered by size (colexicographic rank within a size);
    // built once per group, as the leaf count hardly ever changes.
    if (nl != s_order_nl) {
        for (uint s = lid + 1u; s <= full; s += uint(GROUP)) {
            int k = bitCount(s);
            int pos = 0, j = 0;
            for (int i = 1; i < k; i++)
                pos += BINOM[nl * 9 + i];
            for (int b = 0; b < TREELET_SIZE; b++) {
                if ((s & (1u << b)) != 0u)
                    pos += BINOM[b * 9 + (++j)];
            }
            s_order[pos] = s;
        }
        barrier();
        if (lid == 0u)
            s_order_nl = nl;
    }

    // The DP, one subset size at a time. All (subset, partition) pairs of
    // a size are spread evenly over the group, so no invocation walks a
    // long run of partitions while others wait (the longest chain is 10
    // pairs for 7 leaves, against 60 when each subset had its own lanes,
    // and the time per treelet follows that chain).
    // Per subset, a shared atomicMin of the cost's bits with the partition
    // number in the low 7 bits (up to 127 partitions for 8 leaves) picks the
    // best split: costs are positive, so their bits order like the floats;
    // costs within 2^-16 of each other count as equal and go to the lower
    // partition. The chosen split's exact cost is then recomputed.
    int base = nl;
    for (int k = 2; k <= nl; k++) {
        int n_sub = BINOM[nl * 9 + k];
        uint n_part = (1u << (k - 1)) - 1u;
        uint items = uint(n_sub) * n_part;
        for (uint j = lid; j < uint(n_sub); j += uint(GROUP))
            s_best[j] = 0xffffffffu;
        barrier();
        for (uint t = lid; t < items; t += uint(GROUP)) {
            uint j = t / n_part, m = t - j * n_part;
            uint s = s_order[base + int(j)];
            // The lowest leaf always goes left, so each split is seen once;
            // m < n_part never puts every other leaf left too.
            uint low = s & (~s + 1u);
            uint p = low | deposit(m, s ^ low);
            float c = s_copt[p] + s_copt[s ^ p];
            atomicMin(s_best[j], (floatBitsToUint(c) & ~0x7fu) | m);
        }
        barrier();
        for (uint j = lid; j < uint(n_sub); j += uint(GROUP)) {
            uint s = s_order[base + int(j)];
            uint low = s & (~s + 1u);
            uint p = low | deposit(s_best[j] & 0x7fu, s ^ low);
            finish_subset(s, s_copt[p] + s_copt[s ^ p], p, full, root);
        }
        base += n_sub;
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
    if (lid == 0u) {
        s_ntodo = 0u;
        s_order_nl = 0;
    }
    barrier();
    for (;;) {
        bool pending = false;
        while (p >= 0) {
            if (atomicAdd(counters[p], 1u) == 0u) {
                p = -1;
                break;
            }
            memoryBarrierBuffer();
            ivec2 kids = nodes[p].link.xy;
            int count = (nodes[kids.x].link.w & CV_BVH_COUNT_MASK) +
                        (nodes[kids.y].link.w & CV_BVH_COUNT_MASK);
            int n_inner = int(u_n) - 1;
            bool below = (kids.x < n_inner && stamps[kids.x] == u_round) ||
                         (kids.y < n_inner && stamps[kids.y] == u_round);
            uint last = stamps[p];
            if (below)
                stamps[p] = u_round;
            if (uint(count) >= u_gamma && (below || last + 1u >= u_round)) {
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
