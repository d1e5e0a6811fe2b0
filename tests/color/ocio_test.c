/* ocio_test.c: the OpenColorIO shim without a GPU: where the config comes
 * from ($OCIO, a job's path, CAVALRY_DATA_DIR, the copy in the binary), the
 * errors for missing files and unknown names (which must list the valid
 * ones), what the shipped config's views do to known colours, and which LUT
 * textures and uniforms the generated GPU code asks for. */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "color/ocio.h"
#include "tests/tap.h"

static bool has(const char *msg, const char *needle)
{
    return strstr(msg, needle) != NULL;
}

/* Expects failure; returns the message (static). */
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

/* Applies p's CPU processor to one RGB colour (alpha 1). */
static bool apply1(const struct cv_color_params *p, const float in[3], float out[4])
{
    struct cv_error err = {{0}};
    struct cv_ocio *o = NULL;
    if (!cv_ocio_create(p, &o, &err)) {
        tap_diag("%s", err.msg);
        return false;
    }
    out[0] = in[0], out[1] = in[1], out[2] = in[2], out[3] = 1.0f;
    bool ok = cv_ocio_apply_cpu(o, out, 1, &err);
    cv_ocio_destroy(&o);
    return ok;
}

static bool near3(const float *a, float x, float y, float z, float tol)
{
    return fabsf(a[0] - x) <= tol && fabsf(a[1] - y) <= tol && fabsf(a[2] - z) <= tol;
}

