/* rng.h: the C tests' pseudo-random numbers, three small generators with
 * the state in the caller's variable. Each test keeps the generator and
 * seed its samples were drawn with when it was written: its statistical
 * bounds were checked on those draws, and another generator would draw
 * others. Header-only (the fuzzers have their own, tests/fuzz_mutate.h). */
#ifndef CV_TESTS_RNG_H
#define CV_TESTS_RNG_H

#include <stdint.h>

/* Numerical Recipes' 32-bit LCG: the next state, whose top 24 bits are
 * the draw (the low bits cycle with short periods). */
static inline uint32_t cv_test_lcg32_next(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s;
}

/* ... as a number in [0, 1) with 24 bits (exact in a float). */
static inline double cv_test_lcg32(uint32_t *s)
{
    return (double)(cv_test_lcg32_next(s) >> 8) / 16777216.0;
}

/* Knuth's MMIX 64-bit LCG, in [0, 1) with 53 bits. */
static inline double cv_test_lcg64(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(*s >> 11) * 0x1p-53;
}

/* Marsaglia's xorshift64 (13, 7, 17): the next state; *s must not be 0. */
static inline uint64_t cv_test_xorshift64_next(uint64_t *s)
{
    uint64_t x = *s;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    *s = x;
    return x;
}

/* ... as a number in [0, 1) with 53 bits. */
static inline double cv_test_xorshift64(uint64_t *s)
{
    return (double)(cv_test_xorshift64_next(s) >> 11) * 0x1p-53;
}

#endif
