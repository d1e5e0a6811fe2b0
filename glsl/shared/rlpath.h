/* glsl/shared/rlpath.h: the Q-table of the rlpath integrator (reinforcement
 * learning path guiding after Dahm and Keller, "Learning Light Transport the
 * Reinforced Way", 2017), shared by the host (src/trace/rlpath.c) and the
 * shaders (glsl/trace/rlpath).
 *
 * Space: a uniform grid over the scene bounds, dims.xyz cells (the longest
 * axis gets the option's resolution, the others proportionally fewer), and
 * in each cell CV_RL_ORIENTS keys, one per orientation class of the
 * surface normal (the axis of its largest component and that component's
 * sign): the two sides of a wall, or a floor and the wall beside it in one
 * cell, learn apart.
 * Direction: the whole sphere of world directions in a cylindrical
 * equal-area map: z = cos(theta) in [-1, 1] split into dirs.x equal bands,
 * phi in [-pi, pi) into dirs.y equal sectors; every bin has the solid angle
 * 4 pi / (dirs.x * dirs.y), so sampling uniformly in (z, phi) within a bin
 * is uniform in solid angle.
 *
 * The tables and the path state are buffers read through buffer textures
 * bound as images, not as storage blocks: the shade stage already declares
 * 14 of the 16 storage blocks Mesa allows per shader (more as the pipeline
 * grows), and image atomics serve as well.
 *
 * Learning table (image unit CV_IMAGE_RL_Q, r32ui texels),
 * CV_RL_LEARN_TEXELS(bins) texels per key k from t = k * CV_RL_LEARN_TEXELS:
 *   t + 3b:      the sum of the temporal-difference targets of bin b less
 *                their emitted part (below), as float bits;
 *   t + 3b + 1:  visits of bin b (targets summed);
 *   t + 3b + 2:  the sum of the emitted parts of those targets: radiance of
 *                a light that the bounce found at the next vertex, which
 *                next-event estimation at this vertex samples already;
 *   t + 3 bins:  1 when the key changed since its last rebuild.
 * Q, the learned incident radiance (scalar: the channel mean), is the two
 * sums over the visits: the running mean that Dahm and Keller's learning
 * rate 1 / (1 + visits) gives, without a compare-and-swap loop that threads
 * of a bright bin would contend in. Q builds the targets of the bounces
 * before; the first sum alone over the visits (I, Q less the light that
 * light sampling covers) is what the distribution guides by. Two sums, not
 * Q and its emitted part: the difference of two float sums of a million
 * lamp-sized targets loses the small indirect part to rounding.
 * An entry e = k * bins + b names one (key, bin). The sums are added by
 * imageAtomicAdd through a second, r32f image over the same buffer
 * (CV_IMAGE_RL_QF) where GL_NV_shader_atomic_float is there (NVIDIA, Mesa),
 * else by compare-and-swap on the bits (GLSL 4.5 core has no float atomics).
 * A stage that adds to the table reads Q for its targets meanwhile: a
 * target may see a sum without its visit, which skews learning a little
 * and never the image (sampling and the mixture density read only the
 * guide table, which rebuild.comp alone writes, in a dispatch of its own).
 *
 * Guide table (rgba32f texels; written through image unit CV_IMAGE_RL_GUIDE,
 * read through buffer texture CV_TEXUNIT_RL_GUIDE),
 * CV_RL_GUIDE_TEXELS(bins) texels per key from g = k * CV_RL_GUIDE_TEXELS,
 * built by rebuild.comp from the learning table; with G =
 * CV_RL_GROUPS(bins) groups of 16 bins:
 *   g:                         x: the key's guiding weight (mixture
 *                              weight): the option's, less for a key with
 *                              few visits, 0 before its first rebuild;
 *                              y: the irradiance that Q gives a surface
 *                              facing the key's class axis, the integral
 *                              of Q cos over the hemisphere about it;
 *   g + 1 + i:                 the CDF at the end of groups 4i .. 4i + 3
 *                              (1 past the last group), i < CV_RL_COARSE(bins);
 *   g + 1 + coarse + 4j + i:   the CDF after bins 16j + 4i .. 16j + 4i + 3
 *                              (1 past the last bin);
 *   g + 1 + coarse + 4G + i:   the probabilities of bins 4i .. 4i + 3 (0
 *                              past the last), each the difference of its
 *                              CDF value and the one before, as sampling
 *                              draws it.
 * Sampling finds its group in the coarse texels and its bin in the group's
 * four: two rounds of loads at 128 bins, where a binary search over the CDF
 * takes seven one after the other (the shade stage waits on each).
 *
 * Path state (image unit CV_IMAGE_RL_PATH, one rg32ui texel per path slot,
 * glsl/shared/trace.h; each slot has one path in flight): x: entry of the last bounce
 * whose value the next vertex (a hit, or the environment) learns from
 * (CV_RL_NONE: none), y: the depth that bounce left from. */
