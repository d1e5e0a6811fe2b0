/* bvh_test_util.h: for the BVH test and benchmark. Generated meshes (fixed
 * seeds) uploaded as CvVertex/CvTriangle buffers, the SAH cost of a tree
 * read back from the GPU, and a CPU binned-SAH reference builder that exists
 * only to judge the GPU tree. */
#ifndef CV_TESTS_BVH_UTIL_H
#define CV_TESTS_BVH_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/bvh.h"
#include "glsl/shared/scene.h"
#include "bvh/bvh.h"
#include "gpu/buffer.h"
#include "tests/bvh/sah_ref.h"
#include "tests/bvh/widen_ref.h"

struct mesh {
    CvVertex *v;
    CvTriangle *t;
    uint32_t nv, nt;
};

static uint64_t mesh_rng = 88172645463325252ull;
static inline double mesh_rand(void)
{
    mesh_rng ^= mesh_rng << 13;
    mesh_rng ^= mesh_rng >> 7;
    mesh_rng ^= mesh_rng << 17;
    return (double)(mesh_rng >> 11) * (1.0 / 9007199254740992.0);
}

static inline void mesh_alloc(struct mesh *m, uint32_t nv, uint32_t nt)
{
    m->v = calloc(nv ? nv : 1, sizeof(CvVertex));
    m->t = calloc(nt ? nt : 1, sizeof(CvTriangle));
    m->nv = nv;
    m->nt = nt;
}

static inline void mesh_free(struct mesh *m)
{
    free(m->v);
    free(m->t);
    memset(m, 0, sizeof(*m));
}

static inline void set_v(struct mesh *m, uint32_t i, double x, double y, double z)
{
    m->v[i].pos_u = (cv_vec4){(float)x, (float)y, (float)z, 0};
}

/* Triangle soup of varied sizes: a uniform part and a few dense clusters. */
static inline void mesh_soup(struct mesh *m, uint32_t n)
{
    mesh_alloc(m, 3 * n, n);
    double cl[8][3];
    for (int c = 0; c < 8; c++)
        for (int k = 0; k < 3; k++)
            cl[c][k] = mesh_rand() * 100.0;
    for (uint32_t i = 0; i < n; i++) {
        double c[3], size;
        if (mesh_rand() < 0.5) {
            for (int k = 0; k < 3; k++)
                c[k] = mesh_rand() * 100.0;
            size = mesh_rand() < 0.05 ? 5.0 + mesh_rand() * 10.0 : 0.2 + mesh_rand();
        } else {
            int q = (int)(mesh_rand() * 8);
            for (int k = 0; k < 3; k++)
                c[k] = cl[q][k] + (mesh_rand() - 0.5) * 4.0;
            size = 0.02 + mesh_rand() * 0.1;
        }
        for (int j = 0; j < 3; j++)
            set_v(m, 3 * i + j, c[0] + (mesh_rand() - 0.5) * size, c[1] + (mesh_rand() - 0.5) * size,
                  c[2] + (mesh_rand() - 0.5) * size);
        m->t[i].idx = (cv_uvec4){3 * i, 3 * i + 1, 3 * i + 2, 0};
    }
}

/* A closed-ish bumpy height field: k x k quads sharing edges and vertices. */
static inline void mesh_grid(struct mesh *m, uint32_t k)
{
    mesh_alloc(m, (k + 1) * (k + 1), 2 * k * k);
    for (uint32_t y = 0; y <= k; y++)
        for (uint32_t x = 0; x <= k; x++)
            set_v(m, y * (k + 1) + x, x, y, 2.0 * sin(x * 0.4) * cos(y * 0.3));
    uint32_t t = 0;
    for (uint32_t y = 0; y < k; y++)
        for (uint32_t x = 0; x < k; x++) {
            uint32_t a = y * (k + 1) + x, b = a + 1, c = a + k + 1, d = c + 1;
            m->t[t++].idx = (cv_uvec4){a, b, d, 0};
            m->t[t++].idx = (cv_uvec4){a, d, c, 0};
        }
}

/* Degenerate: every triangle in the plane z = 0, most of them copies of a
 * few (equal centroids, equal Morton codes), some large and overlapping. */
static inline void mesh_planar(struct mesh *m, uint32_t n)
{
    mesh_alloc(m, 3 * n, n);
    for (uint32_t i = 0; i < n; i++) {
        double cx, cy, s;
        if (i % 10 < 7) {
            uint32_t q = (i * 2654435761u) % 23u;
            cx = (q % 5) * 3.0;
            cy = (q / 5) * 3.0;
            s = 1.0;
        } else {
            cx = mesh_rand() * 12.0;
            cy = mesh_rand() * 12.0;
            s = 0.5 + mesh_rand() * 6.0;
        }
        set_v(m, 3 * i, cx - s, cy - s, 0);
        set_v(m, 3 * i + 1, cx + s, cy - 0.5 * s, 0);
        set_v(m, 3 * i + 2, cx, cy + s, 0);
        m->t[i].idx = (cv_uvec4){3 * i, 3 * i + 1, 3 * i + 2, 0};
    }
}

