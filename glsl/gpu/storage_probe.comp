#version 450
// glsl/gpu/storage_probe.comp: does the driver address a storage buffer
// larger than it advertises (GL_MAX_SHADER_STORAGE_BLOCK_SIZE)? Mesa's
// llvmpipe advertises 128 MiB, yet a scene of 1.4 M triangles needs more
// for its BVH build. Pass 0 writes a pattern at each probed word of the
// large buffer; pass 1 (a separate dispatch, so the value comes from
// memory) reads them back with the length the shader sees. The host checks
// those and the words themselves, so that a driver that wraps, clamps or
// drops accesses beyond its limit is caught (src/gpu/storage.c).
layout(local_size_x = 16) in;
#include "shared/bindings.h"

layout(std430, binding = CV_BIND_CHECK_IN) buffer Large { uint large[]; };
// In: the word indices to probe. Out: what the shader read back at each,
// and the array length the shader sees (in out[count]).
layout(std430, binding = CV_BIND_CHECK_OUT) buffer Probe { uint probe[]; };

uniform uint u_count;
uniform uint u_pass;

uint storage_pattern(uint word)
{
    return word * 2654435761u + 0x5bd1e995u;
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i > u_count)
        return;
    if (i == u_count) {
        if (u_pass == 1u)
            probe[2u * u_count] = uint(large.length());
        return;
    }
    uint word = probe[i];
#ifdef CV_STORAGE_PROBE_WRAP
    // Tests only: act as a driver that wraps addresses at this many words.
    word %= uint(CV_STORAGE_PROBE_WRAP);
#endif
    if (u_pass == 0u)
        large[word] = storage_pattern(probe[i]);
    else
        probe[u_count + i] = large[word];
}
