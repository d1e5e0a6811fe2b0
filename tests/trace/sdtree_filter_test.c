/* sdtree_filter_test.c: the filters of rlpath's sdtree training splat
 * (trace/sdtree.c cv_sdtree_splat, the host's copy of sdtree.glsl's
 * cv_sd_splat, which rlpath_sd_sample_test checks against the shaders) on
 * tables written here by hand (layout glsl/shared/sdtree.h):
 * the spatial box filter puts a record's flux into the leaves a box of its
 * leaf's size about it overlaps, each with the share of the box it holds
 * (two leaves side by side, one leaf and four finer ones), and its record
 * counts into its own leaf only; the directional filter gives the four
 * quadrants about a direction their bilinear shares, and conserves the
 * record's flux in a deeper quadtree (its leaf quadrants sum to the
 * record's value, and nothing is added above them: the host sums the
 * inner quadrants), for records anywhere on the square, edges included;
 * and the host's refinement sums those leaf quadrants up, so that a
 * learned quadtree's root probabilities follow all the records, those that
 * landed deep below it too; and the limit of a record's value (clamp
 * times its class's mean value in the iteration before) caps a bright
 * record, passes a dim one whole, and is off at clamp 0. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/sdtree.h"
#include "tests/rng.h"
#include "tests/tap.h"
#include "trace/sdtree.h"

#define PI 3.14159265358979323846

static uint64_t rng_state = 0x853c49e6748fea9bull;
static double rnd(void)
{
    return cv_test_lcg64(&rng_state);
}

/* A hand-made table: n_sp spatial texels (given), then per leaf six class
 * texels, each with a one-node sampling quadtree (uniform) and a training
 * quadtree of its own (given shape: children per node, -1 none). */
struct table {
    float (*x)[4];
    size_t n;
    uint32_t words;
};

static uint32_t push(struct table *t, size_t k)
{
    uint32_t at = (uint32_t)t->n;
    t->n += k;
    t->x = realloc(t->x, t->n * sizeof(*t->x));
    memset(t->x + at, 0, k * sizeof(*t->x));
    return at;
}

/* Appends a training node at depth whose quadrant q0 (recursively, depth
 * levels down) has a child; returns its texel. */
static uint32_t train_node(struct table *t, int depth)
{
    uint32_t q = push(t, 2);
    t->x[q + 1][0] = (float)t->words;
    t->words += CV_SD_NODE_WORDS;
    if (depth > 0) {
        /* children in quadrants 0 and 3 */
        uint32_t a = train_node(t, depth - 1);
        t->x[q][0] = (float)a;
        uint32_t b = train_node(t, depth - 1);
        t->x[q][3] = (float)b;
    }
    return q;
}

/* Fills leaf texel `leaf`: its six classes, each training quadtree
 * `depth` levels below its root in quadrants 0 and 3. */
static void make_leaf(struct table *t, uint32_t leaf, int depth)
{
    uint32_t c = push(t, CV_SD_CLASSES);
    t->x[leaf][0] = (float)CV_SD_LEAF;
    t->x[leaf][2] = (float)c;
    for (uint32_t k = 0; k < CV_SD_CLASSES; k++) {
        uint32_t s = push(t, 1);
        for (int j = 0; j < 3; j++)
            t->x[s][j] = 0.25f;
        t->x[c + k][0] = (float)s;
        t->x[c + k][1] = 0;
        t->x[c + k][3] = (float)t->words;
        t->words += CV_SD_CLASS_WORDS;
        uint32_t tr = train_node(t, depth);
        t->x[c + k][2] = (float)tr;
    }
}

static float flux(const uint32_t *stats, uint32_t w)
{
    float f;
    memcpy(&f, &stats[w], sizeof(f));
    return f;
}

/* The flux a class-4 (+z) record adds: L / pdf times the cosine to +z. */
static double value_of(const struct cv_sd_record *r)
{
    return (double)r->L / r->pdf * (2.0 * (r->u - 4.0) - 1.0);
}

