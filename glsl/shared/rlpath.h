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
 * The table and the path state are buffers read through buffer textures
 * bound as images (r32ui and rgba32ui), not as storage blocks: the shade
 * stage already declares 14 of the 16 storage blocks Mesa allows per shader
 * (more as the pipeline grows), and image atomics serve as well.
 *
 * Table (image unit CV_IMAGE_RL_Q, r32ui texels), CV_RL_KEY_TEXELS(bins)
 * texels per key k from t = k * CV_RL_KEY_TEXELS(bins):
 *   t + 2b:          the sum of the temporal-difference targets of bin b
 *                    as float bits, added by the shade and escaped stages;
 *   t + 2b + 1:      visits of bin b (targets summed); Q, the learned
 *                    incident radiance (scalar: the channel mean), is the
 *                    sum over the visits: the running mean that Dahm and
 *                    Keller's learning rate 1 / (1 + visits) gives, without
 *                    a compare-and-swap loop that threads of a bright bin
 *                    would contend in;
 *   t + 2 bins + b:  the sampling CDF after bin b as float bits (the last
 *                    is exactly 1), written by rebuild.comp from the Q;
 *   t + 3 bins + b:  the part of bin b's target sum that is emission found
 *                    at the next vertex (float bits): light that
 *                    next-event estimation already samples there, which
 *                    rebuild.comp leaves out of the sampling distribution
 *                    (Q itself keeps it: the targets of the bounces before
 *                    are built from Q);
 *   t + 4 bins:      the key's guiding weight (mixture weight) as float bits:
 *                    the option's, less for a key with few visits, 0 before
 *                    its first rebuild;
 *   t + 4 bins + 1:  1 when a Q changed since the last rebuild.
 * An entry e = k * bins + b names one (key, bin). The sums are added by
 * imageAtomicAdd through a second, r32f image over the same buffer
 * (CV_IMAGE_RL_QF) where GL_NV_shader_atomic_float is there (NVIDIA, Mesa),
 * else by compare-and-swap on the bits (GLSL 4.5 core has no float atomics).
 * A stage that adds to the table reads Q for its targets meanwhile: a
 * target may see a sum without its visit, which skews learning a little
 * and never the image (the CDFs and weights that sampling and the mixture
 * density read change only in rebuild.comp, a dispatch of its own).
 *
 * Path state (image unit CV_IMAGE_RL_PATH, one rg32ui texel per pixel of
 * the crop; each pixel has one path in flight): x: entry of the last bounce
 * whose value the next vertex (a hit, or the environment) learns from
 * (CV_RL_NONE: none), y: the depth that bounce left from. */
#ifndef CV_SHARED_RLPATH_H
#define CV_SHARED_RLPATH_H

#include "shared/common.h"
#include "shared/bindings.h"

#define CV_IMAGE_RL_Q 0        /* uimageBuffer r32ui: Q bits and visits */
#define CV_IMAGE_RL_PATH 1     /* uimageBuffer rg32ui: path state per pixel */
#define CV_IMAGE_RL_QF 2       /* imageBuffer r32f: the table again, for float atomics */
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
/* Texels per key: Q and visits per bin, the CDF, the emitted part per bin,
 * mixture weight, dirty flag. */
#define CV_RL_KEY_TEXELS(bins) (4u * (bins) + 2u)
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
 * sampled by its BSDF alone (rlpath/shade.comp: cv_rl_guides). */
#define CV_RL_GLOSSY_ALPHA 0.5

CV_STRUCT(CvRlParams) {
    CV_VEC4 grid_min;      /* xyz: grid origin (world); w: mixture weight of guiding */
    CV_VEC4 grid_scale;    /* xyz: cells per world unit; w: floor share (CV_RL_FLOOR) */
    CV_UVEC4 dims;         /* xyz: cells per axis; w: cells in all */
    CV_UVEC4 dirs;         /* x: z bands; y: phi sectors; z: bins = x * y; w: keys = cells * 6 */
} CV_END(CvRlParams)
CV_CHECK_SIZE(CvRlParams, 64);

#endif
