// glsl/trace/light/light.glsl: light sampling for next-event estimation and
// the emitted radiance / pdfs MIS needs when a path hits a light. Include
// light_buffers.glsl first.
//
// A light is picked by the power CDF (cv_light_cdf_at), then sampled: point and
// spot (pbrt-v4 smoothstep falloff) and distant lights are delta lights;
// area lights (one triangle each) are sampled uniformly by area; constant
// infinite lights uniformly over the sphere; image infinite lights by their
// piecewise-constant distribution (envmap.glsl). All pdfs are per solid
// angle and include the light-selection probability.
#ifndef CV_LIGHT_LIGHT_GLSL
#define CV_LIGHT_LIGHT_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/sampling.glsl"
#include "../bsdf/texture.glsl"
#include "envmap.glsl"
// outside the #ifdef below: the expander pastes a file once, and
// sampler.glsl needs it too
#include "../../lib/rng.glsl"
#ifdef CV_ALPHA_EMITTERS
#include "../bsdf/alpha.glsl"
#endif

// wi: unit direction from p to the light; dist: distance to the sampled point
// (1e30 for infinite and distant lights: trace the shadow ray to infinity;
// for area lights short of the lamp by the point's rounding error);
// L: radiance arriving at p (before any occlusion); delta: point, spot or
// distant light (no MIS with BSDF sampling).
struct CvLightSample { vec3 wi; float dist; vec3 L; float pdf; bool delta; };

#define CV_LIGHT_INFINITE_DIST 1e30

uint cv_light_count() { return uint(lights.length()); }

float cv_light_pmf(uint i)
{
    return cv_light_cdf_at(i) - (i > 0u ? cv_light_cdf_at(i - 1u) : 0.0);
}

uint cv_light_pick(float u)
{
    uint n = cv_light_count();
    uint lo = 0u, hi = n - 1u;
    while (lo < hi) {  // first i with u < cdf[i]
        uint mid = (lo + hi) / 2u;
        if (u < cv_light_cdf_at(mid))
            hi = mid;
        else
            lo = mid + 1u;
    }
    while (lo + 1u < n && cv_light_pmf(lo) <= 0.0)  // never pick a zero-probability light
        lo++;
    return lo;
}

bool cv_light_is_infinite(CvLight l) { return l.type == CV_LIGHT_INFINITE || l.type == CV_LIGHT_INFINITE_MAP; }

// Geometric normal of an emitting triangle, on its emitting side: as pbrt,
// faced towards the interpolated shading normal when the mesh has normals,
// else flipped by CV_TRI_REVERSE.
vec3 cv_light_triangle_normal(uint tri, vec3 b)
{
    CvTriangle t = cv_triangles[tri];
    vec3 p0 = cv_vertices[t.idx.x].pos_u.xyz;
    vec3 p1 = cv_vertices[t.idx.y].pos_u.xyz;
    vec3 p2 = cv_vertices[t.idx.z].pos_u.xyz;
    vec3 n = normalize(cross(p1 - p0, p2 - p0));
    if ((t.idx.w & CV_TRI_HAS_NORMAL) != 0u) {
        vec3 ns = b.x * cv_vertices[t.idx.x].nrm_v.xyz + b.y * cv_vertices[t.idx.y].nrm_v.xyz +
                  b.z * cv_vertices[t.idx.z].nrm_v.xyz;
        if (dot(n, ns) < 0.0)
            n = -n;
    } else if ((t.idx.w & CV_TRI_REVERSE) != 0u) {
        n = -n;
    }
    return n;
}

#ifdef CV_ALPHA_EMITTERS
// pbrt-v4's DiffuseAreaLight::AlphaMasked: whether the point p (surface
// coordinates uv) of a cut-out emitter's triangle emits nothing, against
// a hash of the point where its alpha is between 0 and 1.
bool cv_light_alpha_masked(uint prim, vec2 uv, vec3 p)
{
    float a = cv_material_alpha(cv_triangles[prim].idx.w & CV_TRI_MATERIAL_MASK, uv);
    if (a >= 1.0)
        return false;
    if (a <= 0.0)
        return true;
    uvec3 b = floatBitsToUint(p);
    return cv_uint_to_unit(cv_hash3(b.x, b.y, b.z)) > a;
}
#endif

// Emitted radiance of area light `light` leaving its point p (surface
// coordinates uv) in direction wo_from_light; front: that direction is on
// the emitting normal's side. A cut-out emitter emits nothing where it is
// masked, for light samples and hits alike, as pbrt-v4's L().
vec3 cv_light_Le_area(uint light, vec3 wo_from_light, vec2 uv, bool front, vec3 p)
{
    CvLight l = lights[light];
    if (!front && (l.flags & CV_LIGHTF_TWO_SIDED) == 0u)
        return vec3(0.0);
#ifdef CV_ALPHA_EMITTERS
    if ((l.flags & CV_LIGHTF_ALPHA) != 0u && cv_light_alpha_masked(l.prim, uv, p))
        return vec3(0.0);
#endif
    vec3 L = l.L.rgb;
    if (l.tex >= 0)
        L *= cv_tex_eval(l.tex, vec4(1.0), uv, 0.0).rgb;
    return L;
}

// Solid-angle pdf with which cv_light_sample, seen from p, produces the
// point p_light (normal n_light) on area light `light`.
float cv_light_pdf_area(uint light, vec3 p, vec3 p_light, vec3 n_light)
{
    CvLight l = lights[light];
    vec3 d = p - p_light;
    float d2 = dot(d, d);
    float c = abs(dot(n_light, d)) * inversesqrt(d2);
    if (!(c > 0.0) || !(l.L.w > 0.0))
        return 0.0;
    return cv_light_pmf(light) * d2 / (c * l.L.w);
}

