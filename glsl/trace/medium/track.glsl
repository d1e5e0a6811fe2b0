// glsl/trace/medium/track.glsl: the intersect stage's tracing under volpath
// (CV_MEDIA): a ray's closest surface, through the media on its way. Along
// each stretch of one medium, delta tracking (medium.glsl) decides whether
// the ray collides first; surfaces that are no surface (the "interface"
// material: medium boundaries) and alpha cut-outs that let the ray through
// are passed, a boundary switching the ray's medium, without a new path
// vertex: the ray keeps its origin, so the MIS weights of what it finds
// still refer to the vertex that sent it (pbrt-v4's SkipIntersection keeps
// prevIntrContext). Include after tracing.glsl, geometry.glsl,
// materials.glsl, sampler.glsl and medium.glsl.
#ifndef CV_TRACE_MEDIUM_TRACK_GLSL
#define CV_TRACE_MEDIUM_TRACK_GLSL

#include "random.glsl"

// Per path slot: xyz, the channel ratios r of the slot's path
// (medium.glsl); w, 1 + the sample index of the path they belong to, so
// that a slot's next path starts from r = 1 without any stage that starts
// paths writing here (the buffer starts cleared).
layout(std430, binding = CV_BIND_MEDIUM_PATHS) buffer CvMediumPaths { vec4 medium_paths[]; };

// Traces r. Returns true with h the surface to shade; or sets `event` with
// h.t the distance of a collision in the ray's medium (h.prim
// CV_HIT_MEDIUM); neither: the ray left the scene. r.beta takes the
// tracking's weights and the medium the ray ends in.
bool cv_medium_track(inout CvRayItem r, out CvHit h, out bool event)
{
    event = false;
    uint path = uint(r.o.w);
    uint depth = cv_ray_depth(r);
    uint medium = cv_ray_medium(r);
    vec3 beta = r.beta.rgb;
    uint fp = cv_film_pixel(cv_path_pixel(path)), si = cv_path_sample(path);
    float stamp = float(si + 1u);
    vec4 mp = medium_paths[path];
    vec3 ratios = mp.w == stamp ? mp.xyz : vec3(1.0);
    uint hero = cv_medium_hero_channel(fp, si, 0u);
    float tmin = 0.0, seg0 = 0.0;
    bool hit = false;
#ifdef CV_MEDIUM_GRIDS
    // grid media's random numbers: a counter under the path's key and depth
    uvec3 grid_key = uvec3(cv_film_pixel(cv_path_pixel(path)) ^ u_pass.seed_lo,
                           cv_path_sample(path) ^ cv_hash(u_pass.seed_hi), depth ^ 0x47524944u);
    uint grid_n = 0u;
#endif
    h.t = 0.0;
    h.prim = 0u;
    h.b1 = 0.0;
    h.b2 = 0.0;
    for (uint k = 0u; k < 64u; k++) {
#ifndef CV_EMPTY_SCENE
        hit = cv_trace_closest(r.o.xyz, r.d.xyz, tmin, 1e30, h);
#endif
        bool pass = false;
        uint material = 0u;
        vec3 ng = vec3(0.0);
#ifdef CV_HAS_ALPHA
        if (hit) {
            material = cv_triangles[h.prim].idx.w & CV_TRI_MATERIAL_MASK;
            CvSurface s = cv_surface(h.prim, h.b1, h.b2);
            ng = s.ng;
            // the same test as the path integrator's (intersect.comp)
            float u = cv_uint_to_unit(cv_hash4(cv_film_pixel(cv_path_pixel(path)),
                                               cv_path_sample(path), h.prim, depth * 64u + k));
            pass = cv_material_alpha_pass(material, s.uv, u);
        }
#endif
        if (medium != 0u) {
            float len = (hit ? h.t : 1e30) - seg0;
            float t;
            vec3 w;
            bool collide;
#ifdef CV_MEDIUM_GRIDS
            if (cv_grid_medium(medium)) {
                collide = cv_grid_sample_distance(medium, r.o.xyz, r.d.xyz, seg0, seg0 + len, hero,
                                                  grid_key, grid_n, ratios, t, w);
                t -= seg0;
            } else
#endif
                collide = cv_medium_sample_distance(medium, len, hero, cv_medium_u(fp, si, depth, k),
                                                    ratios, t, w);
            beta *= w;
            if (collide) {
                event = true;
                hit = false;
                h.t = seg0 + t;
                h.prim = CV_HIT_MEDIUM;
                break;
            }
            if (cv_max3(beta) <= 0.0) {  // the tracking ended the path (weight 0)
                hit = false;
                break;
            }
        }
        if (!hit || !pass)
            break;
        if (materials[material].type == CV_MAT_INTERFACE)
            medium = cv_medium_across(material, ng, r.d.xyz, medium);
        seg0 = h.t;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
    r.beta = vec4(beta, cv_ray_meta_in(cv_ray_flags(r), depth, medium));
    medium_paths[path] = vec4(ratios, stamp);
    return hit;
}

#endif
