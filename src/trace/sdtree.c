/* sdtree.c: see sdtree.h. */
#include <math.h>
#include <pthread.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "glsl/shared/sdtree.h"
#include "trace/sdtree.h"

const struct cv_sdtree_opts cv_sdtree_defaults = {
    /* above the Q-table's 0.3: with the adjoint-driven roulette its guided
     * paths end sooner and err less at equal time (bench/RESULTS.md,
     * "sdtree's guiding share with the roulette") */
    .mix = 0.7f,
    /* for the trees that only training draws from (bench/RESULTS.md,
     * "sdtree's share in training") */
    .train_mix = 0.3f,
    .split_c = 8.0f,
    .rho = 0.01f,
    /* the records of a llvmpipe-sized image are few: quadrants split on a
     * handful of bright samples sent guided directions after noise
     * (bench/RESULTS.md, "sdtree guide") */
    .min_split = 64,
    .max_depth = CV_SD_MAX_DEPTH,
    /* the deepest measured, the fastest (bench/RESULTS.md, "sdtree's
     * quadtrees with top blocks") */
    .block_log2 = CV_SD_BLOCK_MAX_LOG2,
    .floor = 0.3f,
    .min_records = 32,
    /* no filter: neither box filter lowered the room's error, and each
     * multiplies the training splat's adds (bench/RESULTS.md, "sdtree:
     * training filters") */
    .filter = 0,
    /* measured on veach-ajar and the closed room (bench/RESULTS.md,
     * "sdtree: what the guide learns") */
    .clamp = 10.0f,
};

/* a training or sampling node's "no node" (a child 0 is a leaf quadrant:
 * a root is never a child) */
#define NONE UINT32_MAX

struct snode {
    uint32_t axis;    /* 0..2, or 3: leaf */
    float split;
    uint32_t child;   /* inner: first child; leaf: its index among the leaves */
};

struct cnode {
    uint32_t samp;    /* sampling quadtree root */
    float weight;
    uint32_t train;   /* training quadtree root */
    float clamp;      /* the limit of a record's value (opts.clamp), 0: none */
    float light;      /* the records' mean value (glsl/shared/sdtree.h) */
    float light_n;    /* ... from this many records; 0: no estimate */
};

struct qnode {        /* sampling */
    float p[4];
    uint32_t child[4];
};

struct tnode {        /* training */
    uint32_t child[4];
};

struct cv_sdtree {
    double lo[3], hi[3];
    struct snode *s;
    size_t ns, cs;
    struct cnode *c;  /* CV_SD_CLASSES per leaf */
    size_t nc, cc;
    struct qnode *q;
    size_t nq, cq;
    struct tnode *t;
    size_t nt, ct;
};

/* The split coordinate of a spatial node over [lo, hi] along an axis: its
 * middle, in double from the cube's corners down, so that every node
 * splitting the same plane holds the same float (the grid block's bounds,
 * grid_bounds, rely on it). */
static double midpoint(double lo, double hi) { return 0.5 * (lo + hi); }

/* Appends a zeroed node to one of the tree's arrays; its index. */
static uint32_t push_s(struct cv_sdtree *t)
{
    CV_PUSH(t->s, t->ns, t->cs, (struct snode){0});
    return (uint32_t)(t->ns - 1);
}

static uint32_t push_c(struct cv_sdtree *t)
{
    CV_PUSH(t->c, t->nc, t->cc, (struct cnode){0});
    return (uint32_t)(t->nc - 1);
}

static uint32_t push_q(struct cv_sdtree *t)
{
    CV_PUSH(t->q, t->nq, t->cq, (struct qnode){0});
    return (uint32_t)(t->nq - 1);
}

static uint32_t push_t(struct cv_sdtree *t)
{
    CV_PUSH(t->t, t->nt, t->ct, (struct tnode){0});
    return (uint32_t)(t->nt - 1);
}

static void free_arrays(struct cv_sdtree *t)
{
    free(t->s);
    free(t->c);
    free(t->q);
    free(t->t);
}

struct cv_sdtree *cv_sdtree_create(const float bmin[3], const float bmax[3])
{
    struct cv_sdtree *t = cv_xcalloc(1, sizeof(*t));
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
    for (int a = 0; a < 3; a++) {
        t->lo[a] = c[a] - ext / 2;
        t->hi[a] = c[a] + ext / 2;
    }
    uint32_t root = push_s(t);
    t->s[root].axis = 3;
    for (uint32_t cls = 0; cls < CV_SD_CLASSES; cls++) {
        uint32_t ci = push_c(t), q = push_q(t);
        for (int k = 0; k < 4; k++)
            t->q[q].p[k] = 0.25f;
        t->c[ci].samp = q;
        t->c[ci].train = push_t(t);
    }
    return t;
}

void cv_sdtree_destroy(struct cv_sdtree **tp)
{
    if (!tp || !*tp)
        return;
    free_arrays(*tp);
    free(*tp);
    *tp = NULL;
}

size_t cv_sdtree_stat_words(const struct cv_sdtree *t)
{
    return CV_SD_CLASS_WORDS * t->nc + CV_SD_NODE_WORDS * t->nt;
}

