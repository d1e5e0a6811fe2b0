/* sdtree_test.c: rlpath's sdtree guide learned on the host (trace/sdtree.c:
 * the records splatted as the shaders do and the tree refined from the
 * statistics until it stops changing; layout glsl/shared/sdtree.h) from
 * synthetic records: no records give one leaf whose six orientation
 * classes have uniform, unguided sampling quadtrees and one training node
 * each, its statistics words where the layout says;
 * records spread over a box give a spatial tree whose leaves hold at most
 * the split threshold, and every record found again in the leaf that the
 * lookup names; the flattened table's links point where the layout says
 * (spatial children inside the spatial part, each leaf to a block of six
 * class texels of its own, sampling nodes one texel each after those with
 * each node's children consecutive after it, the root never a child, each
 * root that guides after its top block); the top blocks hold each cell's
 * density as the walk from the root gives it, the node the walk reaches at
 * the cell, and an alias table whose draws give each cell its mass;
 * every node's four probabilities (the fourth derived) positive and
 * summing to 1; every quadtree's density integrating to 1 over the square
 * (exactly, by walking the tree, and through the lookup the shaders mirror
 * on a midpoint grid, exact for trees at most 8 deep); a class guiding iff
 * it has enough records of radiance in front of its axis (the build
 * weights radiance by the cosine to the axis); the density following the
 * recorded radiance (a bright spot of directions gets many times the
 * uniform density in the classes that face it, a dark half about the
 * floor); each class's light estimate is the mean value of all its
 * records, unlit ones too; records with a non-finite value or no density
 * are ignored; the
 * top blocks take as many levels as fit their texel budget.
 * The grid block at the table's end (its bounds rising and shared by
 * neighbouring cells, each cell naming what the descent from its centre
 * meets after 3 g levels, a leaf as -1 - its class texel) and the leaf
 * depths the build reports (those of the table), for these trees and a
 * deep one (records in a small cluster, leaves below depth 3 g). */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/sdtree.h"
#include "tests/rng.h"
#include "tests/tap.h"
#include "trace/sdtree.h"

static uint64_t rng_state = 0x9e3779b97f4a7c15ull;
static double rnd(void)
{
    return cv_test_lcg64(&rng_state);
}

/* The integral of a quadtree's density over its square, walking every
 * node: sum over leaf quadrants of density times area. */
static double integrate(const float (*t)[4], uint32_t q, double pdf, double area)
{
    double s = 0;
    float pr[4];
    uint32_t ch[4];
    cv_sdtree_node(t, q, pr, ch);
    for (int k = 0; k < 4; k++) {
        double p = pdf * 4 * pr[k];
        uint32_t c = ch[k];
        s += c ? integrate(t, c, p, area / 4) : p * area / 4;
    }
    return s;
}

/* Checks the links and probabilities of the quadtree at q; counts nodes. */
static void check_quad(const float (*t)[4], size_t nt, uint32_t ns, uint32_t q, uint32_t depth,
                       uint32_t *bad_link, uint32_t *bad_prob, uint32_t *nodes)
{
    (*nodes)++;
    double sum = 0;
    float pr[4];
    uint32_t ch[4];
    cv_sdtree_node(t, q, pr, ch);
    for (int k = 0; k < 4; k++) {
        sum += pr[k];
        if (!(pr[k] > 0))
            (*bad_prob)++;
    }
    if (fabs(sum - 1) > 1e-6)
        (*bad_prob)++;
    /* the children's texels: consecutive, after the node (breadth first) */
    uint32_t prev = q;
    for (int k = 0; k < 4; k++) {
        uint32_t c = ch[k];
        if (!c)
            continue;
        bool bad = c <= q || (prev != q && c != prev + 1);
        prev = c;
        if (c < ns || c >= nt || depth + 1 >= CV_SD_MAX_DEPTH || bad) {
            (*bad_link)++;
            continue;
        }
        check_quad(t, nt, ns, c, depth + 1, bad_link, bad_prob, nodes);
    }
}

