/* median_split.h: the host-built trees' split (bvh/curve_bvh.c,
 * bvh/motion_bvh.c): items ordered by their boxes' centres along the
 * widest axis of those centres, so a node's halves are the two halves of
 * the order. Cost class: a sort per node, at scene load. */
#ifndef CV_BVH_MEDIAN_SPLIT_H
#define CV_BVH_MEDIAN_SPLIT_H

#include <stdint.h>

/* Reorders order[0..count) (indices into lo and hi, the items' boxes) by
 * centre along the centres' widest axis, ties by index: one order
 * whatever qsort does. */
void cv_median_split(uint32_t *order, uint32_t count, const float (*lo)[3], const float (*hi)[3]);

#endif
