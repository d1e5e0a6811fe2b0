/* exr_ref.h: reads the R, G, B channels of an OpenEXR reference image,
 * box-downsamples it and averages its regions, for the reference
 * comparisons of the renderer tests. */
#ifndef CV_TESTS_TRACE_EXR_REF_H
#define CV_TESTS_TRACE_EXR_REF_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output/exr_read.h"

/* *rgb: width*height*3 floats, top row first (free()); through the
 * product's reader (output/exr_read.h), keeping R, G and B. */
static inline bool exr_ref_read_rgb(const char *path, float **rgb, uint32_t *width,
                                    uint32_t *height, char *why, size_t why_len)
{
    float *rgba = NULL;
    uint32_t w = 0, h = 0;
    struct cv_error err = {{0}};
    if (!cv_exr_read_rgba(path, &rgba, &w, &h, &err)) {
        snprintf(why, why_len, "%s", err.msg);
        return false;
    }
    float *out = malloc((size_t)w * h * 3 * sizeof(float));
    for (size_t i = 0; i < (size_t)w * h; i++)
        memcpy(out + 3 * i, rgba + 4 * i, 3 * sizeof(float));
    free(rgba);
    *rgb = out;
    *width = w;
    *height = h;
    return true;
}

/* Averages factor x factor blocks of an rgb image (w, h multiples of factor). */
static inline float *exr_ref_downsample(const float *rgb, uint32_t w, uint32_t h, uint32_t factor)
{
    uint32_t ow = w / factor, oh = h / factor;
    float *out = calloc((size_t)ow * oh * 3, sizeof(float));
    for (uint32_t y = 0; y < oh * factor; y++)
        for (uint32_t x = 0; x < ow * factor; x++)
            for (int c = 0; c < 3; c++)
                out[((size_t)(y / factor) * ow + x / factor) * 3 + c] +=
                    rgb[((size_t)y * w + x) * 3 + c] / (float)(factor * factor);
    return out;
}

/* Channel-averaged mean of the pixels [x0, x1) x [y0, y1) of an image
 * `width` pixels wide; stride: floats per pixel (R, G, B first). */
static inline double exr_ref_region_mean(const float *img, int width, int stride, int x0, int y0,
                                         int x1, int y1)
{
    double s = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++) {
            const float *p = img + ((size_t)y * width + x) * stride;
            s += (p[0] + p[1] + p[2]) / 3.0;
        }
    return s / ((double)(x1 - x0) * (y1 - y0));
}

#endif
