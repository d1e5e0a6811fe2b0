// glsl/trace/matte.glsl: coverage and ID mattes (glsl/shared/trace.h,
// CvMatte words) at the first hit of a camera ray, for the path
// integrators' matte stage (matte.comp) and bdpt's camera subpath
// (bdpt/bdpt.comp) alike, so that both write the same words. The host
// defines CV_MATTE_STRIDE (and CV_CRYPTO for Cryptomatte). Each path slot
// has one path in flight, so one invocation at most touches a slot's
// words: no atomics. Camera rays that escape add nothing (coverage 0).
// Include after common.glsl and the mesh and curve buffers.
#ifndef CV_TRACE_MATTE_GLSL
#define CV_TRACE_MATTE_GLSL

layout(binding = CV_TEXUNIT_TRI_OBJECT) uniform usamplerBuffer cv_tri_object;
layout(std430, binding = CV_BIND_MATTE) buffer CvMatte { uint matte[]; };

void cv_matte_add(uint at, float w)
{
    matte[at] = floatBitsToUint(uintBitsToFloat(matte[at]) + w);
}

#ifdef CV_CRYPTO
// Adds the sample's filter weight w (common.glsl: cv_path_weight, the
// sign of the filter where it is importance-sampled, as the colour's) to
// id's pair from `at` on, taking the first free pair for a new id.
void cv_matte_rank(uint at, uint id, float w)
{
    for (uint k = 0u; k < CV_MATTE_RANK; k++) {
        uint cur = matte[at + 2u * k];
        if (cur == id || cur == 0u) {
            matte[at + 2u * k] = id;
            cv_matte_add(at + 2u * k + 1u, w);
            return;
        }
    }
}
#endif

// The camera ray of the path in slot `path` first met primitive `prim`
// (CV_HIT_MEDIUM: it scattered in a medium before any surface: covered,
// not the background, by no object or material).
void cv_matte_first_hit(uint path, uint prim)
{
    uint base = path * CV_MATTE_STRIDE;
    float w = cv_path_weight(path);
    if (prim == CV_HIT_MEDIUM) {
        cv_matte_add(base + CV_MATTE_COVERAGE, w);
        return;
    }
    uint object, word;
#ifdef CV_HAS_CURVES
    if ((prim & CV_PRIM_CURVE) != 0u) {
        uvec4 info = cv_curve_at(prim & ~CV_PRIM_CURVE).info;
        object = info.z + 1u;
        word = info.x;
    } else
#endif
    {
        object = texelFetch(cv_tri_object, int(prim)).x + 1u;
        word = cv_triangles[prim].idx.w;
    }
    uint material = (word & CV_TRI_MATERIAL_MASK) + 1u;
    cv_matte_add(base + CV_MATTE_COVERAGE, w);
    if (cv_path_sample(path) == 0u) {
        matte[base + CV_MATTE_OBJECT_ID] = object;
        matte[base + CV_MATTE_MATERIAL_ID] = material;
    }
#ifdef CV_CRYPTO
    cv_matte_rank(base + CV_MATTE_CRYPTO_OBJECT, object, w);
    cv_matte_rank(base + CV_MATTE_CRYPTO_MATERIAL, material, w);
#endif
}

#endif
