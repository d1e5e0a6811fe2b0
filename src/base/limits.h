/* limits.h: limits of the renderer that the stages before it check, so that
 * a manifest or scene past them fails or warns where it is written rather
 * than when its job reaches the GPU. */
#ifndef CV_BASE_LIMITS_H
#define CV_BASE_LIMITS_H

/* Samples per pixel: a pixel's sample index travels through the GPU as a
 * float (glsl/shared/trace.h, CvFilmPixel.normal.w), exact up to 2^24. */
#define CV_MAX_SPP (1u << 24)

/* Path slots of one render: slot indices travel through the GPU as floats
 * (glsl/shared/trace.h, CvRayItem o.w and d.w), exact up to 2^24. */
#define CV_MAX_PATHS (1u << 24)

/* Rendered pixels of one film (its crop window): each pixel needs a path
 * slot (render.c: choose_paths_per_pixel). 8K UHD (7680x4320) is over it. */
#define CV_MAX_FILM_PIXELS CV_MAX_PATHS

/* Film side [pixels], in a scene's Film or a manifest's resolution. */
#define CV_MAX_FILM_SIDE 65536

/* rlpath's table (src/trace/rlpath.c): cells along the scene's longest axis,
 * and direction bins per key (CV_RL_MAX_BINS in glsl/shared/rlpath.h, which
 * rlpath.c checks against this one). */
#define CV_RL_MAX_GRID 256u
#define CV_RL_MAX_DIRECTIONS 1024u
/* ... and the samples per pixel during which it learns by default
 * (rlpath.train), after Mueller et al. 2017's schedule: learn in the first
 * passes, then render with the frozen guide, so that the rendering passes
 * pay no update, no path state and no rebuild (trace/render.c splits a
 * pass that would cross it). CV_RL_TRAIN_ALWAYS: learn in every pass, Dahm
 * and Keller's online learning (rlpath.train: 0). */
#define CV_RL_DEFAULT_TRAIN 16u
#define CV_RL_TRAIN_ALWAYS 0xffffffffu

/* Bytes of one input file: a scene file, an Include, a PLY mesh (after
 * gzip), a texture, a spectrum, a manifest. Far above any real one (the
 * largest are PLY meshes of a few GB), it stops a sparse or growing file
 * from filling memory; files that are not regular (/dev/zero, a FIFO) are
 * refused before any read. */
#define CV_MAX_INPUT_BYTES (16LL << 30)

/* Jobs one manifest job may expand into through its matrix: the product of
 * its lists. Each job is held in memory and planned before any render; a
 * list of this many stills is a dataset of its own. */
#define CV_MAX_MATRIX_JOBS 65536u

/* Lights a job's lights.scale may name. */
#define CV_MAX_LIGHT_SCALES 32u

#endif