/* Long thin triangles, as lamp shades are made of: open cones of `seg`
 * slivers from apex to rim, of random size, some upright (axis y), some
 * tilted; their boxes overlap the cone's inside, which splitting is for. */
static inline void mesh_cones(struct mesh *m, uint32_t cones, uint32_t seg)
{
    mesh_alloc(m, cones * (seg + 1), cones * seg);
    for (uint32_t c = 0; c < cones; c++) {
        double ctr[3] = {mesh_rand() * 20.0, mesh_rand() * 20.0, mesh_rand() * 20.0};
        double r = 0.5 + mesh_rand() * 3.0, h = 2.0 + mesh_rand() * 6.0;
        double tilt = c % 3 == 0 ? mesh_rand() * 1.2 : 0.0, turn = mesh_rand() * 6.283185307;
        /* axis (sin tilt cos turn, cos tilt, sin tilt sin turn) and two
         * unit vectors across it */
        double ax[3] = {sin(tilt) * cos(turn), cos(tilt), sin(tilt) * sin(turn)};
        double u[3] = {cos(tilt) * cos(turn), -sin(tilt), cos(tilt) * sin(turn)};
        double w[3] = {ax[1] * u[2] - ax[2] * u[1], ax[2] * u[0] - ax[0] * u[2],
                       ax[0] * u[1] - ax[1] * u[0]};
        uint32_t v0 = c * (seg + 1);
        set_v(m, v0, ctr[0] + h * ax[0], ctr[1] + h * ax[1], ctr[2] + h * ax[2]);
        for (uint32_t i = 0; i < seg; i++) {
            double a = 6.283185307 * i / seg, ca = r * cos(a), sa = r * sin(a);
            set_v(m, v0 + 1 + i, ctr[0] + ca * u[0] + sa * w[0], ctr[1] + ca * u[1] + sa * w[1],
                  ctr[2] + ca * u[2] + sa * w[2]);
        }
        for (uint32_t i = 0; i < seg; i++)
            m->t[c * seg + i].idx =
                (cv_uvec4){v0, v0 + 1 + i, v0 + 1 + (i + 1) % seg, 0};
    }
}

/* Degenerate and thin at once: flat fans of `seg` slivers around a centre,
 * all in the plane z = 0, every other one an exact copy of the one before
 * (equal centroids and Morton codes). */
static inline void mesh_fans(struct mesh *m, uint32_t fans, uint32_t seg)
{
    mesh_alloc(m, fans * (seg + 1), fans * seg);
    double cx = 0, cy = 0, r = 1;
    for (uint32_t f = 0; f < fans; f++) {
        if (f % 2 == 0) {
            cx = mesh_rand() * 20.0;
            cy = mesh_rand() * 20.0;
            r = 0.5 + mesh_rand() * 4.0;
        }
        uint32_t v0 = f * (seg + 1);
        set_v(m, v0, cx, cy, 0);
        for (uint32_t i = 0; i < seg; i++)
            set_v(m, v0 + 1 + i, cx + r * cos(6.283185307 * i / seg),
                  cy + r * sin(6.283185307 * i / seg), 0);
        for (uint32_t i = 0; i < seg; i++)
            m->t[f * seg + i].idx = (cv_uvec4){v0, v0 + 1 + i, v0 + 1 + (i + 1) % seg, 0};
    }
}

/* Deep on purpose: `clusters` clusters of `per` small triangles along the
 * x axis at geometrically shrinking distances (cluster i at ratio^i, its
 * size in proportion), each cluster two halves either side of the axis.
 * SAH wants each cluster peeled off in turn with both halves kept as inner
 * nodes, so the tree is about as deep as there are clusters and a query
 * down it pushes several siblings per level. */
static inline void mesh_geometric(struct mesh *m, uint32_t clusters, uint32_t per, double ratio)
{
    mesh_alloc(m, 3 * clusters * per, clusters * per);
    uint32_t t = 0;
    for (uint32_t i = 0; i < clusters; i++) {
        double c = pow(ratio, i);
        for (uint32_t j = 0; j < per; j++, t++) {
            double y = (j & 1) ? 0.3 * c : -0.3 * c;
            for (uint32_t k = 0; k < 3; k++)
                set_v(m, 3 * t + k, c + 0.05 * c * (mesh_rand() - 0.5),
                      y + 0.05 * c * (mesh_rand() - 0.5), 0.05 * c * (mesh_rand() - 0.5));
            m->t[t].idx = (cv_uvec4){3 * t, 3 * t + 1, 3 * t + 2, 0};
        }
    }
}

static inline bool mesh_upload(const struct mesh *m, GLuint *vb, GLuint *tb, struct cv_error *err)
{
    /* An empty mesh still binds: one zeroed element each. */
    *vb = cv_buffer_create((m->nv ? m->nv : 1) * sizeof(CvVertex), m->nv ? m->v : NULL,
                           "test vertices", err);
    *tb = *vb ? cv_buffer_create((m->nt ? m->nt : 1) * sizeof(CvTriangle), m->nt ? m->t : NULL,
                                 "test triangles", err)
              : 0;
    return *tb != 0;
}

