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
// The three estimators are one loop (cv_layered_run), written once and
// reached from one call site per kernel (bsdf.glsl: cv_bsdf_query), which
// asks it once per mode with the mode a constant (cv_layered_estimate):
// compilers inline every call, and the walk's copies were most of a shade
// kernel's build time, so a kernel holds three folded copies, no more
// (tests/trace/bsdf_sites_test counts them).
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
// Probability that a walk (cv_layered_run, CV_LAY_MODE_WALK) from wo returns a
// delta sample.
float cv_layered_delta_prob(CvLayered L, vec3 wo)
{
    if (!cv_lay_coat_smooth(L))
        return 0.0;
    if (cv_lay_base_smooth(L) && !cv_lay_has_medium(L))
        return 1.0;
    return L.eta == 1.0 ? 0.0 : cv_fr_dielectric(wo.z, L.eta);
}

// What cv_layered_run estimates.
#define CV_LAY_MODE_F 0u     // f(wo, wi): walks from both ends with next-event connections
#define CV_LAY_MODE_PDF 1u   // the pdf of wi: the TRT lobe's estimate mixed with a uniform term
#define CV_LAY_MODE_WALK 2u  // one walk out from wo, its first event at the coat drawn with (uc, u)

// Where a walk stands (cv_layered_run).
#define CV_LAY_AT_ENTER_O 0  // the next event: into the slab along wo (WALK: the first event)
#define CV_LAY_AT_ENTER_I 1  // the virtual light's way in along wi (F, PDF)
#define CV_LAY_AT_BASE 2     // PDF: the one reflection at the base
#define CV_LAY_AT_INSIDE 3   // F, WALK: events in the slab, `depth` of them so far

// A connection through the coat that the last event left (cv_layered_run).
#define CV_LAY_CONN_NONE 0
#define CV_LAY_CONN_TOP 1    // F: reflection off the coat, wo to wi; PDF: its density
#define CV_LAY_CONN_EXIT 2   // F: out along w through the coat towards wi
#define CV_LAY_CONN_BASE 3   // PDF: out through the coat after the base, w

