/* bssrdf_table_test.c: the subsurface material's BSSRDF table
 * (src/scene/bssrdf_table.c) against pbrt-v4's own (values printed by a
 * probe linked against pbrt-v4 at the oracle's commit,
 * tests/data/trace/oracle/README: ComputeBeamDiffusionBSSRDF and
 * InvertCatmullRom for three (g, eta)), the reflectance inversion's round
 * trip, the table's integrals against an independent quadrature of its
 * spline, and the material's parameters as the importer reads them
 * (measured names, sigma pairs, reflectance, defaults, errors). */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "scene/bssrdf_table.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

static bool near(double a, double b, double rel) { return fabs(a - b) <= rel * fmax(fabs(b), 1e-6); }

/* pbrt-v4's table at (g, eta): rhoEff at albedo samples 10, 50, 80, 99;
 * the profile at albedo sample 80, radius samples 1, 10, 30, 50; the
 * albedo whose effective albedo is 0.1, 0.5, 0.9. */
static const struct {
    double g, eta;
    double rho_eff[4], profile[4], invert[3];
} pbrt[] = {
    {0, 1.33, {0.07945521, 0.5924852, 0.8849664, 1.019344},
     {0.2885451, 0.3426737, 0.1806552, 0.00470147}, {0.6241637, 0.9695306, 0.999034}},
    {0.3, 1.5, {0.03304313, 0.426949, 0.7792659, 0.9687063},
     {0.1071406, 0.1281781, 0.08578297, 0.008243611}, {0.8159498, 0.9890531, 0.9998077}},
    {0, 1.0, {0.1519777, 0.7751456, 0.9968926, 1.084519},
     {0.4693671, 0.5050673, 0.3217448, 0.003031867}, {0.4259806, 0.9118108, 0.9945108}},
};

/* The spline through the profile at albedo sample i, evaluated at radius
 * r with cv_catmull_rom_weights (not the table's closed-form integral). */
static double profile_at(const float *t, int i, float r)
{
    int off;
    float w[4];
    if (!cv_catmull_rom_weights(t + CV_BSSRDF_RADIUS, CV_BSSRDF_N_RADIUS, r, &off, w))
        return 0;
    double v = 0;
    for (int k = 0; k < 4; k++)
        if (w[k] != 0)
            v += w[k] * t[CV_BSSRDF_PROFILE + i * CV_BSSRDF_N_RADIUS + off + k];
    return v;
}