static inline void tri_box(const struct mesh *m, uint32_t t, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    const uint32_t *ix = &m->t[t].idx.x;
    for (int j = 0; j < 3; j++) {
        const float *p = &m->v[ix[j]].pos_u.x;
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], p[k]);
            hi[k] = fmaxf(hi[k], p[k]);
        }
    }
}

/* ---- CPU binned SAH reference (same costs and leaf limit as the GPU) ---- */

struct ref_ctx {
    const struct mesh *m;
    float (*lo)[3], (*hi)[3], (*c)[3];
    uint32_t *ids;
};

#define REF_BINS 32

static double ref_build(struct ref_ctx *r, uint32_t begin, uint32_t end)
{
    uint32_t n = end - begin;
    const struct sah_ref_tris t = {(const float(*)[3])r->lo, (const float(*)[3])r->hi,
                                   (const float(*)[3])r->c};
    float lo[3], hi[3], clo[3], chi[3];
    sah_ref_bounds(&t, r->ids, begin, end, lo, hi, clo, chi);
    double area = half_area3(lo, hi);
    double leaf = CV_BVH_COST_TRI * area * n;
    if (n == 1)
        return leaf;
    uint32_t mid = sah_ref_split(&t, r->ids, begin, end, clo, chi, REF_BINS);
    double split = CV_BVH_COST_INNER * area + ref_build(r, begin, mid) + ref_build(r, mid, end);
    return n <= CV_BVH_MAX_LEAF && leaf <= split ? leaf : split;
}

/* SAH cost (normalised by the root area) of a binned-SAH build. */
static inline double ref_sah(const struct mesh *m)
{
    struct ref_ctx r = {.m = m};
    uint32_t n = m->nt;
    r.lo = malloc(n * sizeof(*r.lo));
    r.hi = malloc(n * sizeof(*r.hi));
    r.c = malloc(n * sizeof(*r.c));
    r.ids = malloc(n * sizeof(*r.ids));
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t t = 0; t < n; t++) {
        tri_box(m, t, r.lo[t], r.hi[t]);
        const uint32_t *ix = &m->t[t].idx.x;
        for (int k = 0; k < 3; k++) {
            r.c[t][k] = ((&m->v[ix[0]].pos_u.x)[k] + (&m->v[ix[1]].pos_u.x)[k] +
                         (&m->v[ix[2]].pos_u.x)[k]) / 3.0f;
            lo[k] = fminf(lo[k], r.lo[t][k]);
            hi[k] = fmaxf(hi[k], r.hi[t][k]);
        }
        r.ids[t] = t;
    }
    double cost = ref_build(&r, 0, n) / half_area3(lo, hi);
    free(r.lo);
    free(r.hi);
    free(r.c);
    free(r.ids);
    return cost;
}

/* ---- reading a GPU tree back ---- */

struct tree_info {
    bool ok;
    double sah;        /* of the binary tree */
    int depth;         /* of the binary tree */
    int wide_depth;    /* of the 4-wide tree */
    int stack_need;    /* most traversal stack entries a query can need in it */
    char why[256];
};

static inline bool box_in(const float *lo, const float *hi, const float *plo, const float *phi)
{
    for (int k = 0; k < 3; k++)
        if (lo[k] < plo[k] || hi[k] > phi[k])
            return false;
    return true;
}

/* Whether boxes[0..nb) (min xyz, max xyz) together cover triangle t:
 * every point of a barycentric grid of `grid` steps per edge (vertices and
 * edge points included) lies in one of them. Points are taken in double
 * precision and clamped to the triangle's box, where exact ones lie. */
static inline bool tri_covered(const struct mesh *m, uint32_t t, const float (*boxes)[6],
                               uint32_t nb, int grid, double *miss)
{
    float tlo[3], thi[3];
    tri_box(m, t, tlo, thi);
    const uint32_t *ix = &m->t[t].idx.x;
    for (int i = 0; i <= grid; i++)
        for (int j = 0; i + j <= grid; j++) {
            double b1 = (double)i / grid, b2 = (double)j / grid, p[3];
            for (int k = 0; k < 3; k++) {
                p[k] = (1 - b1 - b2) * (&m->v[ix[0]].pos_u.x)[k] + b1 * (&m->v[ix[1]].pos_u.x)[k] +
                       b2 * (&m->v[ix[2]].pos_u.x)[k];
                p[k] = p[k] < tlo[k] ? tlo[k] : p[k] > thi[k] ? thi[k] : p[k];
            }
            bool in = false;
            for (uint32_t b = 0; b < nb && !in; b++)
                in = p[0] >= boxes[b][0] && p[1] >= boxes[b][1] && p[2] >= boxes[b][2] &&
                     p[0] <= boxes[b][3] && p[1] <= boxes[b][4] && p[2] <= boxes[b][5];
            if (!in) {
                memcpy(miss, p, sizeof(p));
                return false;
            }
        }
    return true;
}

