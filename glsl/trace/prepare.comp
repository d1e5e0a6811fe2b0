#version 450
// glsl/trace/prepare.comp: one invocation that turns queue counters into
// indirect dispatch arguments between stages, so the host never reads a
// count back. PREPARE_MODE 0 starts an iteration (the rays written last
// become its input; the other queues empty), 1 follows intersection (hits,
// escaped), 2 follows shading (shadow rays, done pixels).
#include "shared/trace.h"
layout(local_size_x = 1) in;
#include "common.glsl"

uvec4 cv_groups(uint n)
{
    uint g = (n + uint(CV_TRACE_GROUP) - 1u) / uint(CV_TRACE_GROUP);
    uint gy = 1u;
    if (g > 65535u) {
        gy = (g + 65534u) / 65535u;
        g = (g + gy - 1u) / gy;
    }
    return uvec4(g, gy, 1u, 0u);
}

void cv_stat_add(uint slot, uint n)
{
    uint lo = q.stats[slot].x + n;
    if (lo < n)
        q.stats[slot].y += 1u;
    q.stats[slot].x = lo;
}

void main()
{
#if PREPARE_MODE == 0
    uint n = q.count[CV_Q_RAYS_OUT];
    q.count[CV_Q_RAYS_IN] = n;
    q.count[CV_Q_RAYS_OUT] = 0u;
    q.count[CV_Q_HITS] = 0u;
    q.count[CV_Q_HITS_B] = 0u;
    q.count[CV_Q_ESCAPED] = 0u;
    q.count[CV_Q_SHADOW] = 0u;
    q.count[CV_Q_DONE] = 0u;
    q.args[CV_ARGS_RAYS] = cv_groups(n);
    cv_stat_add(CV_STAT_EXTEND, n);
#elif PREPARE_MODE == 1
    q.args[CV_ARGS_HITS] = cv_groups(q.count[CV_Q_HITS]);
    q.args[CV_ARGS_HITS_B] = cv_groups(q.count[CV_Q_HITS_B]);
    q.args[CV_ARGS_HITS_ALL] = cv_groups(q.count[CV_Q_HITS] + q.count[CV_Q_HITS_B]);
    q.args[CV_ARGS_ESCAPED] = cv_groups(q.count[CV_Q_ESCAPED]);
#else
    q.args[CV_ARGS_SHADOW] = cv_groups(q.count[CV_Q_SHADOW]);
    q.args[CV_ARGS_DONE] = cv_groups(q.count[CV_Q_DONE]);
    cv_stat_add(CV_STAT_SHADOW, q.count[CV_Q_SHADOW]);
#endif
}
