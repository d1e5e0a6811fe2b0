/* scan.h: multi-level exclusive prefix sum of a GPU buffer of uint32, in
 * place (glsl/bvh/scan_block.comp, scan_add.comp). Used by the final node
 * layout; exposed for tests. */
#ifndef CV_BVH_SCAN_H
#define CV_BVH_SCAN_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_scan;

/* Scratch for scans of up to max_n elements. NULL on failure. */
struct cv_scan *cv_scan_create(struct cv_gpu *gpu, uint32_t max_n, struct cv_error *err);
/* Replaces buf[0..n) by its exclusive prefix sum; n <= max_n. Binds
 * CV_BIND_SCAN_DATA and CV_BIND_SCAN_SUMS. */
bool cv_scan_exclusive(struct cv_scan *scan, GLuint buf, uint32_t n, struct cv_error *err);
/* Bytes of GPU scratch held. */
uint64_t cv_scan_bytes(const struct cv_scan *scan);
/* Accepts NULL; clears the pointer. */
void cv_scan_destroy(struct cv_scan **scan);

/* Starts compiling the scan's programs (gpu/program.h: cv_program_request). */
void cv_scan_prefetch(struct cv_gpu *gpu);

#endif