/* Reads the binary tree back (built with params.keep_binary) and checks:
 * every leaf slot used once and every triangle in exactly one slot (with
 * triangle splitting, in at least one, and the boxes of its leaves covering
 * it), every node reached exactly once from the root, every child box
 * inside its parent's (a triangle's box inside its leaf's, unless split),
 * and the nodes in left-first depth-first order (an inner left child right
 * after its parent, an inner right child right after the parent's left
 * subtree: what glsl/bvh/layout.comp promises). Also returns the depth and
 * the SAH cost of what was read, and each leaf by its first slot:
 * leaf_count[s] (0 where no leaf starts) and leaf_box[s] (ns + 1 each). */
static inline struct tree_info check_binary(const struct mesh *m, const struct cv_bvh *bvh,
                                            int32_t *leaf_count, float (*leaf_box)[6])
{
    struct tree_info ti = {.ok = true};
    struct cv_error err = {{0}};
    const struct cv_bvh_stats *st = cv_bvh_stats(bvh);
    uint32_t nn = st->n_binary_nodes, n = m->nt, ns = st->n_refs;
    bool split = ns != n;
    CvBvhNode *nodes = malloc((size_t)nn * sizeof(*nodes));
    uint32_t *prims = malloc((ns ? ns : 1) * 4);
    uint32_t *stack = malloc(256 * 4), *depth_of = malloc(256 * 4);
    uint32_t *visits = calloc(nn, 4), *slot_seen = calloc(ns + 1, 4), *prim_seen = calloc(n + 1, 4);
    float (*slot_box)[6] = calloc(ns + 1, sizeof(*slot_box));
    if (ns < n) {
        snprintf(ti.why, sizeof(ti.why), "%u leaf slots for %u triangles", ns, n);
        ti.ok = false;
        goto out;
    }
    if (!cv_bvh_binary_nodes_buffer(bvh)) {
        snprintf(ti.why, sizeof(ti.why), "the binary tree was not kept");
        ti.ok = false;
        goto out;
    }
    if (!cv_buffer_read(cv_bvh_binary_nodes_buffer(bvh), 0, (size_t)nn * sizeof(*nodes), nodes,
                        &err) ||
        !cv_buffer_read(cv_bvh_prims_buffer(bvh), 0, (ns ? ns : 1) * 4, prims, &err)) {
        snprintf(ti.why, sizeof(ti.why), "read back: %.200s", err.msg);
        ti.ok = false;
        goto out;
    }
    int sp = 0;
    stack[sp] = 0;
    depth_of[sp++] = 1;
    visits[0] = 1;
    /* Children are pushed right first, so nodes pop in preorder: each
     * popped node must be the next index. */
    uint32_t next_pre = 0;
    double sum = 0, root_area = 0;
    while (sp > 0 && ti.ok) {
        sp--;
        uint32_t ni = stack[sp], d = depth_of[sp];
        if (ni != next_pre++) {
            snprintf(ti.why, sizeof(ti.why), "node %u is not in depth-first order (expected %u)",
                     ni, next_pre - 1);
            ti.ok = false;
            break;
        }
        if ((int)d > ti.depth)
            ti.depth = (int)d;
        const CvBvhNode *nd = &nodes[ni];
        const cv_vec4 *cb[2][2] = {{&nd->lmin, &nd->lmax}, {&nd->rmin, &nd->rmax}};
        float cbox[2][2][3];
        for (int c = 0; c < 2; c++)
            for (int e = 0; e < 2; e++)
                memcpy(cbox[c][e], cb[c][e], sizeof(cbox[c][e]));
        float ulo[3], uhi[3];
        for (int k = 0; k < 3; k++) {
            ulo[k] = fminf(cbox[0][0][k], cbox[1][0][k]);
            uhi[k] = fmaxf(cbox[0][1][k], cbox[1][1][k]);
        }
        if (ni == 0)
            root_area = half_area3(ulo, uhi);
        sum += CV_BVH_COST_INNER * half_area3(ulo, uhi);
        for (int c = 1; c >= 0 && ti.ok; c--) {
            const float *lo = cbox[c][0], *hi = cbox[c][1];
            int32_t word, count;
            memcpy(&word, &cb[c][0]->w, 4);
            memcpy(&count, &cb[c][1]->w, 4);
            if (count > 0) {
                if (word < 0 || (uint32_t)word + (uint32_t)count > ns) {
                    snprintf(ti.why, sizeof(ti.why), "node %u: leaf range %d+%d out of %u", ni,
                             word, count, ns);
                    ti.ok = false;
                    break;
                }
                if (n >= 2)
                    sum += CV_BVH_COST_TRI * half_area3(lo, hi) * count;
                leaf_count[word] = count;
                memcpy(leaf_box[word], lo, 12);
                memcpy(leaf_box[word] + 3, hi, 12);
                for (int32_t s = word; s < word + count; s++) {
                    slot_seen[s]++;
                    memcpy(slot_box[s], lo, 12);
                    memcpy(slot_box[s] + 3, hi, 12);
                    uint32_t p = prims[s];
                    if (p >= n) {
                        snprintf(ti.why, sizeof(ti.why), "slot %d holds %u", s, p);
                        ti.ok = false;
                        break;
                    }
                    prim_seen[p]++;
                    float tlo[3], thi[3];
                    tri_box(m, p, tlo, thi);
                    if (!split && !box_in(tlo, thi, lo, hi)) {
                        snprintf(ti.why, sizeof(ti.why), "triangle %u outside its leaf box", p);
                        ti.ok = false;
                    }
                }
            } else if (count == 0 && n < 2 && lo[0] > hi[0]) {
                /* the empty child of a trivial tree */
            } else {
                if (count < 0 || word <= 0 || (uint32_t)word >= nn) {
                    snprintf(ti.why, sizeof(ti.why), "node %u: child %d count %d", ni, word, count);
                    ti.ok = false;
                    break;
                }
                if (visits[word]++) {
                    snprintf(ti.why, sizeof(ti.why), "node %d reached twice", word);
                    ti.ok = false;
                    break;
                }
                const CvBvhNode *ch = &nodes[word];
                float b[4][3];
                memcpy(b[0], &ch->lmin, 12);
                memcpy(b[1], &ch->lmax, 12);
                memcpy(b[2], &ch->rmin, 12);
                memcpy(b[3], &ch->rmax, 12);
                if (!box_in(b[0], b[1], lo, hi) || !box_in(b[2], b[3], lo, hi)) {
                    snprintf(ti.why, sizeof(ti.why), "node %d: a child box leaves the parent's", word);
                    ti.ok = false;
                    break;
                }
                if (sp >= 256) {
                    snprintf(ti.why, sizeof(ti.why), "deeper than 256");
                    ti.ok = false;
                    break;
                }
                stack[sp] = (uint32_t)word;
                depth_of[sp++] = d + 1;
            }
        }
    }
    for (uint32_t i = 0; ti.ok && i < nn; i++)
        if (visits[i] != 1) {
            snprintf(ti.why, sizeof(ti.why), "node %u reached %u times", i, visits[i]);
            ti.ok = false;
        }
    for (uint32_t i = 0; ti.ok && i < ns; i++)
        if (slot_seen[i] != 1) {
            snprintf(ti.why, sizeof(ti.why), "slot %u used %u times", i, slot_seen[i]);
            ti.ok = false;
        }
    for (uint32_t i = 0; ti.ok && i < n; i++)
        if (split ? prim_seen[i] == 0 : prim_seen[i] != 1) {
            snprintf(ti.why, sizeof(ti.why), "triangle %u in %u leaf slots", i, prim_seen[i]);
            ti.ok = false;
        }
    if (ti.ok && split) {
        /* Each triangle's leaf boxes, gathered by triangle, must cover it. */
        uint32_t *first = calloc(n + 1, 4);
        float (*by_tri)[6] = malloc((ns ? ns : 1) * sizeof(*by_tri));
        for (uint32_t t = 0; t < n; t++)
            first[t + 1] = first[t] + prim_seen[t];
        for (uint32_t s = 0; s < ns; s++)
            memcpy(by_tri[first[prims[s]] + --prim_seen[prims[s]]], slot_box[s], sizeof(*by_tri));
        for (uint32_t t = 0; ti.ok && t < n; t++) {
            double p[3];
            if (!tri_covered(m, t, by_tri + first[t], first[t + 1] - first[t], 8, p)) {
                snprintf(ti.why, sizeof(ti.why),
                         "triangle %u: point (%g %g %g) outside its %u leaves' boxes", t, p[0],
                         p[1], p[2], first[t + 1] - first[t]);
                ti.ok = false;
            }
        }
        free(first);
        free(by_tri);
    }
    ti.sah = root_area > 0 ? sum / root_area : 0;
out:
    free(stack);
    free(depth_of);
    free(nodes);
    free(prims);
    free(visits);
    free(slot_seen);
    free(prim_seen);
    free(slot_box);
    return ti;
}

