/* materials.c: pbrt-v3 and pbrt-v4 material names onto CvMaterial. v3
 * names use pbrt-v3's roughness remapping, v4 names pbrt-v4's (sqrt), so
 * that each renders as its own pbrt would. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"
#include "scene/bssrdf_table.h"
#include "scene/coat_closed.h"
#include "scene/conductor_fresnel.h"
#include "scene/scattering_presets.h"
#include "scene/measured.h"
#include "scene/rgl_tensor.h"
#include "scene/spectrum.h"

static void mat_init(CvMaterial *m, uint32_t type)
{
    memset(m, 0, sizeof(*m));
    m->type = type;
    m->displacement_tex = m->normal_tex = m->reflectance_tex = m->specular_tex = -1;
    m->roughness_u_tex = m->roughness_v_tex = m->alpha_tex = m->amount_tex = m->eta_tex = -1;
    m->mix_a = m->mix_b = -1;
    m->alpha = 1;
    m->amount = 0.5f;
}

static cv_vec4 v4(const double c[3], double w)
{
    return (cv_vec4){(float)c[0], (float)c[1], (float)c[2], (float)w};
}

static double remap_v3(double r)
{
    if (!(r > 0))
        return 0; /* pbrt-v3: zero roughness stays perfectly specular */
    r = r > 1e-3 ? r : 1e-3;
    double x = log(r);
    return 1.62142 + 0.819955 * x + 0.1734 * x * x + 0.0171201 * x * x * x +
           0.000640711 * x * x * x * x;
}

static double remap_v4(double r) { return sqrt(r > 0 ? r : 0); }

/* roughness / uroughness / vroughness (with prefix) into alpha u,v and
 * textures; def is the default roughness. A textured one that is remapped
 * adds to *remap_flags how the shaders remap it per lookup. */
static bool roughness(struct cv_builder *b, struct cv_params *ps, const char *prefix, double def,
                      bool v3, float *au, float *av, int *tu, int *tv, uint32_t *remap_flags,
                      struct cv_error *err)
{
    char n_r[64], n_u[64], n_v[64];
    snprintf(n_r, sizeof(n_r), "%sroughness", prefix);
    snprintf(n_u, sizeof(n_u), "%suroughness", prefix);
    snprintf(n_v, sizeof(n_v), "%svroughness", prefix);
    double r = def, u, v;
    int tr, t1, t2;
    if (!cv_b_float_tex(b, ps, n_r, &r, &tr, err))
        return false;
    u = v = r;
    t1 = t2 = tr;
    if (!cv_b_float_tex(b, ps, n_u, &u, &t1, err) || !cv_b_float_tex(b, ps, n_v, &v, &t2, err))
        return false;
    if (t1 < 0 && tr >= 0 && !cv_params_find(ps, n_u))
        t1 = tr;
    if (t2 < 0 && tr >= 0 && !cv_params_find(ps, n_v))
        t2 = tr;
    bool remap = cv_params_bool(ps, "remaproughness", true);
    if (remap) {
        u = v3 ? remap_v3(u) : remap_v4(u);
        v = v3 ? remap_v3(v) : remap_v4(v);
    }
    *au = (float)u;
    *av = (float)v;
    if (tu)
        *tu = t1;
    if (tv)
        *tv = t2;
    if ((t1 >= 0 || t2 >= 0) && remap)
        *remap_flags |= CV_MATF_REMAP_ROUGHNESS | (v3 ? CV_MATF_ROUGHNESS_V3 : 0u);
    return true;
}

static bool color(struct cv_builder *b, struct cv_params *ps, const char *name, double def,
                  enum cv_spectrum_kind kind, const char *dir, cv_vec4 *out, int *tex,
                  struct cv_error *err)
{
    double rgb[3] = {def, def, def};
    int t = -1;
    if (!cv_b_color_tex(b, ps, name, kind, dir, rgb, &t, err))
        return false;
    *out = v4(rgb, out->w);
    if (tex)
        *tex = t;
    else if (t >= 0)
        return cv_fail(err, "texture not supported for \"%s\"", name);
    return true;
}

/* The index of the scene's Fresnel table of the conductor eta + i k under a
 * medium of index outer (conductor_fresnel.h), added unless an equal one
 * is there. */
