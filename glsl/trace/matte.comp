#version 450
// glsl/trace/matte.comp: coverage and ID mattes (glsl/shared/trace.h,
// CvMatte words) at the first hit of every camera ray. Runs after the
// intersect stage, over its hits, only for jobs that ask for alpha or ID
// AOVs, so that the other stages stay as they are. Each path slot has one
// path in flight, so one invocation at most touches a slot's words: no
// atomics. Camera rays that escape add nothing (coverage 0).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "../bvh/mesh_buffers.glsl"
#include "../bvh/curves.glsl"

layout(std430, binding = CV_BIND_TRI_OBJECT) readonly buffer CvMatteObjects { uint tri_object[]; };
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

void main()
{
    uint i = cv_global_index();
    if (i >= cv_hit_count())
        return;
    CvHitItem h = hits[cv_hit_slot(i)];
    CvRayItem r = cv_ray_in(h.ray);
    if (cv_ray_depth(r) != 0u || (cv_ray_flags(r) & CV_RAYF_PROBE) != 0u)  // a probe: no camera ray
        return;
    uint path = uint(r.o.w);
    uint base = path * CV_MATTE_STRIDE;
    float w = cv_path_weight(path);
    if (h.prim == CV_HIT_MEDIUM) {
        // scattered in a medium before any surface: covered (not the
        // background), by no object or material
        cv_matte_add(base + CV_MATTE_COVERAGE, w);
        return;
    }
    uint object, word;
#ifdef CV_HAS_CURVES
    if ((h.prim & CV_PRIM_CURVE) != 0u) {
        uvec4 info = cv_curve_at(h.prim & ~CV_PRIM_CURVE).info;
        object = info.z + 1u;
        word = info.x;
    } else
#endif
    {
        object = tri_object[h.prim] + 1u;
        word = cv_triangles[h.prim].idx.w;
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
