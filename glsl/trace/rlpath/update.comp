#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/update.comp: applies the temporal-difference updates of
// one depth to the Q-table, after the shade stage (which only reads the
// table). UPDATE_MODE 0 runs over the hit queue and applies the targets the
// shade stage left in the path state; UPDATE_MODE 1 runs over the escaped
// queue: a bounce that left the scene learns the environment radiance it
// found (0 without an environment).
#include "shared/trace.h"
layout(local_size_x = CV_TRACE_GROUP) in;
#include "../common.glsl"
#include "../geometry.glsl"
#include "../lights.glsl"
#define CV_RL_TABLE_WRITE
#define CV_RL_TABLE_UPDATE
#include "guide.glsl"

layout(rgba32ui, binding = CV_IMAGE_RL_PATH) uniform uimageBuffer rl_path;

void main()
{
    uint i = cv_global_index();
#if UPDATE_MODE == 0
    if (i >= q.count[CV_Q_HITS])
        return;
    uint pixel = uint(cv_ray_in(hits[i].ray).o.w);
    uvec4 st = imageLoad(rl_path, int(pixel));
    if (st.z == CV_RL_NONE)
        return;
    cv_rl_update(st.z, uintBitsToFloat(st.w));
    st.z = CV_RL_NONE;
    imageStore(rl_path, int(pixel), st);
#else
    if (i >= q.count[CV_Q_ESCAPED])
        return;
    CvRayItem r = cv_ray_in(cv_escaped_ray(i));
    uint pixel = uint(r.o.w);
    uvec4 st = imageLoad(rl_path, int(pixel));
    uint depth = cv_ray_depth(r);
    if (depth == 0u || st.x == CV_RL_NONE || st.y + 1u != depth)
        return;
    vec3 Le = cv_env_Le(r.d.xyz);
    cv_rl_update(st.x, (Le.x + Le.y + Le.z) * (1.0 / 3.0));
    st.x = CV_RL_NONE;
    imageStore(rl_path, int(pixel), st);
#endif
}