// One infinite light's radiance along dir and its density per solid angle
// (without the light-selection probability).
vec3 cv_env_light_Le(CvLight l, vec3 dir) { return l.type == CV_LIGHT_INFINITE ? l.L.rgb : cv_env_map_Le(l, dir); }
float cv_env_light_pdf(CvLight l, vec3 dir) { return l.type == CV_LIGHT_INFINITE ? CV_INV_4PI : cv_env_map_pdf(l, dir); }

vec3 cv_env_Le(vec3 dir)
{
    vec3 L = vec3(0.0);
    uint n = cv_light_count();
    for (uint i = 0u; i < n; i++) {
        CvLight l = lights[i];
        if (!cv_light_is_infinite(l))
            break;
        L += cv_env_light_Le(l, dir);
    }
    return L;
}

float cv_env_pdf(vec3 dir)
{
    float pdf = 0.0;
    uint n = cv_light_count();
    for (uint i = 0u; i < n; i++) {
        CvLight l = lights[i];
        if (!cv_light_is_infinite(l))
            break;
        pdf += cv_light_pmf(i) * cv_env_light_pdf(l, dir);
    }
    return pdf;
}

// u3.x picks the light, u3.yz sample it. p: the shading point; n: its normal
// (unused by these strategies, kept for spherical-triangle sampling).
// The host defines CV_NO_ENV for a scene without infinite lights: the
// environment branches then drop out of the stage kernels.
bool cv_light_sample(vec3 p, vec3 n, vec3 u3, out CvLightSample s)
{
    s = CvLightSample(vec3(0.0, 0.0, 1.0), 0.0, vec3(0.0), 0.0, false);
    if (cv_light_count() == 0u)
        return false;
    uint i = cv_light_pick(u3.x);
    float pmf = cv_light_pmf(i);
    if (!(pmf > 0.0))
        return false;
    CvLight l = lights[i];
    vec2 u = u3.yz;
    if (l.type == CV_LIGHT_POINT || l.type == CV_LIGHT_SPOT) {
        vec3 d = l.position.xyz - p;
        float d2 = dot(d, d);
        if (!(d2 > 0.0))
            return false;
        float dist = sqrt(d2);
        vec3 wi = d / dist;
        vec3 I = l.L.rgb;
        if (l.type == CV_LIGHT_SPOT) {
            float cos_theta = dot(-wi, normalize(l.direction.xyz));
            I *= cv_smoothstep(l.direction.w, l.position.w, cos_theta);
        }
        s = CvLightSample(wi, dist, I / d2, pmf, true);
    } else if (l.type == CV_LIGHT_DISTANT) {
        s = CvLightSample(-normalize(l.direction.xyz), CV_LIGHT_INFINITE_DIST, l.L.rgb, pmf, true);
    } else if (l.type == CV_LIGHT_AREA) {
        CvTriangle t = cv_triangles[l.prim];
        vec3 b = cv_sample_uniform_triangle(u);
        CvVertex v0 = cv_vertices[t.idx.x], v1 = cv_vertices[t.idx.y], v2 = cv_vertices[t.idx.z];
        vec3 pl = b.x * v0.pos_u.xyz + b.y * v1.pos_u.xyz + b.z * v2.pos_u.xyz;
        vec2 uv = (t.idx.w & CV_TRI_HAS_UV) != 0u
                      ? b.x * vec2(v0.pos_u.w, v0.nrm_v.w) + b.y * vec2(v1.pos_u.w, v1.nrm_v.w) +
                            b.z * vec2(v2.pos_u.w, v2.nrm_v.w)
                      : b.x * vec2(0.0) + b.y * vec2(1.0, 0.0) + b.z * vec2(1.0);
        vec3 nl = cv_light_triangle_normal(l.prim, b);
        vec3 d = pl - p;
        float d2 = dot(d, d);
        if (!(d2 > 0.0))
            return false;
        float dist = sqrt(d2);
        vec3 wi = d / dist;
        float c = dot(nl, -wi);
        if (c == 0.0 || !(l.L.w > 0.0))
            return false;
        vec3 L = cv_light_Le_area(i, -wi, uv, c > 0.0, pl);
        // the shadow ray stops short of the lamp by its point's rounding
        // error (cv_point_error), measured along wi, so that it does not
        // find the lamp itself in the way
        float back = cv_point_error(v0.pos_u.xyz, v1.pos_u.xyz, v2.pos_u.xyz) / abs(c);
        s = CvLightSample(wi, max(dist - back, 0.0), L, pmf * d2 / (abs(c) * l.L.w), false);
#ifndef CV_NO_ENV
    } else if (l.type == CV_LIGHT_INFINITE || l.type == CV_LIGHT_INFINITE_MAP) {
        float pdf = CV_INV_4PI;
        vec3 wi = l.type == CV_LIGHT_INFINITE ? cv_sample_uniform_sphere(u) : cv_env_map_sample(l, u, pdf);
        vec3 L = cv_env_light_Le(l, wi);
        pdf *= pmf;
        // Every infinite light shines along wi: the sample carries their sum
        // and the density of the mixture over all of them (cv_env_Le,
        // cv_env_pdf), as an escaped ray's MIS weight sees them; one light's
        // share alone would be weighed against the sum's pdf there.
        for (uint j = 0u; j < cv_light_count() && cv_light_is_infinite(lights[j]); j++) {
            if (j != i) {
                L += cv_env_light_Le(lights[j], wi);
                pdf += cv_light_pmf(j) * cv_env_light_pdf(lights[j], wi);
            }
        }
        s = CvLightSample(wi, CV_LIGHT_INFINITE_DIST, L, pdf, false);
#endif
    } else {
        return false;
    }
    return s.pdf > 0.0 && cv_max3(s.L) > 0.0;
}

#endif
