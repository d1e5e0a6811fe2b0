/* motion_bvh.c: the moving shapes' trees (motion_bvh.h). */
#include "bvh/motion_bvh.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "bvh/median_split.h"
#include "glsl/shared/bvh.h"

/* vec4s of a shape's record (glsl/bvh/motion.glsl) */
#define GROUP_VEC4 11

struct out {
    float *v;        /* vec4s */
    size_t n, cap;   /* in vec4s */
};

static float *grow(struct out *o, size_t n_vec4)
{
    o->v = cv_xgrow(o->v, &o->cap, 4 * (o->n + n_vec4), sizeof(float));
    float *p = o->v + 4 * o->n;
    memset(p, 0, n_vec4 * 4 * sizeof(float));
    o->n += n_vec4;
    return p;
}

struct tree {
    struct out *o;
    const float (*lo)[3], (*hi)[3];
    uint32_t *order;   /* items, reordered into leaf order */
    uint32_t leaf;     /* most items a leaf */
    uint32_t n_nodes;  /* nodes so far (all trees) */
};

static void set_child(struct tree *t, uint32_t node, int side, const float lo[3], const float hi[3],
                      int32_t word, int32_t count)
{
    float *v = t->o->v + 4 * (1 + 4 * (size_t)node + 2 * side);
    memcpy(v, lo, 3 * sizeof(float));
    memcpy(&v[3], &word, 4);
    memcpy(&v[4], hi, 3 * sizeof(float));
    memcpy(&v[7], &count, 4);
}

/* Fills node `node` over order[first..+count): a median split of the
 * items' centres along their widest axis. Leaf words are item positions
 * in order[] plus `base`. */
static void build_node(struct tree *t, uint32_t node, uint32_t first, uint32_t count, uint32_t base)
{
    uint32_t half[2] = {count / 2, count - count / 2};
    if (count > 1) {
        cv_median_split(t->order + first, count, t->lo, t->hi);
    } else {
        half[0] = count;
        half[1] = 0;
    }
    uint32_t start = first;
    for (int side = 0; side < 2; side++) {
        uint32_t c = half[side];
        if (c == 0) {
            float e[3] = {CV_BVH_EMPTY, CV_BVH_EMPTY, CV_BVH_EMPTY},
                  f[3] = {-CV_BVH_EMPTY, -CV_BVH_EMPTY, -CV_BVH_EMPTY};
            set_child(t, node, side, e, f, 0, 0);
            continue;
        }
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (uint32_t k = start; k < start + c; k++)
            for (int a = 0; a < 3; a++) {
                lo[a] = fminf(lo[a], t->lo[t->order[k]][a]);
                hi[a] = fmaxf(hi[a], t->hi[t->order[k]][a]);
            }
        if (c <= t->leaf) {
            set_child(t, node, side, lo, hi, (int32_t)(base + start), (int32_t)c);
        } else {
            uint32_t child = t->n_nodes++;
            grow(t->o, 4);
            set_child(t, node, side, lo, hi, (int32_t)child, 0);
            build_node(t, child, start, c, base);
        }
        start += c;
    }
}

/* A tree over n >= 1 boxes from a new root node; returns the root. */
static uint32_t build_tree(struct out *o, uint32_t *n_nodes, const float (*lo)[3], const float (*hi)[3],
                           uint32_t n, uint32_t leaf, uint32_t *order, uint32_t base)
{
    struct tree t = {o, lo, hi, order, leaf, *n_nodes};
    uint32_t root = t.n_nodes++;
    grow(o, 4);
    for (uint32_t i = 0; i < n; i++)
        order[i] = i;
    build_node(&t, root, 0, n, base);
    *n_nodes = t.n_nodes;
    return root;
}

static void put3(float *v, const double x[3], double w)
{
    v[0] = (float)x[0];
    v[1] = (float)x[1];
    v[2] = (float)x[2];
    v[3] = (float)w;
}

