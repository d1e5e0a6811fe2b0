// glsl/trace/bsdf/bsdf.glsl: the BSDF interface the wavefront shade stage
// calls. cv_bsdf_at resolves a material at a shading point (mix materials,
// textures, bump and normal maps, shading frame) into a CvBsdf; the other
// functions evaluate, sample and give the pdf of it in world space.
//
// The including shader must declare the scene's material, texture and texel
// buffers first (include material_buffers.glsl).
//
// Conventions (pbrt-v4): directions point away from the surface; f carries no
// cosine; pdfs are per solid angle. The shading frame's z is the shading
// normal (turned to ng's side); reflection-only BSDFs are two-sided (they
// reflect on whichever side wo lies); dielectrics see eta from +z and 1/eta
// from below. Transmission through a dielectric divides radiance by eta^2.
// CV_MAT_INTERFACE is no surface: cv_material_alpha_pass reports it as
// passed-through, and a CvBsdf of that type reflects nothing.
//
// CV_BSDF_DIFFUSE_ONLY (defined by the includer) compiles the diffuse
// material alone, textures and bump and normal maps included: every
// material passed in must be CV_MAT_DIFFUSE (the shade stage of the
// diffuse bin, trace/shade.comp). Type switches then fold to one case, so
// the other lobes' code and registers drop out of the kernel; the entry
// points skip their switches in the preprocessor as well, because Mesa's
// GLSL compiler inlines every case's callee (the coated walk too) before it
// folds a switch on a constant, which made the diffuse kernel cost nearly
// as much compile time as the full one (bench/RESULTS.md).
//
// CV_BSDF_WALK_ONLY (defined by the host) compiles the two coated
// materials alone: every material passed in is a coated diffuse or a
// coated conductor, never a mix (the coated walk's bin where none of its
// materials is a mix: src/trace/shade_bins.h). The walk's own lobes
// (layered.glsl) stay; the other types' cases drop out of the switches,
// which in that kernel are dead code the compiler cannot see as such.
#ifndef CV_BSDF_BSDF_GLSL
#define CV_BSDF_BSDF_GLSL

// CV_BSDF_ANY_TYPE: neither cut-down kernel, so any material type may
// come (mixes resolved); each case of a type outside theirs needs it
#if !defined(CV_BSDF_DIFFUSE_ONLY) && !defined(CV_BSDF_WALK_ONLY)
#define CV_BSDF_ANY_TYPE
#endif
#if !defined(CV_BSDF_ANY_TYPE) && !defined(CV_NO_HAIR)
#define CV_NO_HAIR
#endif

#include "../../lib/constants.glsl"
#include "../../lib/frame.glsl"
#include "bsdf_sample.glsl"
#include "bsdf_query.glsl"
#include "fresnel.glsl"
#include "microfacet.glsl"
#include "diffuse.glsl"
#include "conductor.glsl"
#include "dielectric.glsl"
#include "layered.glsl"
#include "coated_closed.glsl"
#include "plastic.glsl"
#include "hair.glsl"
// measured BRDFs: only in kernels of scenes that have them (the host
// defines CV_NO_MEASURED otherwise), never in the cut-down ones
#if !defined(CV_BSDF_ANY_TYPE) && !defined(CV_NO_MEASURED)
#define CV_NO_MEASURED
#endif
#ifndef CV_NO_MEASURED
#include "measured.glsl"
#endif
#include "texture.glsl"
#include "alpha.glsl"
#ifdef CV_HAS_SUBSURFACE
#include "sss_exit.glsl"
#endif

// Not a material: the exit lobe of a subsurface material's BSSRDF probe
// (sss_exit.glsl; built by trace/sss_vertex.glsl, eta in eta).
#define CV_BSDF_SSS_EXIT 64u

// ng: geometric normal as stored (oriented by CV_TRI_REVERSE); ns: shading
// normal (interpolated), dpdu: surface tangent along u; front: wo on ng's
// side. uv: surface texture coordinates.
struct CvShadingPoint { vec3 p; vec3 ng; vec3 ns; vec3 dpdu; vec2 uv; bool front; };

// A material resolved at one point. Fields by type:
//  DIFFUSE c0 = R | CONDUCTOR c0 = eta, c1 = k, alpha.xy
//  DIELECTRIC eta, alpha.xy, c0 = Kr, c1 = Kt | THIN_DIELECTRIC eta | MIRROR c0 = Kr
//  COATED_DIFFUSE c0 = R, eta, alpha.xy (coat), thickness, medium, walk, coat_closed
//  COATED_CONDUCTOR eta (coat), alpha.xy (coat), alpha.zw (base), c0/c1 = base eta/k over coat eta,
//    thickness, medium, walk
//  DIFFUSE_TRANSMISSION c0 = R, c1 = T | PLASTIC c0 = Kd, c1 = Ks, alpha.xy | INTERFACE none
//  HAIR c0 = sigma_a, eta, alpha = (beta_m, beta_n, scale tilt in degrees, h across the fibre)
//  SUBSURFACE as DIELECTRIC (c0 = c1 = 1), and the material's two coefficients at the point:
//    medium.rgb and (alpha.zw, thickness) (glsl/shared/scene.h: CV_MATF_SSS_POINT)
//  MEASURED walk.x = word offset of its tables (glsl/shared/measured.h)
struct CvBsdf {
    uint type;  // read through CV_BSDF_TYPE
    uint material;
    CvFrame frame;
    vec3 ng;
    vec3 c0;
    vec3 c1;
    vec4 alpha;
    float eta;
    float thickness;
    vec4 medium;  // coated: slab albedo (rgb), Henyey-Greenstein g (w)
    ivec2 walk;   // coated: max depth, samples per estimate
    vec2 coat_closed;  // coated diffuse in closed form: r_in, t_out (coated_closed.glsl); x < 0: random walk
    uint stream;  // key of the stochastic BSDFs' random streams (cv_bsdf_set_stream)
};