/* The first statistics word of training node j. */
static size_t train_word(const struct cv_sdtree *t, uint32_t j)
{
    return CV_SD_CLASS_WORDS * t->nc + CV_SD_NODE_WORDS * (size_t)j;
}

/* The grid block's bounds texels along axis a (shared/sdtree.h), cells
 * [c0, c1) over [lo, hi]: each plane between two cells gets the split
 * coordinate the tree's nodes there hold (the same midpoint recursion from
 * the cube's faces). */
static void grid_bounds(const struct cv_sdtree *t, float (*b)[4], int a, uint32_t c0,
                        uint32_t c1, double lo, double hi)
{
    if (c0 == 0)
        b[a * CV_SD_GRID_CELLS][0] = (float)t->lo[a];
    if (c1 == CV_SD_GRID_CELLS)
        b[a * CV_SD_GRID_CELLS + c1 - 1][1] = (float)t->hi[a];
    if (c1 - c0 < 2)
        return;
    uint32_t cm = (c0 + c1) / 2;
    double mid = midpoint(lo, hi);
    b[a * CV_SD_GRID_CELLS + cm - 1][1] = (float)mid;
    b[a * CV_SD_GRID_CELLS + cm][0] = (float)mid;
    grid_bounds(t, b, a, c0, cm, lo, mid);
    grid_bounds(t, b, a, cm, c1, mid, hi);
}

/* The grid block's cells (shared/sdtree.h) of spatial node `node` at
 * depth, which covers the cells [c0, c1) (per axis): a leaf, or the node
 * at depth 3 g, fills them; an inner node above hands each half to a
 * child (its split is the middle plane along axis depth % 3). */
static void grid_cells(const struct cv_sdtree *t, float *cells, uint32_t node, uint32_t depth,
                       const uint32_t c0[3], const uint32_t c1[3])
{
    const struct snode *s = &t->s[node];
    if (s->axis >= 3 || depth >= 3 * CV_SD_GRID_LOG2) {
        float v = s->axis >= 3 ? -1.0f - (float)(t->ns + (size_t)s->child * CV_SD_CLASSES)
                               : (float)node;
        for (uint32_t z = c0[2]; z < c1[2]; z++)
            for (uint32_t y = c0[1]; y < c1[1]; y++)
                for (uint32_t x = c0[0]; x < c1[0]; x++)
                    cells[x + CV_SD_GRID_CELLS * (y + CV_SD_GRID_CELLS * z)] = v;
        return;
    }
    uint32_t a = s->axis, l[3], h[3];
    memcpy(l, c0, sizeof(l));
    memcpy(h, c1, sizeof(h));
    h[a] = l[a] = (c0[a] + c1[a]) / 2;
    grid_cells(t, cells, s->child, depth + 1, c0, h);
    grid_cells(t, cells, s->child + 1, depth + 1, l, c1);
}

/* Sampling nodes' children offsets stay below this (shared/sdtree.h). */
#define CHILD_OFFSET_LIMIT (1u << 20)

uint32_t cv_sdtree_block_log2(size_t roots, uint32_t max)
{
    uint32_t l = max < CV_SD_BLOCK_MAX_LOG2 ? max : CV_SD_BLOCK_MAX_LOG2;
    while (l > 0 && roots > CV_SD_BLOCK_MAX_TEXELS >> (2 * l))
        l--;
    return l;
}

/* Fills the cells of a top block b of 2^l cells a side under the square
 * of sampling node q (table x) at depth d, corner (cx, cy) in cells, the
 * density pdf above it: each cell's density as the shaders' walk
 * multiplies it (float, level by level) and the node at the cell. */
static void block_cells(const float (*x)[4], float (*b)[4], uint32_t l, uint32_t q, uint32_t d,
                        uint32_t cx, uint32_t cy, float pdf)
{
    uint32_t side = 1u << l;
    if (d == l) {
        b[cx + side * cy][0] = pdf;
        b[cx + side * cy][3] = (float)q;
        return;
    }
    float p[4];
    uint32_t ch[4], half = 1u << (l - d - 1);
    cv_sdtree_node(x, q, p, ch);
    for (uint32_t k = 0; k < 4; k++) {
        uint32_t x0 = cx + (k & 1u) * half, y0 = cy + (k >> 1) * half;
        float pk = pdf * (4.0f * p[k]);
        if (ch[k]) {
            block_cells(x, b, l, ch[k], d + 1, x0, y0, pk);
            continue;
        }
        for (uint32_t j = 0; j < half; j++)   /* a leaf quadrant: its cells alike */
            for (uint32_t i = 0; i < half; i++) {
                b[x0 + i + side * (y0 + j)][0] = pk;
                b[x0 + i + side * (y0 + j)][3] = 0.0f;
            }
    }
}

/* The top block of l levels of the sampling quadtree at texel root of
 * table x (its nodes written), in the texels before it (shared/sdtree.h):
 * the cells, then Walker's alias table of their masses (Vose's
 * construction, in double). */