// The layered BSDF's three estimators as one walk, so that a kernel holds
// one copy of the interfaces' code per mode however many estimates it asks
// for (GLSL compilers inline every call: bsdf.glsl's cv_bsdf_query calls
// this through cv_layered_estimate from one site). mode CV_LAY_MODE_F
// returns f(wo, wi) in f (0 where either direction is below, since the base
// transmits nothing); CV_LAY_MODE_PDF the pdf estimate in pdf;
// CV_LAY_MODE_WALK one walk out of the layers in s (false: the walk died),
// whose s.pdf is proportional to the density only (pbrt-v4's
// pdfIsProportional): a caller restates a non-delta sample with the pdf
// estimate. One iteration of the loop makes at most one event (an interface
// sample, or a scattering in the slab) and evaluates at most one connection
// through the coat, the one the event before left, in the same order of
// random numbers as pbrt-v4's three separate loops.
bool cv_layered_run(CvLayered L, uint mode, vec3 wo, vec3 wi, float uc0, vec2 u0, out vec3 f,
                    out float pdf, out CvBsdfSample s)
{
    bool fm = mode == CV_LAY_MODE_F, pm = mode == CV_LAY_MODE_PDF, walk = mode == CV_LAY_MODE_WALK;
    s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    bool coat_smooth = cv_lay_coat_smooth(L), base_smooth = cv_lay_base_smooth(L);
    bool medium = cv_lay_has_medium(L);
    float n = float(L.n_samples), th = L.thickness;
    // F and PDF hash both directions into their streams (in opposite
    // orders, so the two estimates stay independent); the walk its
    // direction and random numbers
    CvRng rng = cv_rng_init(cv_hash2(L.key, cv_lay_dir_hash(pm ? wi : wo)),
                            walk ? cv_hash3(floatBitsToUint(uc0), floatBitsToUint(u0.x), floatBitsToUint(u0.y))
                                 : cv_lay_dir_hash(pm ? wo : wi));
    vec3 fsum = vec3(0.0);  // F: the estimate's sum
    float psum = 0.0;       // PDF: the estimate's sum
    vec3 beta = vec3(0.0);  // F: throughput of the walk from wo; WALK: its f
    float wpdf = 1.0;       // WALK: its pdf
    bool specular = false;  // WALK: every event so far specular
    CvBsdfSample wos = s, wis = s, bs = s;
    bool wos_ok = false;
    vec3 w = vec3(0.0);     // the walk's direction of travel
    float z = th;
    int depth = 0, smp = 0, at = CV_LAY_AT_ENTER_O;
    int conn = CV_LAY_CONN_NONE;
    float conn_pdf = 0.0;       // the density of w's sampling, for the exit's MIS weight
    bool conn_weighted = true;  // EXIT: weigh it against the other strategy
    float rpdf = 0.0;           // PDF: the base's density towards wis
    // F and PDF only where both directions are above (the base transmits
    // nothing); the all-delta layers are the one exact shortcut (every walk
    // of F adds 0)
    bool live = walk || (wo.z > 0.0 && wi.z > 0.0 && cv_layered_delta_prob(L, wo) < 1.0);
    if (live && !walk)
        conn = CV_LAY_CONN_TOP;
    int bound = L.n_samples * (L.max_depth + 4) + 4;
    for (int it = 0; live && it < bound; it++) {
        // The connection the last event left: f through the coat (F) and
        // the coat's density the MIS weight or the pdf estimate needs.
        if (conn != CV_LAY_CONN_NONE) {
            vec3 ca = conn == CV_LAY_CONN_TOP ? wo : -w;
            float fe = fm ? cv_lay_coat_f(L, ca, wi, true) : 0.0;
            // exit: the density with which wis's strategy makes w (cv_lay_exit_pdf)
            bool exit = conn == CV_LAY_CONN_EXIT;
            float cp = 0.0;
            if (pm || (exit && fe > 0.0 && conn_weighted))
                cp = cv_lay_coat_pdf(L, exit ? wi : ca, exit ? -w : wi,
                                     conn == CV_LAY_CONN_TOP ? CV_LAY_R : (exit ? CV_LAY_T : CV_LAY_RT));
            if (conn == CV_LAY_CONN_TOP) {
                if (fm)
                    fsum = vec3(n * fe);
                else
                    psum = n * cp;
            } else if (exit) {
                if (fe > 0.0)
                    fsum += beta * cv_lay_tr(th - z, w) * fe * (conn_weighted ? cv_lay_power(conn_pdf, cp) : 1.0);
            } else if (base_smooth) {
                psum += cp;
            } else {
                psum += cv_lay_power(wis.pdf, rpdf) * rpdf;
                psum += cv_lay_power(conn_pdf, cp) * cp;
            }
            conn = CV_LAY_CONN_NONE;
        }

        // The next event: an interface (the coat from above or below, or
        // the base) seen from win, or a scattering in the slab.
        bool at_base = false, scatter = false, radiance = true, end = false;
        float zp = z;  // a scattering's height
        vec3 win = wo;
        uint mask = walk ? CV_LAY_RT : CV_LAY_T;
        float uc = uc0;
        vec2 u2 = u0;
        if (at == CV_LAY_AT_ENTER_O || at == CV_LAY_AT_ENTER_I) {
            if (!walk && smp == L.n_samples)
                break;
            radiance = at == CV_LAY_AT_ENTER_O;
            win = radiance ? wo : wi;
            if (!walk) {
                uc = cv_lay_next(rng);
                u2 = cv_lay_next2(rng);
            }
        } else if (at == CV_LAY_AT_BASE) {
            at_base = true;
            w = wos.wi;
            win = -w;
        } else {
            if (depth == L.max_depth || w.z == 0.0)
                end = true;
            if (!end && depth > 3) {
                // Russian roulette
                float rr = walk ? cv_max3(beta) / wpdf : cv_max3(beta);
                if (rr < 0.25) {
                    float q = max(0.0, 1.0 - rr);
                    if (cv_lay_next(rng) < q)
                        end = true;
                    else if (walk)
                        wpdf *= 1.0 - q;
                    else
                        beta /= 1.0 - q;
                }
            }
            if (!end && medium) {
                float dz = -log(1.0 - cv_lay_next(rng)) * abs(w.z);
                zp = w.z > 0.0 ? z + dz : z - dz;
                if (zp == z) {
                    // no progress: F goes on to its next depth, the walk dies
                    end = walk;
                    depth++;
                    if (!end)
                        continue;
                } else if (0.0 < zp && zp < th) {
                    scatter = true;
                    if (fm) {
                        // next event: the phase function towards wis
                        float ph = cv_lay_hg(dot(-w, -wis.wi), L.g);
                        float wt = coat_smooth ? 1.0 : cv_lay_power(wis.pdf, ph);
                        fsum += beta * L.albedo * ph * wt * cv_lay_tr(zp - th, wis.wi) * wis.f / wis.pdf;
                    }
                } else {
                    z = clamp(zp, 0.0, th);
                }
            } else if (!end) {
                z = (z == th) ? 0.0 : th;
                beta *= cv_lay_tr(th, w);
            }
            if (!end && !scatter) {
                at_base = z == 0.0;
                win = -w;
                mask = walk ? CV_LAY_RT : CV_LAY_R;
                uc = cv_lay_next(rng);
                u2 = cv_lay_next2(rng);
            }
        }
        if (!end && at_base && (pm || (fm && !base_smooth))) {
            // the base towards wis: F's next event, PDF's TRT term
            float bp = (pm || !coat_smooth) ? cv_lay_base_pdf(L, -w, -wis.wi) : 0.0;
            if (fm) {
                float wt = coat_smooth ? 1.0 : cv_lay_power(wis.pdf, bp);
                fsum += beta * cv_lay_base_f(L, -w, -wis.wi) * abs(wis.wi.z) * wt * cv_lay_tr(th, wis.wi) *
                        wis.f / wis.pdf;
            } else {
                rpdf = bp;
                if (coat_smooth) {
                    psum += bp;
                    end = true;
                } else {
                    uc = cv_lay_next(rng);
                    u2 = cv_lay_next2(rng);
                }
            }
        }
        if (end) {
            if (walk)
                return false;
            smp++;
            at = CV_LAY_AT_ENTER_O;
            continue;
        }

        // The event: the one place the interfaces and the phase function
        // are sampled.
        bool ok;
        float ppdf = 0.0;
        if (scatter) {
            bs.wi = cv_lay_hg_sample(-w, L.g, cv_lay_next2(rng), ppdf);
            ok = ppdf > 0.0 && bs.wi.z != 0.0;
        } else if (at_base) {
            ok = cv_lay_base_sample(L, win, u2, bs);
        } else {
            ok = cv_lay_coat_sample(L, win, uc, u2, radiance, mask, bs);
        }

        // What it did to the walk.
        if (at == CV_LAY_AT_ENTER_O) {
            bool good = ok && cv_lay_ok(bs);
            if (walk) {
                if (!good)
                    return false;
                if ((bs.flags & CV_BSDF_REFLECTION) != 0u) {
                    s = bs;
                    return true;
                }
                w = bs.wi;
                specular = (bs.flags & CV_BSDF_SPECULAR) != 0u;
                beta = bs.f * abs(bs.wi.z);
                wpdf = bs.pdf;
                at = CV_LAY_AT_INSIDE;
            } else if (fm && !good) {
                smp++;
            } else {
                wos = bs;
                wos_ok = ok;
                at = CV_LAY_AT_ENTER_I;
            }
        } else if (at == CV_LAY_AT_ENTER_I) {
            wis = bs;
            at = CV_LAY_AT_ENTER_O;
            if (fm) {
                if (ok && cv_lay_ok(bs)) {
                    beta = wos.f * abs(wos.wi.z) / wos.pdf;
                    z = th;
                    w = wos.wi;
                    depth = 0;
                    at = CV_LAY_AT_INSIDE;
                } else {
                    smp++;
                }
            } else if (wos_ok && ok && cv_max3(wos.f) > 0.0 && wos.pdf > 0.0 && cv_max3(wis.f) > 0.0 &&
                       wis.pdf > 0.0) {
                at = CV_LAY_AT_BASE;  // transmission in, reflection at the base, transmission out
            } else {
                smp++;
            }
        } else if (at == CV_LAY_AT_BASE) {
            if (ok && cv_max3(bs.f) > 0.0 && bs.pdf > 0.0) {
                w = bs.wi;
                conn = CV_LAY_CONN_BASE;
                conn_pdf = bs.pdf;
            }
            smp++;
            at = CV_LAY_AT_ENTER_O;
        } else if (scatter) {
            depth++;
            if (!ok) {
                if (walk)
                    return false;
                continue;  // F goes on to its next depth
            }
            if (walk) {
                beta *= L.albedo * ppdf;
                wpdf *= ppdf;
                specular = false;
            } else {
                beta *= L.albedo;
            }
            w = bs.wi;
            z = zp;
            if (fm && w.z > 0.0 && !coat_smooth) {
                // next event: the scattered direction out through the coat
                conn = CV_LAY_CONN_EXIT;
                conn_pdf = ppdf;
                conn_weighted = true;
            }
        } else {
            depth++;
            if (!ok || !cv_lay_ok(bs)) {
                if (walk)
                    return false;
                smp++;
                at = CV_LAY_AT_ENTER_O;
                continue;
            }
            w = bs.wi;
            if (walk) {
                beta *= bs.f;
                wpdf *= bs.pdf;
                specular = specular && (bs.flags & CV_BSDF_SPECULAR) != 0u;
                if ((bs.flags & CV_BSDF_TRANSMISSION) != 0u) {
                    uint flags = (w.z > 0.0 ? CV_BSDF_REFLECTION : CV_BSDF_TRANSMISSION) |
                                 (specular ? CV_BSDF_SPECULAR : 0u);
                    s = CvBsdfSample(w, beta, wpdf, flags);
                    return true;
                }
                beta *= abs(bs.wi.z);
            } else {
                beta *= bs.f * abs(bs.wi.z) / bs.pdf;
                if (at_base && !coat_smooth) {
                    // next event: the sampled direction out through the coat
                    conn = CV_LAY_CONN_EXIT;
                    conn_pdf = bs.pdf;
                    conn_weighted = !base_smooth;
                }
            }
        }
    }
    f = fsum / n;
    pdf = mix(CV_INV_4PI, psum / n, 0.9);
    return false;
}

// cv_layered_run with its mode a constant in each call, so each inlined
// copy folds to one estimator. With the mode known only at run time, one
// copy keeps every mode's state and branches live through the loop, and
// NVIDIA's compiled walk runs far slower (bench/RESULTS.md, issue 26);
// three folded copies cost some build time instead.
bool cv_layered_estimate(CvLayered L, uint mode, vec3 wo, vec3 wi, float uc, vec2 u, out vec3 f,
                         out float pdf, out CvBsdfSample s)
{
    if (mode == CV_LAY_MODE_F)
        return cv_layered_run(L, CV_LAY_MODE_F, wo, wi, uc, u, f, pdf, s);
    if (mode == CV_LAY_MODE_PDF)
        return cv_layered_run(L, CV_LAY_MODE_PDF, wo, wi, uc, u, f, pdf, s);
    return cv_layered_run(L, CV_LAY_MODE_WALK, wo, wi, uc, u, f, pdf, s);
}

#endif
