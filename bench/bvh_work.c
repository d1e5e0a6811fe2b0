/* bvh_work.c: traversal work per ray of the renderer's triangle tree on a
 * real scene, independent of the GPU's speed. Loads a pbrt scene through
 * the normal loader, builds the tree as cavalry-batch does (cv_bvh_build
 * with the CAVALRY_BVH_* knobs), reads the 4-wide tree back and walks it on
 * the CPU with the order of glsl/bvh/traverse.glsl (nearest inner child
 * first, the others pushed farthest first, a node's leaf children tested
 * as one run, children beyond the current hit culled), counting nodes
 * visited and triangles tested per query. The rays look like a path
 * tracer's (bench/rays.h, spawned from this walk's hits): camera rays, two
 * diffuse bounces from real hit points, and a shadow ray (any hit) to a
 * light chosen by power from every hit point. Prints per query type the mean
 * nodes and triangles, the cost c_node * nodes + c_tri * triangles, and of
 * the tree: the SAH cost (binary, the build's constants; wide, the cost
 * model's), the leaf-size histogram, depth, node count and how much child
 * boxes overlap.
 *   bvh_work SCENE.pbrt [--res N] [--seed S] [--ref] [--verify] [--tail N]
 *            [--rounds R] [--split F] [--treelet S] [--c-node X] [--c-tri Y]
 *            [--rewiden greedy|sah] [--wide K] [--ref-widen greedy|sah]
 *            [--ref-inner X] [--ref-tri Y] [--ref-leaf N] [--ref-bins B]
 * --rewiden keeps the renderer's binary tree and widens it here to K
 * children (2..8) by least node area, the renderer's rule (its home is
 * glsl/bvh/widen.glsl; its CPU copy tests/bvh/widen_ref.h serves other
 * widths, and with K 4 gives the renderer's own tree: bench_test.sh and
 * the BVH tests check it), or greedily
 * (the inner child of largest area opened first: the renderer's rule
 * before least node area).
 * --res N: camera rays on an N-wide grid (height by the film's aspect).
 * --ref also builds a binned-SAH tree on the CPU (over the triangles, no
 * splitting; the build's leaf costs unless --ref-* say otherwise), widens
 * it by the GPU's rule (or --ref-widen greedy) and walks the same rays
 * through it: what a good host build would cost.
 * --verify traces the camera rays through the GPU's own traversal
 * (glsl/bvh/rays_test.comp, CV_BVH_COUNT_STEPS) and checks that its hits
 * and node counts equal this walk's (exit status 1 if not).
 * The walk uses a double-precision triangle test, not the watertight one,
 * so a ray grazing an edge may hit one neighbour instead of the other:
 * work figures, not images. Run from the build tree (embedded shaders) or
 * with CAVALRY_DATA_DIR at the source tree. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh/bvh.h"
#include "cli/knobs.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/bvh.h"
#include "glsl/shared/scene.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "tests/bvh/sah_ref.h"
#include "bench/rays.h"
#include "bench/scene_tree.h"
#include "tests/bvh/widen_ref.h"

/* ---- the scene's triangles ---- */

/* Möller-Trumbore in double: t and the barycentrics, or false. */
static bool ray_tri(const struct bench_tris *m, uint32_t t, const double o[3], const double d[3],
                    double *th, double *b1, double *b2)
{
    double p[3][3], e1[3], e2[3], s[3], q[3], h[3];
    bench_tri_pos(m, t, p);
    for (int k = 0; k < 3; k++) {
        e1[k] = p[1][k] - p[0][k];
        e2[k] = p[2][k] - p[0][k];
        s[k] = o[k] - p[0][k];
    }
    h[0] = d[1] * e2[2] - d[2] * e2[1];
    h[1] = d[2] * e2[0] - d[0] * e2[2];
    h[2] = d[0] * e2[1] - d[1] * e2[0];
    double a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (a == 0.0)
        return false;
    double f = 1.0 / a;
    double u = f * (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]);
    if (u < 0.0 || u > 1.0)
        return false;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    double v = f * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]);
    if (v < 0.0 || u + v > 1.0)
        return false;
    *th = f * (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]);
    *b1 = u;
    *b2 = v;
    return true;
}

/* ---- a wide tree as traversal reads it ---- */

/* Up to WIDE_MAX children per node: the renderer's trees have 4 (read back
 * from CvBvhNode4); --wide re-widens binary trees to other widths. Used
 * children first, in the binary tree's left-to-right order. */
#define WIDE_MAX WIDEN_REF_MAX
struct gnode {
    int n;
    float lo[WIDE_MAX][3], hi[WIDE_MAX][3];
    int32_t word[WIDE_MAX];   /* inner: node index; leaf: first leaf slot */
    int32_t count[WIDE_MAX];  /* leaf: primitives; 0: inner */
};

static void gnode_from4(const CvBvhNode4 *in, struct gnode *out)
{
    out->n = 0;
    for (int c = 0; c < 4; c++) {
        const float lo[3] = {(&in->lox.x)[c], (&in->loy.x)[c], (&in->loz.x)[c]};
        const float hi[3] = {(&in->hix.x)[c], (&in->hiy.x)[c], (&in->hiz.x)[c]};
        if (!(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2]))
            continue; /* unused slot */
        memcpy(out->lo[out->n], lo, sizeof(lo));
        memcpy(out->hi[out->n], hi, sizeof(hi));
        out->word[out->n] = (&in->word.x)[c];
        out->count[out->n] = (&in->count.x)[c];
        out->n++;
    }
}