static void top_block(float (*x)[4], uint32_t root, uint32_t l)
{
    enum { MAX = 1u << (2 * CV_SD_BLOCK_MAX_LOG2) };
    uint32_t n = 1u << (2 * l);
    float(*b)[4] = x + root - n;
    block_cells((const float(*)[4])x, b, l, root, 0, 0, 0, 1.0f);
    double prob[MAX], sum = 0;
    for (uint32_t c = 0; c < n; c++)
        sum += b[c][0];
    uint32_t small[MAX], large[MAX], ns = 0, nl = 0;
    for (uint32_t c = 0; c < n; c++) {
        prob[c] = sum > 0 ? b[c][0] * n / sum : 1.0;
        if (prob[c] < 1.0)
            small[ns++] = c;
        else
            large[nl++] = c;
    }
    while (ns && nl) {
        uint32_t s = small[--ns], g = large[nl - 1];
        b[s][1] = (float)prob[s];
        b[s][2] = (float)g;
        prob[g] -= 1.0 - prob[s];
        if (prob[g] < 1.0) {
            nl--;
            small[ns++] = g;
        }
    }
    /* what is left holds its own mass (up to rounding) */
    while (nl) {
        uint32_t g = large[--nl];
        b[g][1] = 1.0f;
        b[g][2] = (float)g;
    }
    while (ns) {
        uint32_t s = small[--ns];
        b[s][1] = 1.0f;
        b[s][2] = (float)s;
    }
}

/* The top blocks of a table, shared out among threads: each block is
 * written by one thread alone and reads only the nodes laid out before,
 * so the table is the same bits whatever the count. They are most of the
 * host's work at a training iteration's end, while the GPU waits. */
struct blocks {
    float (*x)[4];
    const uint32_t *roots;
    size_t n;
    uint32_t l;
    unsigned threads;
    unsigned index;   /* a thread's own share (its copy) */
};

/* A block every `threads` roots, from the thread's index on. */
static void *blocks_share(void *arg)
{
    const struct blocks *b = arg;
    for (size_t i = b->index; i < b->n; i += b->threads)
        top_block(b->x, b->roots[i], b->l);
    return NULL;
}

/* At most this many threads, and one for every this many blocks: a thread
 * costs more than a few blocks. */
enum { BLOCK_THREADS_MAX = 16, BLOCKS_A_THREAD = 64 };

static void top_blocks(float (*x)[4], const uint32_t *roots, size_t n, uint32_t l)
{
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    size_t want = n / BLOCKS_A_THREAD;
    if (cores > BLOCK_THREADS_MAX)
        cores = BLOCK_THREADS_MAX;
    unsigned threads = cores < 1 ? 1 : (unsigned)cores;
    if (want < threads)
        threads = want < 1 ? 1 : (unsigned)want;
    struct blocks b[BLOCK_THREADS_MAX];
    pthread_t id[BLOCK_THREADS_MAX];
    bool started[BLOCK_THREADS_MAX] = {false};
    for (unsigned k = 0; k < threads; k++) {
        b[k] = (struct blocks){x, roots, n, l, threads, k};
        /* the calling thread takes share 0, and any share no thread took */
        started[k] = k > 0 && pthread_create(&id[k], NULL, blocks_share, &b[k]) == 0;
    }
    for (unsigned k = 0; k < threads; k++)
        if (!started[k])
            blocks_share(&b[k]);
    for (unsigned k = 1; k < threads; k++)
        if (started[k])
            pthread_join(id[k], NULL);
}

