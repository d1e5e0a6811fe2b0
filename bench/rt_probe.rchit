#version 460
// bench/rt_probe.rchit: a closest hit's distance and triangle (the
// primitive index in the one geometry of the BLAS: the scene's triangle).
#extension GL_EXT_ray_tracing : require
#extension GL_GOOGLE_include_directive : require
#include "rt_probe_payload.glsl"

layout(location = 0) rayPayloadInEXT RtProbeHit hit;

void main()
{
    hit.t = gl_HitTEXT;
    hit.prim = uint(gl_PrimitiveID);
}
