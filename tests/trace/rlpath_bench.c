/* rlpath_bench.c: a benchmark, not a test (built by `make
 * tests/trace/rlpath_bench`, never run by `make check`): error against a
 * converged reference versus GPU render time, `path` against `rlpath`.
 *   rlpath_bench [--scene FILE] [--res W H] [--ref-spp N] [--time-ms T]
 *                [--grid G] [--dirs D] [--mix M] [--svg FILE]
 * Without --scene it renders the test room of rlpath_converge_test (a
 * partition hides the lamp from most of what the camera sees: light arrives
 * indirectly). The reference is `path` at
 * --ref-spp with another seed. Each integrator renders passes of 1, 1, 2,
 * 4, ... spp until its GPU time (GL_TIME_ELAPSED of the passes) exceeds
 * --time-ms; after each pass it prints the RMSE and the relative MSE
 * (mean of (v - ref)^2 / (ref^2 + 1e-2), channel mean) against the
 * reference. --svg writes a log-log plot of relative MSE against time. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tests/trace/rlpath_room.h"
#include "tests/trace/trace_test_util.h"

#define MAX_POINTS 64

struct curve {
    int n;
    double ms[MAX_POINTS], relmse[MAX_POINTS], rmse[MAX_POINTS];
    uint32_t spp[MAX_POINTS];
};

static void errors(const float *img, const float *ref, size_t n, double *rmse, double *relmse)
{
    double se = 0, rel = 0;
    for (size_t i = 0; i < n; i++) {
        double v = (img[4 * i] + img[4 * i + 1] + img[4 * i + 2]) / 3.0;
        double r = (ref[4 * i] + ref[4 * i + 1] + ref[4 * i + 2]) / 3.0;
        se += (v - r) * (v - r);
        rel += (v - r) * (v - r) / (r * r + 1e-2);
    }
    *rmse = sqrt(se / n);
    *relmse = rel / n;
}

static bool run(struct cv_gpu *gpu, const struct cv_scene *s, const struct cv_render_params *p,
                const float *ref, double time_ms, struct curve *c, struct cv_error *err)
{
    struct cv_renderer *r = NULL;
    if (!cv_renderer_create(gpu, s, p, &r, err))
        return false;
    uint32_t w, h;
    cv_renderer_size(r, &w, &h);
    size_t n = (size_t)w * h;
    float *img = cv_xmalloc(n * 4 * sizeof(float));
    uint32_t spp = 1;
    bool ok = true;
    c->n = 0;
    while (ok && c->n < MAX_POINTS) {
        struct cv_render_counters rc;
        ok = cv_renderer_pass(r, spp, err) && cv_renderer_counters(r, &rc, err) &&
             cv_renderer_read(r, img, NULL, NULL, NULL, err);
        if (!ok)
            break;
        int k = c->n++;
        c->ms[k] = rc.gpu_ms;
        c->spp[k] = cv_renderer_spp_done(r);
        errors(img, ref, n, &c->rmse[k], &c->relmse[k]);
        printf("%-7s %10.1f ms %7u spp  rmse %.6f  relmse %.6g\n",
               cv_integrator_name(p->integrator), c->ms[k], c->spp[k],
               c->rmse[k], c->relmse[k]);
        fflush(stdout);
        if (rc.gpu_ms > time_ms)
            break;
        if (cv_renderer_spp_done(r) >= 2)
            spp = cv_renderer_spp_done(r);
    }
    free(img);
    cv_renderer_destroy(&r);
    return ok;
}

static void svg(const char *path, const struct curve *c, int nc, const char *const *names,
                const char *title)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return;
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (int k = 0; k < nc; k++)
        for (int i = 0; i < c[k].n; i++) {
            if (c[k].ms[i] <= 0 || c[k].relmse[i] <= 0)
                continue;
            x0 = fmin(x0, log10(c[k].ms[i])), x1 = fmax(x1, log10(c[k].ms[i]));
            y0 = fmin(y0, log10(c[k].relmse[i])), y1 = fmax(y1, log10(c[k].relmse[i]));
        }
    x0 = floor(x0), x1 = ceil(x1), y0 = floor(y0), y1 = ceil(y1);
    if (x1 <= x0) x1 = x0 + 1;
    if (y1 <= y0) y1 = y0 + 1;
    const double W = 640, H = 480, L = 70, R = 20, T = 40, B = 50;
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
               "font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
            W, H);
    fprintf(f, "<text x=\"%g\" y=\"20\" text-anchor=\"middle\">%s</text>\n", W / 2, title);
#define PX(v) (L + ((v) - x0) / (x1 - x0) * (W - L - R))
#define PY(v) (H - B - ((v) - y0) / (y1 - y0) * (H - T - B))
    for (double e = x0; e <= x1; e++)
        fprintf(f, "<line x1=\"%.1f\" y1=\"%g\" x2=\"%.1f\" y2=\"%g\" stroke=\"#ddd\"/>"
                   "<text x=\"%.1f\" y=\"%g\" text-anchor=\"middle\">1e%g</text>\n",
                PX(e), T, PX(e), H - B, PX(e), H - B + 18, e);
    for (double e = y0; e <= y1; e++)
        fprintf(f, "<line x1=\"%g\" y1=\"%.1f\" x2=\"%g\" y2=\"%.1f\" stroke=\"#ddd\"/>"
                   "<text x=\"%g\" y=\"%.1f\" text-anchor=\"end\">1e%g</text>\n",
                L, PY(e), W - R, PY(e), L - 6, PY(e) + 4, e);
    fprintf(f, "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">GPU time [ms]</text>\n", W / 2, H - 12);
    fprintf(f, "<text x=\"16\" y=\"%g\" transform=\"rotate(-90 16 %g)\" text-anchor=\"middle\">"
               "relative MSE</text>\n", H / 2, H / 2);
    const char *colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
    for (int k = 0; k < nc; k++) {
        fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"2\" points=\"", colors[k % 4]);
        for (int i = 0; i < c[k].n; i++)
            if (c[k].ms[i] > 0 && c[k].relmse[i] > 0)
                fprintf(f, "%.1f,%.1f ", PX(log10(c[k].ms[i])), PY(log10(c[k].relmse[i])));
        fprintf(f, "\"/>\n<text x=\"%g\" y=\"%g\" fill=\"%s\">%s</text>\n", W - R - 120,
                T + 20 + 16 * k, colors[k % 4], names[k]);
    }
    fprintf(f, "</svg>\n");
    fclose(f);
}

int main(int argc, char **argv)
{
    const char *scene_path = NULL, *svg_path = NULL;
    uint32_t w = 0, h = 0, ref_spp = 1024, grid = 0, dirs = 0;
    double time_ms = 2000;
    float mix = -1;   /* the default */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--scene") && i + 1 < argc)
            scene_path = argv[++i];
        else if (!strcmp(argv[i], "--res") && i + 2 < argc)
            w = (uint32_t)atoi(argv[i + 1]), h = (uint32_t)atoi(argv[i + 2]), i += 2;
        else if (!strcmp(argv[i], "--ref-spp") && i + 1 < argc)
            ref_spp = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--time-ms") && i + 1 < argc)
            time_ms = atof(argv[++i]);
        else if (!strcmp(argv[i], "--grid") && i + 1 < argc)
            grid = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--dirs") && i + 1 < argc)
            dirs = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--mix") && i + 1 < argc)
            mix = (float)atof(argv[++i]);
        else if (!strcmp(argv[i], "--svg") && i + 1 < argc)
            svg_path = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--scene FILE] [--res W H] [--ref-spp N] [--time-ms T] "
                            "[--grid G] [--dirs D] [--mix M] [--svg FILE]\n", argv[0]);
            return 2;
        }
    }
    struct cv_error err = {{0}};
    struct cv_gpu *gpu = NULL;
    if (!cv_gpu_create(&(struct cv_gpu_params){.gpu_index = -1}, &gpu, &err)) {
        fprintf(stderr, "gpu: %s\n", err.msg);
        return 1;
    }
    printf("GPU: %s\n", gpu->info.renderer);
    struct cv_scene *s = NULL;
    struct cv_scene_load_params lp = {0};
    bool ok = scene_path ? cv_scene_load(scene_path, &lp, &s, &err)
                         : cv_scene_load_string("room.pbrt", rlpath_room, strlen(rlpath_room), &lp,
                                                &s, &err);
    if (!ok) {
        fprintf(stderr, "scene: %s\n", err.msg);
        return 1;
    }
    if (!w && !scene_path)
        w = h = 128;
    CvCamera cam = w ? test_camera(s, w, h) : s->camera;
    struct cv_render_params p = {.camera = &cam, .seed = 99};
    struct cv_renderer *r = NULL;
    if (!cv_renderer_create(gpu, s, &p, &r, &err)) {
        fprintf(stderr, "reference: %s\n", err.msg);
        return 1;
    }
    for (uint32_t done = 0; done < ref_spp && ok; done += 64)
        ok = cv_renderer_pass(r, ref_spp - done < 64 ? ref_spp - done : 64, &err);
    uint32_t iw, ih;
    cv_renderer_size(r, &iw, &ih);
    float *ref = cv_xmalloc((size_t)iw * ih * 4 * sizeof(float));
    struct cv_render_counters rc;
    ok = ok && cv_renderer_read(r, ref, NULL, NULL, NULL, &err) && cv_renderer_counters(r, &rc, &err);
    cv_renderer_destroy(&r);
    if (!ok) {
        fprintf(stderr, "reference: %s\n", err.msg);
        return 1;
    }
    printf("reference: path, %u spp, %ux%u, %.0f ms\n", ref_spp, iw, ih, rc.gpu_ms);
    struct curve c[2];
    p.seed = 5;
    ok = run(gpu, s, &p, ref, time_ms, &c[0], &err);
    p.integrator = CV_INTEGRATOR_RLPATH;
    p.rl_grid = grid, p.rl_directions = dirs, p.rl_mix = mix;
    ok = ok && run(gpu, s, &p, ref, time_ms, &c[1], &err);
    if (!ok) {
        fprintf(stderr, "render: %s\n", err.msg);
        return 1;
    }
    if (svg_path) {
        const char *names[] = {"path", "rlpath"};
        svg(svg_path, c, 2, names, scene_path ? scene_path : "room (indirect light)");
    }
    free(ref);
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return 0;
}