/* Checks the top block of the quadtree at root (glsl/shared/sdtree.h)
 * against the walk from the root: a cell's node is the one the walk
 * reaches at the cell's depth (0 where it ends above), its density the
 * walk's there (at two points of the cell, through the walk below its
 * node); and its alias table: a draw of u.x in [0, 1) lands in cell j with
 * probability 1/N, keeps it below y_j of the way and else takes z_j, so
 * cell c gets (y_c + sum over j with z_j = c of (1 - y_j)) / N, which must
 * be its mass x_c / N. */
static void check_block(const float (*t)[4], uint32_t root, uint32_t *bad_block,
                        uint32_t *bad_alias)
{
    const uint32_t L = (uint32_t)t[0][3], S = 1u << L, N = S * S;
    const float(*b)[4] = t + root - N;
    double got[1u << (2 * CV_SD_BLOCK_MAX_LOG2)] = {0}, sum = 0;
    for (uint32_t c = 0; c < N; c++) {
        uint32_t cx = c % S, cy = c / S, q = root;
        for (uint32_t d = 0; d < L && q; d++) {
            float pr[4];
            uint32_t ch[4];
            cv_sdtree_node(t, q, pr, ch);
            q = ch[((cx >> (L - 1 - d)) & 1u) + 2u * ((cy >> (L - 1 - d)) & 1u)];
        }
        *bad_block += b[c][3] != (float)q;
        for (int i = 0; i < 2; i++) {
            double lx = i ? 0.3 : 0.71, ly = i ? 0.84 : 0.12;
            double want = cv_sdtree_pdf_square(t, root, (cx + lx) / S, (cy + ly) / S);
            double have = b[c][0] * (q ? cv_sdtree_pdf_square(t, q, lx, ly) : 1.0);
            *bad_block += !(fabs(have - want) <= 1e-5 * want);
        }
        uint32_t z = (uint32_t)b[c][2];
        if (!(b[c][1] >= 0 && b[c][1] <= 1) || z >= N) {
            (*bad_alias)++;
            continue;
        }
        got[c] += b[c][1];
        got[z] += 1.0 - b[c][1];
        sum += b[c][0];
    }
    for (uint32_t c = 0; c < N; c++)
        *bad_alias += !(fabs(got[c] - b[c][0] * N / sum) <= 1e-5);
}

/* The cosine of direction (u, v) on the square to the axis of class c. */
static double class_cos(uint32_t c, double u, double v)
{
    double z = 2 * u - 1, phi = 2 * M_PI * v - M_PI, s = sqrt(fmax(0, 1 - z * z));
    double w[3] = {s * cos(phi), s * sin(phi), z};
    return w[c / 2] * (c & 1 ? -1 : 1);
}

static uint32_t quad_depth(const float (*t)[4], uint32_t q)
{
    uint32_t d = 0;
    float pr[4];
    uint32_t ch[4];
    cv_sdtree_node(t, q, pr, ch);
    for (int k = 0; k < 4; k++) {
        uint32_t c = ch[k];
        if (c) {
            uint32_t e = quad_depth(t, c);
            if (e > d)
                d = e;
        }
    }
    return d + 1;
}

/* The depths of the spatial leaves below node i at depth d: least, most,
 * their sum and count. */
static void leaf_depths(const float (*t)[4], uint32_t i, uint32_t d, uint32_t *lo, uint32_t *hi,
                        double *sum, uint32_t *n)
{
    if (t[i][0] != (float)CV_SD_LEAF) {
        leaf_depths(t, (uint32_t)t[i][2], d + 1, lo, hi, sum, n);
        leaf_depths(t, (uint32_t)t[i][2] + 1, d + 1, lo, hi, sum, n);
        return;
    }
    *lo = *n == 0 || d < *lo ? d : *lo;
    *hi = d > *hi ? d : *hi;
    *sum += d;
    ++*n;
}