#ifdef CV_BSDF_DIFFUSE_ONLY
#define CV_BSDF_TYPE(b) CV_MAT_DIFFUSE
#else
#define CV_BSDF_TYPE(b) ((b).type)
#endif

float cv_roughness_v3_to_alpha(float r)
{
    float x = log(max(r, 1e-3));
    return 1.62142 + 0.819955 * x + 0.1734 * x * x + 0.0171201 * x * x * x + 0.000640711 * x * x * x * x;
}

vec2 cv_material_alpha(CvMaterial m, float ru, float rv)
{
    vec2 a = m.roughness.xy;
    bool remap = (m.flags & CV_MATF_REMAP_ROUGHNESS) != 0u;
    bool v3 = (m.flags & CV_MATF_ROUGHNESS_V3) != 0u;
    if (m.roughness_u_tex >= 0)
        a.x = remap ? (v3 ? cv_roughness_v3_to_alpha(ru) : sqrt(max(ru, 0.0))) : ru;
    if (m.roughness_v_tex >= 0)
        a.y = remap ? (v3 ? cv_roughness_v3_to_alpha(rv) : sqrt(max(rv, 0.0))) : rv;
    return max(a, vec2(0.0));
}

// Conductor eta and k; "reflectance" conductors as pbrt-v4: eta = 1,
// k = 2 sqrt(r) / sqrt(1 - r), which reproduces r at normal incidence;
// conductors given by spectra: eta -1, k their Fresnel table
// (cv_fr_complex reads it).
void cv_material_conductor(CvMaterial m, vec3 refl, out vec3 eta, out vec3 k)
{
    if ((m.flags & CV_MATF_CONDUCTOR_REFLECTANCE) != 0u) {
        vec3 r = clamp(refl, 0.0, 0.9999);
        eta = vec3(1.0);
        k = 2.0 * sqrt(r) / sqrt(1.0 - r);
#ifdef CV_CONDUCTOR_TABLES
    } else if ((m.flags & CV_MATF_CONDUCTOR_FRESNEL) != 0u) {
        eta = vec3(-1.0);
        k = vec3(m.k.w);
#endif
    } else {
        eta = m.eta.rgb;
        k = m.k.rgb;
    }
}

// Bump mapping as pbrt's BumpMap from displacement values at uv, uv + (du, 0)
// and uv + (0, dv) (CV_BUMP_DELTA: no ray differentials here); dpdv is taken
// perpendicular to dpdu with the same length, since the shading point
// carries no dpdv.
#define CV_BUMP_DELTA 0.0005
vec3 cv_bump_normal(float d0, float d_u, float d_v, vec3 ns, vec3 dpdu)
{
    vec3 tu = dpdu - ns * dot(ns, dpdu);
    if (!(dot(tu, tu) > 1e-20))
        return ns;
    vec3 tv = cross(ns, tu);
    vec3 pu = tu + (d_u - d0) / CV_BUMP_DELTA * ns;
    vec3 pv = tv + (d_v - d0) / CV_BUMP_DELTA * ns;
    vec3 n = cross(pu, pv);
    if (!(dot(n, n) > 0.0))
        return ns;
    n = normalize(n);
    return dot(n, ns) < 0.0 ? -n : n;
}

// Tangent-space normal map as pbrt-v4: rgb in [0,1] -> [-1,1], frame (dpdu, ns).
vec3 cv_normal_map(vec3 rgb, vec3 ns, vec3 dpdu)
{
    vec3 c = 2.0 * rgb - 1.0;
    if (!(dot(c, c) > 0.0))
        return ns;
    CvFrame f = cv_frame_from_xz(dpdu, ns);
    return normalize(cv_from_local(f, normalize(c)));
}

// Picks among nested mix materials: mix_b with probability `amount`, the
// random number rescaled at each level so nested mixes stay independent.
uint cv_material_resolve(uint material, vec2 uv, float u_mix, float lod)
{
    for (int depth = 0; depth < 8; depth++) {
        CvMaterial m = materials[material];
        if (m.type != CV_MAT_MIX)
            break;
        if (m.mix_a < 0 || m.mix_b < 0)
            break;  // malformed: resolves to no surface
        float amt = cv_tex_eval(m.amount_tex, vec4(m.amount), uv, lod).x;
        if (amt <= 0.0) {
            material = uint(m.mix_a);
        } else if (amt >= 1.0) {
            material = uint(m.mix_b);
        } else if (u_mix < amt) {
            material = uint(m.mix_b);
            u_mix = u_mix / amt;
        } else {
            material = uint(m.mix_a);
            u_mix = (u_mix - amt) / (1.0 - amt);
        }
        u_mix = min(u_mix, CV_ONE_MINUS_EPS);
    }
    return material;
}

