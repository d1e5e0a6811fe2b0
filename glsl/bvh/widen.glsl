// glsl/bvh/widen.glsl: which binary subtrees become the children of one
// node of the 4-wide tree (glsl/shared/bvh.h), by least node area: of all
// ways to cut the binary tree into wide nodes of at most four children,
// the one whose wide nodes' summed surface area (the SAH's node term; the
// leaves are the same either way) is least. This is the home of the rule;
// tests/bvh/widen_ref.h is its CPU copy (for other widths too), against
// which the BVH tests check the GPU's tree slot for slot, and which
// bench/bvh_work re-widens with. It replaced opening the inner child
// of largest area greedily (bench/RESULTS.md, "The 4-wide tree by least
// node area").
//
// Dynamic programming over the binary tree, bottom-up (widen_cost.comp):
// for binary node b, g_s(b) (s = 2, 3, 4) is the least cost of covering
// b's two children with at most s slots, each inner child either kept (one
// slot, costing its own wide node's f) or opened in place (its children
// covered with the slots it was given); f(b) = area(b) + g_4(b) is b's
// cost as a wide node. Top-down (cv_widen_children), a wide node follows
// the same choices: its four slots split between its children as the
// least cost says, and a child given s >= 2 slots opened where that costs
// less than keeping it (ties keep it, and give the left child fewer
// slots). Opening in place keeps the binary tree's left-to-right order.
// widen_level.comp finds the wide nodes with it level by level and
// widen_emit.comp writes them, so both open the same children by
// construction. A wide node may be left with fewer than four children and
// an inner one among them, where opening that child would cost more.
//
// The binary nodes are bound at CV_BIND_WIDEN_BIN; n_bin is their count
// (info[CV_BVH_INFO_NODES]). A child word outside 1..n_bin-1 is not
// opened and not kept as an inner child: the binary tree is emit.comp's
// and valid, but nothing here may run away on a bad one.
#ifndef CV_BVH_WIDEN_GLSL
#define CV_BVH_WIDEN_GLSL

#include "shared/bvh.h"
#include "shared/bindings.h"

// Invocations per group of widen_level.comp, which widen_next.comp's
// dispatch counts assume.
#define CV_WIDEN_GROUP 64

// widen_up.comp's up word for the root: no parent.
#define CV_WIDEN_ROOT 0x7fffffffu

layout(std430, binding = CV_BIND_WIDEN_BIN) readonly buffer CvWidenBin { CvBvhNode cv_widen_bin[]; };
// Per binary node: (g_2, g_3, g_4, f), see the top; widen_cost.comp
// writes them and defines the access first.
#ifndef CV_WIDEN_COST_ACCESS
#define CV_WIDEN_COST_ACCESS readonly
#endif
layout(std430, binding = CV_BIND_WIDEN_COST) CV_WIDEN_COST_ACCESS buffer CvWidenCost {
    vec4 cv_widen_cost[];
};

struct CvWideKids {
    vec4 lo[4];   // .xyz: box
    vec4 hi[4];
    int word[4];  // binary node (inner) or first leaf slot (leaf)
    int count[4]; // leaf primitives; 0: inner (or invalid, see cv_widen_inner)
    vec4 cost[4]; // an inner child's cv_widen_cost
    int slots[4]; // the slots its cover may use
    int n;
};

bool cv_widen_is_inner(int word, int count, int n_bin)
{
    return count == 0 && word > 0 && word < n_bin;
}

// Whether slot c holds an inner child that may be opened or kept.
bool cv_widen_inner(CvWideKids k, int c, int n_bin)
{
    return c < k.n && cv_widen_is_inner(k.word[c], k.count[c], n_bin);
}

float cv_widen_area(vec3 lo, vec3 hi)
{
    precise vec3 e = max(hi - lo, vec3(0.0));
    precise float a = e.x * e.y + e.y * e.z + e.z * e.x;
    return a;
}

float cv_widen_g(vec4 cost, int s)
{
    return s <= 2 ? cost.x : s == 3 ? cost.y : cost.z;
}

// Whether an inner child of cost `cost` given s slots is opened.
bool cv_widen_opens(vec4 cost, int s)
{
    return s >= 2 && cv_widen_g(cost, s) < cost.w;
}

// The least cost of covering one child with at most s >= 1 slots.
float cv_widen_side(bool inner, vec4 cost, int s)
{
    return !inner ? 0.0 : cv_widen_opens(cost, s) ? cv_widen_g(cost, s) : cost.w;
}

// The least cost of covering two children with at most s (2..4) slots,
// and the slots of the left one.
float cv_widen_split(bool l_inner, vec4 l_cost, bool r_inner, vec4 r_cost, int s, out int s_left)
{
    s_left = 1;
    precise float best = cv_widen_side(l_inner, l_cost, 1) + cv_widen_side(r_inner, r_cost, s - 1);
    for (int sl = 2; sl < 4; sl++) {
        precise float c =
            cv_widen_side(l_inner, l_cost, sl) + cv_widen_side(r_inner, r_cost, s - sl);
        if (sl < s && c < best) {
            best = c;
            s_left = sl;
        }
    }
    return best;
}

