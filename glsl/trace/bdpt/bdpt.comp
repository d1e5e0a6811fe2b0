#version 450
// glsl/trace/bdpt/bdpt.comp: the bdpt integrator: pbrt-v4's BDPTIntegrator
// (Veach's bidirectional path tracing), media included. One invocation runs
// one pixel sample of its path slot (trace.h; the host dispatches one round
// of samples at a time, u_pass.iteration counting the rounds, in waves of
// at most u_wave_paths slots that the vertex store holds): the camera
// subpath (the same random numbers as the path integrator's camera path)
// and a light subpath, both kept in the vertex store (glsl/shared/bdpt.h),
// then every connection strategy (s, t) of pbrt-v4's Li: s = 0 (the
// camera subpath hits a lamp), s = 1 (a point sampled on a light), t = 1
// (light tracing: the light subpath connected to the lens and splatted
// into the film around its raster position, cv_bdpt_splat), and the rest
// (a subpath vertex of each side joined), each weighed by pbrt-v4's MIS
// weight: the balance heuristic over all strategies that could have made
// the same path, from the vertices' forward and reverse area densities.
// Visibility is traced here, inline. Contributions of t >= 2 go to the
// slot's film entry with the sample's filter weight, as the path
// integrator's; t = 1 ones to the splat film. No Russian roulette (pbrt-v4's
// BDPT has none): subpaths end at the maximum depth. Participating media
// (CV_MEDIA) as pbrt-v4's BDPT has them (media.glsl): subpaths scatter in
// them, connections carry the transmittance between their ends; a
// medium's emission is found by the camera subpath alone (pbrt-v4's BDPT
// drops it; volpath does not), so it is added unweighted. Light subpaths
// start from area, point, spot, distant and infinite lights. The camera
// is perspective or orthographic, still or moving: both subpaths, every
// connection and every moving shape are seen at the time the camera ray
// drew (path_time.glsl, as the path integrator's). With CV_MATTE_STRIDE
// (a job with alpha or ID AOVs) the camera subpath's first hit writes the
// mattes as the path integrators' matte stage does (matte.glsl); with
// CV_FILM_TRANSPARENT the environment seen directly adds nothing, as
// escaped.comp.
#include "shared/trace.h"
#include "shared/bdpt.h"
#define CV_NO_QUEUES
layout(local_size_x = CV_TRACE_GROUP) in;
#include "../common.glsl"
#include "../sampler.glsl"
#include "../tracing.glsl"
#include "../geometry.glsl"
#include "../materials.glsl"
#include "../lights.glsl"
#include "../surface_inputs.glsl"
#include "../regenerate.glsl"
#include "endpoints.glsl"
#ifdef CV_MATTE_STRIDE
#include "../matte.glsl"
#endif

layout(std430, binding = CV_BIND_BDPT_VERTICES) buffer CvBdptStore { CvBdptVertex bv[]; };
layout(std430, binding = CV_BIND_BDPT_SPLAT) buffer CvBdptSplat { uint splat[]; };

// The wave this dispatch runs (src/trace/integrator.h): path slots
// u_wave_first .. u_wave_first + u_wave_paths - 1, slot u_wave_first + i
// in column i of the vertex store.
uniform uint u_wave_first;
uniform uint u_wave_paths;

// This invocation's path slot, its column of the vertex store, film pixel
// (full film) and sample index.
uint g_slot, g_column, g_fp, g_sample;

// Random number pairs: the camera subpath's as the path integrator's
// (common.glsl: CV_PAIR_* of each bounce); the light subpath's from
// CV_BDPT_LIGHT_PAIRS on, CV_PAIRS_PER_BOUNCE per vertex.
#define CV_BDPT_LIGHT_PAIRS 0x40000000u
#define CV_BDPT_PAIR_EMIT 0u      // light vertex: x picks the light
#define CV_BDPT_PAIR_EMIT_POS 1u  // light vertex: its point
#define CV_BDPT_PAIR_EMIT_DIR 2u  // light vertex: its direction
#define CV_BDPT_PAIR_LENS 2u      // light subpath surface vertex: the lens point (t = 1)

vec2 cv_bdpt_u(uint pair)
{
    return cv_sample_2d(g_fp, g_sample, pair, uvec2(u_pass.seed_lo, u_pass.seed_hi), u_pass.sampler);
}
#include "media.glsl"

uint cv_bdpt_cam_pair(uint vertex, uint which) { return 2u + (vertex - 1u) * CV_PAIRS_PER_BOUNCE + which; }
uint cv_bdpt_light_pair(uint vertex, uint which) { return CV_BDPT_LIGHT_PAIRS + vertex * CV_PAIRS_PER_BOUNCE + which; }

uint cv_bdpt_index(bool light_side, uint k)
{
    return ((light_side ? CV_BDPT_CAMERA_VERTS(cv_max_depth()) : 0u) + k) * u_wave_paths + g_column;
}
CvBdptVertex cv_bdpt_cam(uint k) { return bv[cv_bdpt_index(false, k)]; }
CvBdptVertex cv_bdpt_light(uint k) { return bv[cv_bdpt_index(true, k)]; }

bool cv_bdpt_on_surface(CvBdptVertex v) { return dot(v.ng.xyz, v.ng.xyz) > 0.0; }
bool cv_bdpt_infinite(CvBdptVertex v) { return v.id.x == CV_BDPT_LIGHT && (v.id.y & CV_BDPT_INFINITE) != 0u; }

// The scene's bounding sphere (glsl/shared/bdpt.h), and pbrt-v4's density
// of a light subpath's start on an infinite light: uniform over the disk
// of its radius (planar, per unit area).
vec4 cv_bdpt_sphere()
{
    return vec4(uintBitsToFloat(splat[0]), uintBitsToFloat(splat[1]), uintBitsToFloat(splat[2]),
                uintBitsToFloat(splat[3]));
}
float cv_bdpt_pdf_planar()
{
    float r = cv_bdpt_sphere().w;
    return r > 0.0 ? 1.0 / (CV_PI * r * r) : 0.0;
}
bool cv_bdpt_delta(CvBdptVertex v) { return (v.id.y & CV_BDPT_DELTA) != 0u; }
// pbrt-v4's InfiniteLightDensity: the density per solid angle of light
// sampling's infinite lights towards w (distant lights are not among them).
float cv_bdpt_env_density(vec3 w)
{
#ifdef CV_NO_ENV
    return 0.0;
#else
    return cv_env_pdf(w);
#endif
}
float cv_bdpt_remap0(float f) { return f != 0.0 ? f : 1.0; }

