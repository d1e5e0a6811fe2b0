#version 450
// glsl/bvh/treelet.comp: one round of treelet restructuring (Karras & Aila
// 2013). Invocations climb from the leaves like refit.comp (the second
// arrival at an inner node carries on); nodes whose subtree holds fewer than
// u_gamma primitives only have their cost refreshed on the way. An
// invocation that reaches a larger node stops there, and its workgroup then
// restructures the pending roots of all its members, TEAMS at a time: the
// group is split into teams of TEAM invocations (slices of the group, not
// subgroups, so any subgroup size works), and each team takes one root, as
// Karras & Aila give each treelet one warp. In a team, invocation 0 grows a
// treelet of TREELET_SIZE leaves (always opening the leaf of largest area),
// the team finds the SAH-optimal binary tree over those leaves by dynamic
// programming over all subsets (all subsets of one size at once, their
// (subset, partition) pairs spread evenly over the team), and invocation 0
// rewires the treelet when that is cheaper. The group then climbs on.
// Nothing waits on another workgroup: the counters only decide who carries
// on, as in refit.
// Shared memory bounds the treelets in flight: the groups' own clock
// counts showed that only a few tens of KiB of it per multiprocessor hold
// resident groups, so a group of a few KiB keeps several treelets going
// where one of tens of KiB keeps less than one (bench/RESULTS.md, "Figures
// behind the code"). So a team keeps per subset
// only its cost and best split (768 bytes for 7 leaves, 1.2 KiB per team
// in all); a subset's bounds are the union of its leaves' and are formed
// where needed, and the work lists come from a read-only buffer
// (src/bvh/treelet_schedule.c).
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
#define N_LEAVES TREELET_SIZE
#define N_SUBSETS (1 << N_LEAVES)
#define FULL uint(N_SUBSETS - 1)
#define GROUP 128
// Lanes per treelet: one warp's worth; wider teams wait more on each
// other's subsets than they gain in parallel work (bench/RESULTS.md).
#define TEAM 32
#define TEAMS (GROUP / TEAM)
#define POPT_COLLAPSE 0x100u

layout(local_size_x = GROUP) in;
#include "../lib/index.glsl"

layout(std430, binding = CV_BIND_BUILD_NODES) coherent buffer Nodes { CvBvhBuildNode nodes[]; };
layout(std430, binding = CV_BIND_BUILD_COUNTERS) coherent buffer Counters { uint counters[]; };
layout(std430, binding = CV_BIND_TREELET_STAMPS) coherent buffer Stamps { uint stamps[]; };
// The subsets of 2..N_LEAVES leaves by size, then the pairs of sizes 3 and
// up as subset | left part << 8 (src/bvh/treelet_schedule.h).
layout(std430, binding = CV_BIND_TREELET_SCHEDULE) readonly restrict buffer Schedule { uint sched[]; };

uniform uint u_n;
uniform uint u_gamma;  // at least TREELET_SIZE (src/bvh/bvh.c)
uniform uint u_round;  // 1-based

#include "sah.glsl"

// C(N_LEAVES, k).
const int BINOM[9] = int[](
#if N_LEAVES == 3
    1, 3, 3, 1, 0, 0, 0, 0, 0
#elif N_LEAVES == 4
    1, 4, 6, 4, 1, 0, 0, 0, 0
#elif N_LEAVES == 5
    1, 5, 10, 10, 5, 1, 0, 0, 0
#elif N_LEAVES == 6
    1, 6, 15, 20, 15, 6, 1, 0, 0
#elif N_LEAVES == 7
    1, 7, 21, 35, 35, 21, 7, 1, 0
#else
    1, 8, 28, 56, 70, 56, 28, 8, 1
#endif
);

// Per team t, at [t * N_SUBSETS + subset] (bit k = leaf k): the bits of the
// subset's optimal cost; while its size is searched, the least (cost bits
// with the low 8 bits cleared | left part). Costs are positive, so their
// bits order like the floats.
shared uint s_cost[TEAMS * N_SUBSETS];
// Per team and subset, 16 bits, two to a word: the best left part |
// POPT_COLLAPSE when the subset is cheaper as one leaf.
shared uint s_popt[TEAMS * N_SUBSETS / 2];
// Per team, at [t * N_LEAVES + k]: leaf k's box (its cost in lo.w), count,
// node, children and area; and the treelet's inner nodes.
shared vec4 s_llo[TEAMS * N_LEAVES], s_lhi[TEAMS * N_LEAVES];
shared int s_lcount[TEAMS * N_LEAVES], s_lnode[TEAMS * N_LEAVES];
shared ivec2 s_lkids[TEAMS * N_LEAVES];
shared float s_larea[TEAMS * N_LEAVES];
shared int s_inner[TEAMS * N_LEAVES];
shared int s_nl[TEAMS];
shared float s_root_cost[TEAMS];
shared int s_todo[GROUP];
shared uint s_ntodo;

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

