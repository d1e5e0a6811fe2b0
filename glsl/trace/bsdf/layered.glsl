// glsl/trace/bsdf/layered.glsl: coateddiffuse and coatedconductor as
// pbrt-v4's LayeredBxDF (two-sided, dielectric coat on top, diffuse or
// conductor base at the bottom, a homogeneous slab of unit density, given
// thickness, scattering albedo and Henyey-Greenstein g between them).
//
// f, the sample and the pdf are stochastic estimates, as pbrt-v4's: f is a
// random walk between the interfaces with next-event connections through
// the coat, averaged over n_samples walks of at most max_depth events (one
// deliberate difference: the MIS weights of the exits through a rough coat,
// cv_lay_exit_pdf); the
// sample follows one walk out (its f / pdf is the walk's weight); the pdf is
// an estimate of the TRT lobe mixed with a uniform sphere term (as
// pbrt-v4's, it leaves out the refraction Jacobians, so it integrates to
// more than 1: it only weights MIS, and samples keep their walk's f / pdf
// ratio). Each
// estimate draws from its own stream, a hash of the per-shade key (CvLayered
// .key, from the shade stage's sampler) and the directions involved, so one
// seed renders one image.
//
// Local frame, wo on +z (bsdf.glsl mirrors both directions when wo is
// below). Cost class: O(n_samples * max_depth) interface evaluations per
// call, where the closed forms were O(1).
#ifndef CV_BSDF_LAYERED_GLSL
#define CV_BSDF_LAYERED_GLSL

#include "../../lib/constants.glsl"
#include "../../lib/frame.glsl"
#include "../../lib/rng.glsl"
#include "../../lib/sampling.glsl"
#include "fresnel.glsl"
#include "microfacet.glsl"
#include "conductor.glsl"
#include "dielectric.glsl"
#include "diffuse.glsl"
#include "bsdf_sample.glsl"

struct CvLayered {
    float eta;        // coat IOR (outside 1)
    vec2 coat_alpha;  // coat roughness
    bool conductor;   // base: conductor (c0 eta, c1 k, relative to the coat) or diffuse (c0 = R)
    vec3 c0;
    vec3 c1;
    vec2 base_alpha;
    float thickness;
    vec3 albedo;      // slab single-scattering albedo (0: no medium, transmittance only)
    float g;          // Henyey-Greenstein asymmetry
    int max_depth;
    int n_samples;
    uint key;         // per-shade stream key
};

// Sample restriction masks for the interfaces (pbrt's BxDFReflTransFlags).
#define CV_LAY_R CV_BSDF_REFLECTION
#define CV_LAY_T CV_BSDF_TRANSMISSION
#define CV_LAY_RT (CV_BSDF_REFLECTION | CV_BSDF_TRANSMISSION)

bool cv_lay_has_medium(CvLayered L) { return cv_max3(L.albedo) > 0.0; }
bool cv_lay_coat_smooth(CvLayered L) { return cv_mf_smooth(L.coat_alpha); }
bool cv_lay_base_smooth(CvLayered L) { return L.conductor && cv_mf_smooth(L.base_alpha); }

// Transmittance of the slab (unit density) over height dz along w.
float cv_lay_tr(float dz, vec3 w)
{
    if (abs(dz) <= 1.17549435e-38)
        return 1.0;
    return exp(-abs(dz / w.z));
}

uint cv_lay_dir_hash(vec3 w) { return cv_hash3(floatBitsToUint(w.x), floatBitsToUint(w.y), floatBitsToUint(w.z)); }

float cv_lay_next(inout CvRng r) { return min(cv_rng_next(r), CV_ONE_MINUS_EPS); }
vec2 cv_lay_next2(inout CvRng r)
{
    float x = cv_lay_next(r);
    return vec2(x, cv_lay_next(r));
}

