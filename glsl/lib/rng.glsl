// glsl/lib/rng.glsl: a counter-based random number generator. Each stream is
// a pure function of (key, counter): PCG's output permutation applied to a
// mixed 32-bit state, so a path can draw dimension d of sample s without
// carrying state between kernels.
#ifndef CV_LIB_RNG_GLSL
#define CV_LIB_RNG_GLSL

// PCG-RXS-M-XS 32-bit hash (Jarzynski & Olano, "Hash functions for GPU
// rendering", 2020): a bijection on uint with good avalanche.
uint cv_pcg_hash(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

uint cv_hash2(uint a, uint b) { return cv_pcg_hash(a ^ cv_pcg_hash(b)); }
uint cv_hash3(uint a, uint b, uint c) { return cv_pcg_hash(a ^ cv_pcg_hash(b ^ cv_pcg_hash(c))); }

// 24 high bits -> [0,1): exactly representable, never 1.
float cv_uint_to_unit(uint x) { return float(x >> 8u) * (1.0 / 16777216.0); }

struct CvRng { uint key; uint counter; };

CvRng cv_rng_init(uint a, uint b) { return CvRng(cv_hash2(a, b), 0u); }

float cv_rng_next(inout CvRng r)
{
    r.counter++;
    return cv_uint_to_unit(cv_hash2(r.key, r.counter));
}

vec2 cv_rng_next2(inout CvRng r)
{
    float x = cv_rng_next(r);
    return vec2(x, cv_rng_next(r));
}

#endif
