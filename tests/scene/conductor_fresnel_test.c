/* conductor_fresnel_test.c: the Fresnel tables of conductors given by
 * spectra (src/scene/conductor_fresnel.c): pbrt-v4's copper, silver and
 * gold against a direct spectral integral (a conductor's reflectance by
 * another formula, pbrt-v3's FrConductor, at every nm, weighted by
 * cv_spectrum_rgb_weights) at the table's entries and between them;
 * constant spectra against the scalar Fresnel term; a coat's index as a
 * divisor; and which materials the importer gives a table (named, file,
 * pair and float spectra and the default copper do; rgb eta or k and
 * reflectance do not; equal conductors share one). */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "scene/conductor_fresnel.h"
#include "scene/fresnel.h"
#include "scene/spectrum.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

enum { FLOATS = 4 * CV_CONDUCTOR_FRESNEL_N };

/* Reflectance of a conductor eta + i k at cos_i by pbrt-v3's FrConductor
 * (real arithmetic; the table uses complex arithmetic). */
static double fr_conductor_v3(double cos_i, double eta, double k)
{
    double c2 = cos_i * cos_i, s2 = 1 - c2, e2 = eta * eta, k2 = k * k;
    double t0 = e2 - k2 - s2, a2b2 = sqrt(t0 * t0 + 4 * e2 * k2), a = sqrt(fmax(0, 0.5 * (a2b2 + t0)));
    double t1 = a2b2 + c2, t2 = 2 * cos_i * a;
    double rs = (t1 - t2) / (t1 + t2);
    double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    double rp = rs * (t3 - t4) / (t3 + t4);
    return (rs + rp) / 2;
}

/* The direct integral: F at every nm of the spectra (pbrt-v4 evaluates
 * them as cv_spectrum_at does) to RGB by cv_spectrum_rgb_weights over
 * nodes at every nm. */
static void direct(const char *metal, double cos_i, double outer, double rgb[3])
{
    char ne[64], nk[64];
    snprintf(ne, sizeof(ne), "metal-%s-eta", metal);
    snprintf(nk, sizeof(nk), "metal-%s-k", metal);
    size_t n_eta, n_k;
    const double *eta = cv_metal_spectrum(ne, &n_eta), *k = cv_metal_spectrum(nk, &n_k);
    static float lambda[CV_SPECTRUM_NM];
    static double w[3 * CV_SPECTRUM_NM];
    for (int i = 0; i < CV_SPECTRUM_NM; i++)
        lambda[i] = (float)(CV_SPECTRUM_NM_MIN + i);
    cv_spectrum_rgb_weights(lambda, CV_SPECTRUM_NM, w);
    rgb[0] = rgb[1] = rgb[2] = 0;
    for (int i = 0; i < CV_SPECTRUM_NM; i++) {
        double f = fr_conductor_v3(cos_i, cv_spectrum_at(eta, n_eta, lambda[i]) / outer,
                                   cv_spectrum_at(k, n_k, lambda[i]) / outer);
        for (int c = 0; c < 3; c++)
            rgb[c] += w[3 * i + c] * f;
    }
}

static void metal_table(const char *metal, double outer, float *table)
{
    char ne[64], nk[64];
    snprintf(ne, sizeof(ne), "metal-%s-eta", metal);
    snprintf(nk, sizeof(nk), "metal-%s-k", metal);
    size_t n_eta, n_k;
    const double *eta = cv_metal_spectrum(ne, &n_eta), *k = cv_metal_spectrum(nk, &n_k);
    cv_conductor_fresnel_table(eta, n_eta, k, n_k, outer, table);
}

/* The table at cos_i, interpolated as glsl/trace/bsdf/fresnel.glsl does. */
static double lookup(const float *table, double cos_i, int c)
{
    double x = cos_i * (CV_CONDUCTOR_FRESNEL_N - 1);
    int i = (int)x < CV_CONDUCTOR_FRESNEL_N - 2 ? (int)x : CV_CONDUCTOR_FRESNEL_N - 2;
    double t = x - i;
    return table[4 * i + c] * (1 - t) + table[4 * (i + 1) + c] * t;
}

static void check_against_direct(const char *metal, double outer)
{
    static float table[FLOATS];
    metal_table(metal, outer, table);
    /* entries (cos 1 and 0.2: i = 255, 51) and between them, towards
     * grazing where F bends most */
    static const double cosines[] = {1.0, 0.8, 0.5, 0.2, 0.05, 0.913, 0.4321, 0.1234, 0.0123, 0.003};
    double worst = 0, at = 0;
    for (size_t j = 0; j < sizeof(cosines) / sizeof(cosines[0]); j++) {
        double d[3];
        direct(metal, cosines[j], outer, d);
        for (int c = 0; c < 3; c++)
            if (fabs(lookup(table, cosines[j], c) - d[c]) > worst) {
                worst = fabs(lookup(table, cosines[j], c) - d[c]);
                at = cosines[j];
            }
    }
    tap_ok(worst < 1e-4, "metal-%s over index %g: table within 1e-4 of the spectral integral at 10 angles "
           "(worst %.2g at cos %g)", metal, outer, worst, at);
}

