/* curve_bvh.c: the curves' binary BVH (curve_bvh.h). */
#include "bvh/curve_bvh.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "bvh/median_split.h"
#include "glsl/shared/bvh.h"
#include "scene/scene.h"

static double blossom(const double p[4], double a, double b, double c)
{
    double q0 = p[0] + a * (p[1] - p[0]), q1 = p[1] + a * (p[2] - p[1]), q2 = p[2] + a * (p[3] - p[2]);
    double r0 = q0 + b * (q1 - q0), r1 = q1 + b * (q2 - q1);
    return r0 + c * (r1 - r0);
}

void cv_curve_box(const CvCurve *c, const CvCurveXform *xforms, float lo[3], float hi[3])
{
    double u0 = c->cp[2].w, u1 = c->cp[3].w;
    double w0 = c->cp[0].w + u0 * (c->cp[1].w - c->cp[0].w), w1 = c->cp[0].w + u1 * (c->cp[1].w - c->cp[0].w);
    double r = 0.5 * fmax(w0, w1), l[3], h[3];
    for (int a = 0; a < 3; a++) {
        double p[4] = {(&c->cp[0].x)[a], (&c->cp[1].x)[a], (&c->cp[2].x)[a], (&c->cp[3].x)[a]};
        double q[4] = {blossom(p, u0, u0, u0), blossom(p, u0, u0, u1), blossom(p, u0, u1, u1),
                       blossom(p, u1, u1, u1)};
        l[a] = fmin(fmin(q[0], q[1]), fmin(q[2], q[3])) - r;
        h[a] = fmax(fmax(q[0], q[1]), fmax(q[2], q[3])) + r;
    }
    uint32_t xf = c->info.y >> CV_CURVE_XF_SHIFT;
    if (xf) /* the object-space box's image holds the piece's */
        cv_curve_xform_box(&xforms[xf - 1], l, h, l, h);
    for (int a = 0; a < 3; a++) {
        /* a float ulp outwards: the box must hold the piece */
        lo[a] = nextafterf((float)l[a], -INFINITY);
        hi[a] = nextafterf((float)h[a], INFINITY);
    }
}

struct build {
    float (*lo)[3], (*hi)[3];
    uint32_t *order;
    float *out;     /* vec4s */
    uint32_t n_nodes;
};

static void range_box(const struct build *b, uint32_t first, uint32_t count, float lo[3], float hi[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY;
        hi[a] = -INFINITY;
    }
    for (uint32_t k = first; k < first + count; k++)
        for (int a = 0; a < 3; a++) {
            lo[a] = fminf(lo[a], b->lo[b->order[k]][a]);
            hi[a] = fmaxf(hi[a], b->hi[b->order[k]][a]);
        }
}

/* A child slot of node `node` (side 0 left, 1 right) over order[first..+count). */
static void set_child(struct build *b, uint32_t node, int side, const float lo[3], const float hi[3], int32_t word,
                      int32_t count)
{
    float *v = b->out + 4 * (1 + 4 * (size_t)node + 2 * side);
    v[0] = lo[0];
    v[1] = lo[1];
    v[2] = lo[2];
    memcpy(&v[3], &word, 4);
    v[4] = hi[0];
    v[5] = hi[1];
    v[6] = hi[2];
    memcpy(&v[7], &count, 4);
}

/* Fills node `node` for order[first..+count), count > CV_CURVE_LEAF or the root. */
static void build_node(struct build *b, uint32_t node, uint32_t first, uint32_t count)
{
    uint32_t half[2] = {count / 2, count - count / 2};
    if (count > 1) {
        cv_median_split(b->order + first, count, (const float (*)[3])b->lo,
                        (const float (*)[3])b->hi);
    } else {
        half[0] = count;
        half[1] = 0;
    }
    uint32_t start = first;
    for (int side = 0; side < 2; side++) {
        uint32_t c = half[side];
        float lo[3], hi[3];
        if (c == 0) {
            float e[3] = {(float)CV_BVH_EMPTY, (float)CV_BVH_EMPTY, (float)CV_BVH_EMPTY},
                  f[3] = {-(float)CV_BVH_EMPTY, -(float)CV_BVH_EMPTY, -(float)CV_BVH_EMPTY};
            set_child(b, node, side, e, f, 0, 0);
            continue;
        }
        range_box(b, start, c, lo, hi);
        if (c <= CV_CURVE_LEAF) {
            set_child(b, node, side, lo, hi, (int32_t)start, (int32_t)c);
        } else {
            uint32_t child = b->n_nodes++;
            set_child(b, node, side, lo, hi, (int32_t)child, 0);
            build_node(b, child, start, c);
        }
        start += c;
    }
}

