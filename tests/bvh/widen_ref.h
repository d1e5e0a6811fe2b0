/* widen_ref.h: the CPU copy of the renderer's widening rule (least summed
 * node area; glsl/bvh/widen.glsl is its home and says how it works), for
 * any width up to WIDEN_REF_MAX: the BVH tests check the GPU's 4-wide
 * tree against it (bvh_test_util.h: check_widening) and bench/bvh_work
 * widens binary trees with it (--rewiden, --ref). The same float
 * arithmetic in the same order and the same ties as the shader, so that
 * with 4 children it gives the GPU's tree exactly. Tools only. */
#ifndef CV_TESTS_BVH_WIDEN_REF_H
#define CV_TESTS_BVH_WIDEN_REF_H

#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#define WIDEN_REF_MAX 8

/* A binary tree whose inner nodes are numbered with children after their
 * parents: kid[b][side] the inner child's index, or -1 for a leaf child;
 * lo/hi each inner node's box (the union of its children's, as the GPU
 * has it). g[b][s] (s = 2..k) is the least cost of covering b's two
 * children with at most s slots, f[b] = area(b) + g[b][k] b's cost as a
 * wide node (widen_ref_run fills them). */
struct widen_ref {
    int k;
    uint32_t n;
    const int32_t (*kid)[2];
    const float (*lo)[3], (*hi)[3];
    float (*g)[WIDEN_REF_MAX + 1];
    float *f;
};

/* cv_widen_area */
static inline float widen_ref_area(const float lo[3], const float hi[3])
{
    float e[3];
    for (int k = 0; k < 3; k++)
        e[k] = fmaxf(hi[k] - lo[k], 0.0f);
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
}

/* cv_widen_opens */
static inline bool widen_ref_opens(const struct widen_ref *w, int32_t c, int s)
{
    return c >= 0 && s >= 2 && w->g[c][s] < w->f[c];
}

/* cv_widen_side: a child's least cost with at most s >= 1 slots */
static inline float widen_ref_side(const struct widen_ref *w, int32_t c, int s)
{
    return c < 0 ? 0.0f : widen_ref_opens(w, c, s) ? w->g[c][s] : w->f[c];
}

/* cv_widen_split: the least cost of covering b's children with at most s
 * slots, and the left child's slots */
static inline float widen_ref_split(const struct widen_ref *w, uint32_t b, int s, int *s_left)
{
    int32_t l = w->kid[b][0], r = w->kid[b][1];
    *s_left = 1;
    float best = widen_ref_side(w, l, 1) + widen_ref_side(w, r, s - 1);
    for (int sl = 2; sl < s; sl++) {
        float c = widen_ref_side(w, l, sl) + widen_ref_side(w, r, s - sl);
        if (c < best) {
            best = c;
            *s_left = sl;
        }
    }
    return best;
}

/* Fills g and f (allocated here; widen_ref_free), bottom-up. */
static inline void widen_ref_run(struct widen_ref *w)
{
    w->g = calloc(w->n ? w->n : 1, sizeof(*w->g));
    w->f = calloc(w->n ? w->n : 1, sizeof(*w->f));
    for (uint32_t i = w->n; i-- > 0;) {
        int sl;
        for (int s = 2; s <= w->k; s++)
            w->g[i][s] = widen_ref_split(w, i, s, &sl);
        w->f[i] = widen_ref_area(w->lo[i], w->hi[i]) + w->g[i][w->k];
    }
}

static inline void widen_ref_free(struct widen_ref *w)
{
    free(w->g);
    free(w->f);
    w->g = NULL;
    w->f = NULL;
}

/* The children of b's cover with at most s slots, left to right, each as
 * 2 * (its binary parent) + side (0 left, 1 right); returns their count. */
static inline int widen_ref_cover(const struct widen_ref *w, uint32_t b, int s, uint32_t *kid)
{
    int sl, n = 0;
    widen_ref_split(w, b, s, &sl);
    const int ss[2] = {sl, s - sl};
    for (int side = 0; side < 2; side++) {
        int32_t c = w->kid[b][side];
        if (widen_ref_opens(w, c, ss[side]))
            n += widen_ref_cover(w, (uint32_t)c, ss[side], kid + n);
        else
            kid[n++] = 2 * b + (uint32_t)side;
    }
    return n;
}

/* The children of wide node b (at most k, see widen_ref_cover). */
static inline int widen_ref_kids(const struct widen_ref *w, uint32_t b, uint32_t *kid)
{
    return widen_ref_cover(w, b, w->k, kid);
}

#endif