/* The box of 4-wide slot c: min xyz, max xyz. */
static inline void wide_box(const CvBvhNode4 *nd, int c, float box[6])
{
    const cv_vec4 *v[6] = {&nd->lox, &nd->loy, &nd->loz, &nd->hix, &nd->hiy, &nd->hiz};
    for (int k = 0; k < 6; k++)
        box[k] = (&v[k]->x)[c];
}

static inline bool wide_slot_unused(const CvBvhNode4 *nd, int c)
{
    float box[6];
    wide_box(nd, c, box);
    const float e = (float)CV_BVH_EMPTY;
    return (&nd->word.x)[c] == 0 && (&nd->count.x)[c] == 0 && box[0] == e && box[1] == e &&
           box[2] == e && box[3] == -e && box[4] == -e && box[5] == -e;
}

/* Reads the 4-wide tree back and checks it against the binary tree's
 * leaves from check_binary: every node reached once from the root, in
 * depth-first preorder with children in slot order; used slots first and
 * unused ones exactly as glsl/shared/bvh.h has them; every leaf child one
 * of the binary tree's leaves (its first slot, count and box, bit for bit),
 * every slot in one leaf, so the two trees hold the same leaves; every inner
 * child's box the union of its own children's; at least two children per
 * node (widening by least node area may leave a node with an inner child
 * fewer than four, glsl/bvh/widen.glsl). Sets ti->wide_depth. */
