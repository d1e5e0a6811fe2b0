// glsl/bvh/widen.glsl: which binary subtrees become the children of one
// node of the 4-wide tree (glsl/shared/bvh.h). widen_level.comp finds the
// wide nodes with it level by level and widen_emit.comp writes them, so
// both open the same children by construction.
//
// A wide node starts from its binary node's two children and opens the
// inner child of largest surface area (the one most rays enter, so the
// fetch most worth saving) into its two children, in place, until it has
// four children or only leaves; ties go to the leftmost. Opening in place
// keeps the binary tree's left-to-right order. This is the rule of the
// experiment that chose the 4-wide tree (bench/RESULTS.md, "The 4-wide
// tree, measured first"); no other rule has been measured.
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

layout(std430, binding = CV_BIND_WIDEN_BIN) readonly buffer CvWidenBin { CvBvhNode cv_widen_bin[]; };

struct CvWideKids {
    vec4 lo[4];   // .xyz: box
    vec4 hi[4];
    int word[4];  // binary node (inner) or first leaf slot (leaf)
    int count[4]; // leaf primitives; 0: inner (or invalid, see cv_widen_inner)
    int n;
};

// Whether slot c holds an inner child that may be opened or kept.
bool cv_widen_inner(CvWideKids k, int c, int n_bin)
{
    return c < k.n && k.count[c] == 0 && k.word[c] > 0 && k.word[c] < n_bin;
}

// Binary node b's child `side` (0 left, 1 right) into slot c.
void cv_widen_take(inout CvWideKids k, int c, CvBvhNode nd, int side)
{
    k.lo[c] = side == 0 ? nd.lmin : nd.rmin;
    k.hi[c] = side == 0 ? nd.lmax : nd.rmax;
    k.word[c] = floatBitsToInt(k.lo[c].w);
    k.count[c] = floatBitsToInt(k.hi[c].w);
}

float cv_widen_area(vec3 lo, vec3 hi)
{
    vec3 e = max(hi - lo, vec3(0.0));
    return e.x * e.y + e.y * e.z + e.z * e.x;
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
    }
    CvBvhNode nd = cv_widen_bin[b];
    cv_widen_take(k, 0, nd, 0);
    cv_widen_take(k, 1, nd, 1);
    k.n = 2;
    for (int opened = 0; opened < 2; opened++) {
        int best = -1, open = 0;
        float best_area = -1.0;
        for (int c = 0; c < 4; c++) {
            float a = cv_widen_area(k.lo[c].xyz, k.hi[c].xyz);
            if (cv_widen_inner(k, c, n_bin) && a > best_area) {
                best = c;
                best_area = a;
                open = k.word[c];
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
            }
        }
        for (int c = 0; c < 4; c++) {
            if (c == best)
                cv_widen_take(k, c, nd, 0);
            else if (c == best + 1)
                cv_widen_take(k, c, nd, 1);
        }
        k.n++;
    }
}

#endif