// Binary node nd's cv_widen_cost, its children's costs read (those of the
// inner ones must be final).
vec4 cv_widen_node_cost(CvBvhNode nd, int n_bin)
{
    int lw = floatBitsToInt(nd.lmin.w), rw = floatBitsToInt(nd.rmin.w);
    bool li = cv_widen_is_inner(lw, floatBitsToInt(nd.lmax.w), n_bin);
    bool ri = cv_widen_is_inner(rw, floatBitsToInt(nd.rmax.w), n_bin);
    vec4 lc = li ? cv_widen_cost[lw] : vec4(0.0), rc = ri ? cv_widen_cost[rw] : vec4(0.0);
    int sl;
    vec4 g;
    g.x = cv_widen_split(li, lc, ri, rc, 2, sl);
    g.y = cv_widen_split(li, lc, ri, rc, 3, sl);
    g.z = cv_widen_split(li, lc, ri, rc, 4, sl);
    vec3 lo = min(nd.lmin.xyz, nd.rmin.xyz), hi = max(nd.lmax.xyz, nd.rmax.xyz);
    precise float f = cv_widen_area(lo, hi) + g.z;
    g.w = f;
    return g;
}

// Binary node nd's child `side` (0 left, 1 right) into slot c.
void cv_widen_take(inout CvWideKids k, int c, CvBvhNode nd, int side, int n_bin)
{
    k.lo[c] = side == 0 ? nd.lmin : nd.rmin;
    k.hi[c] = side == 0 ? nd.lmax : nd.rmax;
    k.word[c] = floatBitsToInt(k.lo[c].w);
    k.count[c] = floatBitsToInt(k.hi[c].w);
    k.cost[c] = cv_widen_is_inner(k.word[c], k.count[c], n_bin) ? cv_widen_cost[k.word[c]]
                                                                   : vec4(0.0);
}

// Slots c and c + 1 (binary node nd's children, just taken) share s slots.
void cv_widen_share(inout CvWideKids k, int c, int s, int n_bin)
{
    bool li = false, ri = false;
    vec4 lc = vec4(0.0), rc = vec4(0.0);
    for (int j = 0; j < 4; j++) {
        if (j == c) {
            li = cv_widen_inner(k, j, n_bin);
            lc = k.cost[j];
        } else if (j == c + 1) {
            ri = cv_widen_inner(k, j, n_bin);
            rc = k.cost[j];
        }
    }
    int sl;
    cv_widen_split(li, lc, ri, rc, s, sl);
    for (int j = 0; j < 4; j++) {
        if (j == c)
            k.slots[j] = sl;
        else if (j == c + 1)
            k.slots[j] = s - sl;
    }
}

// Every loop here runs over the four slots with a constant bound and
// tests its index, rather than indexing by a variable, so that the arrays
// can stay in registers: indexed by `best`, they went to local memory and
// widening took nearly twice as long (bench/RESULTS.md, "The 4-wide tree,
// built on the GPU").
void cv_widen_children(int b, int n_bin, out CvWideKids k)
{
    for (int c = 0; c < 4; c++) {
        k.lo[c] = vec4(0.0);
        k.hi[c] = vec4(0.0);
        k.word[c] = 0;
        k.count[c] = 0;
        k.cost[c] = vec4(0.0);
        k.slots[c] = 0;
    }
    CvBvhNode nd = cv_widen_bin[b];
    cv_widen_take(k, 0, nd, 0, n_bin);
    cv_widen_take(k, 1, nd, 1, n_bin);
    k.n = 2;
    cv_widen_share(k, 0, 4, n_bin);
    // Each opening turns one entry of s >= 2 slots into two sharing them,
    // so four slots allow two.
    for (int opened = 0; opened < 2; opened++) {
        int best = -1, open = 0, s = 0;
        for (int c = 0; c < 4; c++) {
            if (best < 0 && cv_widen_inner(k, c, n_bin) && cv_widen_opens(k.cost[c], k.slots[c])) {
                best = c;
                open = k.word[c];
                s = k.slots[c];
            }
        }
        if (best < 0)
            break;
        nd = cv_widen_bin[open];
        for (int c = 3; c > 0; c--) {
            if (c > best + 1 && c <= k.n) {
                k.lo[c] = k.lo[c - 1];
                k.hi[c] = k.hi[c - 1];
                k.word[c] = k.word[c - 1];
                k.count[c] = k.count[c - 1];
                k.cost[c] = k.cost[c - 1];
                k.slots[c] = k.slots[c - 1];
            }
        }
        for (int c = 0; c < 4; c++) {
            if (c == best)
                cv_widen_take(k, c, nd, 0, n_bin);
            else if (c == best + 1)
                cv_widen_take(k, c, nd, 1, n_bin);
        }
        k.n++;
        cv_widen_share(k, best, s, n_bin);
    }
}

#endif
