// bench/rt_probe_payload.glsl: the payload of rt_probe's ray-tracing
// shaders (rt_probe.rgen, .rchit, .rmiss).
struct RtProbeHit {
    float t;
    uint prim;  // 0xffffffff: miss
};