// The cosine at vertex v towards w in the connection's G: 1 in a medium.
float cv_bdpt_cos(CvBdptVertex v, vec3 w) { return cv_bdpt_in_medium(v) ? 1.0 : abs(dot(v.ns.xyz, w)); }
// A planar density (an infinite light's) at vertex v, per unit area there.
float cv_bdpt_planar_at(CvBdptVertex v, vec3 w)
{
    return cv_bdpt_pdf_planar() * (cv_bdpt_on_surface(v) ? abs(dot(v.ng.xyz, w)) : 1.0);
}

// The BSDF of a surface vertex, as resolved when the subpath was made.
CvBsdf cv_bdpt_bsdf(CvBdptVertex v)
{
    CvShadingPoint sp;
    sp.p = v.p.xyz;
    sp.ng = v.ng.xyz;
    sp.ns = v.ns.xyz;
    sp.dpdu = v.dpdu.xyz;
    sp.uv = v.uv.xy;
    sp.front = dot(v.wo.xyz, v.ng.xyz) > 0.0;
    CvBsdf b = cv_bsdf_at(v.id.z, sp, v.wo.w);
    cv_bsdf_set_stream(b, v.uv.zw, v.uv.wz);
    return b;
}

// f for light carrying importance (pbrt-v4's TransportMode::Importance):
// radiance's f without its division by etap^2 across a dielectric.
float cv_bdpt_importance_scale(CvBsdf b, vec3 wo, vec3 wi)
{
#ifdef CV_BSDF_BASIC
    return 1.0;
#else
    if (CV_BSDF_TYPE(b) != CV_MAT_DIELECTRIC)
        return 1.0;
    float zo = cv_to_local(b.frame, wo).z, zi = cv_to_local(b.frame, wi).z;
    if (zo * zi >= 0.0)
        return 1.0;
    float etap = zo > 0.0 ? b.eta : 1.0 / b.eta;
    return etap * etap;
#endif
}

vec3 cv_bdpt_f(CvBdptVertex v, CvBsdf b, vec3 wi, bool importance)
{
    if (cv_bdpt_in_medium(v))
        return vec3(cv_bdpt_phase(v, wi));
    vec3 f = cv_bsdf_f(b, v.wo.xyz, wi);
    return importance ? f * cv_bdpt_importance_scale(b, v.wo.xyz, wi) : f;
}

// pbrt-v4's Vertex::ConvertDensity: a density per solid angle at p towards
// vertex next, per unit area at next.
float cv_bdpt_convert(float pdf, vec3 p, CvBdptVertex next)
{
    if (cv_bdpt_infinite(next))
        return pdf;
    vec3 w = next.p.xyz - p;
    float d2 = dot(w, w);
    if (!(d2 > 0.0))
        return 0.0;
    float inv = 1.0 / d2;
    if (cv_bdpt_on_surface(next))
        pdf *= abs(dot(next.ng.xyz, w * sqrt(inv)));
    return pdf * inv;
}

// Vertex::PDF of a surface vertex v (BSDF b) or a medium vertex (its
// phase function): the area density at next of a bounce at v from the
// direction of p_prev.
float cv_bdpt_pdf_surface(CvBdptVertex v, CvBsdf b, vec3 p_prev, CvBdptVertex next)
{
    vec3 wp = p_prev - v.p.xyz, wn = next.p.xyz - v.p.xyz;
    if (!(dot(wp, wp) > 0.0) || !(dot(wn, wn) > 0.0))
        return 0.0;
    wp = normalize(wp);
    wn = normalize(wn);
    float pdf = cv_bdpt_in_medium(v) ? cv_bdpt_hg(v, wp, wn) : cv_bsdf_pdf(b, wp, wn);
    return cv_bdpt_convert(pdf, v.p.xyz, next);
}

// Vertex::PDF of the camera at p_cam towards next.
float cv_bdpt_pdf_camera(vec3 p_cam, CvBdptVertex next)
{
    vec3 w = next.p.xyz - p_cam;
    if (!(dot(w, w) > 0.0))
        return 0.0;
    return cv_bdpt_convert(cv_bdpt_camera_pdf_dir(normalize(w)), p_cam, next);
}

// Vertex::PDFLight: the area density at next of light li's emission from
// its point p with normal n.
float cv_bdpt_pdf_light(uint li, vec3 p, vec3 n, CvBdptVertex next)
{
    vec3 w = next.p.xyz - p;
    float d2 = dot(w, w);
    if (!(d2 > 0.0))
        return 0.0;
    w *= inversesqrt(d2);
    float pdf = cv_bdpt_light_pdf_dir(li, n, w) / d2;
    if (cv_bdpt_on_surface(next))
        pdf *= abs(dot(next.ng.xyz, w));
    return pdf;
}

// Vertex::PDFLightOrigin: light li chosen and its point placed.
float cv_bdpt_pdf_light_origin(uint li) { return cv_light_pmf(li) * cv_bdpt_light_pdf_pos(li); }