float *cv_curve_bvh_pack(const CvCurve *curves, uint32_t n, const CvCurveXform *xforms, uint32_t n_xforms,
                         uint32_t n_shapes, size_t *n_vec4)
{
    struct build b = {0};
    b.lo = cv_xcalloc(n, sizeof(*b.lo));
    b.hi = cv_xcalloc(n, sizeof(*b.hi));
    b.order = cv_xcalloc(n, sizeof(uint32_t));
    /* order[]: the static curves, then each shape's, each group in scene
     * order; first[g + 1], count[g + 1]: shape g's group (g + 1 = info.w) */
    uint32_t *first = cv_xcalloc((size_t)n_shapes + 2, sizeof(uint32_t));
    uint32_t *count = cv_xcalloc((size_t)n_shapes + 1, sizeof(uint32_t));
    for (uint32_t i = 0; i < n; i++) {
        cv_curve_box(&curves[i], xforms, b.lo[i], b.hi[i]);
        uint32_t g = curves[i].info.w <= n_shapes ? curves[i].info.w : 0;
        count[g]++;
    }
    for (uint32_t g = 0; g <= n_shapes; g++)
        first[g + 1] = first[g] + count[g];
    for (uint32_t g = 0; g <= n_shapes; g++)
        count[g] = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t g = curves[i].info.w <= n_shapes ? curves[i].info.w : 0;
        b.order[first[g] + count[g]++] = i;
    }
    /* a binary tree of leaves of 1..CV_CURVE_LEAF curves has fewer nodes
     * than curves, and at least one */
    size_t max_nodes = (size_t)n + n_shapes + 1;
    b.out = cv_xcalloc((1 + 4 * max_nodes + n_shapes + 7 * (size_t)n + 6 * (size_t)n_xforms) * 4, sizeof(float));
    b.n_nodes = 1;
    build_node(&b, 0, 0, count[0]);
    uint32_t *roots = cv_xcalloc((size_t)n_shapes + 1, sizeof(uint32_t));
    for (uint32_t g = 1; g <= n_shapes; g++)
        if (count[g]) {
            roots[g] = b.n_nodes++;
            build_node(&b, roots[g], first[g], count[g]);
        }
    /* the nodes used, the shapes' records (root node, first curve, count),
     * then the curves in leaf order */
    size_t shape_base = 1 + 4 * (size_t)b.n_nodes, curve_base = shape_base + n_shapes;
    uint32_t hdr[4] = {b.n_nodes, n, (uint32_t)curve_base, count[0]};
    memcpy(b.out, hdr, sizeof(hdr));
    for (uint32_t g = 1; g <= n_shapes; g++) {
        uint32_t rec[4] = {roots[g], first[g], count[g], 0};
        memcpy(b.out + 4 * (shape_base + g - 1), rec, sizeof(rec));
    }
    for (uint32_t k = 0; k < n; k++)
        memcpy(b.out + 4 * (curve_base + 7 * (size_t)k), &curves[b.order[k]], sizeof(CvCurve));
    /* the transforms of curves kept in their object space, after them */
    if (n_xforms)
        memcpy(b.out + 4 * (curve_base + 7 * (size_t)n), xforms, n_xforms * sizeof(CvCurveXform));
    *n_vec4 = curve_base + 7 * (size_t)n + 6 * (size_t)n_xforms;
    free(first);
    free(count);
    free(roots);
    free(b.lo);
    free(b.hi);
    free(b.order);
    return b.out;
}