void load_leaf(uint tb, uint lb, int k, int c)
{
    vec4 a = nodes[c].bmin, b = nodes[c].bmax;
    ivec4 l = nodes[c].link;
    s_lnode[lb + k] = c;
    s_lkids[lb + k] = l.xy;
    s_llo[lb + k] = a;
    s_lhi[lb + k] = b;
    s_lcount[lb + k] = l.w & CV_BVH_COUNT_MASK;
    s_larea[lb + k] = cv_half_area(a.xyz, b.xyz);
    s_cost[tb + (1u << k)] = floatBitsToUint(a.w);
}

// Invocation 0 of team `team`: grows the treelet below root.
void form_treelet(uint team, int root)
{
    uint tb = team * uint(N_SUBSETS), lb = team * uint(N_LEAVES);
    int n_inner = int(u_n) - 1;
    ivec4 rlink = nodes[root].link;
    s_inner[lb] = root;
    load_leaf(tb, lb, 0, rlink.x);
    load_leaf(tb, lb, 1, rlink.y);
    // The subtree below was refreshed this round: refresh the root from its
    // children, and compare the optimum against that.
    vec4 l0 = s_llo[lb], l1 = s_llo[lb + 1u];
    vec3 lo = min(l0.xyz, l1.xyz), hi = max(s_lhi[lb].xyz, s_lhi[lb + 1u].xyz);
    int count = s_lcount[lb] + s_lcount[lb + 1u];
    bool collapse;
    float cost = node_cost(cv_half_area(lo, hi), count, l0.w + l1.w, root != 0, collapse);
    nodes[root].bmin = vec4(lo, cost);
    nodes[root].bmax = vec4(hi, 0.0);
    nodes[root].link.w = count | (collapse ? CV_BVH_COLLAPSE : 0);
    s_root_cost[team] = cost;
    int nl = 2, ni = 1;
    while (nl < N_LEAVES) {
        int best = -1;
        float best_area = -1.0;
        for (int k = 0; k < nl; k++) {
            if (s_lnode[lb + k] < n_inner && s_larea[lb + k] > best_area) {
                best_area = s_larea[lb + k];
                best = k;
            }
        }
        if (best < 0)
            break;
        s_inner[lb + ni++] = s_lnode[lb + best];
        ivec2 kids = s_lkids[lb + best];
        load_leaf(tb, lb, best, kids.x);
        load_leaf(tb, lb, nl++, kids.y);
    }
    s_nl[team] = nl;
}

// Bounds and primitive count of subset s: the union of its leaves'.
void subset_box(uint lb, uint s, out vec3 lo, out vec3 hi, out int count)
{
    lo = vec3(3.0e38);
    hi = vec3(-3.0e38);
    count = 0;
    for (int k = 0; k < N_LEAVES; k++) {
        if ((s & (1u << k)) != 0u) {
            lo = min(lo, s_llo[lb + k].xyz);
            hi = max(hi, s_lhi[lb + k].xyz);
            count += s_lcount[lb + k];
        }
    }
}

float cost_of(uint tb, uint s)
{
    return uintBitsToFloat(s_cost[tb + s]);
}

uint popt_of(uint tb, uint s)
{
    return (s_popt[(tb + s) >> 1] >> ((s & 1u) << 4)) & 0xffffu;
}

// Subset s (of two or more leaves) takes its cost from split p, the best
// found; s_cost[s] held the search's minimum until now.
void finish_subset(uint tb, uint lb, uint s, uint p, int root)
{
    vec3 lo, hi;
    int count;
    subset_box(lb, s, lo, hi, count);
    bool collapse;
    float cost = node_cost(cv_half_area(lo, hi), count, cost_of(tb, p) + cost_of(tb, s ^ p),
                           s != FULL || root != 0, collapse);
    s_cost[tb + s] = floatBitsToUint(cost);
    atomicOr(s_popt[(tb + s) >> 1], (p | (collapse ? POPT_COLLAPSE : 0u)) << ((s & 1u) << 4));
}