struct wtree {
    struct gnode *nodes;
    uint32_t n_nodes;
    uint32_t *prims;   /* leaf slot -> triangle */
    uint32_t n_slots;
    float pad_lo[3], pad_hi[3]; /* the root's used slots' box (cv_bvh_pad) */
};

static void wtree_finish(struct wtree *w)
{
    const struct gnode *r = &w->nodes[0];
    for (int k = 0; k < 3; k++) {
        w->pad_lo[k] = 3e38f;
        w->pad_hi[k] = -3e38f;
    }
    for (int c = 0; c < r->n; c++) {
        const float *lo = r->lo[c], *hi = r->hi[c];
        for (int k = 0; k < 3; k++) {
            w->pad_lo[k] = fminf(w->pad_lo[k], lo[k]);
            w->pad_hi[k] = fmaxf(w->pad_hi[k], hi[k]);
        }
    }
}

static void wtree_free(struct wtree *w)
{
    free(w->nodes);
    free(w->prims);
    memset(w, 0, sizeof(*w));
}

struct work {
    uint64_t nodes, tris, queries, hits;
    uint64_t repeats;  /* of tris: a triangle already tested in the same leaf */
};

/* One query, closest (any false) or any hit, in traverse.glsl's order. */
static struct bench_hit walk(const struct wtree *w, const struct bench_tris *m, const struct bench_ray *r, bool any,
                       struct work *wk)
{
    struct bench_hit h = {.t = r->tmax, .prim = UINT32_MAX};
    double od[3] = {r->o[0], r->o[1], r->o[2]}, dd[3] = {r->d[0], r->d[1], r->d[2]};
    float inv[3];
    for (int k = 0; k < 3; k++) {
        float dk = r->d[k];
        if (fabsf(dk) < 1e-30f)
            dk = dk < 0 ? -1e-30f : 1e-30f;
        inv[k] = 1.0f / dk;
    }
    float mx = 0;
    for (int k = 0; k < 3; k++)
        mx += fmaxf(fabsf(w->pad_lo[k] - r->o[k]), fabsf(w->pad_hi[k] - r->o[k]));
    float len = sqrtf(r->d[0] * r->d[0] + r->d[1] * r->d[1] + r->d[2] * r->d[2]);
    float pad = mx * (1.0e-6f / fmaxf(len, 1e-30f));
    int stack[256], sp = 0, node = 0;
    wk->queries++;
    for (uint32_t steps = 0; steps < w->n_nodes; steps++) {
        wk->nodes++;
        const struct gnode *nd = &w->nodes[node];
        float tfar = any ? r->tmax : (float)h.t;
        float dn[WIDE_MAX];
        int inner[WIDE_MAX], run_first[WIDE_MAX], run_count[WIDE_MAX], n_inner = 0;
        for (int c = 0; c < nd->n; c++) {
            const float *lo = nd->lo[c], *hi = nd->hi[c];
            float a = r->tmin, b = tfar;
            for (int k = 0; k < 3; k++) {
                float t0 = (lo[k] - r->o[k]) * inv[k], t1 = (hi[k] - r->o[k]) * inv[k];
                a = fmaxf(a, fminf(t0, t1));
                b = fminf(b, fmaxf(t0, t1));
            }
            a -= fabsf(a) * 2.0e-6f + pad;
            b += fabsf(b) * 2.0e-6f + pad;
            bool in = a <= b && lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2];
            int word = nd->word[c], count = nd->count[c];
            run_first[c] = word;
            run_count[c] = in && count > 0 ? count : 0;
            inner[c] = in && count == 0 && word > 0 && (uint32_t)word < w->n_nodes ? word : -1;
            dn[c] = inner[c] >= 0 ? a : 3.0e38f;
            n_inner += inner[c] >= 0;
        }
        /* the leaf run, slot order */
        for (int c = 0; c < nd->n; c++)
            for (int k = 0; k < run_count[c]; k++) {
                uint32_t slot = (uint32_t)run_first[c] + (uint32_t)k;
                if (slot >= w->n_slots)
                    continue;
                uint32_t p = w->prims[slot];
                wk->tris++;
                for (int j = 0; j < k; j++)
                    if (w->prims[slot - (uint32_t)k + (uint32_t)j] == p) {
                        wk->repeats++;
                        break;
                    }
                double t, b1, b2;
                if (!ray_tri(m, p, od, dd, &t, &b1, &b2) || !(t > r->tmin))
                    continue;
                if (any) {
                    if (t < r->tmax) {
                        h.prim = p;
                        h.t = t;
                        wk->hits++;
                        return h;
                    }
                } else if (t < h.t || (t == h.t && p < h.prim)) {
                    h = (struct bench_hit){t, p, (float)b1, (float)b2};
                }
            }
        /* the next node: nearest inner child; the others pushed farthest
         * first (a stable sort by entry distance, as the exchange network
         * orders distinct distances) */
        int order[WIDE_MAX];
        for (int i = 0; i < nd->n; i++)
            order[i] = i;
        for (int i = 1; i < nd->n; i++)
            for (int j = i; j > 0 && dn[order[j]] < dn[order[j - 1]]; j--) {
                int s = order[j];
                order[j] = order[j - 1];
                order[j - 1] = s;
            }
        if (n_inner > 0) {
            for (int i = n_inner - 1; i >= 1; i--)
                if (sp < 256)
                    stack[sp++] = inner[order[i]];
            node = inner[order[0]];
            continue;
        }
        if (sp == 0)
            break;
        node = stack[--sp];
    }
    if (!any && h.prim != UINT32_MAX)
        wk->hits++;
    return h;
}