// lod: mip level of detail for image textures (0 = finest).
CvBsdf cv_bsdf_at_lod(uint material, CvShadingPoint sp, float u_mix, float lod)
{
    vec2 uv = sp.uv;
#ifdef CV_BSDF_ANY_TYPE
    material = cv_material_resolve(material, uv, u_mix, lod);
#endif
    CvMaterial m = materials[material];
    CvBsdf b;
#ifdef CV_BSDF_DIFFUSE_ONLY
    b.type = CV_MAT_DIFFUSE;
#elif defined(CV_BSDF_WALK_ONLY)
    b.type = m.type;
#else
    b.type = m.type == CV_MAT_MIX ? CV_MAT_INTERFACE : m.type;
#endif
    b.material = material;
    b.ng = sp.ng;
    b.c0 = vec3(0.0);
    b.c1 = vec3(0.0);
    b.alpha = vec4(0.0);
    b.eta = 1.0;
    b.thickness = 0.0;
    b.medium = vec4(0.0);
    b.walk = ivec2(0);
    b.coat_closed = vec2(-1.0);
    b.stream = 0u;

    // Every texture the material reads, evaluated in one loop (one inlined
    // copy of the texture code): reflectance, specular, eta, roughness u, v,
    // normal map, displacement at uv, uv + du, uv + dv. Step k's texture and
    // result are picked by selects into named variables, not an array
    // indexed by k (which the driver places in local memory).
    vec4 refl4 = m.reflectance, spec4 = m.specular, nmap = vec4(0.5, 0.5, 1.0, 1.0);
    float eta = m.eta.x, rough_u = m.roughness.x, rough_v = m.roughness.y;
    float disp = 0.0, disp_du = 0.0, disp_dv = 0.0;
#ifndef CV_NO_TEXTURES
    // (without textures every value is the constant: no loop)
    int n_tex = m.displacement_tex >= 0 ? 9 : 6;
    for (int k = 0; k < n_tex; k++) {
#ifdef CV_BSDF_DIFFUSE_ONLY
        if (k >= 1 && k <= 4)
            continue;  // specular, eta, roughness: not diffuse's
#endif
        int id = k == 0 ? m.reflectance_tex
               : k == 1 ? m.specular_tex
               : k == 2 ? m.eta_tex
               : k == 3 ? m.roughness_u_tex
               : k == 4 ? m.roughness_v_tex
               : k == 5 ? m.normal_tex : m.displacement_tex;
        if (id < 0)
            continue;  // the constant stands
        vec2 tuv = uv + (k == 7 ? vec2(CV_BUMP_DELTA, 0.0) : (k == 8 ? vec2(0.0, CV_BUMP_DELTA) : vec2(0.0)));
        vec4 v = cv_tex_eval(id, vec4(0.0), tuv, lod);  // (id >= 0: no fallback)
        if (k == 0)
            refl4 = v;
        else if (k == 1)
            spec4 = v;
        else if (k == 2)
            eta = v.x;
        else if (k == 3)
            rough_u = v.x;
        else if (k == 4)
            rough_v = v.x;
        else if (k == 5)
            nmap = v;
        else if (k == 6)
            disp = v.x;
        else if (k == 7)
            disp_du = v.x;
        else
            disp_dv = v.x;
    }
#endif
    vec3 refl = refl4.rgb, spec = spec4.rgb;

    vec3 ns = sp.ns;
    if (!(dot(ns, ns) > 0.0))
        ns = sp.ng;
    ns = normalize(ns);
    if (dot(ns, sp.ng) < 0.0)
        ns = -ns;
#ifndef CV_NO_TEXTURES
    if (m.normal_tex >= 0)
        ns = cv_normal_map(nmap.rgb, ns, sp.dpdu);
    else if (m.displacement_tex >= 0)
        ns = cv_bump_normal(disp, disp_du, disp_dv, ns, sp.dpdu);
#endif
    b.frame = cv_frame_from_xz(sp.dpdu, ns);
#ifdef CV_BSDF_DIFFUSE_ONLY
    b.c0 = clamp(refl, 0.0, 1.0);
#else
    vec2 alpha = cv_material_alpha(m, rough_u, rough_v);
    vec3 ceta, ck;
    cv_material_conductor(m, refl, ceta, ck);

    if (b.type == CV_MAT_COATED_DIFFUSE) {
        b.c0 = clamp(refl, 0.0, 1.0);
        b.eta = eta > 0.0 ? eta : 1.5;
        b.alpha.xy = alpha;
        b.thickness = m.roughness.z;
        b.medium = vec4(clamp(spec, 0.0, 1.0), m.roughness.w);
        b.walk = ivec2(m.roughness2.zw);
        if ((m.flags & CV_MATF_COAT_CLOSED) != 0u && max(alpha.x, alpha.y) <= CV_COAT_CLOSED_ALPHA)
            b.coat_closed = m.roughness2.xy;
    } else if (b.type == CV_MAT_COATED_CONDUCTOR) {
        b.eta = m.eta.w > 0.0 ? m.eta.w : 1.5;
        b.alpha.xy = alpha;
        b.alpha.zw = max(m.roughness2.xy, vec2(0.0));
        b.thickness = m.roughness.z;
        b.c0 = ceta;
        b.c1 = ck;
        if (ceta.x >= 0.0) {  // (a table holds the ratio already)
            b.c0 /= b.eta;
            b.c1 /= b.eta;
        }
        b.medium = vec4(clamp(spec, 0.0, 1.0), m.roughness.w);
        b.walk = ivec2(m.roughness2.zw);
    }
    // (the other types: not in the cut-down kernels)
#ifdef CV_BSDF_ANY_TYPE
    else if (b.type == CV_MAT_DIFFUSE) {
        b.c0 = clamp(refl, 0.0, 1.0);
    } else if (b.type == CV_MAT_CONDUCTOR) {
        b.c0 = ceta;
        b.c1 = ck;
        b.alpha.xy = alpha;
    } else if (b.type == CV_MAT_DIELECTRIC) {
        b.eta = eta > 0.0 ? eta : 1.0;
        b.alpha.xy = alpha;
        b.c0 = refl;
        b.c1 = spec;
    } else if (b.type == CV_MAT_SUBSURFACE) {
        // the boundary: a dielectric (the BSSRDF is the path's,
        // sss_vertex.glsl, which reads the coefficients here)
        b.eta = eta > 0.0 ? eta : 1.0;
        b.alpha.xy = alpha;
        b.c0 = vec3(1.0);
        b.c1 = vec3(1.0);
        b.medium.rgb = refl;
        b.alpha.zw = spec.xy;
        b.thickness = spec.z;
    } else if (b.type == CV_MAT_THIN_DIELECTRIC) {
        b.eta = eta > 0.0 ? eta : 1.0;
    } else if (b.type == CV_MAT_MIRROR) {
        b.c0 = refl;
    } else if (b.type == CV_MAT_DIFFUSE_TRANSMISSION) {
        b.c0 = clamp(refl, 0.0, 1.0);
        b.c1 = clamp(spec, 0.0, 1.0);
    } else if (b.type == CV_MAT_PLASTIC) {
        b.c0 = clamp(refl, 0.0, 1.0);
        b.c1 = clamp(spec, 0.0, 1.0);
        b.alpha.xy = alpha;
    }
#endif
#ifndef CV_NO_HAIR
    else if (b.type == CV_MAT_HAIR) {
        // pbrt-v4's HairMaterial: h from v across the curve's width
        b.eta = eta > 0.0 ? eta : 1.55;
        b.alpha = vec4(max(m.roughness.xy, vec2(0.01)), m.roughness.z, clamp(2.0 * uv.y - 1.0, -1.0, 1.0));
        if ((m.flags & CV_MATF_HAIR_SIGMA_A) != 0u)
            b.c0 = max(refl, vec3(0.0));
        else if ((m.flags & CV_MATF_HAIR_REFLECTANCE) != 0u)
            b.c0 = cv_hair_sigma_a_from_reflectance(clamp(refl, 0.0, 1.0), b.alpha.y);
        else
            b.c0 = cv_hair_sigma_a_from_melanin(refl.x, refl.y);
    }
#endif
#ifndef CV_NO_MEASURED
    else if (b.type == CV_MAT_MEASURED) {
        b.walk.x = m.mix_a;
    }
#endif
#endif
    return b;
}

