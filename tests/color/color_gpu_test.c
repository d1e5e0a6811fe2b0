/* color_gpu_test.c: the GPU colour pass equals OpenColorIO's CPU processor
 * (max abs error 1e-4 on every channel) on thousands of random colours:
 * negatives, zero, HDR values far above 1. For every view of every display
 * of the shipped config, with a look and with exposure, and for a test
 * config whose looks are LUT files (3D .cube trilinear and tetrahedral, a
 * long 1D .spi1d folded into a 2D texture, a short one as a 1D texture). */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "color/color.h"
#include "color/ocio.h"
#include "gpu/buf.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"

#define WIDTH 61          /* 61 x 67 = 4087: not a multiple of the work group */
#define HEIGHT 67
#define N_COLOURS (WIDTH * HEIGHT)
#define TOLERANCE 1e-4

static uint32_t rng_state = 20261122u;

static float rnd(void)
{
    return (float)cv_test_lcg32(&rng_state);
}

static float *make_colours(void)
{
    float *c = cv_xmalloc(N_COLOURS * 4 * sizeof(float));
    for (int i = 0; i < N_COLOURS; i++) {
        for (int k = 0; k < 3; k++) {
            float u = rnd(), v;
            switch (i % 5) {
            case 0: v = u; break;                          /* [0, 1) */
            case 1: v = 2.0f * u - 1.0f; break;            /* negatives */
            case 2: v = 64.0f * u * u * u; break;          /* HDR */
            case 3: v = (k == (i / 5) % 3) ? 0.0f : u; break;  /* zeros */
            default: v = 0.25f * u; break;                 /* darks */
            }
            c[4 * i + k] = v;
        }
        c[4 * i + 3] = i % 7 == 0 ? 1.0f : rnd();
    }
    c[0] = c[1] = c[2] = 0.0f;                 /* black */
    c[4] = c[5] = c[6] = 0.18f;                /* mid grey */
    c[8] = c[9] = c[10] = 1000.0f;             /* very bright */
    return c;
}

struct cmp {
    double max_err;
    int worst;
    bool ran;
};

static struct cmp compare(struct cv_gpu *gpu, const struct cv_color_params *p, const float *in,
                          struct cv_error *err)
{
    struct cmp r = {0, -1, false};
    struct cv_color_pass *pass = NULL;
    if (!cv_color_pass_create(gpu, p, &pass, err))
        return r;
    size_t bytes = N_COLOURS * 4 * sizeof(float);
    float *gpu_out = cv_xmalloc(bytes), *cpu_out = cv_xmalloc(bytes);
    memcpy(cpu_out, in, bytes);
    struct cv_buf *b_in = cv_buf_create(
        gpu, &(struct cv_buf_params){.size = bytes, .storable = true, .initial = in,
                                     .label = "colour in"},
        err);
    if (b_in && cv_color_pass_run(pass, b_in, WIDTH, HEIGHT, gpu_out, err) &&
        cv_color_apply_cpu(pass, cpu_out, N_COLOURS, err)) {
        r.ran = true;
        for (int i = 0; i < N_COLOURS * 4; i++) {
            double e = fabs((double)gpu_out[i] - (double)cpu_out[i]);
            if (!(e <= r.max_err)) {   /* NaN counts as the worst */
                r.max_err = isnan(e) ? INFINITY : e;
                r.worst = i;
            }
        }
        if (r.worst >= 0 && r.max_err > TOLERANCE) {
            int px = r.worst / 4;
            tap_diag("worst: pixel %d channel %d in (%g %g %g %g) gpu %.7g cpu %.7g", px,
                     r.worst % 4, in[4 * px], in[4 * px + 1], in[4 * px + 2], in[4 * px + 3],
                     gpu_out[r.worst], cpu_out[r.worst]);
        }
    }
    cv_buf_destroy(&b_in);
    free(gpu_out);
    free(cpu_out);
    cv_color_pass_destroy(&pass);
    return r;
}

