/* sdtree.h: the host build of rlpath's sdtree guide (after Müller, Gross
 * and Novák, "Practical Path Guiding", 2017; table layout in
 * glsl/shared/sdtree.h): from the training records of one pass of doubling
 * length, a spatial binary tree over a cube around the scene whose leaves
 * each hold a directional quadtree of the incident radiance they recorded.
 * Pure C, no GPU: src/trace/rlpath_sd.c uploads the table. Cost class: one
 * pass over the records per tree level, once per training pass. */
#ifndef CV_TRACE_SDTREE_H
#define CV_TRACE_SDTREE_H

#include <stddef.h>
#include <stdint.h>

/* One training record as the shaders append it (two rgba32f texels). */
struct cv_sd_record {
    float p[3];      /* position (world) */
    float pdf;       /* solid-angle density the direction was drawn with, > 0 */
    float u, v;      /* direction on the square [0,1)^2 (cylindrical map); as
                        read back, u has the orientation class added */
    float beta;      /* path throughput after the bounce (the shaders'; the
                        build keeps the class here) */
    float L;         /* incident radiance found along the direction */
};
_Static_assert(sizeof(struct cv_sd_record) == 32, "two rgba32f texels");

struct cv_sdtree_opts {
    float mix;              /* guiding weight of a leaf that learned, in [0, 1] */
    /* A spatial node splits while it holds more than split_c *
     * sqrt(records) records (Müller et al.'s c sqrt(2^k) per pixel, for
     * the whole image). */
    float split_c;
    float rho;              /* a quadrant splits above this share of its leaf's energy */
    uint32_t min_split;     /* ... and with at least this many records */
    uint32_t max_depth;     /* quadtree depth limit (<= CV_SD_MAX_DEPTH) */
    float floor;            /* uniform share added to every leaf's distribution */
    uint32_t min_records;   /* a leaf's class guides with at least this many
                               records of positive radiance */
};

/* The defaults (trace/sdtree.c). */
extern const struct cv_sdtree_opts cv_sdtree_defaults;

struct cv_sdtree_stats {
    uint32_t spatial_nodes, spatial_leaves, quad_nodes, max_quad_depth;
    uint32_t guiding;   /* (leaf, class) quadtrees that guide */
};

/* Builds the table (texels of 4 floats, glsl/shared/sdtree.h) from n
 * records (reordered in place; records with pdf <= 0 or a non-finite
 * value are ignored) for the box [bmin, bmax]. *texels is allocated (free
 * it), *n_texels its length; never fails (no records: one unguided leaf).
 * stats may be NULL. */
void cv_sdtree_build(const float bmin[3], const float bmax[3], struct cv_sd_record *rec,
                     size_t n, const struct cv_sdtree_opts *o, float (**texels)[4],
                     size_t *n_texels, struct cv_sdtree_stats *stats);

/* The density on the square [0,1)^2 of point (u, v) under the quadtree at
 * texel root of a table: the shaders' cv_sd_pdf_square, for tests. */
double cv_sdtree_pdf_square(const float (*texels)[4], uint32_t root, double u, double v);

/* The spatial leaf texel of point p; its class texels start at texel z,
 * each (quadtree root, weight). */
uint32_t cv_sdtree_leaf(const float (*texels)[4], const float p[3]);

#endif
