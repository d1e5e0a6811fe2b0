#version 450
// glsl/trace/shadow.comp: next-event shadow rays; an unoccluded one adds its
// contribution to its path slot's film entry. With alpha cut-outs in the
// scene, occluders that the alpha test lets through are skipped. Under
// volpath (CV_MEDIA) the contribution is multiplied by the transmittance
// along the ray, through the medium boundaries ("interface" surfaces) on
// its way, as pbrt-v4's TraceTransmittance: exact in homogeneous media,
// ratio-tracked in grid media (medium/grid.glsl).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "sampler.glsl"
#include "tracing.glsl"
#include "geometry.glsl"
#include "materials.glsl"
#ifdef CV_RLPATH_SD
#define CV_SD_RECORD
#include "rlpath/sdtree.glsl"
#endif

// An unoccluded shadow ray's contribution L goes to its path slot's film
// entry, weighted by its sample's filter weight (s.m.w: the slot may have
// moved on to its next sample when its path ended at the vertex that sent
// the ray), and, while rlpath's sdtree method trains (CV_RLPATH_SD), to the
// records of the bounces before the vertex that sent it (its depth in
// s.m.z: rlpath/sd_shade.comp).
void cv_shadow_add(CvShadowItem s, uint path, vec3 L)
{
    cv_film_add_weighted(path, s.m.w, L);
#ifdef CV_RLPATH_SD
    if (cv_sd_learning())
        cv_sd_found(path, uint(s.m.z), L);
#endif
}

#ifdef CV_MEDIA
#include "medium/medium.glsl"

// Shadow ray s of path slot `path` through media: its contribution times
// the transmittance, unless a surface other than a boundary or a cut-out
// that lets it through is in the way.
void cv_shadow_media(CvShadowItem s, uint path)
{
    uint medium = uint(s.m.x);
    vec3 T = vec3(1.0);
    float tmin = 0.0, seg0 = 0.0;
    CvHit h;
    for (uint k = 0u; k < 64u; k++) {
        bool hit = false;
#ifndef CV_EMPTY_SCENE
        hit = cv_trace_closest(s.o.xyz, s.d.xyz, tmin, s.o.w, h);
#endif
        if (medium != 0u) {
#ifdef CV_MEDIUM_GRIDS
            // ratio tracking, its random numbers keyed by the shadow ray
            if (cv_grid_medium(medium))
                T *= cv_grid_transmittance(
                    medium, s.o.xyz, s.d.xyz, seg0, hit ? h.t : s.o.w,
                    uvec3(cv_film_pixel(cv_path_pixel(path)) ^ u_pass.seed_lo,
                          uint(s.L.w) ^ floatBitsToUint(s.o.x) ^ cv_hash(floatBitsToUint(s.o.y)),
                          floatBitsToUint(s.o.z) ^ cv_hash(0x52415449u + k)));
            else
#endif
                T *= cv_medium_transmittance(medium, (hit ? h.t : s.o.w) - seg0);
        }
        if (!hit) {
            cv_shadow_add(s, path, s.L.rgb * T);
            return;
        }
#ifdef CV_HAS_ALPHA
        uint material = cv_triangles[h.prim].idx.w & CV_TRI_MATERIAL_MASK;
        CvSurface sf = cv_surface(h.prim, h.b1, h.b2);
        float u = cv_uint_to_unit(
            cv_hash4(cv_film_pixel(cv_path_pixel(path)), uint(s.L.w), h.prim, 0x5bd1e995u + k));
        if (!cv_material_alpha_pass(material, sf.uv, u))
            return;
        if (materials[material].type == CV_MAT_INTERFACE)
            medium = cv_medium_across(material, sf.ng, s.d.xyz, medium);
#else
        return;
#endif
        if (cv_max3(T) <= 0.0)
            return;
        seg0 = h.t;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
}
#endif

void main()
{
    uint i = cv_global_index();
    if (i >= q.count[CV_Q_SHADOW])
        return;
    CvShadowItem s = shadows[i];
    uint path = uint(s.d.w);
#ifdef CV_HAS_MOTION
    cv_trace_time = s.m.y;
#endif
#ifdef CV_MEDIA
    cv_shadow_media(s, path);
#elif defined(CV_HAS_ALPHA)
    float tmin = 0.0;
    CvHit h;
    for (uint k = 0u; k < 64u; k++) {
        if (!cv_trace_closest(s.o.xyz, s.d.xyz, tmin, s.o.w, h)) {
            cv_shadow_add(s, path, s.L.rgb);
            return;
        }
        uint word = cv_prim_word(h.prim);
        CvSurface sf = cv_surface_ray(h.prim, h.b1, h.b2, s.o.xyz, s.d.xyz, h.t);
        float u = cv_uint_to_unit(
            cv_hash4(cv_film_pixel(cv_path_pixel(path)), uint(s.L.w), h.prim, 0x5bd1e995u + k));
        if (!cv_material_alpha_pass(word & CV_TRI_MATERIAL_MASK, sf.uv, u))
            return;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
#elif defined(CV_EMPTY_SCENE)
    cv_shadow_add(s, path, s.L.rgb);
#else
    if (!cv_trace_any(s.o.xyz, s.d.xyz, 0.0, s.o.w))
        cv_shadow_add(s, path, s.L.rgb);
#endif
}