// ---- Henyey-Greenstein, directions pointing away from the scattering point
float cv_lay_hg(float cos_t, float g)
{
    float d = 1.0 + g * g + 2.0 * g * cos_t;
    return CV_INV_4PI * (1.0 - g * g) / (d * cv_safe_sqrt(d));
}

// Draws wi for light arriving along -wo; pdf = phase value.
vec3 cv_lay_hg_sample(vec3 wo, float g, vec2 u, out float pdf)
{
    // cos_s: cosine of the deflection from the travel direction -wo
    float cos_s;
    if (abs(g) < 1e-3) {
        cos_s = 1.0 - 2.0 * u.x;
    } else {
        float t = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
        cos_s = (1.0 + g * g - t * t) / (2.0 * g);
    }
    cos_s = clamp(cos_s, -1.0, 1.0);
    float sin_s = cv_safe_sqrt(1.0 - cos_s * cos_s);
    float phi = 2.0 * CV_PI * u.y;
    CvFrame fr = cv_frame_from_z(-wo);
    vec3 wi = cv_from_local(fr, vec3(sin_s * cos(phi), sin_s * sin(phi), cos_s));
    pdf = cv_lay_hg(dot(wo, wi), g);
    return wi;
}

float cv_lay_power(float f, float g) { return f * f / (f * f + g * g); }

// ---- the coat: a dielectric of IOR eta seen from either side. radiance:
// transport mode (radiance divides transmission by eta'^2, importance not).
float cv_lay_coat_f(CvLayered L, vec3 wo, vec3 wi, bool radiance)
{
    if (cv_lay_coat_smooth(L) || L.eta == 1.0)
        return 0.0;
    float co = wo.z, ci = wi.z, etap;
    vec3 wm;
    bool refl;
    if (!cv_dielectric_half(L.eta, wo, wi, wm, etap, refl))
        return 0.0;
    float F = cv_fr_dielectric(dot(wo, wm), L.eta);
    vec2 a = L.coat_alpha;
    if (refl)
        return cv_mf_D(a, wm) * cv_mf_G(a, wo, wi) * F / abs(4.0 * ci * co);
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap) * ci * co;
    float ft = cv_mf_D(a, wm) * (1.0 - F) * cv_mf_G(a, wo, wi) * abs(dot(wi, wm) * dot(wo, wm) / denom);
    return radiance ? ft / (etap * etap) : ft;
}

float cv_lay_coat_pdf(CvLayered L, vec3 wo, vec3 wi, uint mask)
{
    if (cv_lay_coat_smooth(L) || L.eta == 1.0)
        return 0.0;
    float etap;
    vec3 wm;
    bool refl;
    if (!cv_dielectric_half(L.eta, wo, wi, wm, etap, refl))
        return 0.0;
    float R = cv_fr_dielectric(dot(wo, wm), L.eta);
    float pr = (mask & CV_LAY_R) != 0u ? R : 0.0;
    float pt = (mask & CV_LAY_T) != 0u ? 1.0 - R : 0.0;
    if (pr == 0.0 && pt == 0.0)
        return 0.0;
    vec2 a = L.coat_alpha;
    if (refl)
        return cv_mf_pdf(a, wo, wm) / (4.0 * abs(dot(wo, wm))) * pr / (pr + pt);
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap);
    return cv_mf_pdf(a, wo, wm) * abs(dot(wi, wm)) / denom * pt / (pr + pt);
}