static uint32_t conductor_fresnel(struct cv_builder *b, const double *eta, size_t n_eta,
                                  const double *k, size_t n_k, double outer)
{
    enum { FLOATS = 4 * CV_CONDUCTOR_FRESNEL_N };
    struct cv_scene *s = b->s;
    float table[FLOATS];
    cv_conductor_fresnel_table(eta, n_eta, k, n_k, outer, table);
    for (uint32_t i = 0; i < s->n_conductor_fresnel; i++)
        if (memcmp(s->conductor_fresnel + (size_t)i * FLOATS, table, sizeof(table)) == 0)
            return i;
    uint32_t i = s->n_conductor_fresnel++;
    s->conductor_fresnel = cv_xrealloc(s->conductor_fresnel,
                                       (size_t)s->n_conductor_fresnel * sizeof(table));
    memcpy(s->conductor_fresnel + (size_t)i * FLOATS, table, sizeof(table));
    return i;
}

/* eta and k (or reflectance) of a conductor; outer: the index of the
 * medium above it (1, or a coated conductor's coat). Where both eta and k
 * are spectra (pbrt-v4's default copper, named metals, files, pairs or
 * floats) the Fresnel term comes from a table of their spectral
 * reflectance (CV_MATF_CONDUCTOR_FRESNEL), as pbrt-v4 renders them; eta
 * and k keep RGB averages. An rgb eta or k is rendered as RGB. */
static bool conductor(struct cv_builder *b, struct cv_params *ps, const char *prefix,
                      const char *dir, double outer, CvMaterial *m, cv_vec4 *eta, cv_vec4 *k,
                      struct cv_error *err)
{
    static const double cu_eta[3] = {0.200438, 0.924033, 1.10221},
                        cu_k[3] = {3.91295, 2.45285, 2.14219};
    char n_eta[64], n_k[64], n_r[64];
    snprintf(n_eta, sizeof(n_eta), "%seta", prefix);
    snprintf(n_k, sizeof(n_k), "%sk", prefix);
    snprintf(n_r, sizeof(n_r), "%sreflectance", prefix);
    double e[3], kk[3], r[3];
    bool fe, fk, fr;
    if (!cv_b_color(b, ps, n_eta, CV_SPEC_UNBOUNDED, dir, e, &fe, err) ||
        !cv_b_color(b, ps, n_k, CV_SPEC_UNBOUNDED, dir, kk, &fk, err))
        return false;
    int rt = -1;
    fr = false;
    for (size_t i = 0; i < ps->n; i++)
        if (strcmp(ps->v[i].name, n_r) == 0)
            fr = true;
    if (fr) {
        r[0] = r[1] = r[2] = 0;
        if (!cv_b_color_tex(b, ps, n_r, CV_SPEC_REFLECTANCE, dir, r, &rt, err))
            return false;
        m->flags |= CV_MATF_CONDUCTOR_REFLECTANCE;
        m->reflectance = v4(r, 0);
        m->reflectance_tex = rt;
    }
    *eta = v4(fe ? e : cu_eta, eta->w);
    *k = v4(fk ? kk : cu_k, 0);
    if (fr || (*prefix && cv_params_find(ps, "reflectance")))
        return true; /* by reflectance (a coated conductor's is unprefixed) */
    double *se = NULL, *sk = NULL;
    size_t ne = 0, nk = 0, n_cu_eta, n_cu_k;
    if (!cv_b_spectrum(b, ps, n_eta, dir, &se, &ne, err) ||
        !cv_b_spectrum(b, ps, n_k, dir, &sk, &nk, err)) {
        free(se);
        return false;
    }
    const double *pe = fe ? se : cv_metal_spectrum("metal-Cu-eta", &n_cu_eta),
                 *pk = fk ? sk : cv_metal_spectrum("metal-Cu-k", &n_cu_k);
    if (pe && pk) {
        m->flags |= CV_MATF_CONDUCTOR_FRESNEL;
        k->w = (float)conductor_fresnel(b, pe, fe ? ne : n_cu_eta, pk, fk ? nk : n_cu_k, outer);
    }
    free(se);
    free(sk);
    return true;
}

/* pbrt-v4's HairMaterial. The colour comes from sigma_a if given, else
 * reflectance, else the melanin concentrations (eumelanin 1.3 when none of
 * the three is given); the losers are reported as pbrt-v4 does. beta_m,
 * beta_n, alpha and the melanins are constants here. */
