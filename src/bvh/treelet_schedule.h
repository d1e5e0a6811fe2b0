/* treelet_schedule.h: the fixed work lists of the treelet optimisation
 * (glsl/bvh/treelet.comp), which depend only on the treelet size: the
 * subsets of 2 to n leaves, size by size, and for sizes 3 to n every
 * (subset, left part) pair whose left part holds the subset's lowest leaf
 * (each split once), size by size and partition-major within a size. The
 * shader reads them from a small read-only buffer instead of deriving them
 * per treelet. */
#ifndef CV_BVH_TREELET_SCHEDULE_H
#define CV_BVH_TREELET_SCHEDULE_H

#include <stddef.h>
#include <stdint.h>

/* Most entries cv_treelet_schedule writes (8 leaves). */
#define CV_TREELET_SCHEDULE_MAX 3300

/* Writes the schedule for treelets of `leaves` (3..8) leaves into out
 * (CV_TREELET_SCHEDULE_MAX entries): first the subsets, then the pairs as
 * subset | left part << 8. Returns the entry count, 0 for a size out of
 * range. */
size_t cv_treelet_schedule(int leaves, uint32_t *out);

#endif