// f is colourless: returned in s.f.x.
bool cv_lay_coat_sample(CvLayered L, vec3 wo, float uc, vec2 u, bool radiance, uint mask, out CvBsdfSample s)
{
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    if (wo.z == 0.0)
        return false;
    if (cv_lay_coat_smooth(L) || L.eta == 1.0) {
        float R = L.eta == 1.0 ? 0.0 : cv_fr_dielectric(wo.z, L.eta);
        float pr = (mask & CV_LAY_R) != 0u ? R : 0.0;
        float pt = (mask & CV_LAY_T) != 0u ? 1.0 - R : 0.0;
        if (pr == 0.0 && pt == 0.0)
            return false;
        if (uc < pr / (pr + pt)) {
            vec3 wi = vec3(-wo.xy, wo.z);
            s = CvBsdfSample(wi, vec3(R / abs(wi.z)), pr / (pr + pt), CV_BSDF_REFLECTION | CV_BSDF_SPECULAR);
            return true;
        }
        float etap;
        vec3 wi;
        if (!cv_refract(wo, vec3(0.0, 0.0, 1.0), L.eta, etap, wi))
            return false;
        float ft = (1.0 - R) / abs(wi.z);
        if (radiance)
            ft /= etap * etap;
        s = CvBsdfSample(wi, vec3(ft), pt / (pr + pt), CV_BSDF_TRANSMISSION | CV_BSDF_SPECULAR);
        return true;
    }
    vec2 a = L.coat_alpha;
    vec3 wm = cv_mf_sample_wm(a, wo, u);
    float R = cv_fr_dielectric(dot(wo, wm), L.eta);
    float pr = (mask & CV_LAY_R) != 0u ? R : 0.0;
    float pt = (mask & CV_LAY_T) != 0u ? 1.0 - R : 0.0;
    if (pr == 0.0 && pt == 0.0)
        return false;
    if (uc < pr / (pr + pt)) {
        vec3 wi = reflect(-wo, wm);
        if (!cv_same_hemisphere(wo, wi))
            return false;
        float pdf = cv_mf_pdf(a, wo, wm) / (4.0 * abs(dot(wo, wm))) * pr / (pr + pt);
        float f = cv_mf_D(a, wm) * cv_mf_G(a, wo, wi) * R / (4.0 * abs(wi.z * wo.z));
        s = CvBsdfSample(wi, vec3(f), pdf, CV_BSDF_REFLECTION);
        return pdf > 0.0;
    }
    float etap;
    vec3 wi;
    if (!cv_refract(wo, wm, L.eta, etap, wi) || cv_same_hemisphere(wo, wi) || wi.z == 0.0)
        return false;
    float denom = cv_sqr(dot(wi, wm) + dot(wo, wm) / etap);
    float pdf = cv_mf_pdf(a, wo, wm) * abs(dot(wi, wm)) / denom * pt / (pr + pt);
    float ft = (1.0 - R) * cv_mf_D(a, wm) * cv_mf_G(a, wo, wi) *
               abs(dot(wi, wm) * dot(wo, wm) / (wi.z * wo.z * denom));
    if (radiance)
        ft /= etap * etap;
    s = CvBsdfSample(wi, vec3(ft), pdf, CV_BSDF_TRANSMISSION);
    return pdf > 0.0;
}

// ---- the base: reflection only, seen from above (wo.z > 0)
vec3 cv_lay_base_f(CvLayered L, vec3 wo, vec3 wi)
{
    return L.conductor ? cv_conductor_f(L.base_alpha, L.c0, L.c1, wo, wi) : cv_diffuse_f(L.c0, wo, wi);
}

float cv_lay_base_pdf(CvLayered L, vec3 wo, vec3 wi)
{
    return L.conductor ? cv_conductor_pdf(L.base_alpha, wo, wi) : cv_diffuse_pdf(wo, wi);
}

bool cv_lay_base_sample(CvLayered L, vec3 wo, vec2 u, out CvBsdfSample s)
{
    return L.conductor ? cv_conductor_sample(L.base_alpha, L.c0, L.c1, wo, u, s) : cv_diffuse_sample(L.c0, wo, u, s);
}

// MIS weight partner of the connections out through a rough coat: the
// density with which the other strategy (wis, drawn from wi) makes the
// upward direction w inside the slab, i.e. the coat's transmission pdf
// from wi to -w. pbrt-v4 uses the reverse density (from -w to wi, measured
// outside) here, so its two weights for one path do not sum to 1 and its
// f overshoots its own sampler (and the physics) under a rough coat, by
// how much bsdf_layered_test measures; under a smooth coat the two agree.
float cv_lay_exit_pdf(CvLayered L, vec3 w, vec3 wi) { return cv_lay_coat_pdf(L, wi, -w, CV_LAY_T); }

