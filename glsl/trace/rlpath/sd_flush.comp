#version 450
#extension GL_NV_shader_atomic_float : enable
// glsl/trace/rlpath/sd_flush.comp: at the end of each pass of rlpath's
// sdtree method that trains, splats every path slot's path's records into
// the statistics of the tree being trained (sdtree.glsl: cv_sd_flush). A
// pass that trains gives each slot one path (trace/integrator.h:
// learn_path_a_slot), so every path of the pass has ended, its shadow
// rays too. The splat lives here, not in the shade bins and the escaped
// stage, whose builds its code would lengthen (bench/RESULTS.md, "sdtree's
// splat moved from the shade bins"). One invocation per slot.
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
