/* exr_scale.c: how two EXR renders of one scene relate, for the light
 * override tests:
 *   exr_scale mean FILE              the mean of R, G and B over all pixels
 *   exr_scale times A B K TOL        every RGB value of B is K times A's,
 *                                    within TOL relative (plus 1e-6
 *                                    absolute); exit 1 where not, 2 on a
 *                                    bad use or an unreadable file
 *   exr_scale display EXR PNG K      every R, G, B of the 8-bit PNG (read
 *                                    with libpng) is K times the EXR's
 *                                    value through the sRGB curve, clipped
 *                                    to [0, 1], within one code value; and
 *                                    a quarter of them at least lie off the
 *                                    clip (exit 1 if not) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "output/exr_read.h"

static float *load(const char *path, uint32_t *w, uint32_t *h)
{
    float *px = NULL;
    struct cv_error err = {{0}};
    if (!cv_exr_read_rgba(path, &px, w, h, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(2);
    }
    return px;
}

/* The sRGB curve (IEC 61966-2-1), as OCIO's ExponentWithLinearTransform
 * of gamma 2.4 and offset 0.055 writes it. */
static double srgb_encode(double v)
{
    v = v < 0 ? 0 : v > 1 ? 1 : v;
    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
}

static int display(const char *exr, const char *path, double k)
{
    uint32_t w, h;
    float *lin = load(exr, &w, &h);
    png_image img;
    memset(&img, 0, sizeof(img));
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path) || (img.format & PNG_FORMAT_FLAG_LINEAR)) {
        fprintf(stderr, "%s: not an 8-bit PNG\n", path);
        return 2;
    }
    img.format = PNG_FORMAT_RGB;
    unsigned char *px = malloc(PNG_IMAGE_SIZE(img));
    if (!px || !png_image_finish_read(&img, NULL, px, 0, NULL) || img.width != w ||
        img.height != h) {
        fprintf(stderr, "%s: unreadable, or not %ux%u\n", path, w, h);
        return 2;
    }
    int rc = 0;
    size_t inside = 0, n = (size_t)w * h * 3;
    for (size_t i = 0; i < n; i++) {
        double want = 255 * srgb_encode(k * lin[4 * (i / 3) + i % 3]);
        if (fabs(px[i] - want) > 1) {
            fprintf(stderr, "pixel %zu channel %zu: %u, want %.2f (%g x %g)\n", i / 3, i % 3,
                    px[i], want, k, (double)lin[4 * (i / 3) + i % 3]);
            rc = 1;
            break;
        }
        inside += want > 2 && want < 253;
    }
    if (!rc && inside * 4 < n) {
        fprintf(stderr, "only %zu of %zu values off the clip: too few to tell\n", inside, n);
        rc = 1;
    }
    free(px);
    free(lin);
    return rc;
}

int main(int argc, char **argv)
{
    uint32_t w, h, w2, h2;
    if (argc == 3 && !strcmp(argv[1], "mean")) {
        float *px = load(argv[2], &w, &h);
        double sum = 0;
        for (size_t i = 0; i < (size_t)w * h; i++)
            sum += px[4 * i] + px[4 * i + 1] + px[4 * i + 2];
        printf("%.9g\n", sum / (3.0 * w * h));
        free(px);
        return 0;
    }
    if (argc == 5 && !strcmp(argv[1], "display"))
        return display(argv[2], argv[3], atof(argv[4]));
    if (argc != 6 || strcmp(argv[1], "times") != 0) {
        fprintf(stderr, "usage: exr_scale mean FILE | exr_scale times A B K TOL | "
                        "exr_scale display EXR PNG K\n");
        return 2;
    }
    float *a = load(argv[2], &w, &h), *b = load(argv[3], &w2, &h2);
    double k = atof(argv[4]), tol = atof(argv[5]);
    int rc = 0;
    if (w != w2 || h != h2) {
        fprintf(stderr, "sizes differ: %ux%u, %ux%u\n", w, h, w2, h2);
        rc = 1;
    }
    for (size_t i = 0; !rc && i < (size_t)w * h; i++)
        for (int c = 0; c < 3; c++) {
            double want = k * a[4 * i + c], got = b[4 * i + c];
            if (!(fabs(got - want) <= tol * fabs(want) + 1e-6)) {
                fprintf(stderr, "pixel %zu channel %d: %g, want %g (%g x %g)\n", i, c, got,
                        want, k, a[4 * i + c]);
                rc = 1;
                break;
            }
        }
    free(a);
    free(b);
    return rc;
}
