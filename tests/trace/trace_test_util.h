/* trace_test_util.h: helpers of the renderer tests: load a test scene from
 * tests/data/trace, render it, read the image back, summarise it. */
#ifndef CV_TESTS_TRACE_UTIL_H
#define CV_TESTS_TRACE_UTIL_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/film.h"
#include "scene/scene.h"
#include "tests/gpu/gpu_test_util.h"
#include "trace/render.h"

/* The scene's camera fitted to a w x h film (its crop window kept), as a
 * job's resolution does it. */
static inline CvCamera test_camera(const struct cv_scene *s, uint32_t w, uint32_t h)
{
    CvCamera c = s->camera;
    cv_camera_fit_film(&c, s->settings.crop, w, h);
    return c;
}

static inline struct cv_scene *test_scene(const char *name)
{
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/%s", dir ? dir : "tests/data", name);
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    if (!cv_scene_load(path, &lp, &s, &err)) {
        tap_ok(false, "load %s: %s", path, err.msg);
        free(path);
        exit(tap_done());
    }
    free(path);
    return s;
}

struct test_image {
    uint32_t w, h;
    float *rgba;
    struct cv_render_counters counters;
};

/* Renders passes[0], passes[1], ... spp (0-terminated); false on error. */
static inline bool test_render(struct cv_gpu *gpu, const struct cv_scene *s,
                               const struct cv_render_params *p, const uint32_t *passes,
                               struct test_image *img, struct cv_error *err)
{
    struct cv_renderer *r = NULL;
    if (!cv_renderer_create(gpu, s, p, &r, err))
        return false;
    for (const uint32_t *k = passes; *k; k++)
        if (!cv_renderer_pass(r, *k, err)) {
            cv_renderer_destroy(&r);
            return false;
        }
    cv_renderer_size(r, &img->w, &img->h);
    img->rgba = cv_xmalloc((size_t)img->w * img->h * 4 * sizeof(float));
    bool ok = cv_renderer_read(r, img->rgba, NULL, NULL, NULL, err) &&
              cv_renderer_counters(r, &img->counters, err);
    cv_renderer_destroy(&r);
    return ok;
}

/* Mean of the channel average over all pixels, and the largest deviation of
 * a pixel's channel average from `ref`. */
static inline double test_mean(const struct test_image *img, double ref, double *max_dev)
{
    double sum = 0, dev = 0;
    size_t n = (size_t)img->w * img->h;
    for (size_t i = 0; i < n; i++) {
        const float *p = img->rgba + 4 * i;
        double v = (p[0] + p[1] + p[2]) / 3.0;
        sum += v;
        if (fabs(v - ref) > dev || isnan(v))
            dev = isnan(v) ? INFINITY : fabs(v - ref);
    }
    if (max_dev)
        *max_dev = dev;
    return sum / (double)n;
}

#endif