bool cv_lay_ok(CvBsdfSample s) { return cv_max3(s.f) > 0.0 && s.pdf > 0.0 && s.wi.z != 0.0; }

// ---- the layered BSDF
// Probability that cv_layered_sample returns a delta sample from wo.
float cv_layered_delta_prob(CvLayered L, vec3 wo)
{
    if (!cv_lay_coat_smooth(L))
        return 0.0;
    if (cv_lay_base_smooth(L) && !cv_lay_has_medium(L))
        return 1.0;
    return L.eta == 1.0 ? 0.0 : cv_fr_dielectric(wo.z, L.eta);
}

vec3 cv_layered_f(CvLayered L, vec3 wo, vec3 wi)
{
    if (!(wi.z > 0.0) || !(wo.z > 0.0))
        return vec3(0.0);  // the base transmits nothing
    if (cv_layered_delta_prob(L, wo) == 1.0)
        return vec3(0.0);  // the one exact shortcut: all delta (every walk adds 0)
    float n = float(L.n_samples);
    vec3 f = vec3(n * cv_lay_coat_f(L, wo, wi, true));
    CvRng rng = cv_rng_init(cv_hash2(L.key, cv_lay_dir_hash(wo)), cv_lay_dir_hash(wi));
    bool coat_smooth = cv_lay_coat_smooth(L), base_smooth = cv_lay_base_smooth(L);
    bool medium = cv_lay_has_medium(L);
    float th = L.thickness;
    for (int smp = 0; smp < L.n_samples; smp++) {
        // into the slab along wo, and the virtual light's way in along wi
        CvBsdfSample wos, wis;
        float uc = cv_lay_next(rng);
        if (!cv_lay_coat_sample(L, wo, uc, cv_lay_next2(rng), true, CV_LAY_T, wos) || !cv_lay_ok(wos))
            continue;
        uc = cv_lay_next(rng);
        if (!cv_lay_coat_sample(L, wi, uc, cv_lay_next2(rng), false, CV_LAY_T, wis) || !cv_lay_ok(wis))
            continue;
        vec3 beta = wos.f * abs(wos.wi.z) / wos.pdf;
        float z = th;
        vec3 w = wos.wi;
        for (int depth = 0; depth < L.max_depth; depth++) {
            if (depth > 3 && cv_max3(beta) < 0.25) {
                float q = max(0.0, 1.0 - cv_max3(beta));
                if (cv_lay_next(rng) < q)
                    break;
                beta /= 1.0 - q;
            }
            if (!medium) {
                z = (z == th) ? 0.0 : th;
                beta *= cv_lay_tr(th, w);
            } else {
                float dz = -log(1.0 - cv_lay_next(rng)) * abs(w.z);
                float zp = w.z > 0.0 ? z + dz : z - dz;
                if (zp == z)
                    continue;
                if (0.0 < zp && zp < th) {
                    // scattering in the slab: connect to wi through the coat, then
                    // follow the phase function (and connect that direction too)
                    float ph = cv_lay_hg(dot(-w, -wis.wi), L.g);
                    float wt = coat_smooth ? 1.0 : cv_lay_power(wis.pdf, ph);
                    f += beta * L.albedo * ph * wt * cv_lay_tr(zp - th, wis.wi) * wis.f / wis.pdf;
                    float ppdf;
                    vec3 wn = cv_lay_hg_sample(-w, L.g, cv_lay_next2(rng), ppdf);
                    if (!(ppdf > 0.0) || wn.z == 0.0)
                        continue;
                    beta *= L.albedo;
                    w = wn;
                    z = zp;
                    if (w.z > 0.0 && !coat_smooth) {
                        float fe = cv_lay_coat_f(L, -w, wi, true);
                        if (fe > 0.0) {
                            float wt2 = cv_lay_power(ppdf, cv_lay_exit_pdf(L, w, wi));
                            f += beta * cv_lay_tr(zp - th, w) * fe * wt2;
                        }
                    }
                    continue;
                }
                z = clamp(zp, 0.0, th);
            }
            CvBsdfSample bs;
            if (z == th) {
                // back down off the coat's underside
                uc = cv_lay_next(rng);
                if (!cv_lay_coat_sample(L, -w, uc, cv_lay_next2(rng), true, CV_LAY_R, bs) || !cv_lay_ok(bs))
                    break;
                beta *= bs.f * abs(bs.wi.z) / bs.pdf;
                w = bs.wi;
            } else {
                if (!base_smooth) {
                    // next event: the base towards wis
                    float wt = coat_smooth ? 1.0 : cv_lay_power(wis.pdf, cv_lay_base_pdf(L, -w, -wis.wi));
                    f += beta * cv_lay_base_f(L, -w, -wis.wi) * abs(wis.wi.z) * wt * cv_lay_tr(th, wis.wi) *
                         wis.f / wis.pdf;
                }
                uc = cv_lay_next(rng);
                if (!cv_lay_base_sample(L, -w, cv_lay_next2(rng), bs) || !cv_lay_ok(bs))
                    break;
                beta *= bs.f * abs(bs.wi.z) / bs.pdf;
                w = bs.wi;
                if (!coat_smooth) {
                    // next event: the sampled direction out through the coat
                    float fe = cv_lay_coat_f(L, -w, wi, true);
                    if (fe > 0.0) {
                        float wt = base_smooth ? 1.0 : cv_lay_power(bs.pdf, cv_lay_exit_pdf(L, w, wi));
                        f += beta * cv_lay_tr(th, bs.wi) * fe * wt;
                    }
                }
            }
        }
    }
    return f / n;
}