/* The quadrant sum of training node q's flux words. */
static double node_flux(const float (*x)[4], const uint32_t *stats, uint32_t q)
{
    uint32_t b = (uint32_t)x[q + 1][0];
    return (double)flux(stats, b) + flux(stats, b + 1) + flux(stats, b + 2) + flux(stats, b + 3);
}

/* Root cube [0, 1]^3 split at x = 0.5: a record at x = 0.4 in the left
 * leaf (size 0.5 x 1 x 1) has the footprint x in [0.15, 0.65]: 0.7 of its
 * flux stays, 0.3 goes right; y and z span the cube, the box moved inside
 * it. The right leaf split again at y = 0.5 and z = 0.5: a record at x =
 * 0.4, y = 0.3, z = 0.8 sends its right part (0.3) to the leaf where that
 * part's centre (x 0.575, y 0.5 -> upper half, z 0.5 -> upper) falls. */
static void test_spatial(void)
{
    struct table t = {0};
    uint32_t root = push(&t, 3);
    t.x[root][0] = 0;
    t.x[root][1] = 0.5f;
    t.x[root][2] = 1;
    /* texel 1: left leaf; texel 2: right, split along y, then z */
    uint32_t ry = push(&t, 2), rz0 = push(&t, 2), rz1 = push(&t, 2);
    t.x[2][0] = 1;
    t.x[2][1] = 0.5f;
    t.x[2][2] = (float)ry;
    t.x[ry][0] = 2;
    t.x[ry][1] = 0.5f;
    t.x[ry][2] = (float)rz0;
    t.x[ry + 1][0] = 2;
    t.x[ry + 1][1] = 0.5f;
    t.x[ry + 1][2] = (float)rz1;
    uint32_t leaves[5] = {1, rz0, rz0 + 1, rz1, rz1 + 1};
    for (int i = 0; i < 5; i++)
        make_leaf(&t, leaves[i], 0);
    const float (*x)[4] = (const float(*)[4])t.x;
    struct cv_sd_frame f = {{0, 0, 0, 1}, CV_SD_FILTER_SPATIAL};
    uint32_t *stats = calloc(t.words, sizeof(*stats));
    /* class 4, direction (u 0.75, v 0.3): cos 0.5, quadrant 1 */
    struct cv_sd_record r = {{0.4f, 0.3f, 0.8f}, 0.5f, 4.75f, 0.3f, 1.0f, 2.0f};
    cv_sdtree_splat(x, &f, stats, &r);
    double v = value_of(&r);
    /* leaf i's class-4 texel and its training root's quadrant-1 word */
    double got[5];
    uint32_t counts[5];
    for (int i = 0; i < 5; i++) {
        const float *ct = x[(uint32_t)x[leaves[i]][2] + 4];
        got[i] = node_flux(x, stats, (uint32_t)ct[2]);
        counts[i] = stats[(uint32_t)ct[3]];
        uint32_t b = (uint32_t)x[(uint32_t)ct[2] + 1][0];
        tap_ok(fabs(flux(stats, b + 1) - got[i]) <= 1e-6 * v,
               "spatial: leaf %d's flux all in the record's quadrant", i);
    }
    /* the right part: x in [0.5, 0.65] (centre 0.575); y and z: the box
     * spans the cube, centre 0.5: the upper halves (y >= 0.5, z >= 0.5) */
    tap_ok(fabs(got[0] - 0.7 * v) <= 1e-5 * v, "spatial: the record's leaf keeps 0.7 of %g (%g)",
           v, got[0]);
    tap_ok(fabs(got[4] - 0.3 * v) <= 1e-5 * v,
           "spatial: the leaf of the right part's centre takes 0.3 (%g)", got[4]);
    tap_ok(got[1] == 0 && got[2] == 0 && got[3] == 0, "spatial: the other leaves nothing");
    tap_ok(counts[0] == 1 && counts[1] + counts[2] + counts[3] + counts[4] == 0,
           "spatial: the record counted in its own leaf only");
    /* a record in a right leaf (size 0.5^3 at [0.5,1]x[0,0.5]x[0.5,1]):
     * its box about (0.9, 0.1, 0.7) moves inside the cube in x (centre
     * 0.75), stays in y? centre 0.1 -> 0.25 (moved), z [0.45, 0.95]: 0.1
     * of it below 0.5 (the leaf [0.5,1]x[0,0.5]x[0,0.5]) */
    memset(stats, 0, t.words * sizeof(*stats));
    struct cv_sd_record r2 = {{0.9f, 0.1f, 0.7f}, 0.5f, 4.75f, 0.3f, 1.0f, 2.0f};
    cv_sdtree_splat(x, &f, stats, &r2);
    for (int i = 0; i < 5; i++)
        got[i] = node_flux(x, stats, (uint32_t)x[(uint32_t)x[leaves[i]][2] + 4][2]);
    tap_ok(fabs(got[2] - 0.9 * v) <= 1e-5 * v && fabs(got[1] - 0.1 * v) <= 1e-5 * v &&
               got[0] == 0 && got[3] == 0 && got[4] == 0,
           "spatial: at the cube's edge the box moves inside; 0.9 / 0.1 split in z (%g, %g)",
           got[2] / v, got[1] / v);
    /* the filter off: all in the record's leaf */
    memset(stats, 0, t.words * sizeof(*stats));
    f.filter = 0;
    cv_sdtree_splat(x, &f, stats, &r);
    tap_ok(fabs(node_flux(x, stats, (uint32_t)x[(uint32_t)x[1][2] + 4][2]) - v) <= 1e-6 * v,
           "spatial: without the filter, all in the record's leaf");
    free(stats);
    free(t.x);
}