static bool hair(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                 CvMaterial *m, struct cv_error *err)
{
    bool has_sigma = cv_params_find(ps, "sigma_a") != NULL, has_refl = cv_params_find(ps, "reflectance") != NULL;
    bool has_eu = cv_params_find(ps, "eumelanin") != NULL, has_pheo = cv_params_find(ps, "pheomelanin") != NULL;
    double rgb[3] = {0, 0, 0};
    int tex = -1;
    m->type = CV_MAT_HAIR;
    if (has_sigma) {
        if (!cv_b_color_tex(b, ps, "sigma_a", CV_SPEC_UNBOUNDED, dir, rgb, &tex, err))
            return false;
        m->flags |= CV_MATF_HAIR_SIGMA_A;
    } else if (has_refl) {
        if (!cv_b_color_tex(b, ps, "reflectance", CV_SPEC_REFLECTANCE, dir, rgb, &tex, err))
            return false;
        m->flags |= CV_MATF_HAIR_REFLECTANCE;
    }
    const char *loser = has_sigma && has_refl ? "reflectance" : NULL;
    if ((has_sigma || has_refl) && (has_eu || has_pheo))
        loser = has_eu ? "eumelanin" : "pheomelanin";
    if (loser && !cv_b_warn(b, err, loc, "hair: ignoring \"%s\" since \"%s\" was given", loser,
                            has_sigma ? "sigma_a" : "reflectance"))
        return false;
    /* constants: name, default, where it goes */
    struct { const char *name; double def; float *dst; } k[] = {
        {"eumelanin", has_eu || has_pheo ? 0 : 1.3, &m->reflectance.x},
        {"pheomelanin", 0, &m->reflectance.y},
        {"beta_m", 0.3, &m->roughness.x},
        {"beta_n", 0.3, &m->roughness.y},
        {"alpha", 2, &m->roughness.z},
    };
    m->reflectance = v4(rgb, 0);
    m->reflectance_tex = tex;
    for (size_t i = 0; i < CV_ARRAY_SIZE(k); i++) {
        double v = k[i].def;
        int t = -1;
        if (!cv_b_float_tex(b, ps, k[i].name, &v, &t, err))
            return false;
        if (t >= 0) {
            v = k[i].def;
            if (!cv_b_warn(b, err, loc, "hair: a texture for \"%s\" is not supported; %g used", k[i].name, v))
                return false;
        }
        if (i < 2 && (has_sigma || has_refl))
            continue;  /* the melanins lost */
        *k[i].dst = (float)v;
    }
    double eta = 1.55;
    if (!cv_b_float_tex(b, ps, "eta", &eta, &m->eta_tex, err))
        return false;
    m->eta = (cv_vec4){(float)eta, (float)eta, (float)eta, 0};
    return true;
}

/* The scene's BSSRDF table for (g, eta), computed on first use. */
static uint32_t bssrdf_table(struct cv_builder *b, double g, double eta)
{
    struct cv_scene *s = b->s;
    for (uint32_t i = 0; i < s->n_bssrdf; i++)
        if (s->bssrdf_keys[2 * i] == (float)g && s->bssrdf_keys[2 * i + 1] == (float)eta)
            return i;
    uint32_t i = s->n_bssrdf++;
    s->bssrdf = cv_xrealloc(s->bssrdf, (size_t)s->n_bssrdf * CV_BSSRDF_FLOATS * sizeof(float));
    s->bssrdf_keys = cv_xrealloc(s->bssrdf_keys, (size_t)s->n_bssrdf * 2 * sizeof(float));
    s->bssrdf_keys[2 * i] = (float)g;
    s->bssrdf_keys[2 * i + 1] = (float)eta;
    cv_bssrdf_table_compute(g, eta, s->bssrdf + (size_t)i * CV_BSSRDF_FLOATS);
    return i;
}

/* A subsurface coefficient: its constant (def where absent) and texture
 * (-1 for none). */
static bool coefficient(struct cv_builder *b, struct cv_params *ps, const char *name, double def,
                        enum cv_spectrum_kind kind, const char *dir, double rgb[3], int *tex,
                        struct cv_error *err)
{
    *tex = -1;
    rgb[0] = rgb[1] = rgb[2] = def;
    return cv_b_color_tex(b, ps, name, kind, dir, rgb, tex, err);
}

