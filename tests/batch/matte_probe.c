/* matte_probe.c: what the matte test (mattes_test.sh) asks of an image,
 * read through OpenEXR and libpng rather than through Cavalry's writers:
 *   matte_probe value FILE X Y CHANNEL   the channel's value at the pixel
 *   matte_probe rank FILE X Y TYPE R     "name coverage" of rank R of the
 *                                        Cryptomatte TYPE (CryptoObject):
 *                                        the id's name found in the
 *                                        manifest by its 8 hex digits,
 *                                        "-" for no id
 *   matte_probe sums FILE TYPE           every pixel: the coverages of
 *                                        TYPE sum to A (within 1e-5), fall
 *                                        with the rank, and an id is 0 iff
 *                                        its coverage is 0 (exit 1 if not)
 *   matte_probe png FILE X Y             "r g b a" of an 8-bit RGBA PNG
 *   matte_probe same FILE1 FILE2 CH...   every pixel of each channel CH is
 *                                        the same in both files, bit for
 *                                        bit (exit 1 if not) */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

#include "output/cryptomatte.h"
#include "output/exr_read.h"

static float *channel(const char *path, const char *name, uint32_t *w, uint32_t *h)
{
    float *d = NULL;
    struct cv_error err;
    if (!cv_exr_read_channel(path, name, &d, w, h, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    return d;
}

/* the manifest of type t, found by its name attribute */
static char *manifest(const char *path, const char *type)
{
    char key[16], attr[64], *name = NULL, *m = NULL;
    struct cv_error err;
    snprintf(key, sizeof(key), "%08x", cv_murmur3_32(type, strlen(type), 0));
    key[7] = '\0';
    snprintf(attr, sizeof(attr), "cryptomatte/%s/name", key);
    if (!cv_exr_read_attribute_string(path, attr, &name, &err) || strcmp(name, type) != 0) {
        fprintf(stderr, "%s: no %s naming %s\n", path, attr, type);
        exit(1);
    }
    free(name);
    snprintf(attr, sizeof(attr), "cryptomatte/%s/manifest", key);
    if (!cv_exr_read_attribute_string(path, attr, &m, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    return m;
}

/* rank r's id and coverage at pixel i */
static void rank_at(const char *path, const char *type, uint32_t i, int r, float *id, float *cov)
{
    char name[64];
    uint32_t w, h;
    snprintf(name, sizeof(name), "%s%02d.%s", type, r / 2, r % 2 ? "B" : "R");
    float *a = channel(path, name, &w, &h);
    snprintf(name, sizeof(name), "%s%02d.%s", type, r / 2, r % 2 ? "A" : "G");
    float *b = channel(path, name, &w, &h);
    *id = a[i];
    *cov = b[i];
    free(a);
    free(b);
}

static int rank(const char *path, uint32_t x, uint32_t y, const char *type, int r)
{
    uint32_t w, h;
    free(channel(path, "A", &w, &h));
    float id, cov;
    rank_at(path, type, y * w + x, r, &id, &cov);
    char *m = manifest(path, type);
    uint32_t bits;
    memcpy(&bits, &id, sizeof(bits));
    char hex[16];
    snprintf(hex, sizeof(hex), "\"%08x\"", bits);
    /* "name":"hex": the name is the string before ":"hex" */
    const char *at = bits ? strstr(m, hex) : NULL;
    if (!at) {
        printf("- %.4f\n", (double)cov);
    } else {
        const char *end = at - 2, *start = end - 1;
        while (start > m && *start != '"')
            start--;
        printf("%.*s %.4f\n", (int)(end - start - 1), start + 1, (double)cov);
    }
    free(m);
    return 0;
}

static int sums(const char *path, const char *type)
{
    uint32_t w, h;
    float *a = channel(path, "A", &w, &h);
    int bad = 0;
    for (uint32_t i = 0; i < w * h; i++) {
        float sum = 0, last = 2;
        for (int r = 0; r < (int)CV_MATTE_RANK; r++) {
            float id, cov;
            rank_at(path, type, i, r, &id, &cov);
            if ((id == 0) != (cov == 0) || cov > last || cov < 0) {
                fprintf(stderr, "pixel %u rank %d: id %g coverage %g\n", i, r, (double)id,
                        (double)cov);
                bad = 1;
            }
            last = cov;
            sum += cov;
        }
        if (fabsf(sum - a[i]) > 1e-5f) {
            fprintf(stderr, "pixel %u: coverage sums to %g, alpha %g\n", i, (double)sum,
                    (double)a[i]);
            bad = 1;
        }
    }
    free(a);
    return bad;
}

static int png(const char *path, uint32_t x, uint32_t y)
{
    png_image img;
    memset(&img, 0, sizeof(img));
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return 1;
    if (img.format != PNG_FORMAT_RGBA) {
        fprintf(stderr, "%s: not 8-bit RGBA\n", path);
        /* Only png_image_finish_read frees what begin_read allocated. */
        png_image_free(&img);
        return 1;
    }
    unsigned char *px = malloc(PNG_IMAGE_SIZE(img));
    if (!px || !png_image_finish_read(&img, NULL, px, 0, NULL)) {
        png_image_free(&img);
        free(px);
        return 1;
    }
    const unsigned char *p = px + 4 * ((size_t)y * img.width + x);
    printf("%u %u %u %u\n", p[0], p[1], p[2], p[3]);
    free(px);
    return 0;
}

static int same(const char *a, const char *b, char **names, int n)
{
    int bad = 0;
    for (int k = 0; k < n; k++) {
        uint32_t wa, ha, wb, hb;
        float *x = channel(a, names[k], &wa, &ha), *y = channel(b, names[k], &wb, &hb);
        if (wa != wb || ha != hb) {
            fprintf(stderr, "%s: %ux%u against %ux%u\n", names[k], wa, ha, wb, hb);
            bad = 1;
        }
        for (uint32_t i = 0; !bad && i < wa * ha; i++)
            if (memcmp(&x[i], &y[i], sizeof(float)) != 0) {
                fprintf(stderr, "%s, pixel %u: %.9g against %.9g\n", names[k], i, (double)x[i],
                        (double)y[i]);
                bad = 1;
            }
        free(x);
        free(y);
    }
    return bad;
}

int main(int argc, char **argv)
{
    if (argc == 6 && strcmp(argv[1], "value") == 0) {
        uint32_t w, h, x = (uint32_t)atoi(argv[3]), y = (uint32_t)atoi(argv[4]);
        float *d = channel(argv[2], argv[5], &w, &h);
        printf("%.6g\n", (double)d[y * w + x]);
        free(d);
        return 0;
    }
    if (argc == 7 && strcmp(argv[1], "rank") == 0)
        return rank(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]), argv[5],
                    atoi(argv[6]));
    if (argc == 4 && strcmp(argv[1], "sums") == 0)
        return sums(argv[2], argv[3]);
    if (argc == 5 && strcmp(argv[1], "png") == 0)
        return png(argv[2], (uint32_t)atoi(argv[3]), (uint32_t)atoi(argv[4]));
    if (argc >= 5 && strcmp(argv[1], "same") == 0)
        return same(argv[2], argv[3], argv + 4, argc - 4);
    fprintf(stderr, "usage: matte_probe value|rank|sums|png|same ...\n");
    return 2;
}