float cv_layered_pdf(CvLayered L, vec3 wo, vec3 wi)
{
    float sum = 0.0;
    if (wo.z > 0.0 && wi.z > 0.0 && cv_layered_delta_prob(L, wo) < 1.0) {
        float n = float(L.n_samples);
        sum = n * cv_lay_coat_pdf(L, wo, wi, CV_LAY_R);
        CvRng rng = cv_rng_init(cv_hash2(L.key, cv_lay_dir_hash(wi)), cv_lay_dir_hash(wo));
        bool coat_smooth = cv_lay_coat_smooth(L), base_smooth = cv_lay_base_smooth(L);
        for (int smp = 0; smp < L.n_samples; smp++) {
            // transmission in, reflection at the base, transmission out
            CvBsdfSample wos, wis, rs;
            float uc = cv_lay_next(rng);
            bool a = cv_lay_coat_sample(L, wo, uc, cv_lay_next2(rng), true, CV_LAY_T, wos);
            uc = cv_lay_next(rng);
            bool b = cv_lay_coat_sample(L, wi, uc, cv_lay_next2(rng), false, CV_LAY_T, wis);
            if (!(a && b && cv_max3(wos.f) > 0.0 && wos.pdf > 0.0 && cv_max3(wis.f) > 0.0 && wis.pdf > 0.0))
                continue;
            if (coat_smooth) {
                sum += cv_lay_base_pdf(L, -wos.wi, -wis.wi);
                continue;
            }
            uc = cv_lay_next(rng);
            if (!cv_lay_base_sample(L, -wos.wi, cv_lay_next2(rng), rs) || !(cv_max3(rs.f) > 0.0 && rs.pdf > 0.0))
                continue;
            if (base_smooth) {
                sum += cv_lay_coat_pdf(L, -rs.wi, wi, CV_LAY_RT);
            } else {
                float rpdf = cv_lay_base_pdf(L, -wos.wi, -wis.wi);
                sum += cv_lay_power(wis.pdf, rpdf) * rpdf;
                float tpdf = cv_lay_coat_pdf(L, -rs.wi, wi, CV_LAY_RT);
                sum += cv_lay_power(rs.pdf, tpdf) * tpdf;
            }
        }
        sum /= n;
    }
    // (transmission: the base passes nothing, the estimate is 0)
    return mix(CV_INV_4PI, sum, 0.9);
}

