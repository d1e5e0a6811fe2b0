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
 * Tree table (buffer texture CV_TEXUNIT_SD_TREE, rgba32f texels), made on the
 * host at the end of each training iteration and uploaded whole (never
 * written by a shader); texel indices and statistics words are floats
 * holding integers below 2^24. It holds two quadtrees per (leaf, class),
 * as Müller et al.'s: the one that samples (learned in the last iteration)
 * and the one that trains (refined from it, its statistics zeroed):
 *   spatial node i (texels 0 .. n_spatial - 1, root 0):
 *     x: the split axis 0, 1, 2, or CV_SD_LEAF for a leaf;
 *     y: inner: the split coordinate (world); leaf: 0;
 *     z: inner: the first child (the second follows: the half above y);
 *        leaf: the first of its CV_SD_CLASSES class texels;
 *     w: 0, but at the root (texel 0): L, the levels of the table's top
 *        blocks (below; the host hands it to the shaders as CvSdParams
 *        grid.y).
 *   class texel c of a leaf (c: the orientation class of the surface
 *   normal, on the side the path arrives from, as the Q-table's:
 *   2 * axis of its largest component, + 1 if negative; the surfaces of a
 *   leaf that face apart see apart):
 *     x: the texel of the class's sampling quadtree root; y: its guiding
 *     weight (0: BSDF sampling alone); z: the texel of its training
 *     quadtree root; w: the class's first statistics word.
 *   the top block of a sampling quadtree that guides (of a class of weight
 *   above 0; the shaders walk no other): the 4^L texels just before its
 *   root (texel root - 4^L + c for cell c), one for each cell of the grid
 *   of 2^L cells a side that the quadtree's first L levels make of the
 *   square (cell c = cx + 2^L cy, cx along u), so that sampling and the
 *   density start with one or two fetches instead of a walk down those
 *   levels (sdtree.glsl):
 *     x: the density on the square over the cell, the product of 4 times
 *        the quadrant's probability of each node above it (of the leaf
 *        quadrant it lies in, where the quadtree ends above the cell);
 *     y, z: its entry of the alias table (Walker) of the cells' masses
 *        (x / 4^L): a draw that lands in the cell keeps it below y of the
 *        way through, else takes cell z;
 *     w: the texel of the quadtree's node whose square is the cell, where
 *        the quadtree goes on below it (the walks go on from there), else 0.
 *   The top block and the walk below its cells give each point the density
 *   the walk from the root gives it. L is the deepest, up to
 *   CV_SD_BLOCK_MAX_LOG2, whose blocks fit in CV_SD_BLOCK_MAX_TEXELS
 *   (cv_sdtree_block_log2); at L = 0 a block is one cell that names the
 *   root.
 *   sampling quadtree node at texel q (one texel: the walks of sampling
 *   and of the density load one texel per level):
 *     xyz: the probabilities of quadrants 0, 1, 2 (index ix + 2 iy, ix = u
 *          in the upper half, iy = v in the upper half); quadrant 3's is
 *          max(0, 1 - (x + y + z)), as host and shaders compute it;
 *     w:   16 off + mask: bit k of mask set where quadrant k has a node;
 *          those nodes are consecutive texels from q + off, in k order
 *          (off < 2^20; the host lays each quadtree out breadth first).
 *   Leaves that split in space share their parent's sampling quadtrees.
 *   training quadtree node at texel q (two texels):
 *     q:     the texels of the quadrants' nodes, 0 for a leaf quadrant;
 *     q + 1: x: the node's first statistics word; y: at a class's root,
 *            the most a record's value adds (its class's records' mean
 *            value in the iteration before times cv_sdtree_opts.clamp;
 *            0: no limit), else 0; z: at a class's root, the mean value
 *            of all its records in the iteration before (with a zero
 *            for each that found nothing: an estimate of the light a
 *            path that bounces on from the class brings back, its
 *            irradiance about the class's axis), which the guided
 *            kernels' Russian roulette weighs (sd_shade.comp), else 0;
 *            w: at a class's root, the records behind z (0: z is no
 *            estimate: too few records), else 0.
 *   the grid block: the table's last CV_SD_GRID_TEXELS texels, from
 *   texel CvSdParams grid.x, a shortcut into the spatial tree. Its splits
 *   are midpoints along the axis depth % 3, so that the nodes down to depth
 *   3 g (g: CV_SD_GRID_LOG2) are unions of the cells of a grid of N = 2^g
 *   cells an axis over the root cube. A lookup finds the point's cell and
 *   continues the descent from the node the cell names, the same leaf as
 *   the full descent for every point (sdtree.glsl: cv_sd_class_texel):
 *   bounds texel a N + j (axis a, cell j along it): x: the cell's lower
 *     bound, y: its upper bound (zw: 0), the float split coordinates the
 *     tree's nodes at those planes hold, whether or not a node splits
 *     there (the descent puts a point at or above a split in the upper
 *     half: a point belongs to cell j where it is at or above x, j > 0,
 *     and below y, j < N - 1, so a point outside the cube falls in the
 *     border cell the descent would take it to);
 *   cell texels from 3 N, four cells each (cell ix + N (iy + N iz): texel
 *     3 N + cell / 4, component cell % 4): the node the descent from the
 *     cell reaches after 3 g levels or, as -1 - its first class texel, the
 *     leaf it meets before (one fetch less).
 * The density of a point is the product over the nodes it passes of 4
 * times its quadrant's probability, on the square; sampling descends the
 * same quadrants (sdtree.glsl), so the pdf it returns is the one it draws.
 *
 * Training records: while the guide learns, every vertex that bounces
 * writes a record of its path slot (CV_IMAGE_SD_VERTS: each slot's
 * CV_SD_MAX_RECORDS records of two texels each, at CV_SD_RECORD_TEXEL),
 * and a path that ends writes the count of its records, which wait to be
 * splatted, to its slot's word of CV_IMAGE_SD_COUNTS. Only the counts, a
 * buffer of their own, start zeroed: a path writes its record at each
 * depth before anything reads it (its count, and the records the later
 * vertices add to, cover the depths it has recorded), so the records need
 * no clearing, and their storage is first touched by the shaders that
 * write it (a clear of fresh storage, even of a part, costs time in
 * proportion to its size: gpu/buffer.h):
 *   0: position xyz; w: the density the bounce was drawn with (solid
 *      angle; 0: not a guided vertex, the record is skipped);
 *   1: the bounce direction (u, v) on the square, u plus the vertex's
 *      orientation class (an integer; u alone below 1); z: the
 *      channel mean of the path throughput after the bounce; w: the
 *      radiance found along it so far (channel mean).
 * Light that the path adds to the film from a later vertex (emission hit
 * or unoccluded shadow ray, MIS-weighted, times the throughput) adds its
 * channel mean over z to each earlier record's w: the path's own Monte
 * Carlo estimate of the incident radiance along the bounce. Once the path
 * has ended and its last shadow rays are traced (at the end of its pass,
 * which gives each slot one path: trace/integrator.h, learn_path_a_slot),
 * its guided records are splatted into the statistics.
 *
 * Statistics (CV_IMAGE_SD_STATS, r32ui words; the float words also through
 * the r32f view CV_IMAGE_SD_FLUX where the driver has float atomics),
 * zeroed at the start of each training iteration and read back by the
 * host at its end (its size is the tree's, not the records'):
 *   class word w (class texel's w): the records of the class in its leaf;
 *   w + 1: those of them with a value above 0;
 *   training node word b (its q + 1 texel's x): b + k, float bits: the sum
 *   of the values (sdtree.glsl: cv_sd_value) of the records in quadrant k;
 *   b + 4 + k: their count. The shaders add to leaf quadrants only (one
 *   add of each kind per record and filter part, none on the hot words
 *   near the roots); the host fills in each inner quadrant as the sum of
 *   its child node's four before it refines (trace/sdtree.c). */
#ifndef CV_SHARED_SDTREE_H
#define CV_SHARED_SDTREE_H

#include "shared/common.h"
#include "shared/bindings.h"

/* rlpath's image units (shared/rlpath.h): the Q-learning method's tables
 * are not bound with this one. */
#define CV_IMAGE_SD_FLUX 0      /* imageBuffer r32f: the statistics, float view */
#define CV_IMAGE_SD_VERTS 1     /* imageBuffer rgba32f: records per path slot */
#define CV_IMAGE_SD_STATS 2     /* uimageBuffer r32ui: the statistics (3: free) */
#define CV_IMAGE_SD_COUNTS 5    /* uimageBuffer r32ui: records waiting per path slot
                                   (4: the renderer's CV_IMAGE_SSS_ENTRY) */
#define CV_UBO_SDTREE 1         /* uniform block CvSdParams (rlpath's) */

#define CV_SD_LEAF 3.0
#define CV_SD_CLASSES 6u
/* Vertices per path that record (the first ones: deeper bounces carry
 * little of the image). */
#define CV_SD_MAX_RECORDS 6u
/* Texels of a path slot's records, and texel t (0 or 1) of its record k
 * among n slots: the records lie in planes, one per texel of a record,
 * each holding every slot's in slot order, so that the neighbouring
 * slots of a wave that write or read their records of one depth touch
 * neighbouring texels. */
#define CV_SD_RECORD_TEXELS (2u * CV_SD_MAX_RECORDS)
#define CV_SD_RECORD_TEXEL(slot, k, t, n) ((2u * (k) + (t)) * (n) + (slot))
/* Quadtree depth limit (a node of side 2^-CV_SD_MAX_DEPTH), and the
 * spatial tree's. */
#define CV_SD_MAX_DEPTH 12u
#define CV_SD_MAX_SPATIAL_DEPTH 48u

/* Sampling quadtrees' top blocks (see above): the most levels one stands
 * for, and the most texels the blocks of a table take (texel indices are
 * floats, exact below 2^24). Deeper blocks replace more of the walks (the
 * bright directions, which draws favour, are where the quadtrees go deep)
 * but cost texels in proportion to 4^L for every quadtree that guides
 * (bench/RESULTS.md, "sdtree's quadtrees with top blocks"). */
#define CV_SD_BLOCK_MAX_LOG2 5u
#define CV_SD_BLOCK_MAX_TEXELS (1u << 22)

/* The grid block (see above): log2 of its cells an axis, its cells an
 * axis, its cell texels and all its texels. */
#define CV_SD_GRID_LOG2 6u
#define CV_SD_GRID_CELLS (1u << CV_SD_GRID_LOG2)
#define CV_SD_GRID_CELL_TEXELS (CV_SD_GRID_CELLS * CV_SD_GRID_CELLS * CV_SD_GRID_CELLS / 4u)
#define CV_SD_GRID_TEXELS (3u * CV_SD_GRID_CELLS + CV_SD_GRID_CELL_TEXELS)

/* Statistics words of a class, and of a training quadtree node. */
#define CV_SD_CLASS_WORDS 2u
#define CV_SD_NODE_WORDS 8u

/* The training splat's filters (CvSdParams learn.y; sdtree.glsl,
 * cv_sd_splat): Müller et al.'s spatial box filter, a record's flux shared
 * by the leaves a box of its leaf's size about it overlaps; and the
 * directional one, shared by the quadrants a square of its quadrant's
 * size about its direction overlaps. Record counts are not filtered. */
#define CV_SD_FILTER_SPATIAL 1u
#define CV_SD_FILTER_DIRECTIONAL 2u

CV_STRUCT(CvSdParams) {
    cv_uvec4 learn;        /* x: 1 while training passes record; y: the
                              filters (CV_SD_FILTER_*); z: path slots; w: 0 */
    cv_vec4 cube;          /* the spatial tree's root cube: xyz its low
                              corner, w its side */
    cv_uvec4 grid;         /* x: the grid block's first texel in the table
                              (its length less CV_SD_GRID_TEXELS); y: L, the
                              levels of its top blocks; zw: 0 */
} CV_END(CvSdParams)
CV_CHECK_SIZE(CvSdParams, 48);

#endif