/* Checks the depths the build reported against the table's. */
static void check_depths(const char *what, const float (*t)[4], const struct cv_sdtree_stats *st)
{
    uint32_t lo = 0, hi = 0, n = 0;
    double sum = 0;
    leaf_depths(t, 0, 0, &lo, &hi, &sum, &n);
    tap_ok(n == st->spatial_leaves && lo == st->min_spatial_depth &&
               hi == st->max_spatial_depth && fabs(sum / n - st->mean_spatial_depth) < 1e-9 &&
               st->record_spatial_depth >= lo && st->record_spatial_depth <= hi,
           "%s: leaf depths min %u mean %.3f max %u (by records %.3f) as the table's (%u %.3f "
           "%u)", what, st->min_spatial_depth, st->mean_spatial_depth, st->max_spatial_depth,
           st->record_spatial_depth, lo, sum / n, hi);
}

/* Checks the grid block (shared/sdtree.h) of table t (nt texels) against
 * the descent from each cell's centre. */
static void check_grid(const char *what, const float (*t)[4], size_t nt)
{
    const uint32_t N = CV_SD_GRID_CELLS;
    const float(*b)[4] = t + nt - CV_SD_GRID_TEXELS;
    const float *cells = &b[3 * N][0];
    uint32_t bad_bounds = 0, bad_cells = 0, inner = 0;
    for (uint32_t a = 0; a < 3; a++)
        for (uint32_t j = 0; j < N; j++)
            bad_bounds += !(b[a * N + j][0] < b[a * N + j][1]) ||
                          (j > 0 && b[a * N + j][0] != b[a * N + j - 1][1]);
    for (uint32_t z = 0; z < N; z++)
        for (uint32_t y = 0; y < N; y++)
            for (uint32_t x = 0; x < N; x++) {
                const uint32_t c[3] = {x, y, z};
                float p[3];
                for (int a = 0; a < 3; a++)
                    p[a] = 0.5f * (b[a * N + c[a]][0] + b[a * N + c[a]][1]);
                uint32_t node = 0;
                for (uint32_t d = 0; d < 3 * CV_SD_GRID_LOG2 && t[node][0] != (float)CV_SD_LEAF;
                     d++) {
                    int axis = (int)t[node][0];
                    node = (uint32_t)t[node][2] + (p[axis] >= t[node][1] ? 1u : 0u);
                }
                bool leaf = t[node][0] == (float)CV_SD_LEAF;
                float want = leaf ? -1.0f - t[node][2] : (float)node;
                inner += !leaf;
                bad_cells += cells[x + N * (y + N * z)] != want;
            }
    tap_ok(bad_bounds == 0 && bad_cells == 0, "%s: grid block: bounds rise and meet (%u bad), "
           "cells name the descent's node from their centres (%u bad, %u inner)", what,
           bad_bounds, bad_cells, inner);
}

/* The top blocks' levels: the most whose texels fit. */
static void test_block_levels(void)
{
    const size_t max = CV_SD_BLOCK_MAX_TEXELS;
    const size_t roots[] = {0, 1, max >> 10, (max >> 10) + 1, max >> 8, (max >> 8) + 1, max,
                            max + 1};
    const uint32_t want[] = {5, 5, 5, 4, 4, 3, 0, 0};
    uint32_t bad = 0;
    for (size_t i = 0; i < sizeof(roots) / sizeof(roots[0]); i++)
        bad += cv_sdtree_block_log2(roots[i], CV_SD_BLOCK_MAX_LOG2) != want[i] ||
               cv_sdtree_block_log2(roots[i], 3) != (want[i] < 3 ? want[i] : 3);
    tap_ok(CV_SD_BLOCK_MAX_LOG2 == 5 && bad == 0, "top blocks of 5 levels up to %zu quadtrees "
           "that guide, then fewer, down to 0 (%u wrong)", max >> 10, bad);
}