static inline void check_wide(const struct mesh *m, const struct cv_bvh *bvh,
                              const int32_t *leaf_count, const float (*leaf_box)[6],
                              struct tree_info *ti)
{
    struct cv_error err = {{0}};
    const struct cv_bvh_stats *st = cv_bvh_stats(bvh);
    uint32_t nn = st->n_nodes, ns = st->n_refs, n = m->nt;
    CvBvhNode4 *nodes = malloc((size_t)(nn ? nn : 1) * sizeof(*nodes));
    uint32_t *visits = calloc(nn + 1, 4), *slot_seen = calloc(ns + 1, 4);
    uint32_t *stack = malloc(4 * 256 * 4), *depth_of = malloc(4 * 256 * 4);
    int *need_of = malloc(4 * 256 * sizeof(int));
    if (nn == 0 || nn > st->n_binary_nodes) {
        snprintf(ti->why, sizeof(ti->why), "%u wide nodes for %u binary ones", nn,
                 st->n_binary_nodes);
        ti->ok = false;
        goto out;
    }
    if (!cv_buffer_read(cv_bvh_nodes_buffer(bvh), 0, (size_t)nn * sizeof(*nodes), nodes, &err)) {
        snprintf(ti->why, sizeof(ti->why), "read back: %.200s", err.msg);
        ti->ok = false;
        goto out;
    }
    int sp = 0;
    stack[sp] = 0;
    need_of[sp] = 0;
    depth_of[sp++] = 1;
    visits[0] = 1;
    uint32_t next_pre = 0;
    while (sp > 0 && ti->ok) {
        sp--;
        uint32_t ni = stack[sp], d = depth_of[sp];
        int need = need_of[sp];
        const CvBvhNode4 *nd = &nodes[ni];
        if (ni != next_pre++) {
            snprintf(ti->why, sizeof(ti->why), "wide node %u is not in preorder (expected %u)", ni,
                     next_pre - 1);
            ti->ok = false;
            break;
        }
        if ((int)d > ti->wide_depth)
            ti->wide_depth = (int)d;
        int used = 0, inner = 0;
        while (used < 4 && !wide_slot_unused(nd, used))
            used++;
        for (int c = 0; c < 4; c++) {
            inner += c < used && (&nd->count.x)[c] == 0;
            if (c >= used && !wide_slot_unused(nd, c)) {
                snprintf(ti->why, sizeof(ti->why), "wide node %u: slot %d used after an unused one",
                         ni, c);
                ti->ok = false;
            }
        }
        /* Traversal pushes all entered inner children but one. */
        int below = need + (inner > 1 ? inner - 1 : 0);
        if (below > ti->stack_need)
            ti->stack_need = below;
        int want = n >= 2 ? 2 : (int)n;
        if (ti->ok && used < want) {
            snprintf(ti->why, sizeof(ti->why), "wide node %u: %d children, %d inner", ni, used,
                     inner);
            ti->ok = false;
        }
        for (int c = used - 1; c >= 0 && ti->ok; c--) {
            float box[6];
            wide_box(nd, c, box);
            int32_t word = (&nd->word.x)[c], count = (&nd->count.x)[c];
            if (count > 0) {
                if (word < 0 || (uint32_t)word + (uint32_t)count > ns ||
                    leaf_count[word] != count || memcmp(box, leaf_box[word], sizeof(box)) != 0) {
                    snprintf(ti->why, sizeof(ti->why),
                             "wide node %u slot %d: leaf %d+%d is not a leaf of the binary tree",
                             ni, c, word, count);
                    ti->ok = false;
                    break;
                }
                for (int32_t k = word; k < word + count; k++)
                    slot_seen[k]++;
                continue;
            }
            if (count < 0 || word <= 0 || (uint32_t)word >= nn || visits[word]++) {
                snprintf(ti->why, sizeof(ti->why), "wide node %u slot %d: child %d count %d%s", ni,
                         c, word, count,
                         word > 0 && (uint32_t)word < nn && visits[word] > 1 ? " reached twice" : "");
                ti->ok = false;
                break;
            }
            float u[6] = {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
            for (int g = 0; g < 4; g++) {
                if (wide_slot_unused(&nodes[word], g))
                    continue;
                float cb[6];
                wide_box(&nodes[word], g, cb);
                for (int k = 0; k < 3; k++) {
                    u[k] = fminf(u[k], cb[k]);
                    u[3 + k] = fmaxf(u[3 + k], cb[3 + k]);
                }
            }
            if (memcmp(u, box, sizeof(u)) != 0) {
                snprintf(ti->why, sizeof(ti->why),
                         "wide node %d: its children's boxes do not make up its box", word);
                ti->ok = false;
                break;
            }
            if (sp >= 4 * 256) {
                snprintf(ti->why, sizeof(ti->why), "wide tree deeper than 256");
                ti->ok = false;
                break;
            }
            stack[sp] = (uint32_t)word;
            need_of[sp] = below;
            depth_of[sp++] = d + 1;
        }
    }
    for (uint32_t i = 0; ti->ok && i < nn; i++)
        if (visits[i] != 1) {
            snprintf(ti->why, sizeof(ti->why), "wide node %u reached %u times", i, visits[i]);
            ti->ok = false;
        }
    for (uint32_t i = 0; ti->ok && i < ns; i++)
        if (slot_seen[i] != 1) {
            snprintf(ti->why, sizeof(ti->why), "slot %u in %u leaves of the wide tree", i,
                     slot_seen[i]);
            ti->ok = false;
        }
out:
    free(nodes);
    free(visits);
    free(slot_seen);
    free(stack);
    free(depth_of);
    free(need_of);
}

/* Whether the 4-wide tree is the binary tree widened by the renderer's
 * rule, as tests/bvh/widen_ref.h (its CPU copy) widens it: from the root,
 * each wide node's children are the reference's, slot for slot (leaves
 * by first slot and count, inner children by the wide node they lead to),
 * and every wide node is reached. */
static inline void check_widening(const struct cv_bvh *bvh, struct tree_info *ti)
{
    struct cv_error err = {{0}};
    const struct cv_bvh_stats *st = cv_bvh_stats(bvh);
    uint32_t nn = st->n_binary_nodes, nw = st->n_nodes, top = 0, reached = 0;
    CvBvhNode *bin = malloc((size_t)(nn ? nn : 1) * sizeof(*bin));
    CvBvhNode4 *wide = malloc((size_t)(nw ? nw : 1) * sizeof(*wide));
    int32_t(*kid)[2] = malloc((size_t)(nn ? nn : 1) * sizeof(*kid));
    float(*lo)[3] = malloc((size_t)(nn ? nn : 1) * sizeof(*lo));
    float(*hi)[3] = malloc((size_t)(nn ? nn : 1) * sizeof(*hi));
    uint32_t(*stack)[2] = malloc((size_t)(nw + 1) * sizeof(*stack));
    struct widen_ref w = {.k = 4, .n = nn, .kid = (const int32_t(*)[2])kid,
                          .lo = (const float(*)[3])lo, .hi = (const float(*)[3])hi};
    if (!cv_buffer_read(cv_bvh_binary_nodes_buffer(bvh), 0, (size_t)nn * sizeof(*bin), bin, &err) ||
        !cv_buffer_read(cv_bvh_nodes_buffer(bvh), 0, (size_t)nw * sizeof(*wide), wide, &err)) {
        snprintf(ti->why, sizeof(ti->why), "read back: %.200s", err.msg);
        ti->ok = false;
        goto out;
    }
    for (uint32_t i = 0; i < nn; i++) {
        const cv_vec4 *b[2][2] = {{&bin[i].lmin, &bin[i].lmax}, {&bin[i].rmin, &bin[i].rmax}};
        for (int side = 0; side < 2; side++) {
            int32_t word, count;
            memcpy(&word, &b[side][0]->w, 4);
            memcpy(&count, &b[side][1]->w, 4);
            kid[i][side] = count == 0 && word > 0 && (uint32_t)word < nn ? word : -1;
        }
        for (int k = 0; k < 3; k++) {
            lo[i][k] = fminf((&b[0][0]->x)[k], (&b[1][0]->x)[k]);
            hi[i][k] = fmaxf((&b[0][1]->x)[k], (&b[1][1]->x)[k]);
        }
    }
    widen_ref_run(&w);
    stack[top][0] = 0;
    stack[top++][1] = 0;
    while (top > 0 && ti->ok) {
        top--;
        uint32_t wi = stack[top][0], bi = stack[top][1];
        if (wi >= nw || bi >= nn) {
            snprintf(ti->why, sizeof(ti->why), "widening: wide node %u for binary %u", wi, bi);
            ti->ok = false;
            break;
        }
        reached++;
        uint32_t enc[4];
        int n = widen_ref_kids(&w, bi, enc), used = 0;
        const CvBvhNode4 *nd = &wide[wi];
        for (int c = 0; c < n && ti->ok; c++) {
            const CvBvhNode *p = &bin[enc[c] / 2];
            bool right = enc[c] % 2;
            const cv_vec4 *cmin = right ? &p->rmin : &p->lmin, *cmax = right ? &p->rmax : &p->lmax;
            int32_t word, count;
            memcpy(&word, &cmin->w, 4);
            memcpy(&count, &cmax->w, 4);
            bool inner = count == 0 && word > 0 && (uint32_t)word < nn;
            if (count <= 0 && !inner)
                continue; /* an empty child (0 or 1 triangles): no slot */
            int32_t ww = (&nd->word.x)[used], wc = (&nd->count.x)[used];
            if (inner ? wc != 0 : (wc != count || ww != word)) {
                snprintf(ti->why, sizeof(ti->why),
                         "widening: wide node %u slot %d is %d+%d, the rule's child %s %d+%d", wi,
                         used, ww, wc, inner ? "inner" : "leaf", word, count);
                ti->ok = false;
            } else if (inner && top < nw) {
                stack[top][0] = (uint32_t)ww;
                stack[top++][1] = (uint32_t)word;
            }
            used++;
        }
        if (ti->ok && used < 4 && !wide_slot_unused(nd, used)) {
            snprintf(ti->why, sizeof(ti->why),
                     "widening: wide node %u has more than the rule's %d children", wi, used);
            ti->ok = false;
        }
    }
    if (ti->ok && reached != nw) {
        snprintf(ti->why, sizeof(ti->why), "widening: the rule reaches %u of %u wide nodes",
                 reached, nw);
        ti->ok = false;
    }
out:
    widen_ref_free(&w);
    free(bin);
    free(wide);
    free(kid);
    free(lo);
    free(hi);
    free(stack);
}

/* check_binary, then check_wide against its leaves and check_widening: the
 * tree must have been built with params.keep_binary. */
static inline struct tree_info check_tree(const struct mesh *m, const struct cv_bvh *bvh)
{
    uint32_t ns = cv_bvh_stats(bvh)->n_refs;
    int32_t *leaf_count = calloc(ns + 1, sizeof(*leaf_count));
    float (*leaf_box)[6] = calloc(ns + 1, sizeof(*leaf_box));
    struct tree_info ti = check_binary(m, bvh, leaf_count, leaf_box);
    if (ti.ok)
        check_wide(m, bvh, leaf_count, (const float (*)[6])leaf_box, &ti);
    if (ti.ok)
        check_widening(bvh, &ti);
    free(leaf_count);
    free(leaf_box);
    return ti;
}

/* ---- rays ---- */

/* Rays (origin, tmin), (direction, tmax) for rays_test.comp: random
 * directions from around the mesh, rays aimed into random triangles or at
 * their vertices, axis-aligned rays, and short finite segments. */
static inline void make_rays(const struct mesh *m, float *rays, uint32_t n)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t i = 0; i < m->nv; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], (&m->v[i].pos_u.x)[k]);
            hi[k] = fmaxf(hi[k], (&m->v[i].pos_u.x)[k]);
        }
    float ext = 0;
    for (int k = 0; k < 3; k++)
        ext = fmaxf(ext, hi[k] - lo[k]);
    ext = fmaxf(ext, 1.0f);
    for (uint32_t i = 0; i < n; i++) {
        float *o = &rays[8 * i], *d = &rays[8 * i + 4];
        for (int k = 0; k < 3; k++)
            o[k] = lo[k] - 0.2f * ext + (float)mesh_rand() * ((hi[k] - lo[k]) + 0.4f * ext);
        o[3] = 0.0f;
        d[3] = 1.0e30f;
        int kind = (int)(mesh_rand() * 5);
        if ((kind == 1 || kind == 2) && m->nt > 0) {
            const uint32_t *ix = &m->t[(uint32_t)(mesh_rand() * m->nt) % m->nt].idx.x;
            float target[3];
            double b1 = mesh_rand(), b2 = mesh_rand();
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            if (kind == 2) {
                b1 = mesh_rand() < 0.5 ? 1 : 0;
                b2 = b1 > 0 ? 0 : (mesh_rand() < 0.5 ? 1 : 0);
            }
            for (int k = 0; k < 3; k++)
                target[k] = (float)((1 - b1 - b2) * (&m->v[ix[0]].pos_u.x)[k] +
                                    b1 * (&m->v[ix[1]].pos_u.x)[k] + b2 * (&m->v[ix[2]].pos_u.x)[k]);
            for (int k = 0; k < 3; k++)
                d[k] = target[k] - o[k];
        } else if (kind == 3) {
            d[0] = d[1] = d[2] = 0.0f;
            d[(int)(mesh_rand() * 3) % 3] = mesh_rand() < 0.5 ? -1.0f : 1.0f;
        } else {
            do {
                for (int k = 0; k < 3; k++)
                    d[k] = (float)(mesh_rand() * 2 - 1);
            } while (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] > 1 ||
                     d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-4);
            if (kind == 4) {
                o[3] = (float)mesh_rand() * 0.1f * ext;
                d[3] = (float)mesh_rand() * 2.0f * ext;
            }
        }
    }
}

/* Rays from one origin, each aimed at a random point of a random triangle
 * (tmin 0, tmax 1e30): rays that enter every box between the origin and
 * their triangle. */
static inline void make_rays_from(const struct mesh *m, const float from[3], float *rays,
                                  uint32_t n)
{
    for (uint32_t i = 0; i < n && m->nt > 0; i++) {
        float *o = &rays[8 * i], *d = &rays[8 * i + 4];
        const uint32_t *ix = &m->t[(uint32_t)(mesh_rand() * m->nt) % m->nt].idx.x;
        double b1 = mesh_rand(), b2 = mesh_rand();
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        for (int k = 0; k < 3; k++) {
            o[k] = from[k];
            d[k] = (float)((1 - b1 - b2) * (&m->v[ix[0]].pos_u.x)[k] +
                           b1 * (&m->v[ix[1]].pos_u.x)[k] + b2 * (&m->v[ix[2]].pos_u.x)[k]) -
                   from[k];
        }
        o[3] = 0.0f;
        d[3] = 1.0e30f;
    }
}

#endif