void cv_sdtree_table(const struct cv_sdtree *t, const struct cv_sdtree_opts *o,
                     float (**texels)[4], size_t *n_texels)
{
    /* spatial nodes, class texels, sampling nodes (one texel each, each
     * node's children consecutive: breadth first from every root, the top
     * block of one that guides before it), training nodes (two texels
     * each), the grid block */
    size_t sbase = t->ns + t->nc;
    uint32_t *pos = cv_xmalloc((t->nq ? t->nq : 1) * sizeof(*pos));
    /* the quadtrees that guide take a top block: the shaders never walk
     * the others (weight 0), and the blocks' texels cost cache */
    uint8_t *guides = cv_xcalloc(t->nq ? t->nq : 1, 1);
    size_t roots = 0;
    for (size_t i = 0; i < t->nc; i++) {
        roots += t->c[i].weight > 0 && !guides[t->c[i].samp];
        guides[t->c[i].samp] |= t->c[i].weight > 0;
    }
    uint32_t l = cv_sdtree_block_log2(roots, o->block_log2), cells = 1u << (2 * l);
    uint32_t *queue = cv_xmalloc((t->nq ? t->nq : 1) * sizeof(*queue));
    for (size_t j = 0; j < t->nq; j++)
        pos[j] = NONE;
    size_t next = sbase;
    for (size_t i = 0; i < t->nc; i++) {
        uint32_t r = t->c[i].samp;
        if (pos[r] != NONE)
            continue;   /* shared by the leaves a split made */
        size_t head = 0, tail = 0;
        next += guides[r] ? cells : 0;
        pos[r] = (uint32_t)next++;
        queue[tail++] = r;
        while (head < tail) {
            uint32_t j = queue[head++];
            for (int k = 0; k < 4; k++) {
                uint32_t c = t->q[j].child[k];
                if (c) {
                    pos[c] = (uint32_t)next++;
                    queue[tail++] = c;
                }
            }
        }
    }
    size_t tbase = next, gbase = tbase + 2 * t->nt, nt = gbase + CV_SD_GRID_TEXELS;
    float(*x)[4] = cv_xcalloc(nt, sizeof(*x));
    x[0][3] = (float)l;   /* the root's w (shared/sdtree.h) */
    for (size_t i = 0; i < t->ns; i++) {
        const struct snode *s = &t->s[i];
        x[i][0] = (float)s->axis;
        if (s->axis < 3) {
            x[i][1] = s->split;
            x[i][2] = (float)s->child;
        } else {
            x[i][2] = (float)(t->ns + (size_t)s->child * CV_SD_CLASSES);
        }
    }
    for (size_t i = 0; i < t->nc; i++) {
        x[t->ns + i][0] = (float)pos[t->c[i].samp];
        x[t->ns + i][1] = t->c[i].weight;
        x[t->ns + i][2] = (float)(tbase + 2 * (size_t)t->c[i].train);
        x[t->ns + i][3] = (float)(CV_SD_CLASS_WORDS * i);
    }
    for (size_t j = 0; j < t->nq; j++) {
        if (pos[j] == NONE)
            continue;   /* no class samples it */
        float *a = x[pos[j]];
        for (int k = 0; k < 3; k++)
            a[k] = t->q[j].p[k];
        uint32_t mask = 0, first = NONE;
        for (int k = 0; k < 4; k++) {
            uint32_t c = t->q[j].child[k];
            if (c) {
                mask |= 1u << k;
                if (first == NONE)
                    first = pos[c];
            }
        }
        /* children past the offset limit (a quadtree of a million nodes)
         * are left out: sampling and the density still agree */
        if (mask && first - pos[j] >= CHILD_OFFSET_LIMIT)
            mask = 0;
        a[3] = (float)(mask ? 16u * (first - pos[j]) + mask : 0u);
    }
    /* each root that guides once, however many leaves share it */
    size_t nb = 0;
    for (size_t j = 0; j < t->nq; j++)
        if (guides[j])
            queue[nb++] = pos[j];
    top_blocks(x, queue, nb, l);
    for (size_t j = 0; j < t->nt; j++) {
        float *ch = x[tbase + 2 * j];
        for (int k = 0; k < 4; k++)
            ch[k] = t->t[j].child[k] ? (float)(tbase + 2 * (size_t)t->t[j].child[k]) : 0.0f;
        x[tbase + 2 * j + 1][0] = (float)train_word(t, (uint32_t)j);
    }
    for (size_t i = 0; i < t->nc; i++) {
        float *r = x[tbase + 2 * (size_t)t->c[i].train + 1];
        r[1] = t->c[i].clamp;
        r[2] = t->c[i].light;
        r[3] = t->c[i].light_n;
    }
    for (int a = 0; a < 3; a++)
        grid_bounds(t, x + gbase, a, 0, CV_SD_GRID_CELLS, t->lo[a], t->hi[a]);
    const uint32_t c0[3] = {0, 0, 0},
                   c1[3] = {CV_SD_GRID_CELLS, CV_SD_GRID_CELLS, CV_SD_GRID_CELLS};
    grid_cells(t, &x[gbase + 3 * CV_SD_GRID_CELLS][0], 0, 0, c0, c1);
    free(pos);
    free(queue);
    free(guides);
    *texels = x;
    *n_texels = nt;
}

void cv_sdtree_node(const float (*x)[4], uint32_t q, float p[4], uint32_t child[4])
{
    const float *n = x[q];
    p[0] = n[0];
    p[1] = n[1];
    p[2] = n[2];
    /* as the shaders compute it (sdtree.glsl: cv_sd_node_probs) */
    p[3] = fmaxf(0.0f, 1.0f - (n[0] + n[1] + n[2]));
    uint32_t code = (uint32_t)n[3], mask = code & 15u, at = q + (code >> 4);
    for (int k = 0; k < 4; k++)
        child[k] = mask & (1u << k) ? at++ : 0;
}

/* What a record adds to its quadtree (the shaders' cv_sd_value): the Monte
 * Carlo estimate of the integral of the incident radiance times the cosine
 * to its class's axis (the normal of a wall that faces the axis) over
 * directions; the guide then stands for the diffuse integrand, not the
 * radiance alone, which sends samples to grazing and back-facing
 * directions. -1: the record does not count (no density, a value not
 * finite or below 0, a position not finite). */
static float rec_value(const struct cv_sd_record *r, int cls, double u)
{
    double L = (double)r->L / r->pdf;
    if (!(r->pdf > 0) || !isfinite(L) || !(L >= 0) || !isfinite(r->p[0]) ||
        !isfinite(r->p[1]) || !isfinite(r->p[2]))
        return -1;
    double z = 2.0 * u - 1, phi = 2 * M_PI * r->v - M_PI, s = sqrt(fmax(0, 1 - z * z));
    double w[3] = {s * cos(phi), s * sin(phi), z};
    double c = w[cls / 2] * (cls & 1 ? -1 : 1);
    return c > 0 ? (float)(L * c) : 0.0f;
}

static void add_float(uint32_t *word, float v)
{
    float f;
    memcpy(&f, word, sizeof(f));
    f += v;
    memcpy(word, &f, sizeof(f));
}