/* pbrt-v4's SubsurfaceMaterial: a dielectric boundary (eta, roughness)
 * over a tabulated BSSRDF. The coefficients come, in pbrt-v4's order, from
 * a measured medium's name (g forced to 0: the data are reduced
 * coefficients), from sigma_a and sigma_s, from reflectance (and mfp,
 * inverted through the table), or from pbrt-v4's defaults (whole milk per
 * mm); all times scale. reflectance = sigma_a, specular = sigma_s (per
 * scene unit), k.x = the table (glsl/shared/scene.h); with a texture, the
 * coefficients as given and their textures, for the GPU to scale or
 * invert per point (CV_MATF_SSS_POINT, CV_MATF_SSS_DIFFUSE). */
static bool subsurface(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                       const char *dir, CvMaterial *m, struct cv_error *err)
{
    double g = cv_params_float(ps, "g", 0), sa[3], ss[3], scale;
    const char *name = cv_params_string(ps, "name", NULL);
    bool from_diffuse = false;
    double refl[3], mfp[3];
    int tex_a = -1, tex_s = -1;
    m->type = CV_MAT_SUBSURFACE;
    if (name && *name) {
        if (!cv_scattering_preset(name, sa, ss))
            return cv_fail(err, "%s:%d:%d: subsurface: unknown measured medium \"%s\"", loc->file,
                           loc->line, loc->col, name);
        if (g != 0 && !cv_b_warn(b, err, loc, "subsurface: non-zero \"g\" ignored with named scattering coefficients"))
            return false;
        g = 0;
    } else if (cv_params_find(ps, "sigma_a") || cv_params_find(ps, "sigma_s")) {
        if (!cv_params_find(ps, "sigma_a") || !cv_params_find(ps, "sigma_s"))
            return cv_fail(err, "%s:%d:%d: subsurface: \"sigma_a\" and \"sigma_s\" go together", loc->file,
                           loc->line, loc->col);
        if (!coefficient(b, ps, "sigma_a", 0, CV_SPEC_UNBOUNDED, dir, sa, &tex_a, err) ||
            !coefficient(b, ps, "sigma_s", 0, CV_SPEC_UNBOUNDED, dir, ss, &tex_s, err))
            return false;
    } else if (cv_params_find(ps, "reflectance")) {
        from_diffuse = true;
        if (!coefficient(b, ps, "reflectance", 0, CV_SPEC_REFLECTANCE, dir, refl, &tex_a, err) ||
            !coefficient(b, ps, "mfp", 1, CV_SPEC_UNBOUNDED, dir, mfp, &tex_s, err))
            return false;
    } else {
        static const double def_a[3] = {.0011, .0024, .014}, def_s[3] = {2.55, 3.21, 3.77};
        memcpy(sa, def_a, sizeof(sa));
        memcpy(ss, def_s, sizeof(ss));
    }
    scale = cv_params_float(ps, "scale", 1);
    double eta = 1.33;
    bool found;
    if (!cv_b_scalar_eta(b, ps, "eta", dir, &eta, &found, err))
        return false;
    uint32_t table = bssrdf_table(b, g, eta);
    const float *t = b->s->bssrdf + (size_t)table * CV_BSSRDF_FLOATS;
    m->eta = (cv_vec4){(float)eta, (float)eta, (float)eta, 0};
    m->k = (cv_vec4){(float)table, 0, 0, 0};
    if (tex_a >= 0 || tex_s >= 0) {
        /* textured: the GPU scales (or inverts) per point */
        m->flags |= CV_MATF_SSS_POINT | (from_diffuse ? CV_MATF_SSS_DIFFUSE : 0);
        m->reflectance = v4(from_diffuse ? refl : sa, 0);
        m->specular = v4(from_diffuse ? mfp : ss, 0);
        m->reflectance_tex = tex_a;
        m->specular_tex = tex_s;
        m->k.y = (float)scale;
        (void)loc;
        return true;
    }
    for (int c = 0; c < 3; c++) {
        if (from_diffuse) {
            float a, s;
            double r = refl[c] < 0 ? 0 : refl[c] > 1 ? 1 : refl[c];
            double free_path = scale * mfp[c] > 1e-30 ? scale * mfp[c] : 1e-30;
            cv_bssrdf_from_diffuse(t, (float)r, (float)free_path, &a, &s);
            sa[c] = a;
            ss[c] = s;
        } else {
            sa[c] = sa[c] * scale > 0 ? sa[c] * scale : 0;
            ss[c] = ss[c] * scale > 0 ? ss[c] * scale : 0;
        }
    }
    m->reflectance = v4(sa, 0);
    m->specular = v4(ss, 0);
    (void)loc;
    return true;
}