/* The ray generator's tracer: this walk's closest hits. */
struct walk_tracer {
    const struct wtree *w;
    const struct bench_tris *m;
};

static bool walk_trace(void *ctx, const struct bench_ray *r, uint32_t n, struct bench_hit *out)
{
    const struct walk_tracer *wt = ctx;
    struct work dummy = {0};
    for (uint32_t i = 0; i < n; i++)
        out[i] = walk(wt->w, wt->m, &r[i], false, &dummy);
    return true;
}

/* ---- figures of a tree ---- */

struct tree_figures {
    double sah_wide;        /* c_node per node entered + c_tri per triangle, / A(root) */
    double overlap;         /* mean over inner nodes of sum(child areas) / node area */
    int depth;
    uint32_t leaves, leaf_hist[CV_BVH_MAX_LEAF + 2], slots_used;
    double fill;            /* mean used slots per node */
    uint32_t dup_slots;     /* leaf slots repeating a triangle of the same leaf */
};

static struct tree_figures figures(const struct wtree *w, double c_node, double c_tri)
{
    struct tree_figures f = {0};
    float rlo[3] = {w->pad_lo[0], w->pad_lo[1], w->pad_lo[2]};
    float rhi[3] = {w->pad_hi[0], w->pad_hi[1], w->pad_hi[2]};
    double root = half_area3(rlo, rhi);
    /* node index, depth, the node's own area (its slot in the parent) */
    struct fnode { uint32_t n; int d; double a; } *st = malloc(sizeof(*st) * 4096);
    int sp = 0;
    st[sp++] = (struct fnode){0, 1, root};
    double sum = 0, ovl = 0;
    uint32_t inner_nodes = 0, used = 0;
    while (sp > 0) {
        struct fnode e = st[--sp];
        const struct gnode *nd = &w->nodes[e.n];
        if (e.d > f.depth)
            f.depth = e.d;
        sum += c_node * e.a;
        inner_nodes++;
        double kids = 0;
        for (int c = 0; c < nd->n; c++) {
            const float *lo = nd->lo[c], *hi = nd->hi[c];
            used++;
            double a = half_area3(lo, hi);
            kids += a;
            int word = nd->word[c], count = nd->count[c];
            if (count > 0) {
                sum += c_tri * a * count;
                f.leaves++;
                f.leaf_hist[count <= CV_BVH_MAX_LEAF ? count : CV_BVH_MAX_LEAF + 1]++;
                f.slots_used += (uint32_t)count;
                for (int i = 1; i < count; i++)
                    for (int j = 0; j < i; j++)
                        if ((uint32_t)(word + i) < w->n_slots &&
                            w->prims[word + i] == w->prims[word + j]) {
                            f.dup_slots++;
                            break;
                        }
            } else if (word > 0 && (uint32_t)word < w->n_nodes && sp < 4096) {
                st[sp++] = (struct fnode){(uint32_t)word, e.d + 1, a};
            }
        }
        ovl += e.a > 0 ? kids / e.a : 0;
    }
    free(st);
    f.sah_wide = root > 0 ? sum / root : 0;
    f.overlap = inner_nodes ? ovl / inner_nodes : 0;
    f.fill = inner_nodes ? (double)used / inner_nodes : 0;
    return f;
}

/* ---- the CPU reference: binned SAH, widened as the GPU widens ---- */

struct ref_params {
    double c_inner, c_tri;
    int max_leaf, bins;
    bool widen_sah;   /* widen by least node area (dynamic programming), not greedily */
};

struct bnode {
    float lo[3], hi[3];
    int32_t left, right;       /* inner: binary node indices; leaf: -1 */
    uint32_t first, count;     /* leaf: ids[first .. first+count) */
};

struct rbuild {
    const struct bench_tris *m;
    struct ref_params p;
    float (*lo)[3], (*hi)[3], (*c)[3];
    uint32_t *ids;
    struct bnode *nodes;
    uint32_t n_nodes, cap;
};

static uint32_t rnode_new(struct rbuild *b)
{
    if (b->n_nodes == b->cap) {
        b->cap = b->cap ? 2 * b->cap : 1024;
        b->nodes = realloc(b->nodes, b->cap * sizeof(*b->nodes));
    }
    return b->n_nodes++;
}

/* Builds [begin, end) into node `at` and returns its SAH cost (not
 * normalised); a subtree cheaper as one leaf is collapsed into one. */
static double rbuild(struct rbuild *b, uint32_t at, uint32_t begin, uint32_t end)
{
    uint32_t n = end - begin;
    const struct sah_ref_tris t = {(const float(*)[3])b->lo, (const float(*)[3])b->hi,
                                   (const float(*)[3])b->c};
    float lo[3], hi[3], clo[3], chi[3];
    sah_ref_bounds(&t, b->ids, begin, end, lo, hi, clo, chi);
    struct bnode *nd = &b->nodes[at];
    memcpy(nd->lo, lo, sizeof(lo));
    memcpy(nd->hi, hi, sizeof(hi));
    nd->left = nd->right = -1;
    nd->first = begin;
    nd->count = n;
    double area = half_area3(lo, hi), leaf = b->p.c_tri * area * n;
    if (n == 1)
        return leaf;
    uint32_t mid = sah_ref_split(&t, b->ids, begin, end, clo, chi, b->p.bins);
    uint32_t mark = b->n_nodes;
    uint32_t l = rnode_new(b), r = rnode_new(b);
    double split = b->p.c_inner * area + rbuild(b, l, begin, mid) + rbuild(b, r, mid, end);
    nd = &b->nodes[at];
    if ((int)n <= b->p.max_leaf && leaf <= split) {
        b->n_nodes = mark; /* the subtree goes: its nodes were the last made */
        return leaf;
    }
    nd->left = (int32_t)l;
    nd->right = (int32_t)r;
    nd->count = 0;
    return split;
}