CvBsdf cv_bsdf_at(uint material, CvShadingPoint sp, float u_mix)
{
    return cv_bsdf_at_lod(material, sp, u_mix, 0.0);
}

// The stochastic BSDFs (coated: a random walk per evaluation) draw their
// random numbers from streams keyed by the shade stage's sampler values at
// this vertex (u_a, u_b: any two of its pairs), hashed with the directions
// of each call: one seed, one image. Without it every vertex shares key 0.
void cv_bsdf_set_stream(inout CvBsdf b, vec2 u_a, vec2 u_b)
{
    b.stream = cv_hash3(floatBitsToUint(u_a.x), floatBitsToUint(u_a.y),
                        cv_hash2(floatBitsToUint(u_b.x), floatBitsToUint(u_b.y)));
}

// pbrt-v4's LayeredBxDF parameters of a coated material.
CvLayered cv_bsdf_layered(CvBsdf b)
{
    CvLayered L;
    L.eta = b.eta;
    L.coat_alpha = b.alpha.xy;
    L.conductor = CV_BSDF_TYPE(b) == CV_MAT_COATED_CONDUCTOR;
    L.c0 = b.c0;
    L.c1 = b.c1;
    L.base_alpha = b.alpha.zw;
    L.thickness = max(b.thickness, 1.17549435e-38);
    L.albedo = b.medium.rgb;
    L.g = b.medium.w;
    L.max_depth = b.walk.x;
    L.n_samples = max(b.walk.y, 1);
    L.key = b.stream;
    return L;
}

CvHair cv_bsdf_hair(CvBsdf b)
{
    return cv_hair_make(b.alpha.w, b.eta, b.c0, b.alpha.x, b.alpha.y, b.alpha.z);
}

// Whether a coated diffuse takes the closed form (coated_closed.glsl). With
// CV_NO_COAT_CLOSED (the host defines it where no material may take it),
// as with CV_NO_HAIR, that code stays out of the kernels: every material
// of a shade bin pays for the registers of the largest case in it
// (bench/RESULTS.md).
bool cv_bsdf_coat_closed(CvBsdf b)
{
#ifdef CV_NO_COAT_CLOSED
    return false;
#else
    return CV_BSDF_TYPE(b) == CV_MAT_COATED_DIFFUSE && b.coat_closed.x >= 0.0;
#endif
}

CvCoatClosed cv_bsdf_coat_closed_params(CvBsdf b)
{
    return CvCoatClosed(b.eta, b.alpha.xy, b.c0, max(b.thickness, 1.17549435e-38), b.walk.x, b.coat_closed.x,
                        b.coat_closed.y);
}

