#version 450
// glsl/trace/rlpath/update.comp: applies the temporal-difference updates of
// one depth to the Q-table, after the shade stage (which only reads the
// table). UPDATE_MODE 0 runs over the hit queue and applies the targets the
// shade stage left in the path state; UPDATE_MODE 1 runs over the escaped
// queue: a bounce that left the scene learns the environment radiance it
// found (0 without an environment).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "../common.glsl"
#include "../shading.glsl"
#include "guide.glsl"

layout(std430, binding = CV_BIND_RL_PATH) buffer CvRlPath { uvec4 rl_path[]; };

void main()
{
    uint i = cv_global_index();
#if UPDATE_MODE == 0
    if (i >= q.count_a.z)
        return;
    uint pixel = floatBitsToUint(rays_in[hits[i].ray].o.w);
    uvec4 st = rl_path[pixel];
    if (st.z == CV_RL_NONE)
        return;
    cv_rl_update(st.z, uintBitsToFloat(st.w));
    rl_path[pixel].z = CV_RL_NONE;
#else
    if (i >= q.count_a.w)
        return;
    CvRayItem r = rays_in[escaped[i]];
    uint pixel = floatBitsToUint(r.o.w);
    uvec4 st = rl_path[pixel];
    uint depth = cv_depth();
    if (depth == 0u || st.x == CV_RL_NONE || st.y + 1u != depth)
        return;
    vec3 Le = cv_env_Le(r.d.xyz);
    cv_rl_update(st.x, (Le.x + Le.y + Le.z) * (1.0 / 3.0));
    rl_path[pixel].x = CV_RL_NONE;
#endif
}
