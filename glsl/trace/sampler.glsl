// glsl/trace/sampler.glsl: per-pixel sample values, deterministic from the
// job seed, pixel, sample index and dimension.
// Sobol: the 2D Sobol (0,2)-sequence for each pair of dimensions ("padded"
// like pbrt-v4's PaddedSobolSampler), with the sample index shuffled and both
// coordinates Owen-scrambled by hash-based nested uniform scrambling (Burley,
// "Practical Hash-based Owen Scrambling", JCGT 2020), seeded per pixel, pair
// and job. Any prefix of 2^k samples of a pixel stays stratified, so passes
// of any size continue the same sequence.
// Independent: a hash of everything, uniform and uncorrelated.
#ifndef CV_TRACE_SAMPLER_GLSL
#define CV_TRACE_SAMPLER_GLSL

#include "../lib/rng.glsl"   // cv_uint_to_unit

uint cv_hash(uint x)
{
    // lowbias32 (Wellons): good avalanche for 32-bit keys
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

uint cv_hash4(uint a, uint b, uint c, uint d)
{
    return cv_hash(a ^ cv_hash(b ^ cv_hash(c ^ cv_hash(d + 0x9e3779b9u))));
}

uint cv_lk_permute(uint x, uint seed)
{
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

uint cv_nested_scramble(uint x, uint seed)
{
    return bitfieldReverse(cv_lk_permute(bitfieldReverse(x), seed));
}

// Second dimension of the Sobol sequence: r = sum of i's bits k times the
// direction numbers v_k (Pascal's triangle mod 2, most significant bit
// first). Bit 31-m of r is the parity of i's bits k that contain m as a bit
// subset (Lucas: C(k, m) is odd iff m & k == m), which five shift-xor steps
// compute for all m at once (a superset transform over GF(2)). Same bits as
// the 32-step loop over i's bits that it replaces, without the loop that a
// scrambled (random) index runs in full.
uint cv_sobol1(uint i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0f0f0f0fu;
    i ^= (i >> 8) & 0x00ff00ffu;
    i ^= (i >> 16) & 0x0000ffffu;
    return bitfieldReverse(i);
}

// pixel: linear pixel index of the full film; index: the pixel's sample
// number; pair: dimension pair (dimensions 2*pair and 2*pair+1).
vec2 cv_sample_2d(uint pixel, uint index, uint pair, uvec2 seed, uint sampler)
{
    uint h = cv_hash4(pixel, pair, seed.x, seed.y);
    if (sampler != 0u) {
        uint a = cv_hash4(h, index, 0x51ed27u, 1u);
        uint b = cv_hash(a ^ 0x68bc21ebu);
        return vec2(cv_uint_to_unit(a), cv_uint_to_unit(b));
    }
    uint i = cv_nested_scramble(index, h);
    uint x = bitfieldReverse(i);
    uint y = cv_sobol1(i);
    x = cv_nested_scramble(x, cv_hash(h ^ 0xa511e9b3u));
    y = cv_nested_scramble(y, cv_hash(h ^ 0x63d83595u));
    return vec2(cv_uint_to_unit(x), cv_uint_to_unit(y));
}

#endif