/* Children per wide node when widening a binary tree here (--wide). */
static int wide_k = 4;

/* Opens binary node b into up to wide_k children greedily, as the
 * renderer did before least node area: the inner child of largest area,
 * ties to the leftmost. */
static int widen_kids(const struct rbuild *rb, uint32_t b, uint32_t kid[WIDE_MAX])
{
    const struct bnode *nd = &rb->nodes[b];
    kid[0] = (uint32_t)nd->left;
    kid[1] = (uint32_t)nd->right;
    int n = 2;
    for (int opened = 0; opened < wide_k - 2; opened++) {
        int best = -1;
        double best_area = -1;
        for (int c = 0; c < n; c++) {
            const struct bnode *k = &rb->nodes[kid[c]];
            double a = half_area3(k->lo, k->hi);
            if (k->left >= 0 && a > best_area) {
                best = c;
                best_area = a;
            }
        }
        if (best < 0)
            break;
        const struct bnode *o = &rb->nodes[kid[best]];
        for (int c = n; c > best + 1; c--)
            kid[c] = kid[c - 1];
        kid[best] = (uint32_t)o->left;
        kid[best + 1] = (uint32_t)o->right;
        n++;
    }
    return n;
}

/* The renderer's rule (--rewiden sah, --ref-widen sah): least summed node
 * area, by tests/bvh/widen_ref.h (a copy of glsl/bvh/widen.glsl for any
 * width). NULL: the greedy rule. */
static const struct widen_ref *widen_dp;

/* rb as widen_ref.h reads it; lo/hi and kid allocated here. */
static void widen_ref_of(const struct rbuild *rb, struct widen_ref *w)
{
    int32_t(*kid)[2] = malloc((rb->n_nodes ? rb->n_nodes : 1) * sizeof(*kid));
    float(*lo)[3] = malloc((rb->n_nodes ? rb->n_nodes : 1) * sizeof(*lo));
    float(*hi)[3] = malloc((rb->n_nodes ? rb->n_nodes : 1) * sizeof(*hi));
    for (uint32_t i = 0; i < rb->n_nodes; i++) {
        const struct bnode *nd = &rb->nodes[i];
        kid[i][0] = kid[i][1] = -1;
        memcpy(lo[i], nd->lo, sizeof(lo[i]));
        memcpy(hi[i], nd->hi, sizeof(hi[i]));
        if (nd->left < 0)
            continue;
        const struct bnode *l = &rb->nodes[nd->left], *r = &rb->nodes[nd->right];
        kid[i][0] = l->left >= 0 ? nd->left : -1;
        kid[i][1] = r->left >= 0 ? nd->right : -1;
        /* the node's box as the union of its children's, as the GPU has it */
        for (int k = 0; k < 3; k++) {
            lo[i][k] = fminf(l->lo[k], r->lo[k]);
            hi[i][k] = fmaxf(l->hi[k], r->hi[k]);
        }
    }
    *w = (struct widen_ref){.k = wide_k, .n = rb->n_nodes, .kid = (const int32_t(*)[2])kid,
                            .lo = (const float(*)[3])lo, .hi = (const float(*)[3])hi};
    widen_ref_run(w);
}

/* The children of b by the rule, as bnode indices, left to right. */
static int dp_kids(const struct rbuild *rb, uint32_t b, uint32_t *kid)
{
    uint32_t enc[WIDE_MAX];
    int n = widen_ref_kids(widen_dp, b, enc);
    for (int c = 0; c < n; c++) {
        const struct bnode *p = &rb->nodes[enc[c] / 2];
        kid[c] = (uint32_t)(enc[c] % 2 ? p->right : p->left);
    }
    return n;
}

static uint32_t wemit(const struct rbuild *rb, struct wtree *w, uint32_t b)
{
    uint32_t at = w->n_nodes++;
    uint32_t kid[WIDE_MAX];
    int n = widen_dp ? dp_kids(rb, b, kid) : widen_kids(rb, b, kid);
    struct gnode nd = {.n = n};
    for (int c = 0; c < n; c++) {
        const struct bnode *k = &rb->nodes[kid[c]];
        memcpy(nd.lo[c], k->lo, sizeof(k->lo));
        memcpy(nd.hi[c], k->hi, sizeof(k->hi));
        nd.word[c] = k->left < 0 ? (int32_t)k->first : 0;
        nd.count[c] = k->left < 0 ? (int32_t)k->count : 0;
    }
    for (int c = 0; c < n; c++)
        if (rb->nodes[kid[c]].left >= 0)
            nd.word[c] = (int32_t)wemit(rb, w, kid[c]);
    w->nodes[at] = nd;
    return at;
}

/* The wide tree of binary tree b (root 0) in w, greedily or by the DP; its
 * leaf slots are b->ids (w takes them). */
