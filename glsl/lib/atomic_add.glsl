// glsl/lib/atomic_add.glsl: float atomic adds into an image buffer, one
// home for the two ways to do them. GLSL 4.5 core has no float atomics:
// where the driver has GL_NV_shader_atomic_float (NVIDIA, Mesa's llvmpipe)
// an r32f view of the words takes imageAtomicAdd; elsewhere the r32ui view
// takes a compare-and-swap on the float's bits, retried while another
// thread changed the word in between. Each macro defines
// `void NAME(int word, float v)`; the caller picks one by its own test of
// the extension (tests force the compare-and-swap one) and, for the
// compare-and-swap, its retry policy:
//   CV_ATOMIC_ADD_RETRY_EXACT: retry until the add lands (as exact as the
//     native add; the cost is unbounded under contention);
//   a bound n > 0: give up after n tries, for sums where a lost add only
//     skews what is learned and never what is rendered.
// The image arguments are image variables (declared coherent by the
// caller), not values: these are macros because GLSL functions cannot
// take an image of a caller-chosen binding.
#ifndef CV_LIB_ATOMIC_ADD_GLSL
#define CV_LIB_ATOMIC_ADD_GLSL

#define CV_ATOMIC_ADD_RETRY_EXACT 0u

// NAME adds through the r32f image FIMG with the native float atomic.
#define CV_ATOMIC_ADD_NATIVE(NAME, FIMG) \
    void NAME(int word, float v) { imageAtomicAdd(FIMG, word, v); }

// NAME adds through the r32ui image UIMG by compare-and-swap, with at most
// TRIES tries (CV_ATOMIC_ADD_RETRY_EXACT: no bound).
#define CV_ATOMIC_ADD_CAS(NAME, UIMG, TRIES) \
    void NAME(int word, float v) \
    { \
        uint old = imageLoad(UIMG, word).x; \
        for (uint i = 0u; (TRIES) == 0u || i < (TRIES); i++) { \
            uint seen = imageAtomicCompSwap(UIMG, word, old, \
                                            floatBitsToUint(uintBitsToFloat(old) + v)); \
            if (seen == old) \
                break; \
            old = seen; \
        } \
    }

#endif
