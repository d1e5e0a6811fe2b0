/* exr_probe.c: what the crop, tile and metadata tests ask of an image, read
 * through OpenEXR's C API and libpng rather than through Cavalry's writers:
 *   exr_probe windows FILE         "display x0 y0 x1 y1 data x0 y0 x1 y1"
 *   exr_probe attr FILE NAME       an attribute of any scalar type, as text
 *   exr_probe point FILE NAME X Y Z  the m44f NAME applied to the point
 *                                  (row vector, divided by w): "x y z"
 *   exr_probe inside FULL PART     every channel of PART equals, bit for
 *                                  bit, the same pixels of FULL (exit 1 if not)
 *   exr_probe pngtext FILE KEY     the PNG text chunks named KEY, one a line
 *   exr_probe stats FILE           "mean R G B nonfinite N": the RGB means
 *                                  over the finite values and the count of
 *                                  NaN or infinite R, G, B values */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>
#include <png.h>

#include "output/exr_read.h"

static void quiet(exr_const_context_t ctxt, exr_result_t code, const char *msg)
{
}

static exr_context_t open_exr(const char *path)
{
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = quiet;
    exr_context_t ctxt = NULL;
    if (exr_start_read(&ctxt, path, &init) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "%s: cannot read\n", path);
        exit(1);
    }
    return ctxt;
}

static int windows(const char *path)
{
    exr_context_t c = open_exr(path);
    exr_attr_box2i_t d, w;
    exr_get_display_window(c, 0, &d);
    exr_get_data_window(c, 0, &w);
    printf("display %d %d %d %d data %d %d %d %d\n", d.min.x, d.min.y, d.max.x, d.max.y,
           w.min.x, w.min.y, w.max.x, w.max.y);
    exr_finish(&c);
    return 0;
}

static int attr(const char *path, const char *name)
{
    exr_context_t c = open_exr(path);
    const exr_attribute_t *a = NULL;
    int rc = 0;
    if (exr_get_attribute_by_name(c, 0, name, &a) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "%s: no attribute %s\n", path, name);
        rc = 1;
    } else if (a->type == EXR_ATTR_STRING) {
        printf("%.*s\n", a->string->length, a->string->str);
    } else if (a->type == EXR_ATTR_INT) {
        printf("%d\n", a->i);
    } else if (a->type == EXR_ATTR_FLOAT) {
        printf("%.9g\n", (double)a->f);
    } else if (a->type == EXR_ATTR_M44F) {
        for (int i = 0; i < 16; i++)
            printf("%s%.9g", i ? " " : "", (double)a->m44f->m[i]);
        printf("\n");
    } else {
        printf("(type %d)\n", (int)a->type);
    }
    exr_finish(&c);
    return rc;
}

static int point(const char *path, const char *name, char **xyz)
{
    exr_context_t c = open_exr(path);
    exr_attr_m44f_t m;
    if (exr_attr_get_m44f(c, 0, name, &m) != EXR_ERR_SUCCESS) {
        fprintf(stderr, "%s: no m44f attribute %s\n", path, name);
        return 1;
    }
    exr_finish(&c);
    double p[4] = {atof(xyz[0]), atof(xyz[1]), atof(xyz[2]), 1}, q[4] = {0};
    for (int col = 0; col < 4; col++)
        for (int row = 0; row < 4; row++)
            q[col] += p[row] * m.m[4 * row + col];
    printf("%.4f %.4f %.4f\n", q[0] / q[3], q[1] / q[3], q[2] / q[3]);
    return 0;
}

static int inside(const char *full, const char *part)
{
    exr_context_t cf = open_exr(full), cp = open_exr(part);
    exr_attr_box2i_t wf, wp;
    const exr_attr_chlist_t *lf = NULL, *lp = NULL;
    exr_get_data_window(cf, 0, &wf);
    exr_get_data_window(cp, 0, &wp);
    exr_get_channels(cf, 0, &lf);
    exr_get_channels(cp, 0, &lp);
    int rc = 0;
    if (lf->num_channels != lp->num_channels) {
        fprintf(stderr, "%d channels, %d channels\n", lf->num_channels, lp->num_channels);
        rc = 1;
    }
    for (int i = 0; rc == 0 && i < lp->num_channels; i++) {
        const char *name = lp->entries[i].name.str;
        if (lp->entries[i].pixel_type != lf->entries[i].pixel_type ||
            strcmp(name, lf->entries[i].name.str) != 0) {
            fprintf(stderr, "channel %d: %s differs\n", i, name);
            rc = 1;
            break;
        }
        float *a = NULL, *b = NULL;
        uint32_t aw, ah, bw, bh;
        struct cv_error err;
        if (!cv_exr_read_channel(full, name, &a, &aw, &ah, &err) ||
            !cv_exr_read_channel(part, name, &b, &bw, &bh, &err)) {
            fprintf(stderr, "%s\n", err.msg);
            return 1;
        }
        size_t diff = 0;
        for (uint32_t y = 0; y < bh; y++) {
            const float *row = a + (size_t)(y + (uint32_t)(wp.min.y - wf.min.y)) * aw +
                               (uint32_t)(wp.min.x - wf.min.x);
            if (memcmp(row, b + (size_t)y * bw, bw * sizeof(float)) != 0)
                diff++;
        }
        if (diff) {
            fprintf(stderr, "channel %s: %zu rows differ\n", name, diff);
            rc = 1;
        }
        free(a);
        free(b);
    }
    exr_finish(&cf);
    exr_finish(&cp);
    return rc;
}

static int pngtext(const char *path, const char *key)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return 1;
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png_create_info_struct(png);
    if (setjmp(png_jmpbuf(png))) {
        fclose(f);
        return 1;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    png_textp text = NULL;
    int n = png_get_text(png, info, &text, NULL);
    for (int i = 0; i < n; i++)
        if (strcmp(text[i].key, key) == 0)
            printf("%s\n", text[i].text);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return 0;
}

static int stats(const char *path)
{
    float *rgba = NULL;
    uint32_t w, h;
    struct cv_error err;
    if (!cv_exr_read_rgba(path, &rgba, &w, &h, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    double sum[3] = {0};
    size_t bad = 0, n = (size_t)w * h;
    for (size_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            float v = rgba[i * 4 + c];
            if (isfinite(v))
                sum[c] += v;
            else
                bad++;
        }
    free(rgba);
    printf("mean %.6g %.6g %.6g nonfinite %zu\n", n ? sum[0] / n : 0.0, n ? sum[1] / n : 0.0,
           n ? sum[2] / n : 0.0, bad);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "windows") == 0)
        return windows(argv[2]);
    if (argc == 4 && strcmp(argv[1], "attr") == 0)
        return attr(argv[2], argv[3]);
    if (argc == 7 && strcmp(argv[1], "point") == 0)
        return point(argv[2], argv[3], argv + 4);
    if (argc == 4 && strcmp(argv[1], "inside") == 0)
        return inside(argv[2], argv[3]);
    if (argc == 4 && strcmp(argv[1], "pngtext") == 0)
        return pngtext(argv[2], argv[3]);
    if (argc == 3 && strcmp(argv[1], "stats") == 0)
        return stats(argv[2]);
    fprintf(stderr, "usage: exr_probe windows|attr|point|inside|pngtext|stats ...\n");
    return 2;
}
