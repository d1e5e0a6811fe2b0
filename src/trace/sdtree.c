/* sdtree.c: see sdtree.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/rlpath.h"
#include "glsl/shared/sdtree.h"
#include "trace/sdtree.h"

const struct cv_sdtree_opts cv_sdtree_defaults = {
    .mix = CV_RL_DEFAULT_MIX,   /* the Q-table's: 0.5 measured worse (bench/RESULTS.md) */
    .split_c = 8.0f,
    .rho = 0.01f,
    /* the records of a llvmpipe-sized image are few: quadrants split on a
     * handful of bright samples sent guided directions after noise
     * (bench/RESULTS.md, "sdtree guide") */
    .min_split = 64,
    .max_depth = CV_SD_MAX_DEPTH,
    .floor = 0.3f,
    .min_records = 32,
};

struct snode {
    uint32_t axis;    /* 0..2, or 3: leaf */
    float split;
    uint32_t child;   /* inner: first child; leaf: its index among the leaves */
};

struct cnode {
    uint32_t quad;    /* quadtree root node */
    float weight;
};

struct qnode {
    float p[4];
    uint32_t child[4];   /* quadtree node, 0: leaf quadrant (the root is never a child) */
};

struct build {
    const struct cv_sdtree_opts *o;
    double thresh;
    struct snode *s;
    size_t ns, cs;
    struct qnode *q;
    size_t nq, cq;
    struct cnode *c;   /* CV_SD_CLASSES per leaf */
    size_t nc, cc;
    struct cv_sdtree_stats st;
};

/* What a record adds to its quadtree: the Monte Carlo estimate of the
 * integral of the incident radiance times the cosine to its class's axis
 * (the normal of a wall that faces the axis) over directions; the guide
 * then stands for the diffuse integrand, not the radiance alone, which
 * sends samples to grazing and back-facing directions. Computed once per
 * record (cv_sdtree_build keeps it in pdf, the class in beta): the tree
 * levels sum it again at every depth. */
static double rec_value(const struct cv_sd_record *r, int cls)
{
    double z = 2.0 * r->u - 1, phi = 2 * M_PI * r->v - M_PI, s = sqrt(fmax(0, 1 - z * z));
    double w[3] = {s * cos(phi), s * sin(phi), z};
    double c = w[cls / 2] * (cls & 1 ? -1 : 1);
    return c > 0 ? (double)r->L / r->pdf * c : 0;
}

static uint32_t push_s(struct build *b)
{
    if (b->ns == b->cs) {
        b->cs = b->cs ? 2 * b->cs : 64;
        b->s = cv_xrealloc(b->s, b->cs * sizeof(*b->s));
    }
    memset(&b->s[b->ns], 0, sizeof(*b->s));
    return (uint32_t)b->ns++;
}

static uint32_t push_q(struct build *b)
{
    if (b->nq == b->cq) {
        b->cq = b->cq ? 2 * b->cq : 256;
        b->q = cv_xrealloc(b->q, b->cq * sizeof(*b->q));
    }
    memset(&b->q[b->nq], 0, sizeof(*b->q));
    return (uint32_t)b->nq++;
}

/* Moves the records with key(r) below `at` to the front; returns their
 * count. key: coordinate k of the position (0..2), u (3), v (4) or the
 * class (5). */
static size_t partition(struct cv_sd_record *r, size_t n, int key, double at)
{
    size_t i = 0, j = n;
    while (i < j) {
        const struct cv_sd_record *x = &r[i];
        double c = key < 3 ? x->p[key] : key == 3 ? x->u : key == 4 ? x->v : x->beta;
        if (c < at) {
            i++;
        } else {
            struct cv_sd_record t = r[i];
            r[i] = r[--j];
            r[j] = t;
        }
    }
    return i;
}

/* The quadtree node over the square [u0, u0 + side) x [v0, v0 + side) at
 * depth, from its n records; E: the leaf's energy, fe: the floor's energy
 * per unit area of the square. */
