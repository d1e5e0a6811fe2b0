// glsl/bvh/radix_digits.glsl: the digit of a key in one radix sort pass, and
// per-nibble counts packed 16 bits each into two uvec4 (nibbles 0-7 in lo,
// 8-15 in hi), so that a count of all 16 values is added or scanned with two
// vector operations. A pass's digit is RADIX_BITS (4..8) wide; the scatter
// ranks it one nibble at a time (radix_scatter.comp).
// With KEY64 a key is two words (low, high) and u_shift runs over 0..63.
#ifndef CV_BVH_RADIX_DIGITS_GLSL
#define CV_BVH_RADIX_DIGITS_GLSL

#define RADIX_BINS (1u << RADIX_BITS)

#ifdef KEY64
#define RadixKey uvec2
#else
#define RadixKey uint
#endif

// The digit of key k at bit `shift`; with KEY64 it may straddle the words.
uint cv_radix_digit(RadixKey k, uint shift)
{
#ifdef KEY64
    uint w = shift >= 32u ? k.y >> (shift - 32u)
                          : (k.x >> shift) | (shift == 0u ? 0u : k.y << (32u - shift));
#else
    uint w = k >> shift;
#endif
    return w & (RADIX_BINS - 1u);
}

// Adds one to nibble value d's field (d < 16).
void cv_radix_count(uint d, inout uvec4 lo, inout uvec4 hi)
{
    uvec4 v = uvec4(0u);
    v[(d & 7u) >> 1] = 1u << (16u * (d & 1u));
    if (d < 8u)
        lo += v;
    else
        hi += v;
}

// Nibble value d's field of the half (lo or hi) that holds it.
uint cv_radix_field(uvec4 v, uint d)
{
    return (v[(d & 7u) >> 1] >> (16u * (d & 1u))) & 0xffffu;
}

#endif