static void check_table(const float *t, int which)
{
    static const int rho_i[4] = {10, 50, 80, 99}, rad_j[4] = {1, 10, 30, 50};
    static const double eff[3] = {0.1, 0.5, 0.9};
    bool ok = true;
    for (int k = 0; k < 4; k++) {
        double a = t[CV_BSSRDF_RHO_EFF + rho_i[k]], b = pbrt[which].rho_eff[k];
        double p = t[CV_BSSRDF_PROFILE + 80 * CV_BSSRDF_N_RADIUS + rad_j[k]], q = pbrt[which].profile[k];
        if (!near(a, b, 2e-3) || !near(p, q, 2e-3)) {
            ok = false;
            tap_diag("rhoEff[%d] %.7g (pbrt-v4 %.7g), profile[80][%d] %.7g (pbrt-v4 %.7g)", rho_i[k], a, b,
                     rad_j[k], p, q);
        }
    }
    tap_ok(ok, "g %g eta %g: effective albedos and profile as pbrt-v4's within 0.2%%", pbrt[which].g,
           pbrt[which].eta);
    ok = true;
    for (int k = 0; k < 3; k++) {
        double rho = cv_bssrdf_invert_rho_eff(t, (float)eff[k]);
        /* near rho 1 the inverse is steep: compare the albedo gap 1 - rho */
        if (!near(1 - rho, 1 - pbrt[which].invert[k], 5e-3)) {
            ok = false;
            tap_diag("invert(%g) %.7g, pbrt-v4 %.7g", eff[k], rho, pbrt[which].invert[k]);
        }
    }
    tap_ok(ok, "g %g eta %g: reflectance inverted to the albedo pbrt-v4 finds", pbrt[which].g,
           pbrt[which].eta);

    /* round trip over the table's range */
    double worst = 0;
    for (int k = 1; k < 50; k++) {
        float r = 0.02f * (float)k;  /* 0.02 .. 0.98 */
        if (r >= t[CV_BSSRDF_RHO_EFF + CV_BSSRDF_N_RHO - 1])
            break;
        float rho = cv_bssrdf_invert_rho_eff(t, r);
        worst = fmax(worst, fabs(cv_bssrdf_rho_eff(t, rho) - r));
    }
    tap_ok(worst < 1e-4, "g %g eta %g: rho_eff(invert(r)) = r within %.2g", pbrt[which].g,
           pbrt[which].eta, worst);

    /* monotone effective albedo; no scattering at albedo 0 */
    ok = t[CV_BSSRDF_RHO_EFF] == 0;
    for (int i = 1; i < CV_BSSRDF_N_RHO; i++)
        ok = ok && t[CV_BSSRDF_RHO_EFF + i] > t[CV_BSSRDF_RHO_EFF + i - 1];
    tap_ok(ok, "g %g eta %g: effective albedo 0 at albedo 0 and increasing", pbrt[which].g, pbrt[which].eta);

    /* the CDF's end (the sampling normalisation) against a fine midpoint
     * quadrature of the interpolated profile, and the CDF increasing */
    double worst_rel = 0;
    ok = true;
    for (int i = 20; i < CV_BSSRDF_N_RHO; i += 20) {
        double sum = 0;
        const float *r = t + CV_BSSRDF_RADIUS;
        for (int j = 0; j + 1 < CV_BSSRDF_N_RADIUS; j++)
            for (int s = 0; s < 400; s++) {
                double h = (r[j + 1] - r[j]) / 400.0;
                sum += h * profile_at(t, i, (float)(r[j] + (s + 0.5) * h));
            }
        double cdf_end = t[CV_BSSRDF_CDF + i * CV_BSSRDF_N_RADIUS + CV_BSSRDF_N_RADIUS - 1];
        worst_rel = fmax(worst_rel, fabs(sum - cdf_end) / cdf_end);
        ok = ok && cdf_end == t[CV_BSSRDF_RHO_EFF + i];
        /* (the spline of a segment may dip below 0 where the profile
         * falls steeply, pbrt-v4's too: by a rounding error's worth) */
        for (int j = 1; j < CV_BSSRDF_N_RADIUS; j++)
            ok = ok && t[CV_BSSRDF_CDF + i * CV_BSSRDF_N_RADIUS + j] >=
                           t[CV_BSSRDF_CDF + i * CV_BSSRDF_N_RADIUS + j - 1] - 1e-6 * cdf_end;
    }
    tap_ok(ok && worst_rel < 1e-3,
           "g %g eta %g: the sampling CDF ends at rho_eff, its profile's integral (off by %.2g), and rises",
           pbrt[which].g, pbrt[which].eta, worst_rel);
}

static const char *const HEAD =
    "Camera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" [4] \"integer yresolution\" [4]\n"
    "WorldBegin\n";
static const char *const TRI =
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point3 P\" [0 0 5 1 0 5 0 1 5]\n";

/* The one material of a scene made of HEAD, `material` and TRI. */
static struct cv_scene *load_material(const char *material, struct cv_error *err)
{
    char text[2048];
    snprintf(text, sizeof(text), "%s%s\n%s", HEAD, material, TRI);
    return th_load(text, false, err);
}