// Two-sided layered lobes work with wo on +z.
bool cv_bsdf_mirrored(CvBsdf b)
{
    uint type = CV_BSDF_TYPE(b);
    return type == CV_MAT_COATED_DIFFUSE || type == CV_MAT_COATED_CONDUCTOR || type == CV_MAT_PLASTIC ||
           type == CV_MAT_MEASURED;
}

// f and pdf of every lobe but the coated walk's (cv_bsdf_query), local
// directions with wo on the side the lobes expect (cv_bsdf_mirrored).
vec3 cv_bsdf_f_local(CvBsdf b, vec3 wo, vec3 wi)
{
#ifdef CV_BSDF_DIFFUSE_ONLY
    return cv_diffuse_f(b.c0, wo, wi);
#else
    switch (CV_BSDF_TYPE(b)) {
    case CV_MAT_COATED_DIFFUSE:
        // (the walk's coats: cv_bsdf_query)
        return cv_bsdf_coat_closed(b) ? cv_coat_closed_f(cv_bsdf_coat_closed_params(b), wo, wi) : vec3(0.0);
#ifdef CV_BSDF_ANY_TYPE
    case CV_MAT_DIFFUSE:
        return cv_diffuse_f(b.c0, wo, wi);
    case CV_MAT_CONDUCTOR:
        return cv_conductor_f(b.alpha.xy, b.c0, b.c1, wo, wi);
    case CV_MAT_DIELECTRIC:
    case CV_MAT_SUBSURFACE:
        return cv_dielectric_f(b.eta, b.alpha.xy, b.c0, b.c1, wo, wi);
#ifdef CV_HAS_SUBSURFACE
    case CV_BSDF_SSS_EXIT:
        return cv_sss_exit_f(b.eta, wo, wi);
#endif
    case CV_MAT_DIFFUSE_TRANSMISSION:
        return cv_difftrans_f(b.c0, b.c1, wo, wi);
    case CV_MAT_PLASTIC:
        return cv_plastic_f(b.c0, b.c1, b.alpha.xy, wo, wi);
#endif
#ifndef CV_NO_HAIR
    case CV_MAT_HAIR:
        return cv_hair_f(cv_bsdf_hair(b), wo, wi);
#endif
#ifndef CV_NO_MEASURED
    case CV_MAT_MEASURED:
        return cv_measured_f(uint(b.walk.x), wo, wi);
#endif
    default:
        return vec3(0.0);
    }
#endif
}

float cv_bsdf_pdf_local(CvBsdf b, vec3 wo, vec3 wi)
{
#ifdef CV_BSDF_DIFFUSE_ONLY
    return cv_diffuse_pdf(wo, wi);
#else
    switch (CV_BSDF_TYPE(b)) {
    case CV_MAT_COATED_DIFFUSE:
        return cv_bsdf_coat_closed(b) ? cv_coat_closed_pdf(cv_bsdf_coat_closed_params(b), wo, wi) : 0.0;
#ifdef CV_BSDF_ANY_TYPE
    case CV_MAT_DIFFUSE:
        return cv_diffuse_pdf(wo, wi);
    case CV_MAT_CONDUCTOR:
        return cv_conductor_pdf(b.alpha.xy, wo, wi);
    case CV_MAT_DIELECTRIC:
    case CV_MAT_SUBSURFACE:
        return cv_dielectric_pdf(b.eta, b.alpha.xy, wo, wi);
#ifdef CV_HAS_SUBSURFACE
    case CV_BSDF_SSS_EXIT:
        return cv_sss_exit_pdf(wo, wi);
#endif
    case CV_MAT_DIFFUSE_TRANSMISSION:
        return cv_difftrans_pdf(b.c0, b.c1, wo, wi);
    case CV_MAT_PLASTIC:
        return cv_plastic_pdf(b.c0, b.c1, b.alpha.xy, wo, wi);
#endif
#ifndef CV_NO_HAIR
    case CV_MAT_HAIR:
        return cv_hair_pdf(cv_bsdf_hair(b), wo, wi);
#endif
#ifndef CV_NO_MEASURED
    case CV_MAT_MEASURED:
        return cv_measured_pdf(uint(b.walk.x), wo, wi);
#endif
    default:
        return 0.0;
    }
#endif
}