/* The flux of the training quadtree below node q: its leaf quadrants'
 * words (the splat adds to leaf quadrants only; the host sums the inner
 * ones); *inner gets the largest magnitude found in an inner word. */
static double tree_flux(const float (*x)[4], const uint32_t *stats, uint32_t q, double *inner)
{
    double sum = 0;
    uint32_t b = (uint32_t)x[q + 1][0];
    for (int k = 0; k < 4; k++) {
        uint32_t c = (uint32_t)x[q][k];
        if (c) {
            *inner = fmax(*inner, fabs(flux(stats, b + k)) + stats[b + 4 + k]);
            sum += tree_flux(x, stats, c, inner);
        } else {
            sum += flux(stats, b + k);
        }
    }
    return sum;
}

static void test_directional(void)
{
    /* one leaf, training quadtree root without children: the footprint is
     * a quadrant's side, 0.5 */
    struct table t = {0};
    push(&t, 1);
    make_leaf(&t, 0, 0);
    const float (*x)[4] = (const float(*)[4])t.x;
    struct cv_sd_frame f = {{0, 0, 0, 1}, CV_SD_FILTER_DIRECTIONAL};
    uint32_t *stats = calloc(t.words, sizeof(*stats));
    /* s = (0.7, 0.4): square [0.45, 0.95] x [0.15, 0.65]: x 0.1 / 0.9,
     * y 0.7 / 0.3 (quadrant k = ix + 2 iy) */
    struct cv_sd_record r = {{0.5f, 0.5f, 0.5f}, 0.25f, 4.7f, 0.4f, 1.0f, 3.0f};
    cv_sdtree_splat(x, &f, stats, &r);
    double v = value_of(&r);
    uint32_t root = (uint32_t)x[(uint32_t)x[0][2] + 4][2], b = (uint32_t)x[root + 1][0];
    const double want[4] = {0.1 * 0.7, 0.9 * 0.7, 0.1 * 0.3, 0.9 * 0.3};
    double bad = 0;
    for (int k = 0; k < 4; k++)
        bad = fmax(bad, fabs(flux(stats, b + k) - want[k] * v) / v);
    tap_ok(bad <= 1e-5, "directional: bilinear shares 0.07 / 0.63 / 0.03 / 0.27 (worst %g)", bad);
    tap_ok(stats[b + 4 + 1] == 1 && stats[b + 4] + stats[b + 6] + stats[b + 7] == 0,
           "directional: the record counted in its own quadrant only");
    free(stats);
    free(t.x);

    /* a quadtree four levels deep (children in quadrants 0 and 3 of every
     * node): 2000 records anywhere, edges and corners included, each alone
     * then all together */
    struct table d = {0};
    push(&d, 1);
    make_leaf(&d, 0, 4);
    x = (const float(*)[4])d.x;
    stats = calloc(d.words, sizeof(*stats));
    root = (uint32_t)x[(uint32_t)x[0][2] + 4][2];
    double worst_root = 0, inner = 0, total = 0;
    for (int i = 0; i < 2000; i++) {
        float u = (float)(0.5 + 0.5 * rnd()), vv = (float)rnd();
        if (i % 10 == 0)
            vv = i % 20 == 0 ? 0.0f : 0.99999994f;
        if (i % 15 == 0)
            u = 1.0f - 0x1p-21f;   /* the last u that 4 + u keeps below 5 */
        struct cv_sd_record ri = {{0.5f, 0.5f, 0.5f}, (float)(0.1 + rnd()), 4.0f + u, vv,
                                  1.0f, (float)(0.5 + rnd())};
        uint32_t *one = calloc(d.words, sizeof(*one));
        cv_sdtree_splat(x, &f, one, &ri);
        double vi = value_of(&ri);
        if (vi > 0)
            worst_root = fmax(worst_root, fabs(tree_flux(x, one, root, &inner) - vi) / vi);
        total += vi > 0 ? vi : 0;
        cv_sdtree_splat(x, &f, stats, &ri);
        free(one);
    }
    tap_ok(worst_root <= 1e-5, "directional: each record's flux conserved over the leaf "
           "quadrants (worst relative difference %g)", worst_root);
    tap_ok(inner == 0, "directional: no flux or count added above a leaf quadrant (%g)", inner);
    double got = tree_flux(x, stats, root, &inner);
    tap_ok(fabs(got - total) <= 1e-4 * total,
           "directional: 2000 records together conserve their flux %g (%g)", total, got);
    free(stats);
    free(d.x);
}

