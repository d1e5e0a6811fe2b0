// glsl/trace/bsdf_basic.glsl: the BSDF interface of glsl/trace/bsdf/bsdf.glsl
// for scenes whose materials are all untextured diffuse or mirror, without
// bump maps or alpha (the host decides: scene_upload.c). The full library
// makes the shade kernel large, and llvmpipe's JIT time grows with the
// kernel's size, so with this file the tests' scenes stay quick
// (bench/RESULTS.md, "Figures behind the code"). Same conventions: f
// without cosine, pdfs per solid angle, two-sided reflection.
#ifndef CV_TRACE_BSDF_BASIC_GLSL
#define CV_TRACE_BSDF_BASIC_GLSL

// (CvBsdfSample and the query: included by materials.glsl)
#include "bsdf/bsdf_query.glsl"

struct CvShadingPoint {
    vec3 p;
    vec3 ng;
    vec3 ns;
    vec3 dpdu;
    vec2 uv;
    bool front;
};

struct CvBsdf {
    vec3 n;      // shading normal
    vec3 r;      // reflectance
    bool mirror;
};


CvBsdf cv_bsdf_at(uint material, CvShadingPoint sp, float u_mix)
{
    CvMaterial m = materials[material];
    CvBsdf b;
    b.n = sp.ns;
    b.r = m.reflectance.rgb;
#ifdef CV_BSDF_DIFFUSE_ONLY
    b.mirror = false;  // the diffuse bin's stage (bsdf/bsdf.glsl)
#else
    b.mirror = m.type == CV_MAT_MIRROR;
#endif
    return b;
}

bool cv_bsdf_is_delta(CvBsdf b) { return b.mirror; }
// as bsdf/bsdf.glsl (nothing here is stochastic)
void cv_bsdf_set_stream(inout CvBsdf b, vec2 u_a, vec2 u_b) {}
// as bsdf/bsdf.glsl
float cv_bsdf_delta_prob(CvBsdf b, vec3 wo) { return b.mirror ? 1.0 : 0.0; }
vec3 cv_bsdf_albedo(CvBsdf b) { return b.r; }

vec3 cv_bsdf_f(CvBsdf b, vec3 wo, vec3 wi)
{
    if (b.mirror || dot(wo, b.n) * dot(wi, b.n) <= 0.0)
        return vec3(0.0);
    return b.r / CV_PI;
}

float cv_bsdf_pdf(CvBsdf b, vec3 wo, vec3 wi)
{
    if (b.mirror || dot(wo, b.n) * dot(wi, b.n) <= 0.0)
        return 0.0;
    return abs(dot(wi, b.n)) / CV_PI;
}

void cv_fallback_basis(vec3 n, out vec3 t, out vec3 bt)
{
    float s = n.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (s + n.z);
    float c = n.x * n.y * a;
    t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
    bt = vec3(c, s + n.y * n.y * a, -n.y);
}

bool cv_bsdf_sample(CvBsdf b, vec3 wo, float uc, vec2 u2, out CvBsdfSample s)
{
    vec3 n = dot(wo, b.n) < 0.0 ? -b.n : b.n;
    if (b.mirror) {
        s.wi = reflect(-wo, n);
        float c = abs(dot(s.wi, n));
        s.f = c > 0.0 ? b.r / c : vec3(0.0);
        s.pdf = 1.0;
        s.flags = CV_BSDF_REFLECTION | CV_BSDF_SPECULAR;
        return c > 0.0;
    }
    float r = sqrt(u2.x), phi = 2.0 * CV_PI * u2.y;
    vec3 t, bt;
    cv_fallback_basis(n, t, bt);
    float z = sqrt(max(0.0, 1.0 - u2.x));
    s.wi = normalize(r * cos(phi) * t + r * sin(phi) * bt + z * n);
    s.pdf = z / CV_PI;
    s.f = b.r / CV_PI;
    s.flags = CV_BSDF_REFLECTION;
    return s.pdf > 0.0;
}

// as bsdf/bsdf.glsl (two small lobes: straight on)
void cv_bsdf_query(CvBsdf b, inout CvBsdfQuery q)
{
    uint a = q.ask;
    q.f0 = (a & CV_BQ_F0) != 0u ? cv_bsdf_f(b, q.wo, q.wi0) : vec3(0.0);
    bool pdf0 = (a & CV_BQ_PDF0) != 0u && ((a & (CV_BQ_GATE0 | CV_BQ_F0)) != (CV_BQ_GATE0 | CV_BQ_F0) ||
                                           cv_max3(q.f0) > 0.0);
    q.pdf0 = pdf0 ? cv_bsdf_pdf(b, q.wo, q.wi0) : 0.0;
    q.s = CvBsdfSample(vec3(0.0), vec3(0.0), 0.0, 0u);
    q.sampled = (a & CV_BQ_SAMPLE) != 0u && cv_bsdf_sample(b, q.wo, q.uc, q.u, q.s) && q.s.pdf > 0.0;
    q.f1 = (a & CV_BQ_F1) != 0u ? cv_bsdf_f(b, q.wo, q.wi1) : vec3(0.0);
    bool pdf1 = (a & CV_BQ_PDF1) != 0u && ((a & (CV_BQ_GATE1 | CV_BQ_F1)) != (CV_BQ_GATE1 | CV_BQ_F1) ||
                                           cv_max3(q.f1) > 0.0);
    q.pdf1 = pdf1 ? cv_bsdf_pdf(b, q.wo, q.wi1) : 0.0;
}

bool cv_material_alpha_pass(uint material, vec2 uv, float u)
{
    return false; // the host picks this file only for scenes without alpha
}

#endif