// Invocation 0 of team `team`: writes the optimal tree of the treelet, top
// down; every node's bounds, count and cost come from the leaves and the
// subset tables, so nothing is read back.
void rewire(uint team, int root)
{
    uint tb = team * uint(N_SUBSETS), lb = team * uint(N_LEAVES);
    uint stack_s[N_LEAVES];
    int stack_node[N_LEAVES];
    int sp = 0, used = 1;
    for (int k = 0; k < N_LEAVES - 1; k++)
        stamps[s_inner[lb + k]] = u_round;
    stack_s[sp] = FULL;
    stack_node[sp++] = root;
    while (sp > 0) {
        sp--;
        uint s = stack_s[sp];
        int node = stack_node[sp];
        uint pp = popt_of(tb, s);
        uint left = pp & (POPT_COLLAPSE - 1u);
        uint part[2] = uint[2](left, s ^ left);
        int child[2];
        for (int k = 0; k < 2; k++) {
            if (bitCount(part[k]) == 1) {
                child[k] = s_lnode[lb + findLSB(part[k])];
            } else {
                child[k] = s_inner[lb + used++];
                stack_s[sp] = part[k];
                stack_node[sp++] = child[k];
            }
            nodes[child[k]].link.z = node;
        }
        vec3 lo, hi;
        int count;
        subset_box(lb, s, lo, hi, count);
        nodes[node].bmin = vec4(lo, cost_of(tb, s));
        nodes[node].bmax = vec4(hi, 0.0);
        nodes[node].link.xy = ivec2(child[0], child[1]);
        nodes[node].link.w = count | ((pp & POPT_COLLAPSE) != 0u ? CV_BVH_COLLAPSE : 0);
    }
}

// Called by the whole workgroup (uniform control flow); root is this
// invocation's team's treelet root, the same across the team, or -1 for a
// team without one.
void restructure(int root)
{
    uint lid = gl_LocalInvocationID.x;
    uint team = lid / uint(TEAM), lane = lid % uint(TEAM);
    uint tb = team * uint(N_SUBSETS), lb = team * uint(N_LEAVES);
    if (root >= 0) {
        // Leaves' entries are formation's (no race: it writes only those).
        for (uint s = lane; s < uint(N_SUBSETS); s += uint(TEAM)) {
            if ((s & (s - 1u)) != 0u)
                s_cost[tb + s] = 0xffffffffu;
        }
        for (uint w = lane; w < uint(N_SUBSETS / 2); w += uint(TEAM))
            s_popt[(tb >> 1) + w] = 0u;
        if (lane == 0u)
            form_treelet(team, root);
    }
    barrier();
    // A subtree of u_gamma >= N_LEAVES primitives always yields a full
    // treelet; the schedule is made for that size only.
    bool busy = root >= 0 && s_nl[team] == N_LEAVES;

    // The DP, one subset size at a time; pairs of size k spread evenly
    // over the team, so no lane walks a long run of partitions while others
    // wait (the longest chain is 10 pairs for 7 leaves and 32 lanes). Per
    // subset, a shared atomicMin of the cost's bits with the left part in
    // the low 8 bits picks the best split: costs within 2^-15 of each other
    // count as equal and go to the lower left part. finish_subset then
    // recomputes the chosen split's exact cost. Pairs of two leaves have one
    // split.
    if (busy) {
        for (uint j = lane; j < uint(BINOM[2]); j += uint(TEAM)) {
            uint s = sched[j];
            finish_subset(tb, lb, s, s & (~s + 1u), root);
        }
    }
    barrier();
    uint sub = uint(BINOM[2]);  // subsets of the size at hand, in sched
    uint pair = 0u;             // its pairs, after all the subsets
    for (int k = 2; k <= N_LEAVES; k++)
        pair += uint(BINOM[k]);
    for (int k = 3; k <= N_LEAVES; k++) {
        uint n_sub = uint(BINOM[k]), items = n_sub * ((1u << (k - 1)) - 1u);
        if (busy) {
            for (uint t = pair + lane; t < pair + items; t += uint(TEAM)) {
                uint e = sched[t];
                uint s = e & 0xffu, p = e >> 8;
                float c = cost_of(tb, p) + cost_of(tb, s ^ p);
                atomicMin(s_cost[tb + s], (floatBitsToUint(c) & ~0xffu) | p);
            }
        }
        barrier();
        if (busy) {
            for (uint j = sub + lane; j < sub + n_sub; j += uint(TEAM)) {
                uint s = sched[j];
                finish_subset(tb, lb, s, s_cost[tb + s] & 0xffu, root);
            }
        }
        barrier();
        sub += n_sub;
        pair += items;
    }

    // Keep the treelet unless the optimum is strictly cheaper.
    if (busy && lane == 0u && cost_of(tb, FULL) < s_root_cost[team] * 0.99999)
        rewire(team, root);
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
        for (uint t = 0u; t < n_todo; t += uint(TEAMS)) {
            uint mine = t + lid / uint(TEAM);
            restructure(mine < n_todo ? s_todo[mine] : -1);
        }
        if (lid == 0u)
            s_ntodo = 0u;
        if (pending)
            p = nodes[p].link.z;
        barrier();
    }
}