static void check_tables(void)
{
    check_against_direct("Cu", 1);
    check_against_direct("Ag", 1);
    check_against_direct("Au", 1);
    check_against_direct("Cu", 1.5); /* a coated conductor's base */

    /* constant spectra: every channel is the scalar term */
    static float table[FLOATS];
    double eta[2] = {550, 0.3}, k[2] = {550, 3.1};
    cv_conductor_fresnel_table(eta, 1, k, 1, 1, table);
    double worst = 0;
    for (int i = 0; i < CV_CONDUCTOR_FRESNEL_N; i++)
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs(table[4 * i + c] -
                                     cv_fresnel_complex((double)i / (CV_CONDUCTOR_FRESNEL_N - 1), 0.3, 3.1)));
    tap_ok(worst < 1e-5, "constant eta 0.3, k 3.1: each channel is the scalar Fresnel term (off by %.2g)", worst);
    tap_ok(fabs(cv_fresnel_complex(0.6, 0.3, 3.1) - fr_conductor_v3(0.6, 0.3, 3.1)) < 1e-9 &&
               fabs(cv_fresnel_complex(0.1, 1.7, 0.0) - cv_fresnel_dielectric(0.1, 1.7)) < 1e-9,
           "cv_fresnel_complex: pbrt-v3's formula, and the dielectric term where k = 0");

    /* the reason for the tables: Fresnel of RGB averages of eta and k is
     * another function (blue at normal incidence about 5 % darker) */
    metal_table("Cu", 1, table);
    static const double cu_eta[3] = {0.200438, 0.924033, 1.10221}, cu_k[3] = {3.91295, 2.45285, 2.14219};
    double rgb_blue = cv_fresnel_complex(1, cu_eta[2], cu_k[2]), spec_blue = table[4 * (CV_CONDUCTOR_FRESNEL_N - 1) + 2];
    tap_ok(spec_blue > 1.03 * rgb_blue, "copper at normal incidence: spectral blue %.4f, from RGB eta and k %.4f",
           spec_blue, rgb_blue);
}

static const char *const HEAD =
    "Camera \"perspective\"\nFilm \"rgb\" \"integer xresolution\" [4] \"integer yresolution\" [4]\n"
    "WorldBegin\n";
#define TRI "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point3 P\" [0 0 5 1 0 5 0 1 5]\n"

static void check_import(void)
{
    th_write_str("cu-eta.spd", "# copper's eta at three wavelengths\n400 1.18\n550 0.95\n700 0.21\n");
    char text[4096];
    snprintf(text, sizeof(text),
             "%s"
             "Material \"conductor\"\n" TRI                                                           /* 0 */
             "Material \"conductor\" \"spectrum eta\" \"metal-Cu-eta\" \"spectrum k\" \"metal-Cu-k\"\n" TRI /* 1 */
             "Material \"conductor\" \"spectrum eta\" \"metal-Au-eta\" \"spectrum k\" \"metal-Au-k\"\n" TRI /* 2 */
             "Material \"conductor\" \"rgb eta\" [0.2 0.9 1.1] \"rgb k\" [3.9 2.4 2.1]\n" TRI            /* 3 */
             "Material \"conductor\" \"rgb reflectance\" [0.8 0.8 0.8]\n" TRI                          /* 4 */
             "Material \"conductor\" \"spectrum eta\" \"cu-eta.spd\" \"spectrum k\" [400 2.2 700 3.9]\n" TRI /* 5 */
             "Material \"conductor\" \"float eta\" 0.3 \"float k\" 3.1\n" TRI                          /* 6 */
             "Material \"conductor\" \"spectrum eta\" \"metal-Cu-eta\" \"rgb k\" [3.9 2.4 2.1]\n" TRI    /* 7 */
             "Material \"coatedconductor\"\n" TRI                                                     /* 8 */
             "Material \"coatedconductor\" \"rgb reflectance\" [0.8 0.8 0.8]\n" TRI                    /* 9 */
             "Material \"coatedconductor\" \"float interface.eta\" 1\n" TRI,                          /* 10 */
             HEAD);
    struct cv_error err = {{0}};
    struct cv_scene *s = th_load(text, false, &err);
    tap_ok(s && s->n_materials == 11, "eleven conductors load (%s)", err.msg);
    if (!s || s->n_materials != 11) {
        cv_scene_destroy(&s);
        return;
    }
    const CvMaterial *m = s->materials;
    bool table[11];
    for (int i = 0; i < 11; i++)
        table[i] = (m[i].flags & CV_MATF_CONDUCTOR_FRESNEL) != 0;
    tap_ok(table[0] && table[1] && table[2] && table[5] && table[6] && table[8] && table[10],
           "tables: default copper, named Cu and Au, file and pairs, floats, coated conductors");
    tap_ok(!table[3] && !table[4] && !table[7] && !table[9],
           "no table: rgb eta and k, reflectance, rgb k with a named eta, coated reflectance");
    /* default copper = named copper; the coat (1.5) another table; over
     * a coat of index 1 the bare conductor's */
    tap_ok(m[0].k.w == m[1].k.w && m[10].k.w == m[0].k.w && m[8].k.w != m[0].k.w && m[2].k.w != m[0].k.w,
           "equal conductors share a table (copper %g, named copper %g, coat of index 1 %g; coat 1.5 %g, gold %g)",
           m[0].k.w, m[1].k.w, m[10].k.w, m[8].k.w, m[2].k.w);
    tap_ok(s->n_conductor_fresnel == 5, "five tables (copper, gold, file, floats, coated copper): %u",
           s->n_conductor_fresnel);
    /* the tables are the ones cv_conductor_fresnel_table makes */
    static float want[FLOATS];
    metal_table("Cu", 1.5, want);
    tap_ok(s->n_conductor_fresnel == 5 &&
               memcmp(s->conductor_fresnel + (size_t)m[8].k.w * FLOATS, want, sizeof(want)) == 0,
           "the coated conductor's table is copper's over index 1.5");
    /* eta and k keep their RGB (named copper as before) */
    tap_ok(fabs(m[1].eta.y - 0.924033) < 1e-5 && fabs(m[1].k.z - 2.14219) < 1e-5,
           "named copper keeps RGB eta and k");
    cv_scene_destroy(&s);
}

int main(void)
{
    th_init();
    check_tables();
    check_import();
    th_cleanup();
    return tap_done();
}