static uint32_t build_quad(struct build *b, struct cv_sd_record *r, size_t n, double u0,
                           double v0, double side, uint32_t depth, double E, double fe)
{
    uint32_t node = push_q(b);
    if (depth + 1 > b->st.max_quad_depth)
        b->st.max_quad_depth = depth + 1;
    double h = side / 2;
    size_t nl = partition(r, n, 3, u0 + h);
    size_t nll = partition(r, nl, 4, v0 + h);
    size_t nrl = partition(r + nl, n - nl, 4, v0 + h);
    /* quadrant k = ix + 2 iy: its first record and count */
    size_t first[4] = {0, nl, nll, nl + nrl};
    size_t cnt[4] = {nll, nrl, nl - nll, n - nl - nrl};
    double e[4], w[4], sum = 0;
    for (int k = 0; k < 4; k++) {
        e[k] = 0;
        for (size_t i = 0; i < cnt[k]; i++)
            e[k] += r[first[k] + i].pdf;
        w[k] = e[k] + fe * h * h;
        sum += w[k];
    }
    for (int k = 0; k < 4; k++)
        b->q[node].p[k] = sum > 0 ? (float)(w[k] / sum) : 0.25f;
    for (int k = 0; k < 4; k++) {
        if (depth + 1 < b->o->max_depth && E > 0 && e[k] > b->o->rho * E &&
            cnt[k] >= b->o->min_split) {
            uint32_t c = build_quad(b, r + first[k], cnt[k], u0 + h * (k & 1), v0 + h * (k >> 1),
                                    h, depth + 1, E, fe);
            b->q[node].child[k] = c;
        }
    }
    return node;
}

static void build_spatial(struct build *b, uint32_t node, struct cv_sd_record *r, size_t n,
                          const double lo[3], const double hi[3], uint32_t depth)
{
    if ((double)n > b->thresh && depth < CV_SD_MAX_SPATIAL_DEPTH) {
        int axis = (int)(depth % 3);
        double mid = 0.5 * (lo[axis] + hi[axis]);
        size_t m = partition(r, n, axis, (float)mid);
        uint32_t c = push_s(b);
        push_s(b);
        b->s[node].axis = (uint32_t)axis;
        b->s[node].split = (float)mid;
        b->s[node].child = c;
        double l[3], h[3];
        memcpy(l, lo, sizeof(l));
        memcpy(h, hi, sizeof(h));
        h[axis] = mid;
        build_spatial(b, c, r, m, l, h, depth + 1);
        h[axis] = hi[axis];
        l[axis] = mid;
        build_spatial(b, c + 1, r + m, n - m, l, h, depth + 1);
        return;
    }
    uint32_t leaf = (uint32_t)(b->nc / CV_SD_CLASSES);
    b->s[node].axis = 3;
    b->s[node].child = leaf;
    b->st.spatial_leaves++;
    if (b->nc + CV_SD_CLASSES > b->cc) {
        b->cc = b->cc ? 2 * b->cc : 64 * CV_SD_CLASSES;
        b->c = cv_xrealloc(b->c, b->cc * sizeof(*b->c));
    }
    b->nc += CV_SD_CLASSES;
    /* one quadtree per orientation class, from that class's records */
    for (uint32_t cls = 0; cls < CV_SD_CLASSES; cls++) {
        size_t m = partition(r, n, 5, cls + 0.5);
        double E = 0;
        size_t lit = 0;
        for (size_t i = 0; i < m; i++) {
            double v = r[i].pdf;
            E += v;
            lit += v > 0;
        }
        struct cnode *c = &b->c[leaf * CV_SD_CLASSES + cls];
        c->weight = lit >= b->o->min_records && E > 0 ? b->o->mix : 0.0f;
        b->st.guiding += c->weight > 0;
        /* the floor spread over the square's unit area */
        uint32_t q = build_quad(b, r, m, 0, 0, 1, 0, E, b->o->floor * E);
        b->c[leaf * CV_SD_CLASSES + cls].quad = q;
        r += m;
        n -= m;
    }
}