#ifndef CV_SHARED_RLPATH_H
#define CV_SHARED_RLPATH_H

#include "shared/common.h"
#include "shared/bindings.h"

#define CV_IMAGE_RL_Q 0        /* uimageBuffer r32ui: learning table */
#define CV_IMAGE_RL_PATH 1     /* uimageBuffer rg32ui: path state per path slot */
#define CV_IMAGE_RL_QF 2       /* imageBuffer r32f: the learning table again, for float atomics */
#define CV_IMAGE_RL_GUIDE 3    /* imageBuffer rgba32f: guide table (rebuild.comp's writes) */
#define CV_UBO_RLPATH 1                        /* uniform block CvRlParams */

#define CV_RL_NONE 0xffffffffu
#define CV_RL_MAX_BINS 1024u

/* Defaults for options given as 0 (or a mix <= 0). */
#define CV_RL_DEFAULT_GRID 4u
#define CV_RL_DEFAULT_DIRECTIONS 128u
#define CV_RL_DEFAULT_MIX 0.3f
/* Every bin gets at least this share of the mean bin value, so the learned
 * distribution never has zero density anywhere on the sphere. */
#define CV_RL_FLOOR 0.02f
/* Normal classes per cell: +x, -x, +y, -y, +z, -z. */
#define CV_RL_ORIENTS 6u
/* Texels per key of the learning table: two sums and visits per bin, the
 * dirty flag. */
#define CV_RL_LEARN_TEXELS(bins) (3u * (bins) + 1u)
/* The guide table's groups of 16 bins, coarse CDF texels, and texels per
 * key: weight, coarse CDF, fine CDF, probabilities. */
#define CV_RL_GROUPS(bins) (((bins) + 15u) / 16u)
#define CV_RL_COARSE(bins) ((CV_RL_GROUPS(bins) + 3u) / 4u)
#define CV_RL_GUIDE_TEXELS(bins) (1u + CV_RL_COARSE(bins) + 4u * CV_RL_GROUPS(bins) + ((bins) + 3u) / 4u)
/* A key guides with the full mixture weight once its bins have this many
 * visits on average; before, with the weight times visits / (this * bins):
 * a young key's Q is one or two noisy samples, and sampling by it alone
 * adds variance that the BSDF would not. */
#define CV_RL_TRUST_VISITS 4.0f
/* Above this many visits, rebuild.comp halves a bin's visits and scales its
 * sum to keep Q: a float sum of 2^24 targets would stop taking in small
 * ones, and the learning rate 1 / (1 + visits) keeps a floor of about 2^-20,
 * so the table still follows a changing estimate in a long render. */
#define CV_RL_MAX_VISITS 1048576u
/* Microfacet roughness (alpha) below which a conductor or dielectric is
 * sampled by its BSDF alone (rlpath/guides.glsl: cv_rl_guides). */
#define CV_RL_GLOSSY_ALPHA 0.5
/* Which material types rlpath's guide may serve, for the shaders'
 * cv_rl_guides (rlpath/guides.glsl) and the host's cv_shade_bins_guided
 * (trace/shade_bins.c), which builds a bin without the guide where none of
 * its materials is served: diffuse-like lobes always; conductors and
 * dielectrics where rough (CV_RL_GLOSSY_ALPHA). */
#define CV_RL_DIFFUSE_LIKE(t)                                                          \
    ((t) == CV_MAT_DIFFUSE || (t) == CV_MAT_COATED_DIFFUSE ||                          \
     (t) == CV_MAT_DIFFUSE_TRANSMISSION || (t) == CV_MAT_PLASTIC)
#define CV_RL_GUIDED_WHERE_ROUGH(t) ((t) == CV_MAT_CONDUCTOR || (t) == CV_MAT_DIELECTRIC)

CV_STRUCT(CvRlParams) {
    cv_vec4 grid_min;      /* xyz: grid origin (world); w: mixture weight of guiding */
    cv_vec4 grid_scale;    /* xyz: cells per world unit; w: floor share (CV_RL_FLOOR) */
    cv_uvec4 dims;         /* xyz: cells per axis; w: cells in all */
    cv_uvec4 dirs;         /* x: z bands; y: phi sectors; z: bins = x * y; w: keys = cells * 6 */
    cv_uvec4 learn;        /* x: 1 while the table learns (this pass adds targets and
                              keeps path state), 0 once the guide is frozen; yzw: 0 */
} CV_END(CvRlParams)
CV_CHECK_SIZE(CvRlParams, 80);

#endif