// Samples every lobe but the coated walk's (cv_bsdf_query), wo local on
// the side the lobes expect (cv_bsdf_mirrored).
bool cv_bsdf_sample_local(CvBsdf b, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    bool ok = false;
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
#ifdef CV_BSDF_DIFFUSE_ONLY
    ok = cv_diffuse_sample(b.c0, wo, u, s);
#else
    switch (CV_BSDF_TYPE(b)) {
    case CV_MAT_COATED_DIFFUSE:
        if (cv_bsdf_coat_closed(b))
            ok = cv_coat_closed_sample(cv_bsdf_coat_closed_params(b), wo, uc, u, s);
        break;
#ifdef CV_BSDF_ANY_TYPE
    case CV_MAT_DIFFUSE:
        ok = cv_diffuse_sample(b.c0, wo, u, s);
        break;
    case CV_MAT_CONDUCTOR:
        ok = cv_conductor_sample(b.alpha.xy, b.c0, b.c1, wo, u, s);
        break;
    case CV_MAT_DIELECTRIC:
    case CV_MAT_SUBSURFACE:
        ok = cv_dielectric_sample(b.eta, b.alpha.xy, b.c0, b.c1, wo, uc, u, s);
        break;
#ifdef CV_HAS_SUBSURFACE
    case CV_BSDF_SSS_EXIT:
        ok = cv_sss_exit_sample(b.eta, wo, u, s);
        break;
#endif
    case CV_MAT_THIN_DIELECTRIC:
        ok = cv_thin_dielectric_sample(b.eta, wo, uc, s);
        break;
    case CV_MAT_MIRROR:
        if (wo.z != 0.0) {
            vec3 wi = vec3(-wo.x, -wo.y, wo.z);
            s = CvBsdfSample(wi, b.c0 / abs(wi.z), 1.0, CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            ok = true;
        }
        break;
    case CV_MAT_DIFFUSE_TRANSMISSION:
        ok = cv_difftrans_sample(b.c0, b.c1, wo, uc, u, s);
        break;
    case CV_MAT_PLASTIC:
        ok = cv_plastic_sample(b.c0, b.c1, b.alpha.xy, wo, uc, u, s);
        break;
#endif
#ifndef CV_NO_HAIR
    case CV_MAT_HAIR:
        ok = cv_hair_sample(cv_bsdf_hair(b), wo, uc, u, s);
        break;
#endif
#ifndef CV_NO_MEASURED
    case CV_MAT_MEASURED:
        ok = cv_measured_sample(uint(b.walk.x), wo, u, s);
        break;
#endif
    default:
        break;
    }
#endif
    return ok;
}

// Whether b is evaluated by the coated walk (layered.glsl): a coated
// material that does not take the closed form. CV_NO_LAYERED (the shade
// bins that never meet one: shade.comp) leaves the walk's code out.
bool cv_bsdf_walks(CvBsdf b)
{
#if defined(CV_NO_LAYERED) || defined(CV_BSDF_DIFFUSE_ONLY)
    return false;
#else
    uint t = CV_BSDF_TYPE(b);
    return (t == CV_MAT_COATED_DIFFUSE || t == CV_MAT_COATED_CONDUCTOR) && !cv_bsdf_coat_closed(b);
#endif
}

// The steps of a query (cv_bsdf_query), one estimate each.
#define CV_BQ_STEP_F0 1u
#define CV_BQ_STEP_PDF0 2u
#define CV_BQ_STEP_SAMPLE 3u
#define CV_BQ_STEP_RESTATE 4u   // the pdf at the sample's direction
#define CV_BQ_STEP_F1 5u
#define CV_BQ_STEP_PDF1 6u

// The step a query with `ask` takes at slot k, and the slot of f at wi1
// (its pdf's is the next). The slots line up the warp's invocations: with
// a coated walk each step is a walk, and a warp runs a slot's walks side
// by side but its slots one after another, so an invocation that samples
// (the BSDF's bounce) and one that evaluates wi1 instead (a guided bounce)
// take the same slots 2 and 3. Only a query that asks for both (a guided
// bounce that lets the BSDF pick a delta lobe) needs more. Only kernels
// that define CV_BQ_WI1 (rlpath's shade stages, the BSDF tests' probe) ask
// at wi1; the others keep the steps in order, which costs path's coated
// walk nothing.
uint cv_bsdf_query_step(uint ask, int k)
{
#ifndef CV_BQ_WI1
    return uint(k) + 1u;   // nothing at wi1: the slots are the steps in order
#else
    bool s = (ask & CV_BQ_SAMPLE) != 0u, w1 = (ask & (CV_BQ_F1 | CV_BQ_PDF1)) != 0u;
    bool delta_only = (ask & CV_BQ_DELTA_ONLY) != 0u;
    if (k < 2)
        return k == 0 ? CV_BQ_STEP_F0 : CV_BQ_STEP_PDF0;
    if (!s)
        return k == 2 ? CV_BQ_STEP_F1 : CV_BQ_STEP_PDF1;
    if (k == 2)
        return CV_BQ_STEP_SAMPLE;
    if (!w1 || (k == 3 && !delta_only))
        return CV_BQ_STEP_RESTATE;
    return k == (delta_only ? 3 : 4) ? CV_BQ_STEP_F1 : CV_BQ_STEP_PDF1;
#endif
}

int cv_bsdf_query_slot_f1(uint ask)
{
    return (ask & CV_BQ_SAMPLE) == 0u ? 2 : ((ask & CV_BQ_DELTA_ONLY) != 0u ? 3 : 4);
}

// Answers q (bsdf_query.glsl): every BSDF function a vertex needs, from this
// one call site, so that each lobe's code is inlined once per kernel (the
// coated walk's once per estimator: layered.glsl). The steps run in one loop
// over slots (cv_bsdf_query_step): f and pdf at wi0, the sample and the pdf
// at its direction, which restates a coated walk's proportional pdf as
// pbrt-v4's LayeredBxDF::Sample does, f and pdf at wi1. Every estimate
// hashes its own directions and numbers, so the slots' order changes no
// answer.
void cv_bsdf_query(CvBsdf b, inout CvBsdfQuery q)
{
    q.f0 = vec3(0.0);
    q.f1 = vec3(0.0);
    q.pdf0 = 0.0;
    q.pdf1 = 0.0;
    q.sampled = false;
    q.s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    uint ask = q.ask;
    bool gate0 = (ask & CV_BQ_GATE0) != 0u, gate1 = (ask & CV_BQ_GATE1) != 0u;
    vec3 wo = cv_to_local(b.frame, q.wo);
    bool flip = cv_bsdf_mirrored(b) && wo.z < 0.0;
    if (flip)
        wo.z = -wo.z;
#ifdef CV_BSDF_DIFFUSE_ONLY
    // one small lobe: straight on, without the loop's bookkeeping
    vec3 wi0 = cv_to_local(b.frame, q.wi0), wi1 = cv_to_local(b.frame, q.wi1);
    if ((ask & CV_BQ_F0) != 0u)
        q.f0 = cv_bsdf_f_local(b, wo, wi0);
    if ((ask & CV_BQ_PDF0) != 0u && (!gate0 || (ask & CV_BQ_F0) == 0u || cv_max3(q.f0) > 0.0))
        q.pdf0 = cv_bsdf_pdf_local(b, wo, wi0);
    if ((ask & CV_BQ_SAMPLE) != 0u)
        q.sampled = cv_bsdf_sample_local(b, wo, q.uc, q.u, q.s);
    if ((ask & CV_BQ_F1) != 0u)
        q.f1 = cv_bsdf_f_local(b, wo, wi1);
    if ((ask & CV_BQ_PDF1) != 0u && (!gate1 || (ask & CV_BQ_F1) == 0u || cv_max3(q.f1) > 0.0))
        q.pdf1 = cv_bsdf_pdf_local(b, wo, wi1);
#else
    bool walks = cv_bsdf_walks(b);
    // todo: the slots still to run (bit k: slot k); the restated pdf's
    // joins once a walk's sample needs it, a gated pdf's leaves where its
    // f is 0
    int f1_slot = cv_bsdf_query_slot_f1(ask);
    uint todo = ask & (CV_BQ_F0 | CV_BQ_PDF0 | CV_BQ_SAMPLE);   // their bits are slots 0-2
#ifdef CV_BQ_WI1
    if ((ask & CV_BQ_F1) != 0u)
        todo |= 1u << uint(f1_slot);
    if ((ask & CV_BQ_PDF1) != 0u)
        todo |= 2u << uint(f1_slot);
#endif
    // k is every invocation's same slot, so a warp's invocations stay
    // together (those with nothing to do at slot k skip it) and the
    // bound, known only at run time, keeps the compiler from copying the
    // body
    for (int k = 0; k <= findMSB(todo); k++) {
        if ((todo & (1u << uint(k))) == 0u)
            continue;
        uint step = cv_bsdf_query_step(ask, k);
        vec3 wi = q.s.wi;  // the restated pdf's: local and mirrored already
        if (step != CV_BQ_STEP_SAMPLE && step != CV_BQ_STEP_RESTATE) {
            wi = cv_to_local(b.frame, step <= CV_BQ_STEP_PDF0 ? q.wi0 : q.wi1);
            if (flip)
                wi.z = -wi.z;
        }
        uint mode = step == CV_BQ_STEP_SAMPLE ? CV_LAY_MODE_WALK
                    : (step == CV_BQ_STEP_F0 || step == CV_BQ_STEP_F1 ? CV_LAY_MODE_F : CV_LAY_MODE_PDF);
        vec3 f = vec3(0.0);
        float pdf = 0.0;
        CvBsdfSample s;
        bool ok = false;
#if !defined(CV_NO_LAYERED) && !defined(CV_BSDF_DIFFUSE_ONLY)
        if (walks)
            ok = cv_layered_estimate(cv_bsdf_layered(b), mode, wo, wi, q.uc, q.u, f, pdf, s);
        else
#endif
        if (mode == CV_LAY_MODE_F)
            f = cv_bsdf_f_local(b, wo, wi);
        else if (mode == CV_LAY_MODE_PDF)
            pdf = cv_bsdf_pdf_local(b, wo, wi);
        else
            ok = cv_bsdf_sample_local(b, wo, q.uc, q.u, s);
        if (step == CV_BQ_STEP_F0) {
            q.f0 = f;
            if (gate0 && !(cv_max3(f) > 0.0))
                todo &= ~CV_BQ_PDF0;
        } else if (step == CV_BQ_STEP_PDF0) {
            q.pdf0 = pdf;
        } else if (step == CV_BQ_STEP_SAMPLE) {
            q.sampled = ok;
            q.s = s;
            if (ok && walks && (s.flags & CV_BSDF_SPECULAR) == 0u && (ask & CV_BQ_DELTA_ONLY) == 0u)
                todo |= 8u;   // slot 3
        } else if (step == CV_BQ_STEP_RESTATE) {
            q.s.f *= pdf / q.s.pdf;
            q.s.pdf = pdf;
        } else if (step == CV_BQ_STEP_F1) {
            q.f1 = f;
            if (gate1 && !(cv_max3(f) > 0.0))
                todo &= ~(2u << uint(f1_slot));
        } else {
            q.pdf1 = pdf;
        }
    }
#endif
    if (q.sampled && (!(q.s.pdf > 0.0) || any(isnan(q.s.f)) || any(isinf(q.s.f))))
        q.sampled = false;
    if (q.sampled) {
        if (flip)
            q.s.wi.z = -q.s.wi.z;
        q.s.wi = normalize(cv_from_local(b.frame, q.s.wi));
    }
}

// One answer each, for code that asks for one thing (tests): every call
// is a copy of cv_bsdf_query, so shade stages ask through one query.
vec3 cv_bsdf_f(CvBsdf b, vec3 wo, vec3 wi)
{
    CvBsdfQuery q = cv_bsdf_query_new(wo);
    q.ask = CV_BQ_F0;
    q.wi0 = wi;
    cv_bsdf_query(b, q);
    return q.f0;
}

float cv_bsdf_pdf(CvBsdf b, vec3 wo, vec3 wi)
{
    CvBsdfQuery q = cv_bsdf_query_new(wo);
    q.ask = CV_BQ_PDF0;
    q.wi0 = wi;
    cv_bsdf_query(b, q);
    return q.pdf0;
}

// uc picks a lobe, u places the direction. s.wi is in world space.
bool cv_bsdf_sample(CvBsdf b, vec3 wo_world, float uc, vec2 u, out CvBsdfSample s)
{
    CvBsdfQuery q = cv_bsdf_query_new(wo_world);
    q.ask = CV_BQ_SAMPLE;
    q.uc = uc;
    q.u = u;
    cv_bsdf_query(b, q);
    s = q.s;
    return q.sampled;
}

bool cv_bsdf_is_delta(CvBsdf b)
{
#ifdef CV_BSDF_DIFFUSE_ONLY
    return false;
#else
#ifdef CV_BSDF_ANY_TYPE
    if (b.type == CV_MAT_MIRROR || b.type == CV_MAT_THIN_DIELECTRIC)
        return true;
    if (b.type == CV_MAT_CONDUCTOR)
        return cv_mf_smooth(b.alpha.xy);
    if (b.type == CV_MAT_DIELECTRIC || b.type == CV_MAT_SUBSURFACE)
        return cv_dielectric_is_delta(b.eta, b.alpha.xy);
#endif
    if (b.type == CV_MAT_COATED_CONDUCTOR)
        return cv_layered_delta_prob(cv_bsdf_layered(b), vec3(0.0, 0.0, 1.0)) == 1.0;
    return false;
#endif
}

// Probability that cv_bsdf_sample, seen from wo_world, picks a delta lobe
// (a sample flagged CV_BSDF_SPECULAR): 1 where cv_bsdf_is_delta, 0 where
// the BSDF has no delta lobe, between for a smooth coat over a rough base
// (or a rough coat over a smooth conductor). Which lobe a sample takes
// depends on uc alone, never on u: rlpath/shade.comp relies on both.
float cv_bsdf_delta_prob(CvBsdf b, vec3 wo_world)
{
#ifdef CV_BSDF_DIFFUSE_ONLY
    return 0.0;
#else
    if (cv_bsdf_is_delta(b))
        return 1.0;
    vec3 wo = cv_to_local(b.frame, wo_world);
    if (cv_bsdf_mirrored(b))
        wo.z = abs(wo.z);
    if (wo.z <= 0.0)
        return 0.0;
    if (cv_bsdf_coat_closed(b))
        return cv_mf_smooth(b.alpha.xy) ? cv_coat_closed_spec_prob(cv_bsdf_coat_closed_params(b), wo) : 0.0;
    if (b.type == CV_MAT_COATED_DIFFUSE || b.type == CV_MAT_COATED_CONDUCTOR)
        return cv_layered_delta_prob(cv_bsdf_layered(b), wo);
#ifdef CV_BSDF_ANY_TYPE
    if (b.type == CV_MAT_PLASTIC)
        return cv_mf_smooth(b.alpha.xy) ? cv_plastic_ps(b.c0, b.c1) : 0.0;
#endif
    return 0.0;
#endif
}

// Surface colour for the albedo AOV.
vec3 cv_bsdf_albedo(CvBsdf b)
{
    switch (CV_BSDF_TYPE(b)) {
    case CV_MAT_COATED_DIFFUSE:
        return b.c0;
    case CV_MAT_COATED_CONDUCTOR:
        return cv_fr_complex(1.0, b.c0, b.c1);
#if !defined(CV_BSDF_WALK_ONLY)
    case CV_MAT_DIFFUSE:
        return b.c0;
#endif
#ifdef CV_BSDF_ANY_TYPE
    case CV_MAT_CONDUCTOR:
        return cv_fr_complex(1.0, b.c0, b.c1);
    case CV_MAT_DIELECTRIC:
    case CV_MAT_SUBSURFACE:
        return b.c1;
    case CV_MAT_THIN_DIELECTRIC:
        return vec3(1.0);
    case CV_MAT_MIRROR:
        return b.c0;
    case CV_MAT_DIFFUSE_TRANSMISSION:
        return clamp(b.c0 + b.c1, 0.0, 1.0);
    case CV_MAT_PLASTIC:
        return clamp(b.c0 + b.c1, 0.0, 1.0);
#endif
#ifndef CV_NO_HAIR
    case CV_MAT_HAIR:
        return exp(-2.0 * b.c0);  // straight through the fibre (h 0, theta 0): its colour
#endif
#ifndef CV_NO_MEASURED
    case CV_MAT_MEASURED:
        return cv_measured_albedo(uint(b.walk.x));
#endif
    default:
        return vec3(0.0);
    }
}

// Alpha cut-outs (pbrt-v4: a stochastic test against u for 0 < alpha < 1)
// and interface materials: true = the ray continues through the surface.
bool cv_material_alpha_pass(uint material, vec2 uv, float u)
{
    if (materials[material].type == CV_MAT_INTERFACE)
        return true;
    float a = cv_material_alpha(material, uv);
    if (a >= 1.0)
        return false;
    if (a <= 0.0)
        return true;
    return u >= a;
}

#endif
