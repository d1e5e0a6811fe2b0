// glsl/trace/bdpt/media.glsl: participating media in bdpt (CV_MEDIA), as
// pbrt-v4's BDPTIntegrator has them: subpaths that scatter in media
// (medium vertices, whose "BSDF" is the Henyey-Greenstein phase function),
// and connections weighed by the transmittance between their ends. The
// tracking is volpath's (medium/medium.glsl, grid.glsl): delta tracking in
// the subpath's hero channel with the channel ratios r, so that a subpath's
// throughput is, in every channel, its one-sample MIS estimate over the
// channels, as volpath's path; connections take the transmittance exact
// in homogeneous media and ratio-tracked in grid media, as volpath's shadow
// rays. The MIS densities of medium vertices are their phase function's,
// per unit volume (no cosine: cv_bdpt_convert), as pbrt-v4's; the
// tracking's distance densities stay out of them, as in pbrt-v4, which
// keeps the weights a partition of unity. Without CV_MEDIA every vertex
// is in vacuum. Include in bdpt.comp after g_fp and g_sample.
#ifndef CV_TRACE_BDPT_MEDIA_GLSL
#define CV_TRACE_BDPT_MEDIA_GLSL

#ifdef CV_MEDIA
#include "../medium/medium.glsl"
#endif
#include "../medium/random.glsl"

// bdpt.comp's tracing, defined after this file
bool cv_bdpt_trace(vec3 o, vec3 d, uint key, out CvHit h);
bool cv_bdpt_visible(vec3 a, float a_err, vec3 a_ng, vec3 b, float b_err, vec3 b_ng);

bool cv_bdpt_in_medium(CvBdptVertex v) { return v.id.x == CV_BDPT_MEDIUM; }

// The medium a vertex's incoming ray travelled in (glsl/shared/bdpt.h).
uint cv_bdpt_arrival_medium(CvBdptVertex v) { return (v.id.y >> CV_BDPT_MEDIUM_SHIFT) & 255u; }

// The medium of a ray leaving vertex v in direction w: a surface's
// MediumInterface where it is a transition, else the one v lies in.
uint cv_bdpt_medium_towards(CvBdptVertex v, vec3 w)
{
#ifdef CV_MEDIA
    uint m = cv_bdpt_arrival_medium(v);
    if (v.id.x == CV_BDPT_SURFACE)
        return cv_medium_across(v.id.z, v.ng.xyz, w, m);
    return m;
#else
    return 0u;
#endif
}

// The phase function of medium vertex v from wo to wi: f, and its density.
float cv_bdpt_hg(CvBdptVertex v, vec3 wo, vec3 wi)
{
#ifdef CV_MEDIA
    return cv_hg_pdf(dot(wo, wi), cv_media(v.id.z).sigma_a.w);
#else
    return 0.0;
#endif
}
float cv_bdpt_phase(CvBdptVertex v, vec3 wi) { return cv_bdpt_hg(v, v.wo.xyz, wi); }