static void test_empty(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(lo, hi, NULL, 0, &cv_sdtree_defaults, &t, &nt, &st);
    uint32_t bad = 0;
    /* no class guides, so no top block: the sampling roots, then the
     * training roots */
    const uint32_t tb = 1 + 2 * CV_SD_CLASSES;
    const size_t want = tb + 2 * CV_SD_CLASSES + CV_SD_GRID_TEXELS;
    for (uint32_t c = 0; c < CV_SD_CLASSES && nt == want; c++) {
        uint32_t root = 1 + CV_SD_CLASSES + c;
        const float *k = t[1 + c], *q = t[root];
        const float *tr = t[tb + 2 * c];
        bad += k[0] != (float)root || k[1] != 0;
        /* the training root and its statistics: the class's two words,
         * then the node's eight */
        bad += k[2] != (float)(tb + 2 * c) || k[3] != (float)(2 * c);
        bad += tr[0] != 0 || tr[1] != 0 || tr[2] != 0 || tr[3] != 0 ||
               tr[4] != (float)(2 * CV_SD_CLASSES + 8 * c);
        /* one texel: three probabilities (the fourth 1 less them), no child */
        bad += q[0] != 0.25f || q[1] != 0.25f || q[2] != 0.25f || q[3] != 0;
    }
    tap_ok(nt == want && t[0][0] == (float)CV_SD_LEAF && t[0][2] == 1,
           "no records: one leaf, its class texels at texel 1 (%zu texels)", nt);
    check_depths("no records", (const float(*)[4])t, &st);
    check_grid("no records", (const float(*)[4])t, nt);
    tap_ok(bad == 0, "no records: every class of weight 0, one uniform sampling quadtree node "
           "and one training node each (%u wrong)", bad);
    tap_ok(st.spatial_leaves == 1 && st.guiding == 0 && st.quad_nodes == CV_SD_CLASSES,
           "no records: stats %u leaves, %u guiding, %u quadtree nodes", st.spatial_leaves,
           st.guiding, st.quad_nodes);
    free(t);
}

/* n records in [0,2]x[0,1]x[0,1]: a share `spot` of them in a small
 * bright spot of directions about (0.8, 0.3) on the square, radiance 20,
 * the rest uniform in u >= 0.5 (radiance 1) with pdf 1 / (4 pi). */
static struct cv_sd_record *make_records(size_t n, double spot)
{
    struct cv_sd_record *r = calloc(n, sizeof(*r));
    for (size_t i = 0; i < n; i++) {
        r[i].p[0] = (float)(2 * rnd());
        r[i].p[1] = (float)rnd();
        r[i].p[2] = (float)rnd();
        r[i].pdf = (float)(1 / (4 * M_PI));
        r[i].beta = 1;
        /* as read back: the class (0 .. 5) added to u */
        r[i].beta = (float)(int)(6 * rnd());
        if (rnd() < spot) {
            r[i].u = (float)(0.8 + 0.01 * (rnd() - 0.5));
            r[i].v = (float)(0.3 + 0.01 * (rnd() - 0.5));
            r[i].L = 20;
        } else {
            r[i].u = (float)(0.5 + 0.5 * rnd());
            r[i].v = (float)rnd();
            r[i].L = rnd() < 0.5 ? 1 : 0;
        }
        r[i].u += r[i].beta;
    }
    return r;
}