struct cv_sd_frame cv_sdtree_frame(const struct cv_sdtree *t, const struct cv_sdtree_opts *o)
{
    struct cv_sd_frame f = {{(float)t->lo[0], (float)t->lo[1], (float)t->lo[2],
                             (float)(t->hi[0] - t->lo[0])},
                            o->filter};
    return f;
}

/* The class texel of point p (-1 past the depth limit) and the box of its
 * leaf (sdtree.glsl: cv_sd_class_texel_box). */
static int32_t class_texel_box(const float (*x)[4], const struct cv_sd_frame *f, const float p[3],
                               uint32_t cls, float lo[3], float size[3])
{
    for (int a = 0; a < 3; a++) {
        lo[a] = f->cube[a];
        size[a] = f->cube[3];
    }
    uint32_t node = 0;
    for (uint32_t d = 0; d < CV_SD_MAX_SPATIAL_DEPTH && x[node][0] < (float)CV_SD_LEAF; d++) {
        int axis = (int)x[node][0];
        size[axis] *= 0.5f;
        bool upper = p[axis] >= x[node][1];
        if (upper)
            lo[axis] = x[node][1];
        node = (uint32_t)x[node][2] + (upper ? 1u : 0u);
    }
    return x[node][0] < (float)CV_SD_LEAF ? -1 : (int32_t)((uint32_t)x[node][2] + cls);
}

/* sdtree.glsl: cv_sd_footprint, in the same float steps. */
static void footprint(float x, float h, float o, float o0, float span, float *plo, float *phi,
                      float *wlo)
{
    float c = fminf(fmaxf(x, o0 + 0.5f * h), o0 + span - 0.5f * h);
    float a = c - 0.5f * h, b = c + 0.5f * h;
    float t = (a - o) / h;
    float i0 = floorf(t);
    float edge = o + (i0 + 1.0f) * h;
    *wlo = 1.0f - (t - i0);
    *plo = 0.5f * (a + edge);
    *phi = 0.5f * (edge + b);
}

/* The quadrant of point s at a node, and s in it. */
static int quadrant(float s[2])
{
    int ix = s[0] < 0.5f ? 0 : 1, iy = s[1] < 0.5f ? 0 : 1;
    s[0] = 2.0f * s[0] - (float)ix;
    s[1] = 2.0f * s[1] - (float)iy;
    return ix + 2 * iy;
}

/* The flux word of the leaf quadrant of point s in the training quadtree
 * at texel q, -1 past the limit, and the quadrant's side (sdtree.glsl:
 * cv_sd_train_leaf). */
static int64_t leaf_word(const float (*x)[4], uint32_t q, const float s0[2], float *side)
{
    float s[2] = {s0[0], s0[1]};
    *side = 1.0f;
    for (uint32_t d = 0; d < CV_SD_MAX_DEPTH; d++) {
        *side *= 0.5f;
        int k = quadrant(s);
        uint32_t c = (uint32_t)x[q][k];
        if (!c)
            return (int64_t)(uint32_t)x[q + 1][0] + k;
        q = c;
    }
    return -1;
}

/* sdtree.glsl: cv_sd_add_leaf. */
static void add_leaf(const float (*x)[4], uint32_t *stats, uint32_t q, const float s[2], float v)
{
    float side;
    int64_t w = v > 0 ? leaf_word(x, q, s, &side) : -1;
    if (w >= 0)
        add_float(&stats[w], v);
}

/* sdtree.glsl: cv_sd_splat_flux (w, h: the leaf quadrant of s0 below q,
 * as leaf_word found it). */
static void splat_flux(const float (*x)[4], const struct cv_sd_frame *f, uint32_t *stats,
                       uint32_t q, const float s0[2], float v, int64_t w, float h)
{
    if (!(f->filter & CV_SD_FILTER_DIRECTIONAL)) {
        if (w >= 0)
            add_float(&stats[w], v);
        return;
    }
    float plo[2], phi[2], wlo[2];
    for (int a = 0; a < 2; a++)
        footprint(s0[a], h, 0.0f, 0.0f, 1.0f, &plo[a], &phi[a], &wlo[a]);
    add_leaf(x, stats, q, (float[2]){plo[0], plo[1]}, v * (wlo[0] * wlo[1]));
    add_leaf(x, stats, q, (float[2]){phi[0], plo[1]}, v * ((1.0f - wlo[0]) * wlo[1]));
    add_leaf(x, stats, q, (float[2]){plo[0], phi[1]}, v * (wlo[0] * (1.0f - wlo[1])));
    add_leaf(x, stats, q, (float[2]){phi[0], phi[1]}, v * ((1.0f - wlo[0]) * (1.0f - wlo[1])));
}