// One walk out of the layers. s.pdf is the walk's pdf, proportional to the
// true density only (pbrt-v4's pdfIsProportional): cv_layered_sample below
// restates a non-delta sample with the pdf estimate.
bool cv_layered_walk(CvLayered L, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    if (!cv_lay_coat_sample(L, wo, uc, u, true, CV_LAY_RT, s) || !cv_lay_ok(s))
        return false;
    if ((s.flags & CV_BSDF_REFLECTION) != 0u)
        return true;
    vec3 w = s.wi;
    bool specular = (s.flags & CV_BSDF_SPECULAR) != 0u;
    CvRng rng = cv_rng_init(cv_hash2(L.key, cv_lay_dir_hash(wo)),
                            cv_hash3(floatBitsToUint(uc), floatBitsToUint(u.x), floatBitsToUint(u.y)));
    vec3 f = s.f * abs(s.wi.z);
    float pdf = s.pdf;
    float th = L.thickness, z = th;
    bool medium = cv_lay_has_medium(L);
    for (int depth = 0; depth < L.max_depth; depth++) {
        float rr = cv_max3(f) / pdf;
        if (depth > 3 && rr < 0.25) {
            float q = max(0.0, 1.0 - rr);
            if (cv_lay_next(rng) < q)
                return false;
            pdf *= 1.0 - q;
        }
        if (w.z == 0.0)
            return false;
        if (medium) {
            float dz = -log(1.0 - cv_lay_next(rng)) * abs(w.z);
            float zp = w.z > 0.0 ? z + dz : z - dz;
            if (zp == z)
                return false;
            if (0.0 < zp && zp < th) {
                float ppdf;
                vec3 wn = cv_lay_hg_sample(-w, L.g, cv_lay_next2(rng), ppdf);
                if (!(ppdf > 0.0) || wn.z == 0.0)
                    return false;
                f *= L.albedo * ppdf;
                pdf *= ppdf;
                specular = false;
                w = wn;
                z = zp;
                continue;
            }
            z = clamp(zp, 0.0, th);
        } else {
            z = (z == th) ? 0.0 : th;
            f *= cv_lay_tr(th, w);
        }
        CvBsdfSample bs;
        float uci = cv_lay_next(rng);
        vec2 ui = cv_lay_next2(rng);
        bool ok = z == 0.0 ? cv_lay_base_sample(L, -w, ui, bs) : cv_lay_coat_sample(L, -w, uci, ui, true, CV_LAY_RT, bs);
        if (!ok || !cv_lay_ok(bs))
            return false;
        f *= bs.f;
        pdf *= bs.pdf;
        specular = specular && (bs.flags & CV_BSDF_SPECULAR) != 0u;
        w = bs.wi;
        if ((bs.flags & CV_BSDF_TRANSMISSION) != 0u) {
            uint flags = (w.z > 0.0 ? CV_BSDF_REFLECTION : CV_BSDF_TRANSMISSION) | (specular ? CV_BSDF_SPECULAR : 0u);
            s = CvBsdfSample(w, f, pdf, flags);
            return true;
        }
        f *= abs(bs.wi.z);
    }
    return false;
}

bool cv_layered_sample(CvLayered L, vec3 wo, float uc, vec2 u, out CvBsdfSample s)
{
    if (!cv_layered_walk(L, wo, uc, u, s))
        return false;
    if ((s.flags & CV_BSDF_SPECULAR) == 0u) {
        float p = cv_layered_pdf(L, wo, s.wi);
        s.f *= p / s.pdf;
        s.pdf = p;
    }
    return true;
}

#endif