void cv_sdtree_build(const float bmin[3], const float bmax[3], struct cv_sd_record *rec,
                     size_t n, const struct cv_sdtree_opts *o, float (**texels)[4],
                     size_t *n_texels, struct cv_sdtree_stats *stats)
{
    /* the records that count: a positive density, a finite value >= 0 */
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        double v = (double)rec[i].L / rec[i].pdf;
        float cls = floorf(rec[i].u);
        if (rec[i].pdf > 0 && isfinite(v) && v >= 0 && isfinite(rec[i].p[0]) &&
            isfinite(rec[i].p[1]) && isfinite(rec[i].p[2]) && cls >= 0 &&
            cls < CV_SD_CLASSES) {
            rec[k] = rec[i];
            rec[k].u -= cls;
            rec[k].beta = cls;
            rec[k].pdf = (float)rec_value(&rec[k], (int)cls);
            k++;
        }
    }
    n = k;
    /* a cube about the box, a little larger */
    double c[3], ext = 0;
    for (int a = 0; a < 3; a++) {
        double l = bmin[a], h = bmax[a];
        if (!isfinite(l) || !isfinite(h) || h < l)
            l = h = 0;
        c[a] = 0.5 * (l + h);
        if (h - l > ext)
            ext = h - l;
    }
    ext = ext > 0 ? ext * 1.002 : 1;
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = c[a] - ext / 2;
        hi[a] = c[a] + ext / 2;
    }
    struct build b = {.o = o};
    b.thresh = o->split_c * sqrt((double)n);
    if (b.thresh < 2 * o->min_records)
        b.thresh = 2 * o->min_records;
    uint32_t root = push_s(&b);
    build_spatial(&b, root, rec, n, lo, hi, 0);
    b.st.spatial_nodes = (uint32_t)b.ns;
    b.st.quad_nodes = (uint32_t)b.nq;

    /* spatial nodes, class texels, quadtree nodes */
    size_t qbase = b.ns + b.nc, nt = qbase + 2 * b.nq;
    float(*t)[4] = cv_xcalloc(nt, sizeof(*t));
    for (size_t i = 0; i < b.ns; i++) {
        const struct snode *s = &b.s[i];
        t[i][0] = (float)s->axis;
        if (s->axis < 3) {
            t[i][1] = s->split;
            t[i][2] = (float)s->child;
        } else {
            t[i][2] = (float)(b.ns + (size_t)s->child * CV_SD_CLASSES);
        }
    }
    for (size_t i = 0; i < b.nc; i++) {
        t[b.ns + i][0] = (float)(qbase + 2 * (size_t)b.c[i].quad);
        t[b.ns + i][1] = b.c[i].weight;
    }
    for (size_t j = 0; j < b.nq; j++) {
        float *a = t[qbase + 2 * j], *ch = t[qbase + 2 * j + 1];
        for (int q = 0; q < 4; q++) {
            a[q] = b.q[j].p[q];
            ch[q] = b.q[j].child[q] ? (float)(qbase + 2 * (size_t)b.q[j].child[q]) : 0.0f;
        }
    }
    free(b.s);
    free(b.q);
    free(b.c);
    *texels = t;
    *n_texels = nt;
    if (stats)
        *stats = b.st;
}

double cv_sdtree_pdf_square(const float (*t)[4], uint32_t root, double u, double v)
{
    uint32_t q = root;
    double pdf = 1;
    for (uint32_t d = 0; d < CV_SD_MAX_DEPTH; d++) {
        int ix = u < 0.5 ? 0 : 1, iy = v < 0.5 ? 0 : 1, k = ix + 2 * iy;
        pdf *= 4.0 * t[q][k];
        u = 2 * u - ix;
        v = 2 * v - iy;
        uint32_t c = (uint32_t)t[q + 1][k];
        if (!c)
            break;
        q = c;
    }
    return pdf;
}

uint32_t cv_sdtree_leaf(const float (*t)[4], const float p[3])
{
    uint32_t node = 0;
    for (uint32_t d = 0; d < CV_SD_MAX_SPATIAL_DEPTH && t[node][0] < 3.0f; d++) {
        int axis = (int)t[node][0];
        node = (uint32_t)t[node][2] + (p[axis] >= t[node][1] ? 1u : 0u);
    }
    return node;
}
