#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/sd_flush.comp: at the end of a training iteration of
// rlpath's sdtree method, splats every path slot's last finished path's
// records into the tree's statistics (sdtree.glsl: cv_sd_flush), which the
// slot's next path would otherwise do. One invocation per slot.
#include "shared/trace.h"
layout(local_size_x = 64) in;
#include "../../lib/index.glsl"
#define CV_SD_RECORD
#define CV_SD_SPLAT
#include "sdtree.glsl"

void main()
{
    uint slot = cv_global_index();
    if (slot < u_sd.learn.z)
        cv_sd_flush(slot);
}