static void check_import(void)
{
    struct cv_error err = {{0}};
    /* a measured medium: per mm, times scale; g ignored (with a warning) */
    struct cv_scene *s = load_material("Material \"subsurface\" \"string name\" \"Skin1\" \"float scale\" [ 10 ]"
                                       " \"float g\" [ 0.5 ] \"float eta\" [ 1.4 ]", &err);
    const char *log = th_log_text();
    const CvMaterial *m = s ? &s->materials[s->n_materials - 1] : NULL;
    tap_ok(m && m->type == CV_MAT_SUBSURFACE && near(m->reflectance.x, 0.32, 1e-5) &&
               near(m->reflectance.z, 4.8, 1e-5) && near(m->specular.y, 8.8, 1e-5) &&
               m->eta.x == 1.4f && s->n_bssrdf == 1 && s->bssrdf_keys[0] == 0 && strstr(log, "\"g\" ignored"),
           "\"name\" Skin1, scale 10: sigma_a and sigma_s' of Jensen et al. per scene unit, g 0 (%s)", err.msg);
    cv_scene_destroy(&s);

    /* reflectance and mfp: the albedo inverted through the table */
    s = load_material("Material \"subsurface\" \"rgb reflectance\" [ 0.5 0.5 0.5 ] \"rgb mfp\" [ 2 2 2 ]"
                      " \"float roughness\" [ 0.25 ]", &err);
    m = s ? &s->materials[s->n_materials - 1] : NULL;
    bool ok = m && s->n_bssrdf == 1;
    if (ok) {
        double rho = m->specular.x / (m->specular.x + m->reflectance.x);
        ok = near(m->specular.x + m->reflectance.x, 0.5, 1e-5) &&
             near(cv_bssrdf_rho_eff(s->bssrdf, (float)rho), 0.5, 1e-4) && near(1 - rho, 1 - 0.9695306, 5e-3) &&
             near(m->roughness.x, 0.5, 1e-6) && m->eta.x == 1.33f;
    }
    tap_ok(ok, "reflectance 0.5, mfp 2: sigma_t 1/2, albedo pbrt-v4's inverse; roughness remapped, eta 1.33 (%s)",
           err.msg);
    cv_scene_destroy(&s);

    /* pbrt-v4's default coefficients; equal (g, eta) share a table */
    s = load_material("MakeNamedMaterial \"a\" \"string type\" \"subsurface\"\n"
                      "MakeNamedMaterial \"b\" \"string type\" \"subsurface\" \"float g\" [ 0 ]\n"
                      "NamedMaterial \"a\"", &err);
    m = s ? &s->materials[s->n_materials - 1] : NULL;
    tap_ok(m && near(m->reflectance.y, 0.0024, 1e-5) && near(m->specular.z, 3.77, 1e-5) && s->n_bssrdf == 1,
           "no coefficients: pbrt-v4's defaults; one table for two materials of one (g, eta) (%s)", err.msg);
    cv_scene_destroy(&s);

    /* a textured coefficient: the values as given, for the GPU */
    s = load_material("Texture \"c\" \"spectrum\" \"checkerboard\" \"rgb tex1\" [ 0.2 0.2 0.2 ]"
                      " \"rgb tex2\" [ 0.8 0.8 0.8 ]\n"
                      "Material \"subsurface\" \"texture reflectance\" \"c\" \"rgb mfp\" [ 3 3 3 ]"
                      " \"float scale\" [ 0.5 ]", &err);
    m = s ? &s->materials[s->n_materials - 1] : NULL;
    tap_ok(m && (m->flags & CV_MATF_SSS_POINT) && (m->flags & CV_MATF_SSS_DIFFUSE) && m->reflectance_tex >= 0 &&
               m->specular_tex < 0 && m->specular.x == 3 && m->k.y == 0.5f,
           "textured reflectance: mfp and scale kept for the GPU's inversion per point (%s)", err.msg);
    cv_scene_destroy(&s);

    s = load_material("Material \"subsurface\" \"string name\" \"Unobtainium\"", &err);
    tap_ok(!s && strstr(err.msg, "Unobtainium"), "an unknown measured medium is an error: %s", err.msg);
    cv_scene_destroy(&s);
    err = (struct cv_error){{0}};
    s = load_material("Material \"subsurface\" \"rgb sigma_a\" [ 1 1 1 ]", &err);
    tap_ok(!s && strstr(err.msg, "sigma_s"), "sigma_a without sigma_s is an error: %s", err.msg);
    cv_scene_destroy(&s);
}

int main(void)
{
    float *t = malloc(CV_BSSRDF_FLOATS * sizeof(float));
    for (size_t k = 0; k < sizeof(pbrt) / sizeof(pbrt[0]); k++) {
        cv_bssrdf_table_compute(pbrt[k].g, pbrt[k].eta, t);
        check_table(t, (int)k);
    }
    free(t);
    th_init();
    check_import();
    th_cleanup();
    return tap_done();
}