void cv_sdtree_splat(const float (*x)[4], const struct cv_sd_frame *f, uint32_t *stats,
                     const struct cv_sd_record *r)
{
    float cls = floorf(r->u);
    if (!(cls >= 0 && cls < CV_SD_CLASSES))
        return;
    float s[2] = {r->u - cls, r->v};
    float v = rec_value(r, (int)cls, s[0]);
    float lo[3], size[3];
    int32_t c = v < 0 ? -1 : class_texel_box(x, f, r->p, (uint32_t)cls, lo, size);
    if (c < 0)
        return;
    const float *ct = x[c];
    float lim = x[(uint32_t)ct[2] + 1][1];
    if (lim > 0 && v > lim)
        v = lim;
    uint32_t w = (uint32_t)ct[3];
    stats[w]++;
    stats[w + 1] += v > 0;
    float h;
    int64_t lw = leaf_word(x, (uint32_t)ct[2], s, &h);
    if (lw >= 0)
        stats[lw + 4]++;
    if (!(v > 0))
        return;
    if (!(f->filter & CV_SD_FILTER_SPATIAL)) {
        splat_flux(x, f, stats, (uint32_t)ct[2], s, v, lw, h);
        return;
    }
    float plo[3], phi[3], wlo[3];
    for (int a = 0; a < 3; a++)
        footprint(r->p[a], size[a], lo[a], f->cube[a], f->cube[3], &plo[a], &phi[a], &wlo[a]);
    for (int b = 0; b < 8; b++) {
        float p[3] = {b & 1 ? phi[0] : plo[0], b & 2 ? phi[1] : plo[1], b & 4 ? phi[2] : plo[2]};
        float wt = (b & 1 ? 1.0f - wlo[0] : wlo[0]) * (b & 2 ? 1.0f - wlo[1] : wlo[1]) *
                   (b & 4 ? 1.0f - wlo[2] : wlo[2]);
        if (!(wt > 0))
            continue;
        float l2[3], s2[3];
        int32_t cb = class_texel_box(x, f, p, (uint32_t)cls, l2, s2);
        if (cb < 0)
            continue;
        uint32_t qb = (uint32_t)x[cb][2];
        float hb;
        int64_t wb = leaf_word(x, qb, s, &hb);
        splat_flux(x, f, stats, qb, s, v * wt, wb, hb);
    }
}

/* One refinement: the old guide and its statistics, the new guide. */
struct refine {
    const struct cv_sdtree *old;
    const uint32_t *stats;   /* NULL: all zero */
    const struct cv_sdtree_opts *o;
    struct cv_sdtree *n;
    double thresh;
    struct cv_sdtree_stats st;
    double depth_sum, weighted_depth, weight;   /* over the new leaves */
};

/* The flux (e) and record counts (cnt) of old training node j's quadrants. */
static void node_stats(const struct refine *r, uint32_t j, double e[4], double cnt[4])
{
    size_t w = train_word(r->old, j);
    for (int k = 0; k < 4; k++) {
        float f = 0;
        if (r->stats)
            memcpy(&f, &r->stats[w + k], sizeof(f));
        e[k] = isfinite(f) && f > 0 ? f : 0;
        cnt[k] = r->stats ? r->stats[w + 4 + k] : 0;
    }
}

/* The sampling node of old training node j, whose square has side `side`,
 * at depth: its quadrants' flux plus the floor's share fe per unit area,
 * normalized. */
static uint32_t make_sampling(struct refine *r, uint32_t j, double side, uint32_t depth,
                              double fe)
{
    uint32_t node = push_q(r->n);
    if (depth + 1 > r->st.max_quad_depth)
        r->st.max_quad_depth = depth + 1;
    double e[4], cnt[4], w[4], sum = 0, h = side / 2;
    node_stats(r, j, e, cnt);
    for (int k = 0; k < 4; k++) {
        w[k] = e[k] + fe * h * h;
        sum += w[k];
    }
    for (int k = 0; k < 4; k++)
        r->n->q[node].p[k] = sum > 0 ? (float)(w[k] / sum) : 0.25f;
    for (int k = 0; k < 4; k++) {
        uint32_t oc = r->old->t[j].child[k];
        if (oc) {
            uint32_t c = make_sampling(r, oc, h, depth + 1, fe);
            r->n->q[node].child[k] = c;
        }
    }
    return node;
}

/* The next training node at depth, from old training node j (NONE: a new
 * one) with its quadrants' flux e and counts cnt; E: its class's flux. A
 * quadrant over rho E with min_split records subdivides; a new node takes a
 * quarter of its quadrant's flux and count in each of its own, so that a
 * bright quadrant may subdivide several levels at once (Müller et al.). */
static uint32_t make_training(struct refine *r, uint32_t j, const double e[4],
                              const double cnt[4], uint32_t depth, double E)
{
    const struct cv_sdtree_opts *o = r->o;
    uint32_t node = push_t(r->n);
    for (int k = 0; k < 4; k++) {
        uint32_t c = 0;
        if (depth + 1 < o->max_depth && E > 0 && e[k] > o->rho * E && cnt[k] >= o->min_split) {
            uint32_t oc = j != NONE ? r->old->t[j].child[k] : 0;
            double ce[4], cc[4];
            if (oc) {
                node_stats(r, oc, ce, cc);
            } else {
                for (int m = 0; m < 4; m++) {
                    ce[m] = e[k] / 4;
                    cc[m] = cnt[k] / 4;
                }
            }
            c = make_training(r, oc ? oc : NONE, ce, cc, depth + 1, E);
        }
        r->n->t[node].child[k] = c;
    }
    return node;
}

/* What an old leaf's class learned, handed to the leaves it splits into. */
struct learned {
    uint32_t samp;
    float weight;
    float clamp, light, light_n;
    uint32_t train;   /* the old training root */
    double e[4], cnt[4], E;
};