/* A tree learned from records at one point (most of them in a small patch
 * of directions, whose root quadrant then has a subtree), then one more
 * iteration: the records splatted into its table and refined. The next
 * sampling root's probabilities must be the records' flux per root
 * quadrant (plus the floor's share), which only the host's sums of the
 * leaf quadrants below give. */
static void test_inner_sums(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const size_t n = 20000;
    struct cv_sd_record *r = calloc(n, sizeof(*r));
    double e[4] = {0}, E = 0;
    for (size_t i = 0; i < n; i++) {
        bool patch = i % 5 != 0;
        double su = patch ? 0.55 + 0.05 * rnd() : 0.5 + 0.5 * rnd();
        double sv = patch ? 0.10 + 0.05 * rnd() : rnd();
        r[i] = (struct cv_sd_record){{0.3f, 0.3f, 0.3f}, 1.0f, 4.0f + (float)su, (float)sv, 1.0f,
                                     1.0f};
        double v = value_of(&r[i]);
        double u = r[i].u - 4.0;
        int k = (u < 0.5 ? 0 : 1) + 2 * (r[i].v < 0.5f ? 0 : 1);
        e[k] += v;
        E += v;
    }
    struct cv_sdtree_opts o = cv_sdtree_defaults;
    o.filter = 0;
    o.clamp = 0;   /* every record whole (test_clamp) */
    struct cv_sdtree *t = cv_sdtree_create(lo, hi);
    cv_sdtree_learn_records(t, r, n, &o, NULL);
    float(*x)[4] = NULL;
    size_t nx = 0;
    cv_sdtree_table(t, &o, &x, &nx);
    uint32_t leaf = cv_sdtree_leaf((const float(*)[4])x, r[0].p);
    uint32_t troot = (uint32_t)x[(uint32_t)x[leaf][2] + 4][2];
    int deep = 0;
    for (int k = 0; k < 4; k++)
        deep += x[troot][k] != 0;
    tap_ok(deep > 0, "inner sums: the learned training root has %d quadrants with a subtree", deep);
    free(x);
    cv_sdtree_learn_iteration(t, r, n, &o, NULL);
    cv_sdtree_table(t, &o, &x, &nx);
    leaf = cv_sdtree_leaf((const float(*)[4])x, r[0].p);
    uint32_t sroot = (uint32_t)x[(uint32_t)x[leaf][2] + 4][0];
    float pr[4];
    uint32_t ch[4];
    cv_sdtree_node((const float(*)[4])x, sroot, pr, ch);
    double worst = 0;
    for (int k = 0; k < 4; k++) {
        double want = (e[k] + o.floor * E / 4) / (E * (1 + o.floor));
        worst = fmax(worst, fabs(pr[k] - want) / want);
    }
    tap_ok(worst <= 1e-4, "inner sums: the sampling root's probabilities are the records' flux "
           "shares %.4f / %.4f / %.4f / %.4f (worst relative difference %g)",
           (double)pr[0], (double)pr[1], (double)pr[2], (double)pr[3],
           worst);
    free(x);
    cv_sdtree_destroy(&t);
    free(r);
}