// pbrt-v4's RandomWalk tracing: the next vertex along o + t d, starting in
// `medium`. Returns 1 with h the surface found, 2 with h.t the distance of
// a scattering event in `medium` (the medium then the event's), 0 where the
// ray leaves the scene or the tracking ends the subpath (beta 0). Medium
// boundaries ("interface" surfaces) and alpha cut-outs that let the ray
// through are passed, a boundary switching the medium; beta takes the
// tracking's weights (medium.glsl) and r the channel ratios; key tells
// the subpath and vertex apart for the random numbers.
uint cv_bdpt_track(vec3 o, vec3 d, uint key, uint hero, inout uint medium, inout vec3 beta,
                   inout vec3 r, out CvHit h)
{
    h = CvHit(0.0, 0u, 0.0, 0.0);
#ifndef CV_MEDIA
    return cv_bdpt_trace(o, d, key, h) ? 1u : 0u;
#else
    float tmin = 0.0, seg0 = 0.0;
#ifdef CV_MEDIUM_GRIDS
    uvec3 grid_key = uvec3(g_fp ^ u_pass.seed_lo, g_sample ^ cv_hash(u_pass.seed_hi), key ^ 0x47524944u);
    uint grid_n = 0u;
#endif
    for (uint k = 0u; k < 64u; k++) {
        bool hit = false;
#ifndef CV_EMPTY_SCENE
        hit = cv_trace_closest(o, d, tmin, 1e30, h);
#endif
#ifdef CV_MATTE_STRIDE
        // the camera ray's first hit gives the mattes, as the matte stage
        // takes path's: the subpath's first vertex may be a scattering
        // in front of it (key 1: the camera side's first ray)
        if (k == 0u && key == 1u && hit)
            cv_matte_first_hit(g_slot, h.prim);
#endif
        bool pass = false;
        uint material = 0u;
        vec3 ng = vec3(0.0);
#ifdef CV_HAS_ALPHA
        if (hit) {
            CvSurface s = cv_surface_ray(h.prim, h.b1, h.b2, o, d, h.t);
            material = cv_prim_word(h.prim) & CV_TRI_MATERIAL_MASK;
            ng = s.ng;
            float u = cv_uint_to_unit(cv_hash4(g_fp, g_sample, h.prim, key * 64u + k));
            pass = cv_material_alpha_pass(material, s.uv, u);
        }
#endif
        if (medium != 0u) {
            float len = (hit ? h.t : 1e30) - seg0, t;
            vec3 w;
            bool collide;
#ifdef CV_MEDIUM_GRIDS
            if (cv_grid_medium(medium)) {
                collide = cv_grid_sample_distance(medium, o, d, seg0, seg0 + len, hero, grid_key,
                                                  grid_n, r, t, w);
                t -= seg0;
            } else
#endif
                collide = cv_medium_sample_distance(medium, len, hero,
                                                    cv_medium_u(g_fp, g_sample, key, k), r, t, w);
            beta *= w;
            if (collide) {
                h.t = seg0 + t;
                return cv_max3(beta) > 0.0 ? 2u : 0u;
            }
            if (!(cv_max3(beta) > 0.0))
                return 0u;
        }
        if (!hit)
            return 0u;
        if (!pass)
            return 1u;
        if (materials[material].type == CV_MAT_INTERFACE)
            medium = cv_medium_across(material, ng, d, medium);
        seg0 = h.t;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
    return 0u;
#endif
}

// The transmittance from a to b, off their surfaces (rounding errors
// a_err, b_err along geometric normals a_ng, b_ng; 0 where not on a
// surface), the ray leaving a in medium `medium`: 0 where a surface other
// than a medium boundary or a cut-out that lets it through is in the way
// (pbrt-v4's Tr: TraceTransmittance). Alpha cut-outs are passed as in
// shadow.comp; key tells the connections apart for the random numbers.
vec3 cv_bdpt_transmittance(vec3 a, float a_err, vec3 a_ng, vec3 b, float b_err, vec3 b_ng,
                           uint medium, uint key)
{
#ifndef CV_MEDIA
    return cv_bdpt_visible(a, a_err, a_ng, b, b_err, b_ng) ? vec3(1.0) : vec3(0.0);
#else
    vec3 o = a, e = b;
    if (dot(a_ng, a_ng) > 0.0)
        o = cv_offset_ray(a, a_err, dot(b - a, a_ng) > 0.0 ? a_ng : -a_ng);
    if (dot(b_ng, b_ng) > 0.0)
        e = cv_offset_ray(b, b_err, dot(a - b, b_ng) > 0.0 ? b_ng : -b_ng);
    vec3 d = e - o;
    float len = length(d);
    if (!(len > 0.0))
        return vec3(1.0);
    d /= len;
    float tmax = len * (1.0 - 1e-4);
    vec3 T = vec3(1.0);
    float tmin = 0.0, seg0 = 0.0;
    CvHit h;
    for (uint k = 0u; k < 64u; k++) {
        bool hit = false;
#ifndef CV_EMPTY_SCENE
        hit = cv_trace_closest(o, d, tmin, tmax, h);
#endif
        if (medium != 0u) {
            float t1 = hit ? h.t : tmax;
#ifdef CV_MEDIUM_GRIDS
            if (cv_grid_medium(medium))
                T *= cv_grid_transmittance(medium, o, d, seg0, t1,
                                           uvec3(g_fp ^ u_pass.seed_lo, g_sample ^ cv_hash(key),
                                                 cv_hash(u_pass.seed_hi ^ (0x52415449u + k))));
            else
#endif
                T *= cv_medium_transmittance(medium, t1 - seg0);
        }
        if (!hit)
            return T;
#ifdef CV_HAS_ALPHA
        CvSurface sf = cv_surface_ray(h.prim, h.b1, h.b2, o, d, h.t);
        uint material = cv_prim_word(h.prim) & CV_TRI_MATERIAL_MASK;
        float u = cv_uint_to_unit(cv_hash4(g_fp, g_sample ^ cv_hash(key), h.prim, 0x5bd1e995u + k));
        if (!cv_material_alpha_pass(material, sf.uv, u))
            return vec3(0.0);
        if (materials[material].type == CV_MAT_INTERFACE)
            medium = cv_medium_across(material, sf.ng, d, medium);
#else
        return vec3(0.0);
#endif
        if (!(cv_max3(T) > 0.0))
            return vec3(0.0);
        seg0 = h.t;
        tmin = h.t * (1.0 + 1e-5) + 1e-6;
    }
    return vec3(0.0);
#endif
}

#endif