/* New spatial node `node` over [lo, hi] at depth, for an old leaf that
 * learned lc and holds `count` records: splits at the middle while the
 * count (halved per level, as the records are unknown) is over the
 * threshold, then makes the leaves, which share the sampling quadtrees. */
static void split_leaf(struct refine *r, uint32_t node, const struct learned *lc, double count,
                       const double lo[3], const double hi[3], uint32_t depth)
{
    if (count > r->thresh && depth < CV_SD_MAX_SPATIAL_DEPTH) {
        int axis = (int)(depth % 3);
        double mid = midpoint(lo[axis], hi[axis]);
        uint32_t c = push_s(r->n);
        push_s(r->n);
        r->n->s[node] = (struct snode){(uint32_t)axis, (float)mid, c};
        double l[3], h[3];
        memcpy(l, lo, sizeof(l));
        memcpy(h, hi, sizeof(h));
        h[axis] = mid;
        split_leaf(r, c, lc, count / 2, l, h, depth + 1);
        h[axis] = hi[axis];
        l[axis] = mid;
        split_leaf(r, c + 1, lc, count / 2, l, h, depth + 1);
        return;
    }
    r->n->s[node] = (struct snode){3, 0.0f, (uint32_t)(r->n->nc / CV_SD_CLASSES)};
    if (r->n->nc == 0 || depth < r->st.min_spatial_depth)
        r->st.min_spatial_depth = depth;
    if (depth > r->st.max_spatial_depth)
        r->st.max_spatial_depth = depth;
    r->depth_sum += depth;
    r->weighted_depth += count * depth;
    r->weight += count;
    for (uint32_t cls = 0; cls < CV_SD_CLASSES; cls++) {
        uint32_t ci = push_c(r->n);
        r->n->c[ci].samp = lc[cls].samp;
        r->n->c[ci].weight = lc[cls].weight;
        r->n->c[ci].clamp = lc[cls].clamp;
        r->n->c[ci].light = lc[cls].light;
        r->n->c[ci].light_n = lc[cls].light_n;
        r->st.guiding += lc[cls].weight > 0;
        uint32_t t = make_training(r, lc[cls].train, lc[cls].e, lc[cls].cnt, 0, lc[cls].E);
        r->n->c[ci].train = t;
    }
}

static void refine_spatial(struct refine *r, uint32_t old, uint32_t node, const double lo[3],
                           const double hi[3], uint32_t depth)
{
    const struct snode *os = &r->old->s[old];
    if (os->axis < 3) {
        uint32_t c = push_s(r->n), oc = os->child;
        push_s(r->n);
        int axis = (int)os->axis;
        r->n->s[node] = r->old->s[old];
        r->n->s[node].child = c;
        double mid = midpoint(lo[axis], hi[axis]), l[3], h[3];
        memcpy(l, lo, sizeof(l));
        memcpy(h, hi, sizeof(h));
        h[axis] = mid;
        refine_spatial(r, oc, c, l, h, depth + 1);
        h[axis] = hi[axis];
        l[axis] = mid;
        refine_spatial(r, oc + 1, c + 1, l, h, depth + 1);
        return;
    }
    struct learned lc[CV_SD_CLASSES];
    double count = 0;
    for (uint32_t cls = 0; cls < CV_SD_CLASSES; cls++) {
        size_t ci = (size_t)os->child * CV_SD_CLASSES + cls, w = CV_SD_CLASS_WORDS * ci;
        const struct cnode *oc = &r->old->c[ci];
        double n = r->stats ? r->stats[w] : 0, lit = r->stats ? r->stats[w + 1] : 0;
        count += n;
        struct learned *l = &lc[cls];
        l->train = oc->train;
        node_stats(r, oc->train, l->e, l->cnt);
        l->E = l->e[0] + l->e[1] + l->e[2] + l->e[3];
        /* the floor spread over the square's unit area */
        l->samp = make_sampling(r, oc->train, 1, 0, r->o->floor * l->E);
        l->weight = lit >= r->o->min_records && l->E > 0 ? r->o->mix : 0.0f;
        /* the records' mean value (the flux is their sum) */
        l->clamp = r->o->clamp > 0 && lit > 0 && l->E > 0 ? (float)(r->o->clamp * l->E / lit) : 0.0f;
        /* ... and over all of them, unlit ones too: the light bouncing on
         * brings back, where enough records say it */
        bool known = n >= r->o->min_records;
        l->light = known ? (float)(l->E / n) : 0.0f;
        l->light_n = known ? (float)n : 0.0f;
    }
    split_leaf(r, node, lc, count, lo, hi, depth);
}

/* The shaders add a record only at the leaf quadrant it falls in
 * (sdtree.glsl, cv_sd_splat): each inner quadrant's flux and count are the
 * sums of its child node's four, filled in here below training node j. */