float *cv_motion_bvh_pack(const struct cv_scene *s, size_t *n_vec4)
{
    uint32_t ng = s->n_motions, n_nodes = 0;
    struct out o = {0};
    grow(&o, 1); /* the header, filled last */
    /* the top tree: one shape a leaf, its word the shape's index */
    float(*glo)[3] = cv_xcalloc(ng, sizeof(*glo)), (*ghi)[3] = cv_xcalloc(ng, sizeof(*ghi));
    for (uint32_t g = 0; g < ng; g++) {
        memcpy(glo[g], s->motions[g].lo, sizeof(glo[g]));
        memcpy(ghi[g], s->motions[g].hi, sizeof(ghi[g]));
    }
    uint32_t *gorder = cv_xcalloc(ng, sizeof(uint32_t));
    build_tree(&o, &n_nodes, (const float(*)[3])glo, (const float(*)[3])ghi, ng, 1, gorder, 0);
    /* top leaves hold positions in gorder: make them shape indices */
    for (uint32_t k = 0; k < n_nodes; k++)
        for (int side = 0; side < 2; side++) {
            float *v = o.v + 4 * (1 + 4 * (size_t)k + 2 * side);
            int32_t word, count;
            memcpy(&word, &v[3], 4);
            memcpy(&count, &v[7], 4);
            if (count > 0) {
                int32_t g = (int32_t)gorder[word];
                memcpy(&v[3], &g, 4);
            }
        }
    free(glo);
    free(ghi);
    free(gorder);
    /* each shape's tree over its object-space triangles; leaf words are
     * triangle slots, counted over all shapes */
    uint32_t *roots = cv_xcalloc(ng, sizeof(uint32_t));
    uint32_t **orders = cv_xcalloc(ng, sizeof(uint32_t *));
    uint32_t n_slots = 0;
    for (uint32_t g = 0; g < ng; g++) {
        const struct cv_motion *m = &s->motions[g];
        float(*lo)[3] = cv_xcalloc(m->count, sizeof(*lo)), (*hi)[3] = cv_xcalloc(m->count, sizeof(*hi));
        for (uint32_t i = 0; i < m->count; i++) {
            const CvTriangle *t = &s->triangles[m->first + i];
            const uint32_t idx[3] = {t->idx.x, t->idx.y, t->idx.z};
            for (int a = 0; a < 3; a++) {
                lo[i][a] = INFINITY;
                hi[i][a] = -INFINITY;
                for (int k = 0; k < 3; k++) {
                    float p = (&s->vertices[idx[k]].pos_u.x)[a];
                    lo[i][a] = fminf(lo[i][a], p);
                    hi[i][a] = fmaxf(hi[i][a], p);
                }
            }
        }
        orders[g] = cv_xcalloc(m->count, sizeof(uint32_t));
        roots[g] = build_tree(&o, &n_nodes, (const float(*)[3])lo, (const float(*)[3])hi, m->count,
                              CV_MOTION_LEAF, orders[g], n_slots);
        n_slots += m->count;
        free(lo);
        free(hi);
    }
    uint32_t group_base = (uint32_t)o.n;
    for (uint32_t g = 0; g < ng; g++) {
        const struct cv_animated *a = &s->motions[g].xf;
        float *v = grow(&o, GROUP_VEC4);
        for (int e = 0; e < 2; e++) {
            float *w = v + 4 * 5 * e;
            put3(w, a->T[e], e ? a->t1 : a->t0);
            for (int i = 0; i < 4; i++)
                w[4 + i] = (float)a->q[e][i];
            for (int r = 0; r < 3; r++)
                put3(w + 8 + 4 * r, a->S[e][r], 0);
        }
        uint32_t info[4] = {roots[g], s->motions[g].first, s->motions[g].count, 0};
        memcpy(v + 4 * 10, info, sizeof(info));
    }
    uint32_t tri_base = (uint32_t)o.n;
    for (uint32_t g = 0; g < ng; g++) {
        const struct cv_motion *m = &s->motions[g];
        for (uint32_t k = 0; k < m->count; k++) {
            uint32_t prim = m->first + orders[g][k];
            const CvTriangle *t = &s->triangles[prim];
            const uint32_t idx[3] = {t->idx.x, t->idx.y, t->idx.z};
            float *v = grow(&o, 3);
            for (int c = 0; c < 3; c++)
                memcpy(v + 4 * c, &s->vertices[idx[c]].pos_u, 3 * sizeof(float));
            memcpy(&v[3], &prim, 4);
        }
        free(orders[g]);
    }
    uint32_t hdr[4] = {ng, group_base, tri_base, cv_scene_static_triangles(s)};
    memcpy(o.v, hdr, sizeof(hdr));
    free(orders);
    free(roots);
    *n_vec4 = o.n;
    return o.v;
}
