#version 450
// glsl/trace/rlpath/sd_flush.comp: after a training pass of rlpath's
// sdtree method, sends every path slot's last finished path's records to
// the host (sdtree.glsl: cv_sd_flush), which the slot's next path would
// otherwise do. One invocation per slot.
#include "shared/trace.h"
layout(local_size_x = 64) in;
#include "../../lib/index.glsl"
#define CV_SD_RECORD
#include "sdtree.glsl"

void main()
{
    uint slot = cv_global_index();
    if (slot < u_sd.learn.z)
        cv_sd_flush(slot);
}