static void sum_inner(const struct cv_sdtree *t, uint32_t *s, uint32_t j)
{
    size_t w = train_word(t, j);
    for (int k = 0; k < 4; k++) {
        uint32_t c = t->t[j].child[k];
        if (!c)
            continue;
        sum_inner(t, s, c);
        size_t cw = train_word(t, c);
        float sum = 0;
        uint32_t cnt = 0;
        for (int m = 0; m < 4; m++) {
            float f;
            memcpy(&f, &s[cw + m], sizeof(f));
            sum += f;
            cnt += s[cw + 4 + m];
        }
        memcpy(&s[w + k], &sum, sizeof(sum));
        s[w + 4 + k] = cnt;
    }
}

void cv_sdtree_refine(struct cv_sdtree *t, const uint32_t *stats, const struct cv_sdtree_opts *o,
                      struct cv_sdtree_stats *st)
{
    struct cv_sdtree n = {0};
    memcpy(n.lo, t->lo, sizeof(n.lo));
    memcpy(n.hi, t->hi, sizeof(n.hi));
    uint32_t *full = NULL;
    if (stats) {
        size_t words = cv_sdtree_stat_words(t);
        full = cv_xmalloc(words * sizeof(*full));
        memcpy(full, stats, words * sizeof(*full));
        for (size_t ci = 0; ci < t->nc; ci++)
            sum_inner(t, full, t->c[ci].train);
    }
    struct refine r = {.old = t, .stats = full, .o = o, .n = &n};
    for (size_t ci = 0; stats && ci < t->nc; ci++)
        r.st.records += stats[CV_SD_CLASS_WORDS * ci];
    r.thresh = o->split_c * sqrt((double)r.st.records);
    if (r.thresh < 2 * o->min_records)
        r.thresh = 2 * o->min_records;
    uint32_t root = push_s(&n);
    refine_spatial(&r, 0, root, t->lo, t->hi, 0);
    free(full);
    free_arrays(t);
    *t = n;
    r.st.spatial_nodes = (uint32_t)t->ns;
    r.st.spatial_leaves = (uint32_t)(t->nc / CV_SD_CLASSES);
    r.st.quad_nodes = (uint32_t)t->nq;
    r.st.train_nodes = (uint32_t)t->nt;
    r.st.mean_spatial_depth = r.depth_sum / r.st.spatial_leaves;
    r.st.record_spatial_depth = r.weight > 0 ? r.weighted_depth / r.weight : 0;
    if (st)
        *st = r.st;
}

void cv_sdtree_learn_iteration(struct cv_sdtree *t, const struct cv_sd_record *rec, size_t n,
                               const struct cv_sdtree_opts *o, struct cv_sdtree_stats *st)
{
    float(*x)[4] = NULL;
    size_t nx = 0;
    cv_sdtree_table(t, o, &x, &nx);
    uint32_t *stats = cv_xcalloc(cv_sdtree_stat_words(t) + 1, sizeof(*stats));
    struct cv_sd_frame f = cv_sdtree_frame(t, o);
    for (size_t i = 0; i < n; i++)
        cv_sdtree_splat((const float(*)[4])x, &f, stats, &rec[i]);
    free(x);
    cv_sdtree_refine(t, stats, o, st);
    free(stats);
}

void cv_sdtree_learn_records(struct cv_sdtree *t, const struct cv_sd_record *rec, size_t n,
                             const struct cv_sdtree_opts *o, struct cv_sdtree_stats *st)
{
    /* each round adds at least a level where the tree changes: the depth
     * limits bound the rounds */
    for (uint32_t round = 0; round < CV_SD_MAX_SPATIAL_DEPTH + CV_SD_MAX_DEPTH + 2; round++) {
        size_t ns = t->ns, nt = t->nt;
        struct snode *s = cv_xmalloc(ns * sizeof(*s));
        struct tnode *tn = cv_xmalloc(nt * sizeof(*tn));
        memcpy(s, t->s, ns * sizeof(*s));
        memcpy(tn, t->t, nt * sizeof(*tn));
        cv_sdtree_learn_iteration(t, rec, n, o, st);
        bool same = t->ns == ns && t->nt == nt && !memcmp(s, t->s, ns * sizeof(*s)) &&
                    !memcmp(tn, t->t, nt * sizeof(*tn));
        free(s);
        free(tn);
        if (same)
            break;
    }
}

void cv_sdtree_build(const float bmin[3], const float bmax[3], const struct cv_sd_record *rec,
                     size_t n, const struct cv_sdtree_opts *o, float (**texels)[4],
                     size_t *n_texels, struct cv_sdtree_stats *stats)
{
    struct cv_sdtree *t = cv_sdtree_create(bmin, bmax);
    cv_sdtree_learn_records(t, rec, n, o, stats);
    cv_sdtree_table(t, o, texels, n_texels);
    cv_sdtree_destroy(&t);
}

double cv_sdtree_pdf_square(const float (*t)[4], uint32_t root, double u, double v)
{
    uint32_t q = root;
    double pdf = 1;
    for (uint32_t d = 0; d < CV_SD_MAX_DEPTH; d++) {
        int ix = u < 0.5 ? 0 : 1, iy = v < 0.5 ? 0 : 1, k = ix + 2 * iy;
        float p[4];
        uint32_t ch[4];
        cv_sdtree_node(t, q, p, ch);
        pdf *= 4.0 * p[k];
        u = 2 * u - ix;
        v = 2 * v - iy;
        if (!ch[k])
            break;
        q = ch[k];
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