/* The limit of a record's value (cv_sdtree_opts.clamp): after an
 * iteration of records of value 1 and a few of 1000 in one class, the
 * class's training root holds clamp times their mean value; in the next
 * iteration a record of any value adds at most that, a record below it
 * adds its own value, and with clamp 0 nothing is limited. */
static void test_clamp(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const size_t n = 1000;
    struct cv_sd_record *r = calloc(n, sizeof(*r));
    double E = 0;
    for (size_t i = 0; i < n; i++) {
        /* straight up (cosine 1 to +z), value L / pdf */
        r[i] = (struct cv_sd_record){{0.3f, 0.3f, 0.3f}, 1.0f, 4.0f + 0.999f, (float)rnd(), 1.0f,
                                     i % 100 == 0 ? 1000.0f : 1.0f};
        E += value_of(&r[i]);
    }
    for (int with = 0; with <= 1; with++) {
        struct cv_sdtree_opts o = cv_sdtree_defaults;
        o.filter = 0;
        o.clamp = with ? 4.0f : 0.0f;
        /* the first iteration: every record whole (no limit yet) */
        struct cv_sdtree *t = cv_sdtree_create(lo, hi);
        cv_sdtree_learn_iteration(t, r, n, &o, NULL);
        float(*x)[4] = NULL;
        size_t nx = 0;
        cv_sdtree_table(t, &o, &x, &nx);
        uint32_t leaf = cv_sdtree_leaf((const float(*)[4])x, r[0].p);
        uint32_t troot = (uint32_t)x[(uint32_t)x[leaf][2] + 4][2];
        double lim = x[troot + 1][1], want = with ? 4.0 * E / (double)n : 0.0;
        tap_ok(fabs(lim - want) <= 1e-5 * want, "clamp %g: the class's limit %g is %g", (double)o.clamp,
               lim, want);
        /* one bright record and one dim one into the next iteration's
         * statistics */
        uint32_t *stats = calloc(cv_sdtree_stat_words(t), sizeof(*stats));
        struct cv_sd_frame f = cv_sdtree_frame(t, &o);
        struct cv_sd_record b = r[0], d = r[1];
        b.L = 1e6f;
        d.L = 0.5f;
        double sum[2];
        for (int k = 0; k < 2; k++) {
            memset(stats, 0, cv_sdtree_stat_words(t) * sizeof(*stats));
            cv_sdtree_splat((const float(*)[4])x, &f, stats, k ? &d : &b);
            double inner = 0;
            sum[k] = tree_flux((const float(*)[4])x, stats, troot, &inner);
        }
        double bv = value_of(&b), dv = value_of(&d);
        tap_ok(fabs(sum[0] - (with ? lim : bv)) <= 1e-5 * sum[0],
               "clamp %g: a record of value %g adds %g (%g)", (double)o.clamp, bv, sum[0],
               with ? lim : bv);
        tap_ok(fabs(sum[1] - dv) <= 1e-5 * dv, "clamp %g: a record of value %g below the limit "
               "adds it whole (%g)", (double)o.clamp, dv, sum[1]);
        free(stats);
        free(x);
        cv_sdtree_destroy(&t);
    }
    free(r);
}

int main(void)
{
    test_spatial();
    test_directional();
    test_inner_sums();
    test_clamp();
    return tap_done();
}
