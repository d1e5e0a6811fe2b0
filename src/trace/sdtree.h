/* sdtree.h: the host side of rlpath's sdtree guide (after Müller, Gross
 * and Novák, "Practical Path Guiding", 2017; table layout in
 * glsl/shared/sdtree.h): a spatial binary tree over a cube around the
 * scene whose leaves each hold directional quadtrees of the incident
 * radiance. The shaders splat each training iteration's records into the
 * statistics of the tree being trained (glsl/trace/rlpath/sdtree.glsl); at
 * the iteration's end cv_sdtree_refine makes from them the next sampling
 * quadtrees and the next tree to train, as Müller et al.: leaves split in
 * space by record count, quadrants by their share of the flux. Pure C, no
 * GPU: src/trace/rlpath_sd.c uploads the table. Cost class: one walk of
 * the tree per refinement, nothing per record. */
#ifndef CV_TRACE_SDTREE_H
#define CV_TRACE_SDTREE_H

#include <stddef.h>
#include <stdint.h>

/* One training record as the shaders keep it per path slot (two rgba32f
 * texels, glsl/shared/sdtree.h). */
struct cv_sd_record {
    float p[3];      /* position (world) */
    float pdf;       /* solid-angle density the direction was drawn with, > 0 */
    float u, v;      /* direction on the square [0,1)^2 (cylindrical map); u
                        has the orientation class added */
    float beta;      /* path throughput after the bounce (unused here) */
    float L;         /* incident radiance found along the direction */
};
_Static_assert(sizeof(struct cv_sd_record) == 32, "two rgba32f texels");

struct cv_sdtree_opts {
    float mix;              /* guiding weight of a leaf that learned, in [0, 1] */
    /* ... in the trees that only serve training (rlpath_sd.c): the first
     * ones are a few quadrants each, whose draws cost more error than
     * they save, and the training's samples stay in the image */
    float train_mix;
    /* A spatial leaf splits while it holds more than split_c *
     * sqrt(records of the iteration) records (Müller et al.'s c sqrt(2^k)
     * per pixel, for the whole image). */
    float split_c;
    float rho;              /* a quadrant splits above this share of its leaf's energy */
    uint32_t min_split;     /* ... and with at least this many records */
    uint32_t max_depth;     /* quadtree depth limit (<= CV_SD_MAX_DEPTH) */
    /* the most levels of the tables' top blocks (<= CV_SD_BLOCK_MAX_LOG2;
     * fewer where they would not fit: cv_sdtree_block_log2) */
    uint32_t block_log2;
    float floor;            /* uniform share added to every leaf's distribution */
    uint32_t min_records;   /* a leaf's class guides with at least this many
                               records of positive radiance */
    uint32_t filter;        /* the splat's filters, CV_SD_FILTER_* (shared/sdtree.h) */
    /* A record adds at most this multiple of the mean value of its
     * class's records of positive value in the iteration before (0: no
     * limit): a rare path that finds a bright light through a narrow
     * feature otherwise becomes the peak of its quadtree. It shapes the
     * learned distribution only; the estimator divides by the exact
     * density, so the image stays unbiased. */
    float clamp;
};

/* The defaults (trace/sdtree.c). */
extern const struct cv_sdtree_opts cv_sdtree_defaults;

struct cv_sdtree_stats {
    uint32_t spatial_nodes, spatial_leaves;
    uint32_t quad_nodes, max_quad_depth;   /* the sampling quadtrees' */
    uint32_t train_nodes;                  /* the training quadtrees' */
    uint32_t guiding;   /* (leaf, class) quadtrees that guide */
    uint64_t records;   /* the statistics' records */
    /* The spatial leaves' depths (the levels a lookup descends): least,
     * mean, most, and the mean weighted by each leaf's records (a leaf
     * that split shares its parent's count, halved per level). */
    uint32_t min_spatial_depth, max_spatial_depth;
    double mean_spatial_depth, record_spatial_depth;
};

/* The guide between iterations: the tree being trained and the sampling
 * quadtrees learned before. */
struct cv_sdtree;

/* The untrained guide over the box [bmin, bmax] (a cube about it): one
 * leaf, whose classes do not guide. */
struct cv_sdtree *cv_sdtree_create(const float bmin[3], const float bmax[3]);

/* Accepts NULL; clears the pointer. */
void cv_sdtree_destroy(struct cv_sdtree **t);

