/* radix_sort.h: stable GPU LSD radix sort of 32- or 64-bit keys with uint32
 * values, 8 bits per pass (glsl/bvh/radix_count.comp, radix_spine.comp,
 * radix_scatter.comp).
 * Any key distribution; equal keys keep their order. A 64-bit key is two
 * uint32 words, low word first. Exposed for tests. */
#ifndef CV_BVH_RADIX_SORT_H
#define CV_BVH_RADIX_SORT_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"

struct cv_radix_sort;

/* Scratch (a second key/value pair, digit counts) for up to max_n pairs of
 * keys of up to max_bits (32 or 64) bits. */
struct cv_radix_sort *cv_radix_sort_create(struct cv_gpu *gpu, uint32_t max_n, int max_bits,
                                           struct cv_error *err);
/* Sorts keys[0..n) by their low `bits` bits (1..max_bits), carrying vals;
 * keys are 64-bit (two words) when bits > 32. The result ends in the same
 * two buffers. n <= max_n. Binds CV_BIND_SORT_*. */
bool cv_radix_sort_run(struct cv_radix_sort *rs, GLuint keys, GLuint vals, uint32_t n,
                       int bits, struct cv_error *err);
uint64_t cv_radix_sort_bytes(const struct cv_radix_sort *rs);
/* Accepts NULL; clears the pointer. */
void cv_radix_sort_destroy(struct cv_radix_sort **rs);

/* Starts compiling the programs of a sort of `bits`-bit keys
 * (gpu/program.h: cv_program_request). */
void cv_radix_sort_prefetch(struct cv_gpu *gpu, int bits);

#endif
