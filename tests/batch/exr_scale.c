/* exr_scale.c: how two EXR renders of one scene relate, for the light
 * override tests:
 *   exr_scale mean FILE              the mean of R, G and B over all pixels
 *   exr_scale times A B K TOL        every RGB value of B is K times A's,
 *                                    within TOL relative (plus 1e-6
 *                                    absolute); exit 1 where not, 2 on a
 *                                    bad use or an unreadable file */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    if (argc != 6 || strcmp(argv[1], "times") != 0) {
        fprintf(stderr, "usage: exr_scale mean FILE | exr_scale times A B K TOL\n");
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