static void test_build(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 1};
    const size_t N = 200000;
    struct cv_sd_record *r = make_records(N, 0.05);
    /* junk the build must ignore */
    r[0].pdf = 0;
    r[1].L = NAN;
    r[2].pdf = -1;
    struct cv_sd_record *copy = malloc(N * sizeof(*r));
    memcpy(copy, r, N * sizeof(*r));
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    struct cv_sdtree_opts o = cv_sdtree_defaults;
    cv_sdtree_build(lo, hi, r, N, &o, &t, &nt, &st);
    uint32_t ns = st.spatial_nodes, nc = CV_SD_CLASSES * st.spatial_leaves, qb = ns + nc;
    tap_ok(st.spatial_leaves > 8 && st.spatial_leaves * 2 - 1 == ns,
           "%u spatial leaves of %u nodes (a full binary tree)", st.spatial_leaves, ns);
    /* the sampling quadtrees (leaves that split share theirs), those that
     * guide with a top block */
    uint32_t roots = 0;
    for (uint32_t k = ns; k < qb; k++) {
        bool first = t[k][1] > 0;
        for (uint32_t j = ns; j < k && first; j++)
            first = t[j][0] != t[k][0] || !(t[j][1] > 0);
        roots += first;
    }
    uint32_t L = (uint32_t)t[0][3], cells = 1u << (2 * L);
    uint32_t qe = qb + st.quad_nodes + roots * cells;   /* the training nodes' first texel */
    tap_ok(L == CV_SD_BLOCK_MAX_LOG2 && nt == qe + 2 * (size_t)st.train_nodes + CV_SD_GRID_TEXELS &&
               st.quad_nodes >= nc && st.train_nodes >= nc,
           "%zu texels: %u spatial + %u class + %u sampling + %u top blocks of %u levels + 2 x %u "
           "training quadtree + the grid block", nt, ns, nc, st.quad_nodes, roots, L,
           st.train_nodes);
    check_depths("box", (const float(*)[4])t, &st);
    check_grid("box", (const float(*)[4])t, nt);
    /* spatial links */
    uint32_t bad_s = 0, leaves = 0;
    uint8_t *seen = calloc(st.spatial_leaves + 1, 1);
    for (uint32_t i = 0; i < ns; i++) {
        if (t[i][0] == (float)CV_SD_LEAF) {
            uint32_t k = (uint32_t)t[i][2];
            leaves++;
            /* a block of its own */
            if (k < ns || k >= qb || (k - ns) % CV_SD_CLASSES || seen[(k - ns) / CV_SD_CLASSES]++)
                bad_s++;
            for (uint32_t c = 0; c < CV_SD_CLASSES && k + c < qb; c++) {
                uint32_t q = (uint32_t)t[k + c][0];
                if (q < qb || q >= qe)
                    bad_s++;
                if (!(t[k + c][1] == 0 || t[k + c][1] == o.mix))
                    bad_s++;
            }
        } else {
            uint32_t c = (uint32_t)t[i][2];
            if (!(t[i][0] == 0 || t[i][0] == 1 || t[i][0] == 2) || c <= i || c + 1 >= ns)
                bad_s++;
        }
    }
    tap_ok(bad_s == 0 && leaves == st.spatial_leaves,
           "spatial nodes link inside the spatial part, each leaf to a block of class "
           "texels of its own, those to quadtree roots (%u bad)", bad_s);
    free(seen);
    /* counts per leaf through the lookup */
    uint32_t *count = calloc(ns, sizeof(uint32_t)), *lit = calloc(nt, sizeof(uint32_t));
    for (size_t i = 3; i < N; i++) {
        uint32_t l = cv_sdtree_leaf((const float(*)[4])t, copy[i].p);
        count[l]++;
        /* radiance that arrives in front of the class's axis */
        uint32_t c = (uint32_t)copy[i].beta;
        lit[(uint32_t)t[l][2] + c] += copy[i].L > 0 && class_cos(c, copy[i].u - c, copy[i].v) > 0;
    }
    double thresh = o.split_c * sqrt((double)(N - 3));
    uint32_t over = 0, misplaced = 0;
    size_t total = 0;
    for (uint32_t i = 0; i < ns; i++) {
        if (t[i][0] != (float)CV_SD_LEAF) {
            misplaced += count[i] != 0;
            continue;
        }
        total += count[i];
        over += count[i] > thresh;
    }
    tap_ok(total == N - 3 && misplaced == 0, "every valid record in a leaf (%zu of %zu)", total,
           N - 3);
    tap_ok(over == 0, "no leaf above the split threshold %.0f (%u are)", thresh, over);
    /* quadtrees */
    uint32_t bad_link = 0, bad_prob = 0, nodes = 0, bad_int = 0, bad_grid = 0, gridded = 0;
    uint32_t bad_weight = 0;
    uint32_t guiding = 0, spot_high = 0;
    double dark_ratio = 0;
    uint32_t bad_block = 0, bad_alias = 0, blocks = 0;
    for (uint32_t k = ns; k < qb; k++) {
        uint32_t q = (uint32_t)t[k][0];
        check_quad((const float(*)[4])t, qe, qb, q, 0, &bad_link, &bad_prob, &nodes);
        if (t[k][1] > 0) {
            check_block((const float(*)[4])t, q, &bad_block, &bad_alias);
            blocks++;
        }
        double s = integrate((const float(*)[4])t, q, 1, 1);
        if (fabs(s - 1) > 1e-5)
            bad_int++;
        /* the lookup on a 256^2 midpoint grid: exact where the quadtree
         * is at most 8 deep (its leaves are whole grid cells) */
        if (quad_depth((const float(*)[4])t, q) <= 8) {
            const int G = 256;
            double g = 0;
            for (int a = 0; a < G; a++)
                for (int b = 0; b < G; b++)
                    g += cv_sdtree_pdf_square((const float(*)[4])t, q, (a + 0.5) / G,
                                              (b + 0.5) / G);
            g /= (double)G * G;
            gridded++;
            bad_grid += fabs(g - 1) > 1e-5;
        }
        bad_weight += (t[k][1] > 0) != (lit[k] >= o.min_records);
        /* the classes that face the spot */
        if (t[k][1] > 0 && class_cos((k - ns) % CV_SD_CLASSES, 0.8, 0.3) > 0.2) {
            double ps = cv_sdtree_pdf_square((const float(*)[4])t, q, 0.8, 0.3);
            double pd = cv_sdtree_pdf_square((const float(*)[4])t, q, 0.25, 0.5);
            guiding++;
            spot_high += ps > 20;
            if (pd > dark_ratio)
                dark_ratio = pd;
        }
    }
    tap_ok(bad_link == 0, "quadtree links at even offsets past the spatial part, depth <= %u "
           "(%u bad)", CV_SD_MAX_DEPTH, bad_link);
    tap_ok(nodes == st.quad_nodes, "every quadtree node reached once (%u of %u)", nodes,
           st.quad_nodes);
    tap_ok(blocks > 0 && bad_block == 0, "top blocks: each cell's density and node as the walk "
           "from the root finds them (%u bad in the blocks of %u classes)", bad_block, blocks);
    tap_ok(bad_alias == 0, "top blocks: the alias tables give each cell its mass (%u bad)",
           bad_alias);
    tap_ok(bad_prob == 0, "quadrant probabilities positive, summing to 1 (%u bad)", bad_prob);
    tap_ok(bad_int == 0, "every leaf's density integrates to 1 over the square (%u not)", bad_int);
    tap_ok(gridded > 0 && bad_grid == 0, "... and through the lookup on a 256^2 midpoint grid "
           "(%u of the %u leaves at most 8 deep differ)", bad_grid, gridded);
    tap_ok(bad_weight == 0, "a leaf's class guides iff it has %u records of radiance in front of its axis "
           "(%u not)",
           o.min_records, bad_weight);
    /* the spot holds most of the energy: 0.05 x 20 against 0.95 x 0.5 */
    tap_ok(guiding > 0 && spot_high >= 0.9 * guiding, "the bright spot's density is above 20 "
           "times uniform in %u of the %u quadtrees that guide and face it", spot_high, guiding);
    tap_ok(dark_ratio < 0.5, "the dark half keeps about the floor (at most %.3f)", dark_ratio);
    free(count);
    free(lit);
    free(t);
    free(r);
    free(copy);
}

