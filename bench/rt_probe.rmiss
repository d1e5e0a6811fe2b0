#version 460
// bench/rt_probe.rmiss: no triangle between tmin and tmax.
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_probe_payload.glsl"

layout(location = 0) rayPayloadInEXT RtProbeHit hit;

void main()
{
    hit.prim = 0xffffffffu;
}
