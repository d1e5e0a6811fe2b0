/* motion_bvh.h: the moving shapes' trees (scene.h, cv_motion), built on
 * the host: pbrt-v4 intersects a moving shape by carrying the ray into
 * the shape's object space at the ray's time, which a tree over
 * world-space triangles cannot do. A top tree over the shapes' motion
 * boxes (world space) leads to one tree per shape over its object-space
 * triangles. Moving shapes are few beside static triangles (these trees
 * are built serially, by median splits); the static triangles keep the
 * GPU-built tree, whose traversal they alone pay for. The result is the
 * one vec4 array glsl/bvh/motion.glsl reads. */
#ifndef CV_BVH_MOTION_BVH_H
#define CV_BVH_MOTION_BVH_H

#include <stddef.h>

#include "scene/scene.h"

/* Most triangles per leaf of a shape's tree. */
#define CV_MOTION_LEAF 4

/* The packed buffer for s's moving shapes (s->n_motions >= 1; layout:
 * glsl/bvh/motion.glsl). *n_vec4 gets its length in vec4s; the caller
 * frees it. */
float *cv_motion_bvh_pack(const struct cv_scene *s, size_t *n_vec4);

#endif