/* pbrt-v4's MeasuredMaterial: the RGL tensor file "filename", read once
 * per scene however many materials name it; its tables go to the scene's
 * measured buffer (glsl/shared/measured.h), the block's offset to mix_a. */
static bool measured(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                     const char *dir, CvMaterial *m, struct cv_error *err)
{
    const char *file = cv_params_string(ps, "filename", NULL);
    if (!file || !*file)
        return cv_fail(err, "%s:%d:%d: measured: \"string filename\" (an RGL .bsdf file) is required",
                       loc->file, loc->line, loc->col);
    m->type = CV_MAT_MEASURED;
    char *path = cv_b_resolve(b, dir, file, err);
    if (!path) {
        cv_error_prefix(err, "%s:%d:%d: measured \"%s\"", loc->file, loc->line, loc->col, file);
        return false;
    }
    int at = cv_b_lookup(b->measured_files, b->n_measured_files, path);
    if (at < 0) {
        struct cv_tensor_file t;
        uint32_t *block = NULL;
        size_t n = 0;
        bool ok = cv_tensor_load(path, &t, err);
        if (ok) {
            ok = cv_measured_tables(path, &t, &block, &n, err);
            cv_tensor_free(&t);
        }
        if (ok && b->s->n_measured + n > (size_t)INT32_MAX)
            ok = cv_fail(err, "%s: the scene's measured tables grow past 2^31 words", path);
        if (!ok) {
            free(path);
            free(block);
            cv_error_prefix(err, "%s:%d:%d: measured", loc->file, loc->line, loc->col);
            return false;
        }
        struct cv_scene *s = b->s;
        at = (int)s->n_measured;
        s->measured = cv_xgrow(s->measured, &b->cap_measured, s->n_measured + n, sizeof(uint32_t));
        memcpy(s->measured + s->n_measured, block, n * sizeof(uint32_t));
        s->n_measured += n;
        free(block);
        cv_b_set_named(&b->measured_files, &b->n_measured_files, &b->cap_measured_files, path, at);
    }
    free(path);
    m->mix_a = at;
    return true;
}