// A ray from a towards b, off their surfaces (rounding errors a_err, b_err
// along geometric normals a_ng, b_ng; 0 where not on a surface): whether
// nothing blocks it. Alpha cut-outs let it through as in shadow.comp.
bool cv_bdpt_visible(vec3 a, float a_err, vec3 a_ng, vec3 b, float b_err, vec3 b_ng)
{
#ifdef CV_EMPTY_SCENE
    return true;
#else
    vec3 o = a, e = b;
    if (dot(a_ng, a_ng) > 0.0)
        o = cv_offset_ray(a, a_err, dot(b - a, a_ng) > 0.0 ? a_ng : -a_ng);
    if (dot(b_ng, b_ng) > 0.0)
        e = cv_offset_ray(b, b_err, dot(a - b, b_ng) > 0.0 ? b_ng : -b_ng);
    vec3 d = e - o;
    float len = length(d);
    if (!(len > 0.0))
        return true;
    d /= len;
    float tmax = len * (1.0 - 1e-4);
#ifdef CV_HAS_ALPHA
    float tmin = 0.0;
    CvHit h;
    for (uint k = 0u; k < 64u; k++) {
        if (!cv_trace_closest(o, d, tmin, tmax, h))
            return true;
        CvSurface sf = cv_surface_ray(h.prim, h.b1, h.b2, o, d, h.t);
        float u = cv_uint_to_unit(cv_hash4(g_fp, g_sample, h.prim, 0x2545f491u + k));
        if (!cv_material_alpha_pass(cv_prim_word(h.prim) & CV_TRI_MATERIAL_MASK, sf.uv, u))
            return false;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
    return false;
#else
    return !cv_trace_any(o, d, 0.0, tmax);
#endif
#endif
}

// The closest surface along o + t d that the alpha test does not let
// through; key tells the subpath and vertex apart for the alpha numbers.
bool cv_bdpt_trace(vec3 o, vec3 d, uint key, out CvHit h)
{
    h = CvHit(0.0, 0u, 0.0, 0.0);
#ifdef CV_EMPTY_SCENE
    return false;
#else
    bool hit = cv_trace_closest(o, d, 0.0, 1e30, h);
#ifdef CV_HAS_ALPHA
    float tmin = 0.0;
    for (uint k = 0u; hit && k < 64u; k++) {
        CvSurface s = cv_surface_ray(h.prim, h.b1, h.b2, o, d, h.t);
        float u = cv_uint_to_unit(cv_hash4(g_fp, g_sample, h.prim, key * 64u + k));
        if (!cv_material_alpha_pass(cv_prim_word(h.prim) & CV_TRI_MATERIAL_MASK, s.uv, u))
            break;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
        hit = cv_trace_closest(o, d, tmin, 1e30, h);
    }
#endif
    return hit;
#endif
}

bool cv_bdpt_runs(uint s, uint t);

// The emission of media that the camera subpath met (media.glsl): found
// by no other strategy, so added with weight 1.
vec3 g_medium_Le = vec3(0.0);

// pbrt-v4's RandomWalk: extends the subpath whose vertex 0 is stored, from
// ray o + t d in medium `medium` with throughput beta and pdf_fwd (solid
// angle) the density of d, up to max_verts vertices in all; returns how
// many there are.
uint cv_bdpt_walk(bool light_side, vec3 o, vec3 d, uint medium, vec3 beta, float pdf_fwd,
                  uint max_verts)
{
    uint n = 1u;
    bool albedo_done = false;
    uint hero = cv_medium_hero_channel(g_fp, g_sample, light_side ? 1u : 0u);
    vec3 ratios = vec3(1.0);
    while (n < max_verts) {
        CvHit h;
        uint key = (light_side ? 0x8000u : 0u) + n;
        uint found = cv_bdpt_track(o, d, key, hero, medium, beta, ratios, h);
        if (found == 2u) {
#ifdef CV_MEDIA
            // a scattering event: a medium vertex, the bounce from its
            // phase function (f / pdf = 1)
            vec3 p = o + h.t * d;
            vec3 sigma_a, sigma_s, Le;
            cv_medium_point(medium, p, sigma_a, sigma_s, Le);
            if (!light_side && cv_media(medium).emissive != 0u && n <= cv_max_depth() &&
                cv_bdpt_runs(0u, n + 1u))
                g_medium_Le += beta * sigma_a * Le;
            beta *= sigma_s;
            if (!cv_finite3(beta)) {
                cv_film_reject();
                break;
            }
            if (!(cv_max3(beta) > 0.0))
                break;
            uint prev_i = cv_bdpt_index(light_side, n - 1u);
            CvBdptVertex v = CvBdptVertex(vec4(p, 0.0), vec4(0.0), vec4(0.0), vec4(-d, 0.0),
                                          vec4(beta, 0.0), vec4(0.0), vec4(0.0),
                                          uvec4(CV_BDPT_MEDIUM, medium << CV_BDPT_MEDIUM_SHIFT,
                                                medium, 0u));
            v.ng.w = cv_bdpt_convert(pdf_fwd, bv[prev_i].p.xyz, v);
            bv[cv_bdpt_index(light_side, n)] = v;
            n++;
            if (n >= max_verts)
                break;
            uint pair = light_side ? cv_bdpt_light_pair(n - 1u, CV_PAIR_BSDF_U2)
                                   : cv_bdpt_cam_pair(n - 1u, CV_PAIR_BSDF_U2);
            float pdf;
            vec3 wi = cv_hg_sample(-d, cv_media(medium).sigma_a.w, cv_bdpt_u(pair), pdf);
            if (!(pdf > 0.0))
                break;
            bv[prev_i].ns.w = cv_bdpt_convert(pdf, p, bv[prev_i]);
            o = p;
            d = wi;
            pdf_fwd = pdf;
#endif
            continue;
        }
        if (found == 0u) {
            if (!(cv_max3(beta) > 0.0))
                break;  // the tracking ended the subpath
#ifndef CV_NO_ENV
            // a camera subpath that escapes ends on the infinite lights
            if (!light_side) {
                bv[cv_bdpt_index(false, n)] = CvBdptVertex(
                    vec4(o + d, 0.0), vec4(0.0, 0.0, 0.0, pdf_fwd), vec4(0.0), vec4(-d, 0.0),
                    vec4(beta, 0.0), vec4(0.0), vec4(0.0),
                    uvec4(CV_BDPT_LIGHT, CV_BDPT_INFINITE, 0u, 0u));
                n++;
            }
#endif
            break;
        }
        CvSurface sf = cv_surface_ray(h.prim, h.b1, h.b2, o, d, h.t);
        uint prev_i = cv_bdpt_index(light_side, n - 1u);
        CvBdptVertex prev = bv[prev_i];
        uint pair_bsdf = light_side ? cv_bdpt_light_pair(n, CV_PAIR_BSDF_U2) : cv_bdpt_cam_pair(n, CV_PAIR_BSDF_U2);
        uint pair_bc = light_side ? cv_bdpt_light_pair(n, CV_PAIR_BSDF_UC) : cv_bdpt_cam_pair(n, CV_PAIR_BSDF_UC);
        vec2 u_bsdf = cv_bdpt_u(pair_bsdf), u_bc = cv_bdpt_u(pair_bc);
        int light = -1;
        if ((h.prim & CV_PRIM_CURVE) == 0u)  // curves emit nothing
            light = cv_tri_light[h.prim];
        CvBdptVertex v;
        v.p = vec4(sf.p, sf.p_err);
        v.ng = vec4(sf.ng, 0.0);
        v.ns = vec4(sf.ns, 0.0);
        v.wo = vec4(-d, u_bc.y);
        v.beta = vec4(beta, 0.0);
        v.dpdu = vec4(sf.dpdu, 0.0);
        v.uv = vec4(sf.uv, u_bsdf);
        v.id = uvec4(CV_BDPT_SURFACE, medium << CV_BDPT_MEDIUM_SHIFT, sf.material,
                     light >= 0 ? uint(light) + 1u : 0u);
        v.ng.w = cv_bdpt_convert(pdf_fwd, prev.p.xyz, v);
#if defined(CV_MATTE_STRIDE) && !defined(CV_MEDIA)
        if (!light_side && n == 1u)  // with media: cv_bdpt_track
            cv_matte_first_hit(g_slot, h.prim);
#endif
        uint vi = cv_bdpt_index(light_side, n);
        bv[vi] = v;
        n++;
        CvBsdf b = cv_bdpt_bsdf(v);
#ifdef CV_AOVS
        if (!light_side) {
            float aov_w = cv_path_weight(g_slot);
            if (n == 2u) {
                film[g_slot].normal.xyz += aov_w * sf.ns;
                film[g_slot].albedo.w += aov_w * h.t;
            }
            if (!albedo_done && !cv_bsdf_is_delta(b)) {
                film[g_slot].albedo.rgb += aov_w * cv_bsdf_albedo(b);
                albedo_done = true;
            }
        }
#endif
        if (n >= max_verts)
            break;
        CvBsdfSample bs;
        if (!cv_bsdf_sample(b, -d, u_bc.x, u_bsdf, bs))
            break;
        bool specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
        // a stochastic BSDF's sample density is proportional only (pbrt-v4's
        // pdfIsProportional): its PDF goes into the MIS densities
        float pf = bs.pdf;
#ifndef CV_BSDF_BASIC
        bool walked = (b.type == CV_MAT_COATED_DIFFUSE || b.type == CV_MAT_COATED_CONDUCTOR) &&
                      !cv_bsdf_coat_closed(b);
        if (walked && !specular)
            pf = cv_bsdf_pdf(b, -d, bs.wi);
#endif
        vec3 f = bs.f;
        if (light_side)
            f *= cv_bdpt_importance_scale(b, -d, bs.wi);
        beta *= f * (abs(dot(bs.wi, sf.ns)) / bs.pdf);
        float pr = cv_bsdf_pdf(b, bs.wi, -d);
        if (specular) {
            bv[vi].id.y |= CV_BDPT_DELTA;
            pr = 0.0;
            pf = 0.0;
        }
        bv[prev_i].ns.w = cv_bdpt_convert(pr, sf.p, prev);
        if (!cv_finite3(beta)) {
            cv_film_reject();
            break;
        }
        if (!(cv_max3(beta) > 0.0))
            break;
        o = cv_spawn_origin(sf, bs.wi);
        d = bs.wi;
        pdf_fwd = pf;
        medium = cv_bdpt_medium_towards(v, d);
    }
    return n;
}

// pbrt-v4's MISWeight for strategy (s, t), given the densities the
// strategy changes: the reverse densities of the connection vertices pt,
// qs and of their predecessors (pt_rev, ptm_rev, qs_rev, qsm_rev); for
// s = 1 the sampled light vertex's forward density and whether it is a
// delta light. Ratios along each subpath count every other strategy that
// makes the same path, but none that would have to connect through a
// specular vertex or hit a delta light.
float cv_bdpt_mis(uint s, uint t, float pt_rev, float ptm_rev, float qs_rev, float qsm_rev,
                  float sampled_fwd, bool sampled_delta_light, float splat_scale)
{
#ifdef CV_BDPT_ONLY_T
    return 1.0;  // one strategy's image alone
#endif
    if (s + t == 2u)
        return 1.0;
    float sum = 0.0, ri = 1.0;
    for (int i = int(t) - 1; i > 0; i--) {
        CvBdptVertex c = cv_bdpt_cam(uint(i));
        float rev = i == int(t) - 1 ? pt_rev : i == int(t) - 2 ? ptm_rev : c.ns.w;
        ri *= cv_bdpt_remap0(rev) / cv_bdpt_remap0(c.ng.w);
        if (i == 1)
            ri /= splat_scale;
        bool di = i == int(t) - 1 ? false : cv_bdpt_delta(c);
        if (!di && !cv_bdpt_delta(cv_bdpt_cam(uint(i - 1))))
            sum += ri;
    }
    ri = 1.0;
    for (int i = int(s) - 1; i >= 0; i--) {
        CvBdptVertex l = cv_bdpt_light(uint(i));
        float rev = i == int(s) - 1 ? qs_rev : i == int(s) - 2 ? qsm_rev : l.ns.w;
        float fwd = s == 1u ? sampled_fwd : l.ng.w;
        ri *= cv_bdpt_remap0(rev) / cv_bdpt_remap0(fwd);
        bool di = i == int(s) - 1 ? false : cv_bdpt_delta(l);
        bool dl = i > 0 ? cv_bdpt_delta(cv_bdpt_light(uint(i - 1)))
                        : (s == 1u ? sampled_delta_light
                                   : (cv_bdpt_light(0u).id.y & CV_BDPT_DELTA_LIGHT) != 0u);
        if (!di && !dl)
            sum += ri;
    }
    if (t == 1u)
        sum /= splat_scale;
    return 1.0 / (1.0 + sum);
}

// ---- the t = 1 splat film -------------------------------------------------

void cv_bdpt_atomic_add(uint i, float v)
{
    i += CV_BDPT_SPLAT_HEADER;
    uint old = splat[i];
    for (uint k = 0u; k < 4096u; k++) {
        uint prev = atomicCompSwap(splat[i], old, floatBitsToUint(uintBitsToFloat(old) + v));
        if (prev == old)
            return;
        old = prev;
    }
}

// The signed density of the camera's filter offsets along one axis at
// offset x (filter.glsl's sampling: piecewise constant over the table's
// cells), so that a splat weighs as the camera's samples do: over the
// radiance sum's filter weights, f / the integral of |f|.
float cv_bdpt_filter_density(float x, uint axis)
{
    float r = u_pass.pixel_filter[axis];
    if (!(abs(x) < r))
        return 0.0;
    uint type = u_pass.filter_type;
    if (type == CV_FILTER_ID_BOX)
        return 0.5 / r;
    if (type == CV_FILTER_ID_TRIANGLE)
        return (r - abs(x)) / (r * r);
    uint cells = uint(u_pass.pixel_filter[2u + axis]);
    uint k = min(uint((x + r) / (2.0 * r) * float(cells)), cells - 1u);
    float dens = (cv_filter_cdf(axis, k + 1u) - cv_filter_cdf(axis, k)) * float(cells) / (2.0 * r);
    if ((u_pass.filter_neg[axis][k >> 7][(k >> 5) & 3u] & (1u << (k & 31u))) != 0u)
        dens = -dens;
    return dens;
}

// Adds light tracing's L at raster position `raster` (full film) to the
// crop pixels whose filter reaches it.
void cv_bdpt_splat(vec2 raster, vec3 L)
{
    vec2 r = u_pass.pixel_filter.xy;
    ivec2 org = ivec2(u_pass.film.zw);
    ivec2 lo = max(ivec2(ceil(raster - 0.5 - r)), org);
    ivec2 hi = min(ivec2(floor(raster - 0.5 + r)), org + ivec2(u_pass.crop_w, u_pass.crop_h) - 1);
    for (int y = lo.y; y <= hi.y; y++) {
        float fy = cv_bdpt_filter_density(raster.y - (float(y) + 0.5), 1u);
        if (fy == 0.0)
            continue;
        for (int x = lo.x; x <= hi.x; x++) {
            float w = fy * cv_bdpt_filter_density(raster.x - (float(x) + 0.5), 0u);
            if (w == 0.0)
                continue;
            uint i = uint(y - org.y) * u_pass.crop_w + uint(x - org.x);
            cv_bdpt_atomic_add(3u * i + 0u, w * L.r);
            cv_bdpt_atomic_add(3u * i + 1u, w * L.g);
            cv_bdpt_atomic_add(3u * i + 2u, w * L.b);
        }
    }
}

// ---- the strategies -------------------------------------------------------

// s = 0: camera vertex t - 1 lies on a lamp.
vec3 cv_bdpt_connect_s0(uint t, float splat_scale)
{
    CvBdptVertex pt = cv_bdpt_cam(t - 1u), pm = cv_bdpt_cam(t - 2u);
    if (cv_bdpt_infinite(pt)) {
#ifdef CV_FILM_TRANSPARENT
        if (t == 2u)
            return vec3(0.0);  // the environment seen directly: alpha 0
#endif
#ifndef CV_NO_ENV
        vec3 d = -pt.wo.xyz;  // the escaped ray's direction
        vec3 L = cv_env_Le(d) * pt.beta.rgb;
        if (!(cv_max3(L) > 0.0))
            return vec3(0.0);
        float ptm_rev = cv_bdpt_planar_at(pm, d);
        return L * cv_bdpt_mis(0u, t, cv_env_pdf(d), ptm_rev, 0.0, 0.0, 0.0, false, splat_scale);
#endif
        return vec3(0.0);
    }
    if (pt.id.x != CV_BDPT_SURFACE || pt.id.w == 0u)
        return vec3(0.0);
    uint li = pt.id.w - 1u;
    vec3 w = pm.p.xyz - pt.p.xyz;
    if (!(dot(w, w) > 0.0))
        return vec3(0.0);
    w = normalize(w);
    vec3 L = cv_light_Le_area(li, w, pt.uv.xy, dot(w, pt.ng.xyz) > 0.0, pt.p.xyz) * pt.beta.rgb;
    if (!(cv_max3(L) > 0.0))
        return vec3(0.0);
    float pt_rev = cv_bdpt_pdf_light_origin(li);
    float ptm_rev = cv_bdpt_pdf_light(li, pt.p.xyz, pt.ng.xyz, pm);
    return L * cv_bdpt_mis(0u, t, pt_rev, ptm_rev, 0.0, 0.0, 0.0, false, splat_scale);
}

// s = 1: a point sampled on a light, joined to camera vertex t - 1 (BSDF bt).
vec3 cv_bdpt_connect_s1(uint t, CvBdptVertex pt, CvBsdf bt, float splat_scale)
{
    vec2 u_light = cv_bdpt_u(cv_bdpt_cam_pair(t - 1u, CV_PAIR_LIGHT_U2));
    vec2 u_lc = cv_bdpt_u(cv_bdpt_cam_pair(t - 1u, CV_PAIR_LIGHT_UC));
    uint li = cv_light_pick(u_lc.x);
    float pmf = cv_light_pmf(li);
    uint type = lights[li].type;
    if (!(pmf > 0.0))
        return vec3(0.0);
    CvBdptVertex pm = cv_bdpt_cam(t - 2u);
    bool distant = type == CV_LIGHT_DISTANT;
    if (distant || type == CV_LIGHT_INFINITE || type == CV_LIGHT_INFINITE_MAP) {
        // a direction from the chosen light alone, as pbrt-v4's SampleLi:
        // a distant light's one direction (a delta density), or one of an
        // infinite light's; the MIS densities count the infinite lights
        // all (cv_bdpt_env_density)
        CvLight l = lights[li];
        vec3 wi, Li;
        float pdf = pmf;
        if (distant) {
            wi = -normalize(l.direction.xyz);
            Li = l.L.rgb;
        } else {
#ifndef CV_NO_ENV
            float pdf_l = CV_INV_4PI;
            wi = type == CV_LIGHT_INFINITE ? cv_sample_uniform_sphere(u_light)
                                           : cv_env_map_sample(l, u_light, pdf_l);
            Li = cv_env_light_Le(l, wi);
            pdf *= pdf_l;
#else
            return vec3(0.0);
#endif
        }
        if (!(cv_max3(Li) > 0.0) || !(pdf > 0.0))
            return vec3(0.0);
        vec3 L = pt.beta.rgb * cv_bdpt_f(pt, bt, wi, false) * (Li / pdf) * cv_bdpt_cos(pt, wi);
        vec3 pl = pt.p.xyz + wi * (2.0 * max(cv_bdpt_sphere().w, 1.0));
        if (!(cv_max3(L) > 0.0))
            return vec3(0.0);
        L *= cv_bdpt_transmittance(pt.p.xyz, pt.p.w, pt.ng.xyz, pl, 0.0, vec3(0.0),
                                   cv_bdpt_medium_towards(pt, wi), 0x10000u + t);
        if (!(cv_max3(L) > 0.0))
            return vec3(0.0);
        CvBdptVertex qs = CvBdptVertex(vec4(pl, 0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0),
                                       vec4(0.0), vec4(0.0),
                                       uvec4(CV_BDPT_LIGHT, CV_BDPT_INFINITE, 0u, li));
        float pt_rev = cv_bdpt_planar_at(pt, wi);
        float ptm_rev = cv_bdpt_pdf_surface(pt, bt, pl, pm);
        float qs_rev = cv_bdpt_pdf_surface(pt, bt, pm.p.xyz, qs);
        return L * cv_bdpt_mis(1u, t, pt_rev, ptm_rev, qs_rev, 0.0, cv_bdpt_env_density(wi),
                               distant, splat_scale);
    }
    if (type != CV_LIGHT_AREA && type != CV_LIGHT_POINT && type != CV_LIGHT_SPOT)
        return vec3(0.0);
    vec3 pl, nl;
    vec2 uvl;
    float errl;
    cv_bdpt_light_point(li, u_light, pl, nl, uvl, errl);
    vec3 d = pl - pt.p.xyz;
    float d2 = dot(d, d);
    if (!(d2 > 0.0))
        return vec3(0.0);
    vec3 wi = d * inversesqrt(d2);
    // radiance arriving over its density per solid angle
    vec3 Li;
    float pdf;
    if (type == CV_LIGHT_AREA) {
        float c = abs(dot(nl, wi));
        if (!(c > 0.0))
            return vec3(0.0);
        Li = cv_light_Le_area(li, -wi, uvl, dot(-wi, nl) > 0.0, pl);
        pdf = pmf * cv_bdpt_light_pdf_pos(li) * d2 / c;
    } else {
        Li = cv_bdpt_light_I(li, -wi) / d2;
        pdf = pmf;
    }
    if (!(cv_max3(Li) > 0.0) || !(pdf > 0.0))
        return vec3(0.0);
    vec3 L = pt.beta.rgb * cv_bdpt_f(pt, bt, wi, false) * (Li / pdf) * cv_bdpt_cos(pt, wi);
    if (!(cv_max3(L) > 0.0))
        return vec3(0.0);
    L *= cv_bdpt_transmittance(pt.p.xyz, pt.p.w, pt.ng.xyz, pl, errl, nl,
                               cv_bdpt_medium_towards(pt, wi), 0x10000u + t);
    if (!(cv_max3(L) > 0.0))
        return vec3(0.0);
    // the sampled light vertex, for the densities
    CvBdptVertex qs = CvBdptVertex(vec4(pl, errl), vec4(nl, 0.0), vec4(nl, 0.0), vec4(0.0),
                                   vec4(0.0), vec4(0.0), vec4(uvl, 0.0, 0.0), uvec4(CV_BDPT_LIGHT, 0u, 0u, li));
    float pt_rev = cv_bdpt_pdf_light(li, pl, nl, pt);
    float ptm_rev = cv_bdpt_pdf_surface(pt, bt, pl, pm);
    float qs_rev = cv_bdpt_pdf_surface(pt, bt, pm.p.xyz, qs);
    return L * cv_bdpt_mis(1u, t, pt_rev, ptm_rev, qs_rev, 0.0, cv_bdpt_pdf_light_origin(li),
                           cv_bdpt_light_is_delta(li), splat_scale);
}

// t = 1: light vertex s - 1 (BSDF bq) seen through the lens: splatted.
void cv_bdpt_connect_t1(uint s, CvBdptVertex qs, CvBsdf bq, float splat_scale)
{
    vec2 u_lens = cv_bdpt_u(cv_bdpt_light_pair(s - 1u, CV_BDPT_PAIR_LENS));
    vec3 p_lens;
    vec2 raster;
    float we_pdf, cos_lens;
    if (!cv_bdpt_camera_sample(qs.p.xyz, u_lens, p_lens, raster, we_pdf, cos_lens))
        return;
    vec3 wi = normalize(p_lens - qs.p.xyz);
    vec3 L = qs.beta.rgb * cv_bdpt_f(qs, bq, wi, true) * (we_pdf * cv_bdpt_cos(qs, wi));
    if (!(cv_max3(L) > 0.0))
        return;
    L *= cv_bdpt_transmittance(qs.p.xyz, qs.p.w, qs.ng.xyz, p_lens, 0.0, vec3(0.0),
                               cv_bdpt_medium_towards(qs, wi), 0x20000u + s);
    if (!(cv_max3(L) > 0.0))
        return;
    L *= splat_scale;
    // the sampled camera vertex, for the densities
    CvBdptVertex pt = CvBdptVertex(vec4(p_lens, 0.0), vec4(0.0), vec4(0.0), vec4(0.0),
                                   vec4(0.0), vec4(0.0), vec4(0.0), uvec4(CV_BDPT_CAMERA, 0u, 0u, 0u));
    CvBdptVertex qm = cv_bdpt_light(s - 2u);
    float pt_rev = cv_bdpt_pdf_surface(qs, bq, qm.p.xyz, pt);
    float qs_rev = cv_bdpt_pdf_camera(p_lens, qs);
    float qsm_rev = cv_bdpt_pdf_surface(qs, bq, p_lens, qm);
    L *= cv_bdpt_mis(s, 1u, pt_rev, 0.0, qs_rev, qsm_rev, 0.0, false, splat_scale);
    if (!cv_finite3(L)) {
        cv_film_reject();
        return;
    }
    if (cv_max3(abs(L)) > 0.0)
        cv_bdpt_splat(raster, L);
}

// s, t >= 2: light vertex s - 1 (BSDF bq) joined to camera vertex t - 1 (bt).
vec3 cv_bdpt_connect(uint s, uint t, CvBdptVertex qs, CvBsdf bq, CvBdptVertex pt, CvBsdf bt,
                     float splat_scale)
{
    vec3 d = pt.p.xyz - qs.p.xyz;
    float d2 = dot(d, d);
    if (!(d2 > 0.0))
        return vec3(0.0);
    vec3 w = d * inversesqrt(d2);  // from qs to pt
    vec3 L = qs.beta.rgb * cv_bdpt_f(qs, bq, w, true) * cv_bdpt_f(pt, bt, -w, false) * pt.beta.rgb;
    L *= cv_bdpt_cos(qs, w) * cv_bdpt_cos(pt, w) / d2;
    if (!(cv_max3(L) > 0.0))
        return vec3(0.0);
    L *= cv_bdpt_transmittance(pt.p.xyz, pt.p.w, pt.ng.xyz, qs.p.xyz, qs.p.w, qs.ng.xyz,
                               cv_bdpt_medium_towards(pt, -w), 0x30000u + s * 64u + t);
    if (!(cv_max3(L) > 0.0))
        return vec3(0.0);
    CvBdptVertex qm = cv_bdpt_light(s - 2u), pm = cv_bdpt_cam(t - 2u);
    float pt_rev = cv_bdpt_pdf_surface(qs, bq, qm.p.xyz, pt);
    float ptm_rev = cv_bdpt_pdf_surface(pt, bt, qs.p.xyz, pm);
    float qs_rev = cv_bdpt_pdf_surface(pt, bt, pm.p.xyz, qs);
    float qsm_rev = cv_bdpt_pdf_surface(qs, bq, pt.p.xyz, qm);
    return L * cv_bdpt_mis(s, t, pt_rev, ptm_rev, qs_rev, qsm_rev, 0.0, false, splat_scale);
}

// Whether strategy (s, t) runs: all of them, unless the host asks for one
// alone (CV_BDPT_ONLY_S, CV_BDPT_ONLY_T: a test of its image, unweighted).
bool cv_bdpt_runs(uint s, uint t)
{
#ifdef CV_BDPT_ONLY_T
    return s == CV_BDPT_ONLY_S && t == CV_BDPT_ONLY_T;
#else
    return true;
#endif
}

// pbrt-v4's GenerateLightSubpath: the light vertex and the walk from it;
// returns the light subpath's vertex count (0: none).
uint cv_bdpt_light_subpath()
{
    if (cv_n_lights() == 0u)
        return 0u;
    uint li = cv_light_pick(cv_bdpt_u(cv_bdpt_light_pair(0u, CV_BDPT_PAIR_EMIT)).x);
    float pmf = cv_light_pmf(li);
    if (!(pmf > 0.0))
        return 0u;
    uint type = lights[li].type;
    // the medium the light sits in (an area light's surface may part two)
    uint light_medium = 0u;
#ifdef CV_MEDIA
    light_medium = (lights[li].flags >> CV_LIGHTF_MEDIUM_SHIFT) & 255u;
#endif
    bool distant = type == CV_LIGHT_DISTANT;
    if (distant || type == CV_LIGHT_INFINITE || type == CV_LIGHT_INFINITE_MAP) {
        // pbrt-v4's SampleLe of an infinite or distant light: a direction
        // from it (a distant light's one direction: a delta density, so
        // that no strategy but s >= 1 finds it, pbrt-v4's IsDeltaLight),
        // and a point on the disk of the scene's radius across it
        CvLight l = lights[li];
        float pdf_dir = 1.0;
        vec3 wl, Le;
        if (distant) {
            wl = -normalize(l.direction.xyz);
            Le = l.L.rgb;
        } else {
#ifndef CV_NO_ENV
            pdf_dir = CV_INV_4PI;
            vec2 u_dir = cv_bdpt_u(cv_bdpt_light_pair(0u, CV_BDPT_PAIR_EMIT_DIR));
            wl = type == CV_LIGHT_INFINITE ? cv_sample_uniform_sphere(u_dir)
                                           : cv_env_map_sample(l, u_dir, pdf_dir);
            Le = cv_env_light_Le(l, wl);
#else
            return 0u;
#endif
        }
        vec4 sph = cv_bdpt_sphere();
        float pdf_pos = cv_bdpt_pdf_planar();
        if (!(pdf_dir > 0.0) || !(pdf_pos > 0.0) || !(cv_max3(Le) > 0.0))
            return 0u;
        vec2 cd = cv_sample_disk_concentric(cv_bdpt_u(cv_bdpt_light_pair(0u, CV_BDPT_PAIR_EMIT_POS)));
        vec3 o = sph.xyz + sph.w * cv_from_local(cv_frame_from_z(-wl), vec3(cd, 0.0)) + sph.w * wl;
        uint flags = CV_BDPT_INFINITE | (distant ? CV_BDPT_DELTA_LIGHT : 0u);
        bv[cv_bdpt_index(true, 0u)] = CvBdptVertex(
            vec4(o, 0.0), vec4(0.0, 0.0, 0.0, pmf * pdf_pos), vec4(0.0), vec4(0.0), vec4(Le, 0.0),
            vec4(0.0), vec4(0.0),
            uvec4(CV_BDPT_LIGHT, flags | (light_medium << CV_BDPT_MEDIUM_SHIFT), 0u, li));
        uint n_inf = cv_bdpt_walk(true, o, -wl, light_medium, Le / (pmf * pdf_pos * pdf_dir),
                                  pdf_dir, CV_BDPT_LIGHT_VERTS(cv_max_depth()));
        // the densities pbrt-v4 corrects for an infinite light's start:
        // vertex 1 per unit area of the disk, vertex 0 per solid angle
        if (n_inf > 1u) {
            uint i1 = cv_bdpt_index(true, 1u);
            bv[i1].ng.w = pdf_pos * (cv_bdpt_on_surface(bv[i1]) ? abs(dot(wl, bv[i1].ng.xyz)) : 1.0);
        }
        bv[cv_bdpt_index(true, 0u)].ng.w = cv_bdpt_env_density(wl);
        return n_inf;
    }
    vec3 p, n;
    vec2 uv;
    float err;
    cv_bdpt_light_point(li, cv_bdpt_u(cv_bdpt_light_pair(0u, CV_BDPT_PAIR_EMIT_POS)), p, n, uv, err);
    vec3 w;
    float pdf_dir;
    if (!cv_bdpt_light_dir(li, n, cv_bdpt_u(cv_bdpt_light_pair(0u, CV_BDPT_PAIR_EMIT_DIR)), w, pdf_dir))
        return 0u;
    vec3 Le = cv_bdpt_light_emit(li, p, n, uv, w);
    float pdf_pos = cv_bdpt_light_pdf_pos(li);
    if (!(cv_max3(Le) > 0.0) || !(pdf_pos > 0.0))
        return 0u;
    CvBdptVertex v;
    v.p = vec4(p, err);
    v.ng = vec4(n, pmf * pdf_pos);
    v.ns = vec4(n, 0.0);
    v.wo = vec4(0.0);
    v.beta = vec4(Le, 0.0);
    v.dpdu = vec4(0.0);
    v.uv = vec4(uv, 0.0, 0.0);
    v.id = uvec4(CV_BDPT_LIGHT,
                 (cv_bdpt_light_is_delta(li) ? CV_BDPT_DELTA_LIGHT : 0u) | (light_medium << CV_BDPT_MEDIUM_SHIFT),
                 0u, li);
    bv[cv_bdpt_index(true, 0u)] = v;
    bool area = dot(n, n) > 0.0;
    float c = area ? abs(dot(n, w)) : 1.0;
    vec3 beta = Le * (c / (pmf * pdf_pos * pdf_dir));
    vec3 o = area ? cv_offset_ray(p, err, dot(w, n) > 0.0 ? n : -n) : p;
#ifdef CV_MEDIA
    if (area)
        light_medium = cv_medium_across(cv_prim_word(lights[li].prim) & CV_TRI_MATERIAL_MASK, n, w,
                                        light_medium);
#endif
    return cv_bdpt_walk(true, o, w, light_medium, beta, pdf_dir, CV_BDPT_LIGHT_VERTS(cv_max_depth()));
}

void main()
{
    uint column = cv_global_index();
    uint slot = u_wave_first + column;
    if (column >= u_wave_paths || slot >= cv_capacity())
        return;
    // the slot's sample of this round (trace.h: slot s takes the samples
    // j with j % K == s / P, in order)
    uint P = u_pass.n_pixels, K = u_pass.paths_per_pixel;
    uint a = u_pass.first_sample + u_pass.iteration * K;
    uint j = a + (slot / P + K - a % K) % K;
    if (j >= u_pass.end_sample)
        return;
    g_slot = slot;
    g_column = column;
    g_sample = j;
    g_fp = cv_film_pixel(cv_path_pixel(slot));
    CvRayItem r = cv_camera_sample(slot, j);  // the filter weight, the path in flight
    // the path's time, as its camera ray drew it: the camera's pose for
    // the connections to the lens, the moving shapes' for every ray
    float u_time = cv_time_sampled() ? cv_time_u(g_fp, j) : 0.0;
    cv_bdpt_camera_at(u_time);
#ifdef CV_HAS_MOTION
    cv_trace_time = cv_path_time(slot);
#endif

    CvBdptVertex c0;
    c0.p = vec4(r.o.xyz, 0.0);
    c0.ng = vec4(0.0);
    c0.ns = vec4(0.0);
    c0.wo = vec4(0.0);
    c0.beta = vec4(1.0, 1.0, 1.0, 0.0);
    c0.dpdu = vec4(0.0);
    c0.uv = vec4(0.0);
    uint cam_medium = 0u;
#ifdef CV_MEDIA
    cam_medium = u_pass.camera_medium;
#endif
    c0.id = uvec4(CV_BDPT_CAMERA,
                  (cv_bdpt_camera_delta() ? CV_BDPT_DELTA : 0u) | (cam_medium << CV_BDPT_MEDIUM_SHIFT),
                  0u, 0u);
    bv[cv_bdpt_index(false, 0u)] = c0;
    uint n_cam = cv_bdpt_walk(false, r.o.xyz, r.d.xyz, cam_medium, vec3(1.0),
                              cv_bdpt_camera_pdf_dir(r.d.xyz), CV_BDPT_CAMERA_VERTS(cv_max_depth()));
    uint n_light = cv_bdpt_light_subpath();

    // pbrt-v4's splat scale: light subpaths start from the crop's pixel
    // samples alone but land anywhere on the film
    float splat_scale = float(u_pass.film.x) * float(u_pass.film.y) / float(P);
    uint max_depth = cv_max_depth();
    vec3 L = vec3(0.0);
    // t = 1: light tracing
    for (uint s = 2u; s <= n_light && s - 1u <= max_depth && cv_bdpt_camera_connectible(); s++) {
        CvBdptVertex qs = cv_bdpt_light(s - 1u);
        CvBsdf bq;
        if (!cv_bdpt_in_medium(qs)) {
            bq = cv_bdpt_bsdf(qs);
            if (cv_bsdf_is_delta(bq))
                continue;
        }
        if (cv_bdpt_runs(s, 1u))
            cv_bdpt_connect_t1(s, qs, bq, splat_scale);
    }
    for (uint t = 2u; t <= n_cam; t++) {
        CvBdptVertex pt = cv_bdpt_cam(t - 1u);
        if (t - 2u <= max_depth && cv_bdpt_runs(0u, t))
            L += cv_bdpt_connect_s0(t, splat_scale);
        CvBsdf bt;
        if (cv_bdpt_in_medium(pt)) {
        } else if (pt.id.x != CV_BDPT_SURFACE) {
            continue;  // escaped: s = 0 alone
        } else {
            bt = cv_bdpt_bsdf(pt);
            if (cv_bsdf_is_delta(bt))
                continue;
        }
        // s = 1 samples a light point of its own: it runs whether or not
        // the light subpath began (pbrt-v4 runs it only where it did, so
        // that a light sample of a cut-out emitter there is masked twice)
        if (t - 1u <= max_depth && cv_bdpt_runs(1u, t))
            L += cv_bdpt_connect_s1(t, pt, bt, splat_scale);
        for (uint s = 2u; s <= n_light && s + t - 2u <= max_depth; s++) {
            if (!cv_bdpt_runs(s, t))
                continue;
            CvBdptVertex qs = cv_bdpt_light(s - 1u);
            CvBsdf bq;
            if (!cv_bdpt_in_medium(qs)) {
                bq = cv_bdpt_bsdf(qs);
                if (cv_bsdf_is_delta(bq))
                    continue;
            }
            L += cv_bdpt_connect(s, t, qs, bq, pt, bt, splat_scale);
        }
    }
    cv_film_add(slot, L + g_medium_Le);
}