/* Fewer records than a leaf guides with: one leaf, weight 0, no light
 * estimate. */
static void test_few(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    struct cv_sd_record *r = make_records(20, 0);
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(lo, hi, r, 20, &cv_sdtree_defaults, &t, &nt, &st);
    tap_ok(st.spatial_leaves == 1 && st.guiding == 0, "20 records: one leaf that does not guide");
    uint32_t known = 0;
    for (uint32_t c = 0; c < CV_SD_CLASSES; c++)
        known += t[(uint32_t)t[(uint32_t)t[0][2] + c][2] + 1][3] != 0;
    tap_ok(known == 0, "20 records: no class has a light estimate (%u have)", known);
    free(t);
    free(r);
}

/* The light estimate at each class's training root (shared/sdtree.h):
 * records in pairs at one point, all of class 4 (+z) looking straight up,
 * one of each pair lit (radiance 1, density 1 / (4 pi)): every leaf's
 * class 4 holds the mean value over all its records, lit or not, about
 * 2 pi, from as many records as it counted; the classes without records
 * hold no estimate. */
static void test_light(void)
{
    const float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const size_t N = 40000;
    const double u = 0.999, want = 2 * M_PI * (2 * u - 1);
    struct cv_sd_record *r = calloc(N, sizeof(*r));
    for (size_t i = 0; i < N; i += 2) {
        for (size_t k = i; k < i + 2; k++) {
            for (int a = 0; a < 3; a++)
                r[k].p[a] = k == i ? (float)rnd() : r[i].p[a];
            r[k].pdf = (float)(1 / (4 * M_PI));
            r[k].u = (float)(4 + u);
            r[k].v = (float)rnd();
            r[k].L = k == i ? 1.0f : 0.0f;
        }
    }
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(lo, hi, r, N, &cv_sdtree_defaults, &t, &nt, &st);
    uint32_t leaves = 0, bad_lit = 0, bad_dark = 0;
    double worst = 0;
    for (uint32_t i = 0; i < st.spatial_nodes; i++) {
        if (t[i][0] != (float)CV_SD_LEAF)
            continue;
        leaves++;
        for (uint32_t c = 0; c < CV_SD_CLASSES; c++) {
            const float *e = t[(uint32_t)t[(uint32_t)t[i][2] + c][2] + 1];
            if (c != 4) {
                bad_dark += e[2] != 0 || e[3] != 0;
                continue;
            }
            double d = fabs(e[2] / want - 1);
            if (d > worst)
                worst = d;
            bad_lit += !(e[3] >= cv_sdtree_defaults.min_records) || e[3] != floorf(e[3]);
        }
    }
    tap_ok(leaves > 8 && bad_lit == 0 && worst < 0.1,
           "light estimate: class 4 of each of %u leaves holds the mean value of all its "
           "records, %.4f within %.3f (10 %% allowed), counted (%u bad)", leaves, want, worst,
           bad_lit);
    tap_ok(bad_dark == 0, "light estimate: none in the classes without records (%u have one)",
           bad_dark);
    free(t);
    free(r);
}

