#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/escaped.comp: rays that left the scene pick up environment
// light, MIS-weighted against the light sampling that could have found the
// same direction (not for camera rays or after specular bounces); their
// paths end, so their slots start their next samples (regenerate.glsl).
// Runs every iteration where the scene has an environment light or
// rlpath learns (CV_RLPATH: the bounce that escaped learns the environment
// radiance it found, 0 without an environment, in the Q-table,
// rlpath/guide.glsl; CV_RLPATH_SD, the sdtree method's records); otherwise
// a miss has nothing to add, and this stage runs only where the host
// chose it over the intersect stage's own regeneration for a scene that
// few rays leave (trace/render.h: enum cv_misses). The host defines
// CV_NO_ENV, as for every stage, when the scene has no environment light.
// With CV_FILM_TRANSPARENT (a job with alpha) the environment seen directly
// by a camera ray adds nothing: alpha 0 and no colour, as Cycles' film
// transparency; it still lights the scene and is seen in reflections.
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "common.glsl"
#include "geometry.glsl"
#include "lights.glsl"
#include "sampler.glsl"
#include "regenerate.glsl"
// the float atomic adds of both rlpath methods: the expander pastes a file
// once, so not first inside the #ifdef of the method not compiled
#include "../lib/atomic_add.glsl"
#ifdef CV_RLPATH
#define CV_RL_TABLE_WRITE
#define CV_RL_TABLE_UPDATE
#include "rlpath/guide.glsl"
layout(rg32ui, binding = CV_IMAGE_RL_PATH) uniform readonly uimageBuffer rl_path;

// The environment's part of the target is not left out of guiding as a
// lamp's is (shade.comp): light sampling covers it, but an environment
// seen through openings is what guiding is for.
void cv_rl_learn_escaped(CvRayItem r)
{
    if (!cv_rl_learning())
        return;   // the guide is frozen (rlpath.train)
    uvec2 st = imageLoad(rl_path, int(r.o.w)).xy;
    uint depth = cv_ray_depth(r);
    if (depth == 0u || st.x == CV_RL_NONE || st.y + 1u != depth)
        return;
    vec3 Le = cv_env_Le(r.d.xyz);
    cv_rl_update(st.x, cv_mean3(Le), 0.0);
}
#endif
#ifdef CV_RLPATH_SD
// rlpath's sdtree method (CV_RLPATH_SD): while training, the environment
// light the path adds to the film adds to its records, which wait for the
// pass's end to be splatted into the tree's statistics
// (rlpath/sd_flush.comp, rlpath/sdtree.glsl).
#define CV_SD_RECORD
#include "rlpath/sdtree.glsl"
void cv_sd_escaped(CvRayItem r)
{
    if (!cv_sd_learning())
        return;
    uint slot = uint(r.o.w), depth = cv_ray_depth(r);
#ifndef CV_NO_ENV
    // what main() adds to the film (to no record at depth 0)
    if (cv_n_lights() > 0u && (cv_ray_flags(r) & CV_RAYF_SPECULAR) == 0u)
        cv_sd_found(slot, depth, r.beta.rgb * cv_env_Le(r.d.xyz) *
                                     cv_power_heuristic(r.d.w, cv_env_pdf(r.d.xyz)));
    else
        cv_sd_found(slot, depth, r.beta.rgb * cv_env_Le(r.d.xyz));
#endif
    cv_sd_path_end(slot, depth);
}
#endif

void main()
{
    uint i = cv_global_index();
    bool push = false;
    CvRayItem nr;
    if (i < q.count[CV_Q_ESCAPED]) {
        CvRayItem r = cv_ray_in(cv_escaped_ray(i));
#ifdef CV_RLPATH
        cv_rl_learn_escaped(r);
#endif
#ifdef CV_RLPATH_SD
        cv_sd_escaped(r);
#endif
#ifndef CV_NO_ENV
        vec3 Le = cv_env_Le(r.d.xyz);
#ifdef CV_FILM_TRANSPARENT
        if (cv_ray_depth(r) == 0u)
            Le = vec3(0.0);
#endif
        if (cv_max3(Le) > 0.0) {
            float w = 1.0;
            if (cv_ray_depth(r) > 0u && (cv_ray_flags(r) & CV_RAYF_SPECULAR) == 0u &&
                cv_n_lights() > 0u)
                w = cv_power_heuristic(r.d.w, cv_env_pdf(r.d.xyz));
            cv_film_add(uint(r.o.w), r.beta.rgb * Le * w);
        }
#endif
        push = cv_regenerate(uint(r.o.w), nr);
    }
    uint slot = cv_queue_slots(push, CV_Q_RAYS_OUT, false, CV_Q_RAYS_OUT).x;
    if (push)
        cv_ray_out(slot, nr);
}