static void check(struct cv_gpu *gpu, const struct cv_color_params *p, const float *in,
                  const char *what)
{
    struct cv_error err = {{0}};
    struct cmp r = compare(gpu, p, in, &err);
    if (!r.ran)
        tap_ok(false, "%s: %s", what, err.msg);
    else
        tap_ok(r.max_err <= TOLERANCE, "%s: GPU equals CPU (max abs error %.3g)", what,
               r.max_err);
}

int main(void)
{
    /* the shipped config, whatever the environment says */
    unsetenv("OCIO");
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    float *in = make_colours();

    char **names = NULL;
    size_t n_pairs = 0;
    bool listed = cv_ocio_list_views(NULL, &names, &n_pairs, &err);
    tap_ok(listed && n_pairs >= 9,
           "shipped config lists %zu display/view pairs %s", n_pairs, err.msg);
    for (size_t i = 0; i < n_pairs; i++) {
        struct cv_color_params p = {.display = names[2 * i], .view = names[2 * i + 1]};
        char *what = cv_xasprintf("shipped %s / %s", p.display, p.view);
        check(gpu, &p, in, what);
        free(what);
    }
    cv_ocio_free_names(&names);

    check(gpu, &(struct cv_color_params){.exposure = 1.5f}, in, "shipped default view, +1.5 EV");
    check(gpu, &(struct cv_color_params){.display = "Display P3", .exposure = -2.0f}, in,
          "shipped Display P3 default view, -2 EV");
    check(gpu,
          &(struct cv_color_params){.display = "sRGB", .view = "ACES 1.0 - SDR Video",
                                    .look = "ACES 1.3 Reference Gamut Compression"},
          in, "shipped sRGB / ACES with the gamut compression look");

    /* Two passes alive at once whose processors differ only in exposure
     * (a dynamic uniform, so one program from the cache may serve both):
     * each run must use its own pass's values, whichever ran before. */
    {
        struct cv_color_pass *up = NULL, *down = NULL;
        size_t nb = N_COLOURS * 4 * sizeof(float);
        float *got = cv_xmalloc(nb), *want = cv_xmalloc(nb);
        struct cv_buf *bi = NULL;
        bool fine = cv_color_pass_create(gpu, &(struct cv_color_params){.exposure = 1}, &up,
                                         &err) &&
                    cv_color_pass_create(gpu, &(struct cv_color_params){.exposure = -1}, &down,
                                         &err) &&
                    (bi = cv_buf_create(gpu, &(struct cv_buf_params){.size = nb, .storable = true,
                                                                      .initial = in,
                                                                      .label = "colour in"},
                                        &err));
        struct cv_color_pass *order[3] = {up, down, up};
        double worst = 0;
        for (int k = 0; fine && k < 3; k++) {
            memcpy(want, in, nb);
            fine = cv_color_pass_run(order[k], bi, WIDTH, HEIGHT, got, &err) &&
                   cv_color_apply_cpu(order[k], want, N_COLOURS, &err);
            for (int i = 0; fine && i < N_COLOURS * 4; i++)
                worst = fmax(worst, fabs((double)got[i] - want[i]));
        }
        tap_ok(fine && worst <= TOLERANCE,
               "+1 EV, -1 EV, +1 EV passes interleaved: each its own (max abs error %.3g) %s",
               worst, err.msg);
        cv_buf_destroy(&bi);
        cv_color_pass_destroy(&up);
        cv_color_pass_destroy(&down);
        free(got);
        free(want);
    }

    /* one pass on half the image and then on all of it (its own output
     * buffer grows), and an input buffer too small for the image */
    struct cv_color_pass *pass = NULL;
    size_t bytes = N_COLOURS * 4 * sizeof(float);
    float *a = cv_xmalloc(bytes), *b = cv_xmalloc(bytes);
    memcpy(b, in, bytes);
    struct cv_buf *buf = NULL, *small = NULL;
    bool ok = cv_color_pass_create(gpu, &(struct cv_color_params){.view = "Un-tone-mapped"}, &pass,
                                   &err) &&
              (buf = cv_buf_create(gpu, &(struct cv_buf_params){.size = bytes, .storable = true,
                                                                .initial = in,
                                                                .label = "colour in"},
                                   &err)) &&
              cv_color_pass_run(pass, buf, WIDTH, HEIGHT / 2, a, &err) &&
              cv_color_pass_run(pass, buf, WIDTH, HEIGHT, a, &err) &&
              cv_color_apply_cpu(pass, b, N_COLOURS, &err);
    double max_err = 0;
    for (int i = 0; ok && i < N_COLOURS * 4; i++)
        max_err = fmax(max_err, fabs((double)a[i] - b[i]));
    tap_ok(ok && max_err <= TOLERANCE, "half the image, then all: GPU equals CPU (%.3g) %s",
           max_err, err.msg);
    tap_ok(ok && strcmp(cv_color_pass_description(pass), "sRGB / Un-tone-mapped") == 0,
           "description \"%s\"", ok ? cv_color_pass_description(pass) : "");
    small = cv_buf_create(gpu, &(struct cv_buf_params){.size = bytes / 2, .storable = true,
                                                       .label = "colour small"},
                          &err);
    cv_error_clear(&err);
    ok = pass && small && !cv_color_pass_run(pass, small, WIDTH, HEIGHT, a, &err);
    tap_ok(ok && strstr(err.msg, "input buffer holds"), "a too-small input buffer is an error: %s",
           err.msg);
    cv_buf_destroy(&buf);
    cv_buf_destroy(&small);
    cv_color_pass_destroy(&pass);
    tap_ok(pass == NULL, "destroy clears the pointer");
    cv_error_clear(&err);
    ok = !cv_color_pass_create(gpu, &(struct cv_color_params){.display = "nope"}, &pass, &err);
    tap_ok(ok && pass == NULL && strstr(err.msg, "\"sRGB\""),
           "a bad display fails creation, listing displays: %s", err.msg);
    free(a);
    free(b);

    /* a config whose looks are LUT files */
    const char *data = getenv("CV_TEST_DATA");
    char *lut_config = cv_xasprintf("%s/color/lut_look.ocio", data ? data : "tests/data");
    listed = cv_ocio_list_views(lut_config, &names, &n_pairs, &err);
    tap_ok(listed && n_pairs == 5,
           "LUT config lists %zu views %s", n_pairs, err.msg);
    for (size_t i = 0; i < n_pairs; i++) {
        struct cv_color_params p = {.config_path = lut_config, .display = names[2 * i],
                                    .view = names[2 * i + 1]};
        char *what = cv_xasprintf("LUT config %s / %s", p.display, p.view);
        check(gpu, &p, in, what);
        free(what);
    }
    cv_ocio_free_names(&names);
    check(gpu,
          &(struct cv_color_params){.config_path = lut_config, .look = "curve, +warm",
                                    .exposure = 0.5f},
          in, "LUT config, looks \"curve, +warm\" overriding the view's, +0.5 EV");
    free(lut_config);

    /* a config whose scene_linear is ACEScg: the GPU pass starts from the
     * render's linear Rec.709 as the CPU does (ocio_spaces_test checks the
     * CPU against colour maths). Views that end in [0, 1]: the linear ones
     * carry the test colours' large values, where float rounding alone
     * passes the absolute tolerance. */
    char *acescg = cv_xasprintf("%s/color/acescg.ocio", data ? data : "tests/data");
    const char *acescg_views[][2] = {
        {"sRGB", "ACES 1.0 - SDR Video"}, {"sRGB", "Encoded"}, {"Display P3", "Encoded"}};
    for (int i = 0; i < 3; i++) {
        struct cv_color_params p = {.config_path = acescg, .display = acescg_views[i][0],
                                    .view = acescg_views[i][1], .exposure = 0.5f};
        char *what = cv_xasprintf("ACEScg config %s / %s, +0.5 EV", p.display, p.view);
        check(gpu, &p, in, what);
        free(what);
    }
    free(acescg);

    free(in);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
