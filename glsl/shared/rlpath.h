/* glsl/shared/rlpath.h: the Q-table of the rlpath integrator (reinforcement
 * learning path guiding after Dahm and Keller, "Learning Light Transport the
 * Reinforced Way", 2017), shared by the host (src/trace/rlpath.c) and the
 * shaders (glsl/trace/rlpath).
 *
 * Space: a uniform grid over the scene bounds, dims.xyz cells (the longest
 * axis gets the option's resolution, the others proportionally fewer).
 * Direction: the whole sphere of world directions in a cylindrical
 * equal-area map: z = cos(theta) in [-1, 1] split into dirs.x equal bands,
 * phi in [-pi, pi) into dirs.y equal sectors; every bin has the solid angle
 * 4 pi / (dirs.x * dirs.y), so sampling uniformly in (z, phi) within a bin
 * is uniform in solid angle. World directions need no frame per point (cells
 * are not tied to one normal, so both sides of a thin wall share a cell and
 * each learns its own hemisphere).
 *
 * The table and the path state are buffers read through buffer textures
 * bound as images (r32ui and rgba32ui), not as storage blocks: the shade
 * stage already declares 14 of the 16 storage blocks Mesa allows per shader
 * (more as the pipeline grows), and image atomics serve as well.
 *
 * Table (image unit CV_IMAGE_RL_Q, r32ui texels): entry e = cell * bins +
 * bin holds texel 2e = Q as float bits (learned incident radiance, scalar:
 * the channel mean), texel 2e+1 = visit count. Floats are updated by a
 * compare-and-swap loop on the bits (GLSL has no float atomics in core 4.5).
 *
 * Path state (image unit CV_IMAGE_RL_PATH, one rgba32ui texel per pixel of
 * the crop; each pixel has one path in flight): x: entry of the last bounce whose value the next hit
 * will update (CV_RL_NONE: none), y: the depth that bounce left from,
 * z: entry of a pending update, w: its target as float bits. */
#ifndef CV_SHARED_RLPATH_H
#define CV_SHARED_RLPATH_H

#include "shared/common.h"
#include "shared/bindings.h"

#define CV_IMAGE_RL_Q 0        /* uimageBuffer r32ui: Q bits and visits */
#define CV_IMAGE_RL_PATH 1     /* uimageBuffer rgba32ui: path state per pixel */
#define CV_UBO_RLPATH 1                        /* uniform block CvRlParams */

#define CV_RL_NONE 0xffffffffu
#define CV_RL_MAX_BINS 1024u

/* Defaults for options given as 0 (or a mix <= 0). */
#define CV_RL_DEFAULT_GRID 8u
#define CV_RL_DEFAULT_DIRECTIONS 128u
#define CV_RL_DEFAULT_MIX 0.3f
/* Every bin gets at least this share of the mean bin value, so the learned
 * distribution never has zero density anywhere on the sphere. */
#define CV_RL_FLOOR 0.02f
/* Added to the clamped cosine of the bin weights: bins below the surface
 * keep some probability (for transmission and the support). */
#define CV_RL_COS_FLOOR 0.1

CV_STRUCT(CvRlParams) {
    CV_VEC4 grid_min;      /* xyz: grid origin (world); w: mixture weight of guiding */
    CV_VEC4 grid_scale;    /* xyz: cells per world unit; w: floor share (CV_RL_FLOOR) */
    CV_UVEC4 dims;         /* xyz: cells per axis; w: cells in all */
    CV_UVEC4 dirs;         /* x: z bands; y: phi sectors; z: bins = x * y; w: flags (0) */
} CV_END(CvRlParams)
CV_CHECK_SIZE(CvRlParams, 64);

#endif
