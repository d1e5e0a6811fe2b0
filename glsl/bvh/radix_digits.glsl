// glsl/bvh/radix_digits.glsl: per-digit counts of a 4-bit radix sort pass
// packed 16 bits each into two uvec4 (digits 0-7 in lo, 8-15 in hi), so a
// count of all 16 digits is added or scanned with two vector operations.
#ifndef CV_BVH_RADIX_DIGITS_GLSL
#define CV_BVH_RADIX_DIGITS_GLSL

// Adds one to digit d's field (d < 16).
void cv_radix_count(uint d, inout uvec4 lo, inout uvec4 hi)
{
    uvec4 v = uvec4(0u);
    v[(d & 7u) >> 1] = 1u << (16u * (d & 1u));
    if (d < 8u)
        lo += v;
    else
        hi += v;
}

// Digit d's field of the half (lo or hi) that holds it.
uint cv_radix_field(uvec4 v, uint d)
{
    return (v[(d & 7u) >> 1] >> (16u * (d & 1u))) & 0xffffu;
}

#endif