bool cv_b_material(struct cv_builder *b, const char *type, const char *name,
                   struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                   struct cv_error *err, int *out)
{
    CvMaterial m;
    uint32_t remap_flags = 0;
    float au, av;
    mat_init(&m, CV_MAT_DIFFUSE);
#define ROUGH(prefix, def, v3)                                                            \
    roughness(b, ps, prefix, def, v3, &au, &av, &m.roughness_u_tex, &m.roughness_v_tex,  \
              &remap_flags, err)

    if (strcmp(type, "diffuse") == 0 || strcmp(type, "matte") == 0) {
        if (!color(b, ps, strcmp(type, "matte") == 0 ? "Kd" : "reflectance", 0.5,
                   CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err))
            return false;
        double sigma = 0;
        int st;
        if (!cv_b_float_tex(b, ps, "sigma", &sigma, &st, err))
            return false;
        if ((sigma != 0 || st >= 0) && !cv_b_warn(b, err, loc, "matte \"sigma\" (Oren-Nayar) is not supported; Lambertian used"))
            return false;
    } else if (strcmp(type, "plastic") == 0 || strcmp(type, "uber") == 0) {
        m.type = CV_MAT_PLASTIC;
        if (!color(b, ps, "Kd", 0.25, CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err) ||
            !color(b, ps, "Ks", 0.25, CV_SPEC_REFLECTANCE, dir, &m.specular, &m.specular_tex, err) ||
            !ROUGH("", 0.1, true))
            return false;
        m.roughness = (cv_vec4){au, av, 0, 0};
        if (strcmp(type, "uber") == 0) {
            cv_vec4 kr = {0}, kt = {0}, op = {0};
            if (!color(b, ps, "Kr", 0, CV_SPEC_REFLECTANCE, dir, &kr, NULL, err) ||
                !color(b, ps, "Kt", 0, CV_SPEC_REFLECTANCE, dir, &kt, NULL, err) ||
                !color(b, ps, "opacity", 1, CV_SPEC_REFLECTANCE, dir, &op, NULL, err))
                return false;
            double eta = cv_params_float(ps, "eta", cv_params_float(ps, "index", 1.5));
            m.eta.x = (float)eta;
            m.alpha = (op.x + op.y + op.z) / 3;
            if ((kr.x + kr.y + kr.z + kt.x + kt.y + kt.z) > 0 &&
                !cv_b_warn(b, err, loc, "uber Kr/Kt are not rendered (plastic approximation)"))
                return false;
        }
    } else if (strcmp(type, "metal") == 0 || strcmp(type, "conductor") == 0) {
        bool v3 = strcmp(type, "metal") == 0;
        m.type = CV_MAT_CONDUCTOR;
        if (!conductor(b, ps, "", dir, 1, &m, &m.eta, &m.k, err) || !ROUGH("", v3 ? 0.01 : 0, v3))
            return false;
        m.roughness = (cv_vec4){au, av, 0, 0};
    } else if (strcmp(type, "glass") == 0 || strcmp(type, "dielectric") == 0 ||
               strcmp(type, "thindielectric") == 0) {
        bool v3 = strcmp(type, "glass") == 0;
        m.type = strcmp(type, "thindielectric") == 0 ? CV_MAT_THIN_DIELECTRIC : CV_MAT_DIELECTRIC;
        double eta = 1.5;
        bool found;
        if (!cv_b_scalar_eta(b, ps, "eta", dir, &eta, &found, err))
            return false;
        if (!found && !cv_b_scalar_eta(b, ps, "index", dir, &eta, &found, err))
            return false;
        m.eta = (cv_vec4){(float)eta, (float)eta, (float)eta, 0};
        m.reflectance = m.specular = (cv_vec4){1, 1, 1, 0};
        if (v3 && (!color(b, ps, "Kr", 1, CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err) ||
                   !color(b, ps, "Kt", 1, CV_SPEC_REFLECTANCE, dir, &m.specular, &m.specular_tex, err)))
            return false;
        if (m.type == CV_MAT_DIELECTRIC) {
            if (!ROUGH("", 0, v3))
                return false;
            m.roughness = (cv_vec4){au, av, 0, 0};
        }
    } else if (strcmp(type, "mirror") == 0) {
        m.type = CV_MAT_MIRROR;
        if (!color(b, ps, "Kr", 0.9, CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err))
            return false;
    } else if (strcmp(type, "substrate") == 0) {
        /* Ashikhmin-Shirley substrate is rendered as a coated diffuse
         * (Kd under a rough dielectric coat, a clear slab: albedo 0).
         * Ks is read for its errors only: specular is the coat's medium
         * albedo in a coated diffuse. */
        m.type = CV_MAT_COATED_DIFFUSE;
        if (!color(b, ps, "Kd", 0.5, CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err) ||
            !color(b, ps, "Ks", 0.5, CV_SPEC_REFLECTANCE, dir, &m.specular, &m.specular_tex, err) ||
            !ROUGH("", 0.1, true))
            return false;
        m.roughness = (cv_vec4){au, av, 0.01f, 0};
        m.eta.x = 1.5f;
        m.roughness2 = (cv_vec4){0, 0, 10, 1};
        m.specular = (cv_vec4){0, 0, 0, 0};
        m.specular_tex = -1;
        if (!cv_b_warn(b, err, loc, "substrate: rendered as coated diffuse (Ks ignored)"))
            return false;
    } else if (strcmp(type, "coateddiffuse") == 0) {
        m.type = CV_MAT_COATED_DIFFUSE;
        if (!color(b, ps, "reflectance", 0.5, CV_SPEC_REFLECTANCE, dir, &m.reflectance, &m.reflectance_tex, err) ||
            !color(b, ps, "albedo", 0, CV_SPEC_REFLECTANCE, dir, &m.specular, &m.specular_tex, err) ||
            !ROUGH("", 0, false))
            return false;
        double eta = 1.5;
        bool found;
        if (!cv_b_scalar_eta(b, ps, "eta", dir, &eta, &found, err))
            return false;
        m.eta.x = (float)eta;
        m.roughness = (cv_vec4){au, av, (float)cv_params_float(ps, "thickness", 0.01),
                                (float)cv_params_float(ps, "g", 0)};
        m.roughness2 = (cv_vec4){0, 0, (float)cv_params_int(ps, "maxdepth", 10),
                                 (float)cv_params_int(ps, "nsamples", 1)};
    } else if (strcmp(type, "coatedconductor") == 0) {
        /* eta.xyz: conductor eta; eta.w: interface (coat) eta. */
        m.type = CV_MAT_COATED_CONDUCTOR;
        float iu, iv;
        double eta = 1.5;
        bool found;
        if (!cv_b_scalar_eta(b, ps, "interface.eta", dir, &eta, &found, err))
            return false;
        int ctu = -1, ctv = -1;
        if (!roughness(b, ps, "interface.", 0, false, &iu, &iv, &m.roughness_u_tex,
                       &m.roughness_v_tex, &remap_flags, err) ||
            !roughness(b, ps, "conductor.", 0, false, &au, &av, &ctu, &ctv, &remap_flags, err) ||
            !conductor(b, ps, "conductor.", dir, eta, &m, &m.eta, &m.k, err))
            return false;
        /* the base's roughness has no texture slot: its constant only */
        if ((ctu >= 0 || ctv >= 0) &&
            !cv_b_warn(b, err, loc, "coatedconductor: a textured conductor roughness is not "
                       "supported; the base is as rough as its constant (default 0)"))
            return false;
        if (cv_params_find(ps, "reflectance") && !(m.flags & CV_MATF_CONDUCTOR_REFLECTANCE)) {
            double r[3] = {0, 0, 0};
            int rt;
            if (!cv_b_color_tex(b, ps, "reflectance", CV_SPEC_REFLECTANCE, dir, r, &rt, err))
                return false;
            m.flags |= CV_MATF_CONDUCTOR_REFLECTANCE;
            m.reflectance = v4(r, 0);
            m.reflectance_tex = rt;
        }
        m.eta.w = (float)eta;
        if (!color(b, ps, "albedo", 0, CV_SPEC_REFLECTANCE, dir, &m.specular, &m.specular_tex, err))
            return false;
        m.roughness = (cv_vec4){iu, iv, (float)cv_params_float(ps, "thickness", 0.01),
                                (float)cv_params_float(ps, "g", 0)};
        m.roughness2 = (cv_vec4){au, av, (float)cv_params_int(ps, "maxdepth", 10),
                                 (float)cv_params_int(ps, "nsamples", 1)};
    } else if (strcmp(type, "diffusetransmission") == 0 || strcmp(type, "translucent") == 0) {
        bool v3 = strcmp(type, "translucent") == 0;
        m.type = CV_MAT_DIFFUSE_TRANSMISSION;
        if (!color(b, ps, v3 ? "reflect" : "reflectance", v3 ? 0.5 : 0.25, CV_SPEC_REFLECTANCE,
                   dir, &m.reflectance, &m.reflectance_tex, err) ||
            !color(b, ps, v3 ? "transmit" : "transmittance", v3 ? 0.5 : 0.25, CV_SPEC_REFLECTANCE,
                   dir, &m.specular, &m.specular_tex, err))
            return false;
        /* v4's "scale", v3's Kd: factors of both colours, textured or not */
        double sc = cv_params_float(ps, "scale", 1), f[3] = {sc, sc, sc};
        if (v3) {
            cv_vec4 kd = {0}, ks = {0};
            if (!color(b, ps, "Kd", 0.25, CV_SPEC_REFLECTANCE, dir, &kd, NULL, err) ||
                !color(b, ps, "Ks", 0.25, CV_SPEC_REFLECTANCE, dir, &ks, NULL, err))
                return false;
            cv_params_float(ps, "roughness", 0);
            f[0] *= kd.x;
            f[1] *= kd.y;
            f[2] *= kd.z;
            if (!cv_b_warn(b, err, loc, "translucent: rendered as diffuse transmission (Ks ignored)"))
                return false;
        }
        cv_vec4 *col[2] = {&m.reflectance, &m.specular};
        int *tex[2] = {&m.reflectance_tex, &m.specular_tex};
        for (int i = 0; i < 2; i++) {
            col[i]->x *= (float)f[0];
            col[i]->y *= (float)f[1];
            col[i]->z *= (float)f[2];
            if (*tex[i] >= 0 && (f[0] != 1 || f[1] != 1 || f[2] != 1))
                *tex[i] = cv_b_texture_times(b, *tex[i], f);
        }
    } else if (strcmp(type, "hair") == 0) {
        if (!hair(b, ps, loc, dir, &m, err))
            return false;
    } else if (strcmp(type, "subsurface") == 0) {
        if (!subsurface(b, ps, loc, dir, &m, err) || !ROUGH("", 0, false))
            return false;
        m.roughness = (cv_vec4){au, av, 0, 0};
    } else if (strcmp(type, "measured") == 0) {
        if (!measured(b, ps, loc, dir, &m, err))
            return false;
    } else if (strcmp(type, "mix") == 0) {
        m.type = CV_MAT_MIX;
        double amount = 0.5;
        int at;
        if (!cv_b_float_tex(b, ps, "amount", &amount, &at, err))
            return false;
        m.amount = (float)amount;
        m.amount_tex = at;
        struct cv_param *mats = cv_params_find(ps, "materials");
        const char *n1 = NULL, *n2 = NULL;
        if (mats && mats->n_strs == 2) {
            n1 = mats->strs[0];
            n2 = mats->strs[1];
        } else {
            /* pbrt-v3 weighs namedmaterial1 by amount, pbrt-v4 its second
             * material (materials.h: ChooseMaterial), so v3's pair is
             * v4's in reverse, as pbrt-v4's --upgrade writes it */
            n1 = cv_params_string(ps, "namedmaterial2", NULL);
            n2 = cv_params_string(ps, "namedmaterial1", NULL);
        }
        if (!n1 || !n2)
            return cv_fail(err, "%s:%d:%d: mix needs two materials (\"string materials\" or namedmaterial1/2)",
                           loc->file, loc->line, loc->col);
        m.mix_a = cv_b_lookup(b->materials_named, b->n_materials_named, n1);
        m.mix_b = cv_b_lookup(b->materials_named, b->n_materials_named, n2);
        if (m.mix_a < 0 || m.mix_b < 0)
            return cv_fail(err, "%s:%d:%d: mix: unknown named material \"%s\"", loc->file,
                           loc->line, loc->col, m.mix_a < 0 ? n1 : n2);
    } else if (strcmp(type, "interface") == 0 || strcmp(type, "") == 0 ||
               strcmp(type, "none") == 0) {
        m.type = CV_MAT_INTERFACE;
        m.eta.x = 1;
    } else {
        if (!cv_b_warn(b, err, loc, "material \"%s\" is not supported; using diffuse 0.5", type))
            return false;
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        m.reflectance = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
    }
#undef ROUGH
    m.flags |= remap_flags;
    /* common to all: bump, normal map, cut-out */
    double d = 0;
    int bump = -1;
    if (!cv_b_float_tex(b, ps, "displacement", &d, &m.displacement_tex, err) ||
        !cv_b_float_tex(b, ps, "bumpmap", &d, &bump, err))
        return false;
    if (bump >= 0)
        m.displacement_tex = bump;
    const char *nm = cv_params_string(ps, "normalmap", NULL);
    if (nm) {
        m.normal_tex = cv_b_image_texture_v4(b, nm, dir, false, "normal map", loc, err);
        if (m.normal_tex < 0)
            return false;
    }
    /* a material's cut-out (pbrt-v4's is the shape's "alpha"); hair's
     * "alpha" is its scales' tilt, read by hair() */
    double alpha = 1;
    if (m.type != CV_MAT_HAIR && !cv_b_float_tex(b, ps, "alpha", &alpha, &m.alpha_tex, err))
        return false;
    if (alpha != 1)
        m.alpha = (float)alpha;
    cv_params_string(ps, "type", NULL);
    cv_coat_closed_prepare(&m);
    *out = (int)cv_b_add_material(b, &m, name);
    return true;
}
