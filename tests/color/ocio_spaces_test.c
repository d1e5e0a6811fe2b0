/* ocio_spaces_test.c: configs whose scene_linear role is not the render's
 * linear Rec.709 (tests/data/color/acescg.ocio: ACEScg), checked against
 * colour maths done here from the primaries (Bradford adaptation, as
 * OpenColorIO's built-in ACES transforms use): the ACEScg view shows the
 * render's colours converted to ACEScg, an sRGB-encoded view gives back the
 * sRGB encoding of the render's colours, and the ACES view equals the
 * shipped config's. Configs that do not say where linear Rec.709 lies, or
 * misname it, fail. And which encoding each view is found to end in (what
 * PNGs are tagged with). */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "color/ocio.h"
#include "tests/tap.h"

typedef double mat3[3][3];

static void mul(const mat3 a, const mat3 b, mat3 out)
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
}

static void inv(const mat3 m, mat3 out)
{
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    out[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    out[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    out[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    out[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    out[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    out[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    out[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    out[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    out[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
}

static void xy_to_XYZ(const double xy[2], double out[3])
{
    out[0] = xy[0] / xy[1];
    out[1] = 1;
    out[2] = (1 - xy[0] - xy[1]) / xy[1];
}

/* RGB -> XYZ of primaries r, g, b and white w (CIE xy). */
static void rgb_to_xyz(const double p[4][2], mat3 out)
{
    mat3 m, mi;
    for (int c = 0; c < 3; c++) {
        double v[3];
        xy_to_XYZ(p[c], v);
        for (int i = 0; i < 3; i++)
            m[i][c] = v[i];
    }
    double w[3], s[3];
    xy_to_XYZ(p[3], w);
    inv(m, mi);
    for (int i = 0; i < 3; i++)
        s[i] = mi[i][0] * w[0] + mi[i][1] * w[1] + mi[i][2] * w[2];
    for (int i = 0; i < 3; i++)
        for (int c = 0; c < 3; c++)
            out[i][c] = m[i][c] * s[c];
}

/* Linear Rec.709 (D65) -> ACEScg (AP1, ACES white), Bradford-adapted. */
static void rec709_to_acescg(mat3 out)
{
    static const double rec709[4][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
    static const double ap1[4][2] = {{0.713, 0.293}, {0.165, 0.830}, {0.128, 0.044},
                                     {0.32168, 0.33767}};
    static const mat3 bfd = {{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367},
                             {0.0389, -0.0685, 1.0296}};
    mat3 a, b, bi, cat, t, ai, diag = {{0}};
    rgb_to_xyz(rec709, a);
    rgb_to_xyz(ap1, b);
    double ws[3], wd[3], cs[3], cd[3];
    xy_to_XYZ(rec709[3], ws);
    xy_to_XYZ(ap1[3], wd);
    for (int i = 0; i < 3; i++) {
        cs[i] = bfd[i][0] * ws[0] + bfd[i][1] * ws[1] + bfd[i][2] * ws[2];
        cd[i] = bfd[i][0] * wd[0] + bfd[i][1] * wd[1] + bfd[i][2] * wd[2];
        diag[i][i] = cd[i] / cs[i];
    }
    inv(bfd, bi);
    mul(bi, diag, t);
    mul(t, bfd, cat);
    inv(b, ai);
    mul(cat, a, t);
    mul(ai, t, out);
}

static double srgb_encode(double v)
{
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static bool apply1(const struct cv_color_params *p, const float in[3], float out[4], char *msg)
{
    struct cv_error err = {{0}};
    struct cv_ocio *o = NULL;
    out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 1;
    bool ok = cv_ocio_create(p, &o, &err) && cv_ocio_apply_cpu(o, out, 1, &err);
    if (!ok && msg)
        snprintf(msg, CV_ERROR_MAX, "%s", err.msg);
    cv_ocio_destroy(&o);
    return ok;
}

static const char *fail_msg(const struct cv_color_params *p)
{
    static struct cv_error err;
    struct cv_ocio *o = NULL;
    cv_error_clear(&err);
    if (cv_ocio_create(p, &o, &err)) {
        cv_ocio_destroy(&o);
        return "(no error)";
    }
    return err.msg;
}

static void check_encoding(const char *config, const char *display, const char *view,
                           enum cv_display_encoding want)
{
    struct cv_error err = {{0}};
    struct cv_ocio *o = NULL;
    struct cv_color_params p = {.config_path = config, .display = display, .view = view};
    bool ok = cv_ocio_create(&p, &o, &err);
    enum cv_display_encoding got = ok ? cv_ocio_display_encoding(o) : CV_DISPLAY_UNKNOWN;
    tap_ok(ok && got == want, "%s: %s / %s ends in %s (found %s) %s",
           config ? strrchr(config, '/') + 1 : "shipped", display, view,
           cv_display_encoding_name(want), cv_display_encoding_name(got), err.msg);
    cv_ocio_destroy(&o);
}

int main(void)
{
    unsetenv("OCIO");
    const char *data = getenv("CV_TEST_DATA");
    char *acescg = cv_xasprintf("%s/color/acescg.ocio", data ? data : "tests/data");
    char *misnamed = cv_xasprintf("%s/color/misnamed.ocio", data ? data : "tests/data");
    char *unplaced = cv_xasprintf("%s/color/unplaced.ocio", data ? data : "tests/data");
    char *lut = cv_xasprintf("%s/color/lut_look.ocio", data ? data : "tests/data");
    char msg[CV_ERROR_MAX] = "";
    /* render colours: greys, saturated primaries (a Cornell box red wall's
     * albedo), mixtures, and one above 1 */
    static const float colours[][3] = {
        {0.18f, 0.18f, 0.18f}, {1, 0, 0}, {0, 1, 0},        {0, 0, 1},
        {0.63f, 0.065f, 0.05f}, {0.14f, 0.45f, 0.091f}, {0.8f, 0.5f, 0.2f}, {4.0f, 2.0f, 0.5f},
    };
    const int n = sizeof(colours) / sizeof(colours[0]);

    /* ACEScg view: the render's colours in ACEScg */
    mat3 m;
    rec709_to_acescg(m);
    double worst = 0;
    bool ok = true;
    for (int k = 0; k < n && ok; k++) {
        float out[4];
        ok = apply1(&(struct cv_color_params){.config_path = acescg, .view = "ACEScg"},
                    colours[k], out, msg);
        for (int i = 0; ok && i < 3; i++) {
            double want = m[i][0] * colours[k][0] + m[i][1] * colours[k][1] +
                          m[i][2] * colours[k][2];
            worst = fmax(worst, fabs(out[i] - want) / fmax(1.0, fabs(want)));
        }
        if (k == 1)
            tap_diag("Rec.709 red in ACEScg: %g %g %g (computed %g %g %g)", out[0], out[1],
                     out[2], m[0][0], m[1][0], m[2][0]);
    }
    tap_ok(ok && worst < 2e-4,
           "ACEScg scene_linear: the ACEScg view holds the render's colours converted from "
           "linear Rec.709 to ACEScg (largest error %.2g) %s", worst, msg);

    /* sRGB-encoded view: the round trip through ACEScg gives sRGB back */
    worst = 0;
    for (int k = 0; k < n - 1 && ok; k++) {
        float out[4];
        ok = apply1(&(struct cv_color_params){.config_path = acescg, .view = "Encoded"},
                    colours[k], out, msg);
        for (int i = 0; ok && i < 3; i++)
            worst = fmax(worst, fabs(out[i] - srgb_encode(colours[k][i])));
    }
    tap_ok(ok && worst < 2e-4,
           "ACEScg scene_linear: the sRGB-encoded view is the sRGB encoding of the render's "
           "colours (largest error %.2g) %s", worst, msg);

    /* the same ACES output transform in both configs shows the same image */
    worst = 0;
    for (int k = 0; k < n && ok; k++) {
        float a[4], b[4];
        ok = apply1(&(struct cv_color_params){.config_path = acescg}, colours[k], a, msg) &&
             apply1(&(struct cv_color_params){0}, colours[k], b, msg);
        for (int i = 0; ok && i < 3; i++)
            worst = fmax(worst, fabs(a[i] - b[i]));
        if (k == 4)
            tap_diag("red wall albedo through ACES SDR video: ACEScg config %g %g %g, shipped "
                     "%g %g %g", a[0], a[1], a[2], b[0], b[1], b[2]);
    }
    tap_ok(ok && worst < 1e-4,
           "ACEScg scene_linear: the ACES SDR view equals the shipped config's (largest "
           "difference %.2g) %s", worst, msg);
    float e1[4], e0[4], half[3] = {0.09f, 0.09f, 0.09f}, grey[3] = {0.18f, 0.18f, 0.18f};
    ok = apply1(&(struct cv_color_params){.config_path = acescg, .exposure = 1}, half, e1, msg) &&
         apply1(&(struct cv_color_params){.config_path = acescg}, grey, e0, msg);
    tap_ok(ok && fabsf(e1[0] - e0[0]) < 1e-5f, "+1 EV doubles the render's values (%g vs %g)",
           e1[0], e0[0]);

    struct cv_error err = {{0}};
    struct cv_ocio *o = NULL;
    ok = cv_ocio_create(&(struct cv_color_params){.config_path = acescg}, &o, &err);
    tap_ok(ok && strstr(cv_ocio_render_space(o), "aces_interchange"),
           "ACEScg config: the render's space found through %s", ok ? cv_ocio_render_space(o) : err.msg);
    cv_ocio_destroy(&o);
    ok = cv_ocio_create(&(struct cv_color_params){0}, &o, &err);
    tap_ok(ok && strcmp(cv_ocio_render_space(o), "colour space \"lin_rec709\"") == 0,
           "shipped config: the render's space is its %s", ok ? cv_ocio_render_space(o) : err.msg);
    cv_ocio_destroy(&o);

    const char *f = fail_msg(&(struct cv_color_params){.config_path = unplaced});
    tap_ok(strstr(f, unplaced) && strstr(f, "does not say where linear Rec.709") &&
               strstr(f, "aces_interchange") && strstr(f, "lin_rec709"),
           "a config that does not say where linear Rec.709 lies fails: %s", f);
    f = fail_msg(&(struct cv_color_params){.config_path = misnamed});
    tap_ok(strstr(f, misnamed) && strstr(f, "\"lin_rec709\" is named as linear Rec.709") &&
               strstr(f, "ACES2065-1"),
           "a space named lin_rec709 that is not is refused: %s", f);

    /* what each view is found to end in */
    check_encoding(NULL, "sRGB", "ACES 1.0 - SDR Video", CV_DISPLAY_SRGB);
    check_encoding(NULL, "sRGB", "Un-tone-mapped", CV_DISPLAY_SRGB);
    check_encoding(NULL, "sRGB", "Raw", CV_DISPLAY_UNKNOWN);
    check_encoding(NULL, "Rec.1886", "ACES 1.0 - SDR Video", CV_DISPLAY_BT1886);
    check_encoding(NULL, "Rec.1886", "Raw", CV_DISPLAY_UNKNOWN);
    check_encoding(NULL, "Display P3", "ACES 1.0 - SDR Video", CV_DISPLAY_P3);
    check_encoding(NULL, "Display P3", "Un-tone-mapped", CV_DISPLAY_P3);
    check_encoding(acescg, "sRGB", "ACES 1.0 - SDR Video", CV_DISPLAY_SRGB);
    check_encoding(acescg, "sRGB", "Encoded", CV_DISPLAY_SRGB);
    check_encoding(acescg, "sRGB", "ACEScg", CV_DISPLAY_UNKNOWN);
    check_encoding(acescg, "sRGB", "Raw", CV_DISPLAY_UNKNOWN);
    check_encoding(acescg, "Display P3", "Encoded", CV_DISPLAY_P3);
    check_encoding(acescg, "Rec.1886", "Encoded", CV_DISPLAY_BT1886);
    check_encoding(lut, "sRGB", "Standard", CV_DISPLAY_SRGB);

    free(acescg);
    free(misnamed);
    free(unplaced);
    free(lut);
    return tap_done();
}