/* Records in a small cluster: leaves deeper than the grid block's 3 g
 * levels, so that its cells name inner nodes there. */
static void test_deep(void)
{
    const float lo[3] = {-1.5f, 2.25f, 100.0f}, hi[3] = {0.5f, 3.0f, 101.0f};
    const size_t N = 100000;
    struct cv_sd_record *r = make_records(N, 0.05);
    for (size_t i = 0; i < N; i++)
        for (int a = 0; a < 3; a++) {
            double f = i % 10 ? 0.3 + 1e-3 * rnd() : rnd();
            r[i].p[a] = (float)(lo[a] + (hi[a] - lo[a]) * f);
        }
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(lo, hi, r, N, &cv_sdtree_defaults, &t, &nt, &st);
    tap_ok(st.max_spatial_depth > 3 * CV_SD_GRID_LOG2 &&
               st.record_spatial_depth > st.mean_spatial_depth,
           "cluster: leaves to depth %u, deeper by records (%.2f) than by leaves (%.2f)",
           st.max_spatial_depth, st.record_spatial_depth, st.mean_spatial_depth);
    check_depths("cluster", (const float(*)[4])t, &st);
    check_grid("cluster", (const float(*)[4])t, nt);
    free(t);
    free(r);
}

int main(void)
{
    test_block_levels();
    test_empty();
    test_build();
    test_few();
    test_light();
    test_deep();
    return tap_done();
}