static void widen_tree(struct rbuild *b, bool dp_rule, uint32_t n_slots, struct wtree *w)
{
    memset(w, 0, sizeof(*w));
    w->nodes = malloc(sizeof(*w->nodes) * (b->n_nodes + 1));
    if (b->nodes[0].left < 0) {
        /* one leaf: a root holding it */
        struct gnode nd = {.n = 1, .count = {(int32_t)b->nodes[0].count}};
        memcpy(nd.lo[0], b->nodes[0].lo, sizeof(nd.lo[0]));
        memcpy(nd.hi[0], b->nodes[0].hi, sizeof(nd.hi[0]));
        w->nodes[0] = nd;
        w->n_nodes = 1;
    } else {
        struct widen_ref dp = {0};
        if (dp_rule) {
            widen_ref_of(b, &dp);
            widen_dp = &dp;
        }
        wemit(b, w, 0);
        widen_dp = NULL;
        widen_ref_free(&dp);
        free((void *)dp.kid);
        free((void *)dp.lo);
        free((void *)dp.hi);
    }
    w->prims = b->ids;
    b->ids = NULL;
    w->n_slots = n_slots;
    wtree_finish(w);
}

/* The renderer's binary tree (CvBvhNode, glsl/shared/bvh.h) as bnodes:
 * its inner nodes keep their indices, each leaf child becomes a node of
 * its own after them. */
static void binary_from_gpu(const CvBvhNode *bin, uint32_t n_bin, uint32_t *prims,
                            struct rbuild *b)
{
    memset(b, 0, sizeof(*b));
    b->cap = 2 * n_bin + 2;
    b->nodes = calloc(b->cap, sizeof(*b->nodes));
    b->n_nodes = n_bin;
    for (uint32_t i = 0; i < n_bin; i++) {
        const CvBvhNode *nd = &bin[i];
        const cv_vec4 *box[2][2] = {{&nd->lmin, &nd->lmax}, {&nd->rmin, &nd->rmax}};
        int32_t child[2];
        float ulo[3] = {INFINITY, INFINITY, INFINITY}, uhi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int c = 0; c < 2; c++) {
            int32_t word, count;
            memcpy(&word, &box[c][0]->w, 4);
            memcpy(&count, &box[c][1]->w, 4);
            const float lo[3] = {box[c][0]->x, box[c][0]->y, box[c][0]->z};
            const float hi[3] = {box[c][1]->x, box[c][1]->y, box[c][1]->z};
            for (int k = 0; k < 3; k++) {
                ulo[k] = fminf(ulo[k], lo[k]);
                uhi[k] = fmaxf(uhi[k], hi[k]);
            }
            if (count > 0) {
                uint32_t l = rnode_new(b);
                struct bnode *ln = &b->nodes[l];
                memcpy(ln->lo, lo, sizeof(lo));
                memcpy(ln->hi, hi, sizeof(hi));
                ln->left = ln->right = -1;
                ln->first = (uint32_t)word;
                ln->count = (uint32_t)count;
                child[c] = (int32_t)l;
            } else {
                child[c] = word;
                memcpy(b->nodes[word].lo, lo, sizeof(lo));
                memcpy(b->nodes[word].hi, hi, sizeof(hi));
            }
        }
        b->nodes[i].left = child[0];
        b->nodes[i].right = child[1];
        b->nodes[i].count = 0;
        if (i == 0) {
            memcpy(b->nodes[0].lo, ulo, sizeof(ulo));
            memcpy(b->nodes[0].hi, uhi, sizeof(uhi));
        }
    }
    b->ids = prims;
}

/* A CPU-built tree over m; returns the binary SAH cost (normalised). */
static double ref_tree(const struct bench_tris *m, struct ref_params p, struct wtree *w)
{
    struct rbuild b = {.m = m, .p = p};
    uint32_t n = m->n;
    b.lo = malloc(n * sizeof(*b.lo));
    b.hi = malloc(n * sizeof(*b.hi));
    b.c = malloc(n * sizeof(*b.c));
    b.ids = malloc(n * sizeof(*b.ids));
    for (uint32_t t = 0; t < n; t++) {
        double q[3][3];
        bench_tri_pos(m, t, q);
        for (int k = 0; k < 3; k++) {
            b.lo[t][k] = (float)fmin(q[0][k], fmin(q[1][k], q[2][k]));
            b.hi[t][k] = (float)fmax(q[0][k], fmax(q[1][k], q[2][k]));
            b.c[t][k] = (float)((q[0][k] + q[1][k] + q[2][k]) / 3.0);
        }
        b.ids[t] = t;
    }
    uint32_t root = rnode_new(&b);
    double cost = rbuild(&b, root, 0, n) / half_area3(b.nodes[0].lo, b.nodes[0].hi);
    widen_tree(&b, p.widen_sah, n, w);
    free(b.lo);
    free(b.hi);
    free(b.c);
    free(b.nodes);
    return cost;
}

/* ---- report ---- */