int main(void)
{
    const char *data = getenv("CV_TEST_DATA");
    char *lut_config = cv_xasprintf("%s/color/lut_look.ocio", data ? data : "tests/data");
    char *broken = cv_xasprintf("%s/color/broken.ocio", data ? data : "tests/data");
    struct cv_error err = {{0}};
    struct cv_ocio *o = NULL;
    const char *m;

    /* $OCIO */
    setenv("OCIO", "/nonexistent/cavalry-test/missing.ocio", 1);
    m = fail_msg(&(struct cv_color_params){0});
    tap_ok(has(m, "/nonexistent/cavalry-test/missing.ocio") && has(m, "$OCIO") &&
               has(m, "does not exist"),
           "$OCIO naming a missing file is an error naming it: %s", m);
    m = fail_msg(&(struct cv_color_params){.config_path = "/nonexistent/job.ocio"});
    tap_ok(has(m, "/nonexistent/job.ocio") && has(m, "no such file"),
           "a job's missing config path is an error naming it: %s", m);
    setenv("OCIO", lut_config, 1);
    bool ok = cv_ocio_create(&(struct cv_color_params){0}, &o, &err);
    tap_ok(ok && strcmp(cv_ocio_config_source(o), lut_config) == 0,
           "$OCIO is used when the job names no config (%s)", ok ? cv_ocio_config_source(o) : err.msg);
    cv_ocio_destroy(&o);
    tap_ok(o == NULL, "destroy clears the pointer");
    ok = cv_ocio_create(&(struct cv_color_params){.config_path = lut_config}, &o, &err);
    cv_ocio_destroy(&o);
    setenv("OCIO", broken, 1);
    m = fail_msg(&(struct cv_color_params){0});
    tap_ok(has(m, broken) && !has(m, "(no error)"), "a config that does not parse names its path: %s", m);
    unsetenv("OCIO");

    /* the shipped config: from the source tree and from the binary */
    const char *data_dir = getenv("CAVALRY_DATA_DIR");
    float grey[3] = {0.18f, 0.18f, 0.18f}, a[4], b[4];
    if (data_dir) {
        char *want = cv_xasprintf("%s/configs/cavalry.ocio", data_dir);
        ok = cv_ocio_create(&(struct cv_color_params){0}, &o, &err);
        tap_ok(ok && strcmp(cv_ocio_config_source(o), want) == 0,
               "CAVALRY_DATA_DIR's configs/cavalry.ocio is used (%s)",
               ok ? cv_ocio_config_source(o) : err.msg);
        cv_ocio_destroy(&o);
        free(want);
        apply1(&(struct cv_color_params){0}, grey, a);
    }
    unsetenv("CAVALRY_DATA_DIR");
    ok = cv_ocio_create(&(struct cv_color_params){0}, &o, &err);
    tap_ok(ok && strcmp(cv_ocio_config_source(o), "shipped cavalry.ocio") == 0,
           "without CAVALRY_DATA_DIR the config compiled into the binary is used (%s)",
           ok ? cv_ocio_config_source(o) : err.msg);
    tap_ok(ok && strcmp(cv_ocio_description(o), "sRGB / ACES 1.0 - SDR Video") == 0,
           "default display and view: \"%s\"", ok ? cv_ocio_description(o) : "");
    cv_ocio_destroy(&o);
    ok = apply1(&(struct cv_color_params){0}, grey, b);
    if (data_dir)
        tap_ok(memcmp(a, b, sizeof(a)) == 0, "file and embedded copies give the same result");
    tap_ok(ok && b[0] > 0.3f && b[0] < 0.5f && b[0] == b[1] && b[1] == b[2],
           "ACES SDR video shows 18%% grey as a neutral mid-tone (%g %g %g)", b[0], b[1], b[2]);

    /* unknown names list the valid ones */
    m = fail_msg(&(struct cv_color_params){.display = "Cinema"});
    tap_ok(has(m, "unknown display \"Cinema\"") && has(m, "\"sRGB\"") && has(m, "\"Rec.1886\"") &&
               has(m, "\"Display P3\""),
           "unknown display lists the displays: %s", m);
    m = fail_msg(&(struct cv_color_params){.display = "sRGB", .view = "Filmic"});
    tap_ok(has(m, "unknown view \"Filmic\"") && has(m, "\"ACES 1.0 - SDR Video\"") &&
               has(m, "\"Un-tone-mapped\"") && has(m, "\"Raw\""),
           "unknown view lists the display's views: %s", m);
    m = fail_msg(&(struct cv_color_params){.look = "Bleach"});
    tap_ok(has(m, "unknown look \"Bleach\"") && has(m, "\"ACES 1.3 Reference Gamut Compression\""),
           "unknown look lists the looks: %s", m);
    m = fail_msg(&(struct cv_color_params){.config_path = lut_config, .look = "warm, -sepia"});
    tap_ok(has(m, "unknown look \"sepia\"") && has(m, "\"warm\"") && has(m, "\"curve\""),
           "an unknown look inside a list is named: %s", m);

    m = fail_msg(&(struct cv_color_params){.exposure = NAN});
    tap_ok(has(m, "exposure"), "a NaN exposure is an error: %s", m);

    /* what the shipped views do */
    float white[3] = {1, 1, 1}, red[3] = {1, 0, 0};
    const struct cv_color_params srgb_std = {.display = "sRGB", .view = "Un-tone-mapped"};
    const struct cv_color_params p3_std = {.display = "Display P3", .view = "Un-tone-mapped"};
    ok = apply1(&srgb_std, grey, a);
    tap_ok(ok && near3(a, 0.4613561f, 0.4613561f, 0.4613561f, 1e-4f),
           "sRGB un-tone-mapped: 0.18 encodes to 0.46136 (%g %g %g)", a[0], a[1], a[2]);
    ok = apply1(&srgb_std, red, a);
    tap_ok(ok && near3(a, 1, 0, 0, 1e-4f),
           "sRGB un-tone-mapped: Rec.709 red stays sRGB red (%g %g %g)", a[0], a[1], a[2]);
    ok = apply1(&(struct cv_color_params){.display = "Rec.1886", .view = "Un-tone-mapped"}, grey, a);
    tap_ok(ok && near3(a, 0.4894371f, 0.4894371f, 0.4894371f, 1e-4f),
           "Rec.1886 un-tone-mapped: 0.18 encodes as 0.18^(1/2.4) (%g)", a[0]);
    ok = apply1(&p3_std, white, a) && apply1(&p3_std, red, b);
    tap_ok(ok && near3(a, 1, 1, 1, 1e-4f) && b[0] > 0.9f && b[0] < 0.93f && b[1] > 0.1f &&
               b[2] > 0.1f,
           "Display P3: white stays white (%g), Rec.709 red lies inside P3 (%g %g %g)", a[0], b[0],
           b[1], b[2]);
    float big[3] = {37.5f, -2.0f, 0.5f};
    ok = apply1(&(struct cv_color_params){.view = "Raw"}, big, a) &&
         apply1(&(struct cv_color_params){.view = "Raw", .exposure = 3}, big, b);
    tap_ok(ok && near3(a, 37.5f, -2.0f, 0.5f, 0.0f) && near3(b, 300.0f, -16.0f, 4.0f, 0.0f),
           "Raw passes values through untouched (%g %g %g); an asked-for exposure still "
           "scales them (+3 EV: %g %g %g)", a[0], a[1], a[2], b[0], b[1], b[2]);
    float half_grey[3] = {0.09f, 0.09f, 0.09f};
    ok = apply1(&(struct cv_color_params){.exposure = 1.0f}, half_grey, a) &&
         apply1(&(struct cv_color_params){0}, grey, b);
    tap_ok(ok && near3(a, b[0], b[1], b[2], 1e-5f),
           "+1 EV doubles scene-linear values before the view (%g vs %g)", a[0], b[0]);
    ok = cv_ocio_create(&(struct cv_color_params){.look = "", .exposure = -0.5f}, &o, &err);
    tap_ok(ok && strcmp(cv_ocio_description(o), "sRGB / ACES 1.0 - SDR Video / exposure -0.5 EV") == 0,
           "description carries exposure: \"%s\"", ok ? cv_ocio_description(o) : err.msg);

    /* the GPU resources OpenColorIO asks for */
    ok = ok && cv_ocio_gpu_extract(o, "f", &err);
    bool exposure_uniform = false;
    for (unsigned i = 0; ok && i < cv_ocio_gpu_uniform_count(o); i++) {
        struct cv_ocio_uniform u;
        if (cv_ocio_gpu_uniform(o, i, &u, &err) && u.type == CV_OCIO_UNIFORM_FLOAT &&
            fabsf(u.v[0] + 0.5f) < 1e-6f)
            exposure_uniform = true;
    }
    tap_ok(exposure_uniform && has(cv_ocio_gpu_source(o), "vec4 f(") ,
           "exposure is a GPU uniform holding -0.5; the function is named f");
    cv_ocio_destroy(&o);

    unsigned dims_seen[4] = {0};
    const char *views[] = {"Warm", "Curve", "Small curve"};
    for (int v = 0; v < 3; v++) {
        ok = cv_ocio_create(&(struct cv_color_params){.config_path = lut_config, .view = views[v]},
                            &o, &err) && cv_ocio_gpu_extract(o, "f", &err);
        for (unsigned i = 0; ok && i < cv_ocio_gpu_texture_count(o); i++) {
            struct cv_ocio_texture t;
            if (cv_ocio_gpu_texture(o, i, &t, &err)) {
                tap_diag("%s: texture %s: %uD %ux%ux%u, %u channel(s), %s", views[v], t.sampler,
                         t.dims, t.width, t.height, t.depth, t.channels,
                         t.linear ? "linear" : "nearest");
                dims_seen[t.dims]++;
            }
        }
        cv_ocio_destroy(&o);
    }
    tap_ok(dims_seen[3] == 1, "the 3D LUT look gives one 3D texture");
    tap_ok(dims_seen[2] == 1, "the 5000-entry 1D LUT comes as a 2D texture");
    tap_ok(dims_seen[1] == 1, "the 65-entry 1D LUT comes as a 1D texture");

    char **names = NULL;
    size_t n = 0;
    ok = cv_ocio_list_views(NULL, &names, &n, &err);
    tap_ok(ok && n == 9, "the shipped config has 3 displays x 3 views (%zu pairs)", n);
    for (size_t i = 0; i < n; i++)
        tap_diag("shipped: %s / %s", names[2 * i], names[2 * i + 1]);
    cv_ocio_free_names(&names);
    tap_ok(names == NULL, "free_names clears the pointer");

    free(lut_config);
    free(broken);
    return tap_done();
}
