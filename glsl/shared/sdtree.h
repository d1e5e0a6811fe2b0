/* glsl/shared/sdtree.h: the guide of rlpath's sdtree method (rlpath.method:
 * sdtree), after Müller, Gross and Novák, "Practical Path Guiding for
 * Efficient Light-Transport Simulation" (2017), shared by the host
 * (src/trace/sdtree.c builds it, src/trace/rlpath_sd.c runs it) and the
 * shaders (glsl/trace/rlpath/sdtree.glsl, sd_shade.comp).
 *
 * Space: a binary tree over a cube around the scene bounds, each inner
 * node split at its middle along one axis. Each leaf holds a directional
 * quadtree over the square [0,1]^2 of world directions in the cylindrical
 * equal-area map u = (cos(theta) + 1) / 2 (cos(theta) = w.z), v = (phi +
 * pi) / (2 pi): a density p on the square is p / (4 pi) in solid angle.
 *
 * Tree table (image unit CV_IMAGE_SD_TREE, rgba32f texels), built on the
 * host between training passes and uploaded whole (never written by a
 * shader); texel indices are floats holding integers below 2^24:
 *   spatial node i (texels 0 .. n_spatial - 1, root 0):
 *     x: the split axis 0, 1, 2, or CV_SD_LEAF for a leaf;
 *     y: inner: the split coordinate (world); leaf: 0;
 *     z: inner: the first child (the second follows: the half above y);
 *        leaf: the first of its CV_SD_CLASSES class texels;
 *     w: 0.
 *   class texel c of a leaf (c: the orientation class of the surface
 *   normal, on the side the path arrives from, as the Q-table's:
 *   2 * axis of its largest component, + 1 if negative; the surfaces of a
 *   leaf that face apart see apart):
 *     x: the texel of the class's quadtree root; y: its guiding weight
 *     (0: BSDF sampling alone); zw: 0.
 *   quadtree node at texel q (two texels):
 *     q:     the probabilities of its four quadrants (index ix + 2 iy,
 *            ix = u in the upper half, iy = v in the upper half), each
 *            above 0, summing to 1;
 *     q + 1: the texels of the quadrants' nodes, 0 for a leaf quadrant.
 * The density of a point is the product over the nodes it passes of 4
 * times its quadrant's probability, on the square; sampling descends the
 * same quadrants (sdtree.glsl), so the pdf it returns is the one it draws.
 *
 * Training records: while the guide learns, every vertex that bounces
 * writes a record of its path slot (CV_IMAGE_SD_VERTS, CV_SD_SLOT_TEXELS
 * per slot: x of the first the records of a path that ended and waits to
 * be sent, then CV_SD_MAX_RECORDS records of two texels each):
 *   t:     position xyz; w: the density the bounce was drawn with (solid
 *          angle; 0: not a guided vertex, the record is skipped);
 *   t + 1: the bounce direction (u, v) on the square, u plus the vertex's
 *          orientation class (an integer; u alone below 1); z: the
 *          channel mean of the path throughput after the bounce; w: the
 *          radiance found along it so far (channel mean).
 * Light that the path adds to the film from a later vertex (emission hit
 * or unoccluded shadow ray, MIS-weighted, times the throughput) adds its
 * channel mean over z to each earlier record's w: the path's own Monte
 * Carlo estimate of the incident radiance along the bounce. Once the path
 * has ended and its last shadow rays are traced (when its slot's next path
 * starts, or after the pass), its guided records are appended to
 * CV_IMAGE_SD_OUT (two texels each, as above) at an index taken from the
 * counter CV_IMAGE_SD_COUNT (r32ui texel 0: records wanted; those past the
 * capacity are dropped), read back by the host after each training pass. */
#ifndef CV_SHARED_SDTREE_H
#define CV_SHARED_SDTREE_H

#include "shared/common.h"
#include "shared/bindings.h"

/* rlpath's image units (shared/rlpath.h): the Q-learning method's tables
 * are not bound with this one. */
#define CV_IMAGE_SD_OUT 0       /* imageBuffer rgba32f: appended records */
#define CV_IMAGE_SD_VERTS 1     /* imageBuffer rgba32f: records per path slot */
#define CV_IMAGE_SD_COUNT 2     /* uimageBuffer r32ui: records wanted */
#define CV_IMAGE_SD_TREE 3      /* imageBuffer rgba32f: the tree table */
#define CV_UBO_SDTREE 1         /* uniform block CvSdParams (rlpath's) */

#define CV_SD_LEAF 3.0
#define CV_SD_CLASSES 6u
/* Vertices per path that record (the first ones: deeper bounces carry
 * little of the image). */
#define CV_SD_MAX_RECORDS 6u
/* Texels per path slot: its pending count, then its records. */
#define CV_SD_SLOT_TEXELS (1u + 2u * CV_SD_MAX_RECORDS)
/* Quadtree depth limit (a node of side 2^-CV_SD_MAX_DEPTH), and the
 * spatial tree's. */
#define CV_SD_MAX_DEPTH 12u
#define CV_SD_MAX_SPATIAL_DEPTH 48u

/* A training iteration keeps a uniform share of the paths' records (keep.x),
 * so that the host's build sees a bounded number spread over the whole
 * image rather than the first ones flushed (src/trace/rlpath_sd.c). */
#define CV_SD_KEEP_ALL 0xffffffffu

CV_STRUCT(CvSdParams) {
    cv_uvec4 learn;        /* x: 1 while training passes record; y: record capacity
                              left in this pass; z: path slots; w: 0 */
    cv_uvec4 keep;         /* x: a path's records are kept iff a hash of it is at
                              most x (CV_SD_KEEP_ALL: all); y: the pass (the hash's
                              seed); zw: 0 */
} CV_END(CvSdParams)
CV_CHECK_SIZE(CvSdParams, 32);

#endif
