#version 450
// glsl/trace/test/bsdf_probe.comp: drives the shipped BSDF code for the
// tests in tests/trace/bsdf_*: samples it (mode 0) or evaluates f and pdf at
// given directions (mode 1) for one material at one fixed shading point;
// mode 2 resolves the material at probe_in[i] = (u, v, u_mix, u_alpha) and
// returns (albedo, alpha pass) and (shading normal, type); mode 3 asks one
// query of u_ask (bsdf/bsdf_query.glsl) with wi0, wi1 and (uc, u) from
// probe_in[3i..3i+2] and returns (f0, pdf0), (f1, pdf1), (wi, pdf) and
// (f, flags; -1: no sample) of the answer.
layout(local_size_x = 64) in;

#define CV_BQ_WI1  // asks its BSDF at a second direction (bsdf/bsdf.glsl)
#include "lib/index.glsl"
#include "lib/rng.glsl"
#include "trace/bsdf/material_buffers.glsl"
#include "trace/bsdf/bsdf.glsl"

layout(std430, binding = CV_BIND_PROBE_IN) readonly buffer ProbeIn { vec4 probe_in[]; };
layout(std430, binding = CV_BIND_PROBE_OUT) writeonly buffer ProbeOut { vec4 probe_out[]; };

uniform uint u_mode;
uniform uint u_ask;
uniform uint u_count;
uniform uint u_material;
uniform uint u_seed;
uniform vec3 u_wo;
uniform vec3 u_ng;
uniform vec3 u_ns;
uniform vec3 u_dpdu;
uniform vec2 u_uv;

void main()
{
    uint i = cv_global_index();
    if (i >= u_count)
        return;
    /* probe */
    if (u_mode == 2u) {
        vec4 q = probe_in[i];
        CvShadingPoint spq = CvShadingPoint(vec3(0.0), u_ng, u_ns, u_dpdu, q.xy, true);
        CvBsdf bq = cv_bsdf_at(u_material, spq, q.z);
        probe_out[2u * i] = vec4(cv_bsdf_albedo(bq), cv_material_alpha_pass(u_material, q.xy, q.w) ? 1.0 : 0.0);
        probe_out[2u * i + 1u] = vec4(bq.frame.z, float(bq.type));
        return;
    }
    CvShadingPoint sp = CvShadingPoint(vec3(0.0), u_ng, u_ns, u_dpdu, u_uv, dot(u_wo, u_ng) > 0.0);
    CvRng rng = cv_rng_init(u_seed, i);
    CvBsdf b = cv_bsdf_at(u_material, sp, cv_rng_next(rng));
    CvRng stream = cv_rng_init(u_seed ^ 0x5bd1e995u, i);  // own stream: the draws below stay as they were
    cv_bsdf_set_stream(b, cv_rng_next2(stream), cv_rng_next2(stream));
    // Every answer through one query call site, as a shade stage asks
    // (bsdf/bsdf_query.glsl): mode 0 samples, then evaluates f and pdf at
    // the sampled direction; mode 1 evaluates at probe_in[i]; mode 3 asks
    // u_ask once.
    CvBsdfQuery q = cv_bsdf_query_new(u_wo);
    if (u_mode == 3u) {
        q.ask = u_ask;
        q.wi0 = probe_in[3u * i].xyz;
        q.wi1 = probe_in[3u * i + 1u].xyz;
        q.uc = probe_in[3u * i + 2u].x;
        q.u = probe_in[3u * i + 2u].yz;
    } else if (u_mode == 0u) {
        q.ask = CV_BQ_SAMPLE;
        q.uc = cv_rng_next(rng);
        q.u = cv_rng_next2(rng);
    } else {
        q.ask = CV_BQ_F0 | CV_BQ_PDF0;
        q.wi0 = probe_in[i].xyz;
    }
    CvBsdfSample s = q.s;
    for (uint pass = 0u; pass < 2u; pass++) {
        cv_bsdf_query(b, q);
        if (u_mode == 3u || q.ask != CV_BQ_SAMPLE)
            break;
        s = q.s;
        if (!q.sampled) {
            probe_out[3u * i] = vec4(0.0, 0.0, 0.0, -1.0);
            probe_out[3u * i + 1u] = vec4(0.0);
            probe_out[3u * i + 2u] = vec4(0.0);
            return;
        }
        q.ask = CV_BQ_F0 | CV_BQ_PDF0;
        q.wi0 = s.wi;
    }
    if (u_mode == 3u) {
        probe_out[4u * i] = vec4(q.f0, q.pdf0);
        probe_out[4u * i + 1u] = vec4(q.f1, q.pdf1);
        probe_out[4u * i + 2u] = vec4(q.s.wi, q.s.pdf);
        probe_out[4u * i + 3u] = vec4(q.s.f, q.sampled ? float(q.s.flags) : -1.0);
    } else if (u_mode == 0u) {
        probe_out[3u * i] = vec4(s.wi, s.pdf);
        probe_out[3u * i + 1u] = vec4(s.f, float(s.flags));
        probe_out[3u * i + 2u] = vec4(q.f0, q.pdf0);
    } else {
        probe_out[i] = vec4(q.f0, q.pdf0);
    }
}