/* The table of the guide (glsl/shared/sdtree.h), its top blocks of at
 * most o->block_log2 levels: *texels is allocated (free it), *n_texels its
 * length. */
void cv_sdtree_table(const struct cv_sdtree *t, const struct cv_sdtree_opts *o,
                     float (**texels)[4], size_t *n_texels);

/* The levels of the top blocks of a table whose sampling quadtrees that
 * guide number `roots` (glsl/shared/sdtree.h): the most, up to max, whose
 * blocks fit in CV_SD_BLOCK_MAX_TEXELS. The table holds it at its root's
 * w. */
uint32_t cv_sdtree_block_log2(size_t roots, uint32_t max);

/* Sampling node q of a table (glsl/shared/sdtree.h): its quadrants'
 * probabilities, the fourth derived as the shaders derive it, and the
 * texels of their nodes (0: a leaf quadrant). */
void cv_sdtree_node(const float (*texels)[4], uint32_t q, float p[4], uint32_t child[4]);

/* Words of the statistics the table's training tree takes. */
size_t cv_sdtree_stat_words(const struct cv_sdtree *t);

/* What the splat needs besides the table (the shaders' CvSdParams): the
 * root cube (low corner, side) and the filters (CV_SD_FILTER_*). */
struct cv_sd_frame {
    float cube[4];
    uint32_t filter;
};

/* The frame of guide t with the filters of o. */
struct cv_sd_frame cv_sdtree_frame(const struct cv_sdtree *t, const struct cv_sdtree_opts *o);

/* Splats record r (as the shaders keep it: u with the class added) into
 * the statistics of the table's training tree, as the shaders'
 * cv_sd_splat does, in the same float arithmetic (the host's copy of it,
 * for tests and cv_sdtree_learn_records). */
void cv_sdtree_splat(const float (*texels)[4], const struct cv_sd_frame *f, uint32_t *stats,
                     const struct cv_sd_record *r);

/* The end of a training iteration: from the statistics splatted into the
 * table's training tree (cv_sdtree_stat_words words; the splat adds at
 * leaf quadrants only, the inner ones are summed here first), the next
 * sampling quadtrees (the training ones with the flux as their
 * probabilities, and the guiding weights) and the next training tree
 * (leaves over split_c * sqrt(records) records split in space, halving the
 * count per level; quadrants over rho of their class's flux, with
 * min_split records, subdivided, a new quadrant taking a quarter of its
 * parent's, and the others pruned). stats may be NULL. */
void cv_sdtree_refine(struct cv_sdtree *t, const uint32_t *stats, const struct cv_sdtree_opts *o,
                      struct cv_sdtree_stats *st);

/* One training iteration on the host, as the renderer's pass: the n
 * records splatted into the statistics of t's training tree (as
 * cv_sdtree_splat), then t refined from them. st may be NULL. */
void cv_sdtree_learn_iteration(struct cv_sdtree *t, const struct cv_sd_record *rec, size_t n,
                               const struct cv_sdtree_opts *o, struct cv_sdtree_stats *st);

/* Learns from n records on the host: splats them and refines, again and
 * again until the tree no longer changes, so that the sampling quadtrees
 * follow the records alone (tests, bench). Records with pdf <= 0 or a
 * non-finite value are ignored. st may be NULL. */
void cv_sdtree_learn_records(struct cv_sdtree *t, const struct cv_sd_record *rec, size_t n,
                             const struct cv_sdtree_opts *o, struct cv_sdtree_stats *st);

/* The table of a guide learned from n records alone (cv_sdtree_create,
 * cv_sdtree_learn_records, cv_sdtree_table); never fails (no records: one
 * unguided leaf). stats may be NULL. */
void cv_sdtree_build(const float bmin[3], const float bmax[3], const struct cv_sd_record *rec,
                     size_t n, const struct cv_sdtree_opts *o, float (**texels)[4],
                     size_t *n_texels, struct cv_sdtree_stats *stats);

/* The density on the square [0,1)^2 of point (u, v) under the quadtree at
 * texel root of a table: the shaders' cv_sd_pdf_square, for tests. */
double cv_sdtree_pdf_square(const float (*texels)[4], uint32_t root, double u, double v);

/* The spatial leaf texel of point p; its class texels start at texel z,
 * each (quadtree root, weight). */
uint32_t cv_sdtree_leaf(const float (*texels)[4], const float p[3]);

#endif