static int tail_n;             /* --tail: how many of the costliest queries to list */
static const double *tail_cost;
static int cmp_by_cost(const void *a, const void *b)
{
    double x = tail_cost[*(const uint32_t *)a], y = tail_cost[*(const uint32_t *)b];
    return (x < y) - (x > y);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

struct costs {
    double c_node, c_tri;
};

static double report_tree(const char *label, const struct wtree *w, double sah_bin,
                          double c_inner, double c_leaf, const struct bench_rayset sets[BENCH_Q_TYPES],
                          const struct bench_tris *m, struct costs cm)
{
    struct tree_figures f = figures(w, cm.c_node, cm.c_tri);
    printf("%s: %u nodes, depth %d, %.2f children per node, %u leaves, %.2f slots per "
           "leaf, %u slots (%.3f per triangle)\n",
           label, w->n_nodes, f.depth, f.fill, f.leaves,
           f.leaves ? (double)f.slots_used / f.leaves : 0, w->n_slots,
           (double)w->n_slots / (m->n ? m->n : 1));
    printf("  SAH binary %.3f (c_inner %g, c_tri %g), wide %.3f (c_node %g, c_tri %g); child "
           "area / node area %.3f\n",
           sah_bin, c_inner, c_leaf, f.sah_wide, cm.c_node, cm.c_tri,
           f.overlap);
    printf("  leaf slots repeating a triangle of their leaf: %u\n", f.dup_slots);
    printf("  leaf sizes:");
    for (int k = 1; k <= CV_BVH_MAX_LEAF + 1; k++)
        if (f.leaf_hist[k])
            printf(" %d:%.1f%%", k, 100.0 * f.leaf_hist[k] / f.leaves);
    printf("\n");
    double total_cost = 0, total_q = 0, all_nodes = 0, all_tris = 0, all_warp = 0,
           all_repeats = 0;
    printf("  %-8s %8s %9s %9s %8s %9s %9s %9s\n", "query", "rays", "nodes", "tris", "hit%", "cost",
           "p99 cost", "warp max");
    for (int q = 0; q < BENCH_Q_TYPES; q++) {
        struct work wk = {0};
        double *per = malloc(sizeof(double) * (sets[q].n + 1)), warp = 0, wmax = 0;
        for (uint32_t i = 0; i < sets[q].n; i++) {
            struct work one = {0};
            walk(w, m, &sets[q].r[i], q == BENCH_Q_SHADOW, &one);
            wk.nodes += one.nodes;
            wk.tris += one.tris;
            wk.hits += one.hits;
            wk.repeats += one.repeats;
            wk.queries++;
            per[i] = cm.c_node * one.nodes + cm.c_tri * one.tris;
            /* SIMT lanes wait for the slowest of 32 neighbours (rays in
             * pixel order, as the renderer's queues roughly keep them) */
            wmax = fmax(wmax, per[i]);
            if (i % 32 == 31 || i + 1 == sets[q].n) {
                warp += wmax * (i % 32 + 1);
                wmax = 0;
            }
        }
        if (tail_n > 0) {
            /* the costliest queries of this set, for a look at why */
            uint32_t *idx = malloc(sizeof(uint32_t) * (sets[q].n + 1));
            for (uint32_t i = 0; i < sets[q].n; i++)
                idx[i] = i;
            tail_cost = per;
            qsort(idx, sets[q].n, sizeof(uint32_t), cmp_by_cost);
            for (uint32_t j = 0; j < sets[q].n && j < (uint32_t)tail_n; j++) {
                const struct bench_ray *r = &sets[q].r[idx[j]];
                struct work one = {0};
                struct bench_hit h = walk(w, m, r, q == BENCH_Q_SHADOW, &one);
                printf("    %s #%u: %llu nodes, %llu triangles, o (%g %g %g) d (%g %g %g) "
                       "tmax %g, hit %s t %g prim %d\n",
                       bench_q_names[q], idx[j], (unsigned long long)one.nodes,
                       (unsigned long long)one.tris, r->o[0], r->o[1], r->o[2], r->d[0], r->d[1],
                       r->d[2], r->tmax, h.prim == UINT32_MAX ? "none" : "yes", h.t,
                       h.prim == UINT32_MAX ? -1 : (int)h.prim);
            }
            free(idx);
        }
        qsort(per, sets[q].n, sizeof(double), cmp_double);
        double nq = wk.queries ? (double)wk.queries : 1;
        double cost = (cm.c_node * wk.nodes + cm.c_tri * wk.tris) / nq;
        printf("  %-8s %8u %9.2f %9.2f %7.1f%% %9.2f %9.2f %9.2f\n", bench_q_names[q], sets[q].n,
               wk.nodes / nq, wk.tris / nq, 100.0 * wk.hits / nq, cost,
               sets[q].n ? per[(size_t)(sets[q].n * 0.99)] : 0, warp / nq);
        free(per);
        all_warp += warp;
        total_cost += cost * wk.queries;
        all_nodes += wk.nodes;
        all_tris += wk.tris;
        all_repeats += wk.repeats;
        total_q += wk.queries;
    }
    double mean = total_q ? total_cost / total_q : 0;
    printf("  all queries: %.3f nodes, %.3f triangles, cost %.3f per query, warp max %.3f\n",
           total_q ? all_nodes / total_q : 0, total_q ? all_tris / total_q : 0, mean,
           total_q ? all_warp / total_q : 0);
    printf("  triangle tests repeating one of the same leaf: %.3f per query (%.1f%% of tests)\n",
           total_q ? all_repeats / total_q : 0, all_tris ? 100.0 * all_repeats / all_tris : 0);
    return mean;
}

/* The camera rays through the GPU's traversal (rays_test.comp): the hits
 * and the nodes visited (closest + any per ray) must equal this walk's. */
static bool verify(struct cv_gpu *gpu, struct cv_bvh *bvh, GLuint vb, GLuint tb,
                   const struct wtree *w, const struct bench_tris *m, const struct bench_rayset *cam)
{
    struct cv_error err = {{0}};
    uint32_t n = cam->n;
    GLuint rb = cv_buffer_create((size_t)n * 32, cam->r, "rays", &err);
    GLuint res = rb ? cv_buffer_create((size_t)n * 16, NULL, "ray results", &err) : 0;
    const char *defs[2] = {cv_bvh_stack_define(bvh), NULL};
    struct cv_program *prog = res ? cv_program_get(gpu, "bvh/rays_test.comp", defs, &err) : NULL;
    uint32_t *got = malloc((size_t)n * 16);
    bool ok = prog != NULL;
    if (ok) {
        cv_buffer_bind(vb, CV_BIND_VERTICES);
        cv_buffer_bind(tb, CV_BIND_TRIANGLES);
        cv_bvh_bind(bvh);
        cv_buffer_bind(rb, CV_BIND_PROBE_IN);
        cv_buffer_bind(res, CV_BIND_PROBE_OUT);
        cv_program_set_uint(prog, "u_n_rays", n);
        cv_program_set_uint(prog, "u_n_tris", m->n);
        cv_program_dispatch_1d(prog, n);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        ok = cv_buffer_read(res, 0, (size_t)n * 16, got, &err);
    }
    if (!ok) {
        fprintf(stderr, "bvh_work: verify: %s\n", err.msg);
    } else {
        uint64_t gpu_steps = 0, cpu_steps = 0;
        uint32_t differ = 0, steps_differ = 0;
        for (uint32_t i = 0; i < n; i++) {
            struct work wk = {0};
            struct bench_hit h = walk(w, m, &cam->r[i], false, &wk);
            walk(w, m, &cam->r[i], true, &wk);
            gpu_steps += got[4 * i + 3];
            cpu_steps += wk.nodes;
            differ += got[4 * i + 1] != h.prim;
            steps_differ += got[4 * i + 3] != wk.nodes;
        }
        printf("verify: %u camera rays; GPU traversal %.3f nodes per ray (both queries), this "
               "walk %.3f; %u rays with other node counts, %u with another hit\n",
               n, (double)gpu_steps / n, (double)cpu_steps / n, steps_differ, differ);
        /* grazing rays may take another neighbour (double precision here) */
        ok = differ <= n / 200 + 1 && steps_differ <= n / 50 + 1;
    }
    free(got);
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&res);
    return ok;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s SCENE.pbrt [--res N] [--seed S] [--ref] [--verify] "
                        "[--rounds R] [--split F] [--treelet S] [--c-node X] [--c-tri Y] "
                        "[--ref-inner X] [--ref-tri Y] [--ref-leaf N] [--ref-bins B]\n",
                argv[0]);
        return 2;
    }
    const char *path = argv[1];
    int res = 64;
    bool ref = false, do_verify = false, rewiden = false, rewiden_dp = false;
    uint64_t seed = 1;
    struct cv_bvh_params params = cv_knobs_from_environment().bvh;
    /* A 4-wide node fetch (128 bytes, four slab tests, the ordering)
     * against one triangle test (48 bytes, the watertight test). */
    struct costs cm = {.c_node = 1.0, .c_tri = 0.5};
    struct ref_params rp = {.c_inner = CV_BVH_COST_INNER, .c_tri = CV_BVH_COST_TRI,
                            .max_leaf = CV_BVH_MAX_LEAF, .bins = 32, .widen_sah = true};
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--ref"))
            ref = true;
        else if (!strcmp(a, "--verify"))
            do_verify = true;
        else if (v && !strcmp(a, "--res"))
            res = atoi(argv[++i]);
        else if (v && !strcmp(a, "--rewiden") && (!strcmp(v, "sah") || !strcmp(v, "greedy"))) {
            rewiden = params.keep_binary = true;
            rewiden_dp = !strcmp(argv[++i], "sah");
        } else if (v && !strcmp(a, "--wide"))
            wide_k = atoi(argv[++i]);
        else if (v && !strcmp(a, "--tail"))
            tail_n = atoi(argv[++i]);
        else if (v && !strcmp(a, "--seed"))
            seed = strtoull(argv[++i], NULL, 10);
        else if (v && !strcmp(a, "--rounds"))
            params.treelet_rounds = atoi(argv[++i]);
        else if (v && !strcmp(a, "--split"))
            params.split_budget = (float)atof(argv[++i]);
        else if (v && !strcmp(a, "--treelet"))
            params.treelet_size = atoi(argv[++i]);
        else if (v && !strcmp(a, "--c-node"))
            cm.c_node = atof(argv[++i]);
        else if (v && !strcmp(a, "--c-tri"))
            cm.c_tri = atof(argv[++i]);
        else if (v && !strcmp(a, "--ref-inner"))
            rp.c_inner = atof(argv[++i]);
        else if (v && !strcmp(a, "--ref-tri"))
            rp.c_tri = atof(argv[++i]);
        else if (v && !strcmp(a, "--ref-leaf"))
            rp.max_leaf = atoi(argv[++i]);
        else if (v && !strcmp(a, "--ref-widen") && (!strcmp(v, "sah") || !strcmp(v, "greedy")))
            rp.widen_sah = !strcmp(argv[++i], "sah");
        else if (v && !strcmp(a, "--ref-bins"))
            rp.bins = atoi(argv[++i]);
        else {
            fprintf(stderr, "bvh_work: unknown argument %s\n", a);
            return 2;
        }
    }
    if (res < 1 || res > 4096 || wide_k < 2 || wide_k > WIDE_MAX || rp.max_leaf < 1 || rp.max_leaf > CV_BVH_MAX_LEAF ||
        rp.bins < 2 || rp.bins > 4096) {
        fprintf(stderr, "bvh_work: --res 1..4096, --wide 2..%d, --ref-leaf 1..%d, --ref-bins "
                "2..4096\n", WIDE_MAX, CV_BVH_MAX_LEAF);
        return 2;
    }
    struct cv_error err = {{0}};
    struct bench_scene_tree tree;
    if (!bench_scene_tree_open(path, &params, &tree, &err)) {
        fprintf(stderr, "bvh_work: %s\n", err.msg);
        return 1;
    }
    struct cv_scene *sc = tree.sc;
    struct bench_tris m = tree.m;
    struct cv_gpu *gpu = tree.gpu;
    GLuint vb = tree.vb, tb = tree.tb;
    struct cv_bvh *bvh = tree.bvh;
    const struct cv_bvh_stats *st = cv_bvh_stats(bvh);
    struct wtree gw = {.n_nodes = st->n_nodes, .n_slots = st->n_refs};
    CvBvhNode4 *n4 = malloc((size_t)gw.n_nodes * sizeof(CvBvhNode4));
    CvBvhNode *bin = rewiden ? malloc((size_t)st->n_binary_nodes * sizeof(CvBvhNode)) : NULL;
    gw.nodes = malloc((size_t)gw.n_nodes * sizeof(*gw.nodes));
    gw.prims = malloc((size_t)gw.n_slots * 4);
    if (!cv_buffer_read(cv_bvh_nodes_buffer(bvh), 0, (size_t)gw.n_nodes * sizeof(CvBvhNode4),
                        n4, &err) ||
        !cv_buffer_read(cv_bvh_prims_buffer(bvh), 0, (size_t)gw.n_slots * 4, gw.prims, &err) ||
        (bin && !cv_buffer_read(cv_bvh_binary_nodes_buffer(bvh), 0,
                                (size_t)st->n_binary_nodes * sizeof(CvBvhNode), bin, &err))) {
        fprintf(stderr, "bvh_work: reading the tree back: %s\n", err.msg);
        return 1;
    }
    for (uint32_t i = 0; i < gw.n_nodes; i++)
        gnode_from4(&n4[i], &gw.nodes[i]);
    free(n4);
    wtree_finish(&gw);

    struct walk_tracer wt = {&gw, &m};
    struct bench_rayset sets[BENCH_Q_TYPES] = {{0}};
    bench_rays_make(&(struct bench_rays_params){.sc = sc, .m = &m, .res = res, .seed = seed,
                                                .trace = walk_trace, .ctx = &wt},
                    sets);

    /* why a scene is expensive: how much larger a triangle's box is than
     * the triangle (long thin triangles across the axes) */
    double ratio_sum = 0, box_sum = 0, tri_sum = 0;
    for (uint32_t t = 0; t < m.n; t++) {
        double q[3][3];
        bench_tri_pos(&m, t, q);
        float lo[3], hi[3];
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) {
            lo[k] = (float)fmin(q[0][k], fmin(q[1][k], q[2][k]));
            hi[k] = (float)fmax(q[0][k], fmax(q[1][k], q[2][k]));
            e1[k] = q[1][k] - q[0][k];
            e2[k] = q[2][k] - q[0][k];
        }
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        double ta = 0.5 * sqrt(cx * cx + cy * cy + cz * cz), ba = half_area3(lo, hi);
        box_sum += ba;
        tri_sum += ta;
        ratio_sum += ta > 0 ? fmin(ba / ta, 1e3) : 1e3;
    }
    printf("%s: %u static triangles, %u lights; rays from a %d-wide camera grid, seed %llu; cost "
           "= %g * nodes + %g * triangles\n",
           path, m.n, sc->n_lights, res, (unsigned long long)seed, cm.c_node, cm.c_tri);
    printf("  triangle box half-area / triangle area: mean %.2f, area-weighted %.2f\n",
           ratio_sum / m.n, tri_sum > 0 ? box_sum / tri_sum : 0);
    char label[160];
    snprintf(label, sizeof(label), "GPU tree (rounds %d, treelet %d, split %g)",
             params.treelet_rounds, params.treelet_size, params.split_budget);
    double gpu_cost = report_tree(label, &gw, st->sah_cost, CV_BVH_COST_INNER,
                                  CV_BVH_COST_TRI, sets, &m, cm);
    int status = 0;
    if (do_verify && !verify(gpu, bvh, vb, tb, &gw, &m, &sets[BENCH_Q_CAMERA]))
        status = 1;
    if (bin) {
        /* the renderer's binary tree widened here: --wide 4 sah must
         * give the renderer's own tree, figures and all */
        struct rbuild b;
        uint32_t *prims = malloc((size_t)gw.n_slots * 4);
        memcpy(prims, gw.prims, (size_t)gw.n_slots * 4);
        binary_from_gpu(bin, st->n_binary_nodes, prims, &b);
        struct wtree xw;
        widen_tree(&b, rewiden_dp, gw.n_slots, &xw);
        free(b.nodes);
        snprintf(label, sizeof(label), "GPU binary tree widened here (%d-wide, %s)", wide_k,
                 rewiden_dp ? "least node area" : "greedily");
        report_tree(label, &xw, st->sah_cost, CV_BVH_COST_INNER, CV_BVH_COST_TRI, sets, &m, cm);
        wtree_free(&xw);
        free(bin);
    }
    if (ref) {
        struct wtree rw;
        double rsah = ref_tree(&m, rp, &rw);
        snprintf(label, sizeof(label),
                 "CPU binned SAH (%d bins, c_inner %g, c_tri %g, leaves up to %d, widened %s)",
                 rp.bins, rp.c_inner, rp.c_tri, rp.max_leaf, rp.widen_sah ? "by DP" : "greedily");
        double ref_cost = report_tree(label, &rw, rsah, rp.c_inner, rp.c_tri, sets, &m, cm);
        printf("  GPU tree / CPU tree: %.3f of the cost per query\n",
               ref_cost > 0 ? gpu_cost / ref_cost : 0);
        wtree_free(&rw);
    }
    bench_rays_free(sets);
    wtree_free(&gw);
    bench_scene_tree_close(&tree);
    return status;
}
