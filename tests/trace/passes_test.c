/* passes_test.c: the renderer's contract beyond radiance: the same seed
 * gives the same image, another seed another; progressive passes continue
 * the sample sequence (4 + 4 + 8 spp equals 16 spp in one pass); counters;
 * the AOVs (depth, normal, albedo of a floor under an area light); the
 * resolution override and crop; rejected parameters. */
#include "config.h"

#include "tests/trace/trace_test_util.h"

static bool same(const struct test_image *a, const struct test_image *b, double *max_diff)
{
    size_t n = (size_t)a->w * a->h * 4;
    double d = 0;
    for (size_t i = 0; i < n; i++)
        d = fmax(d, fabs((double)a->rgba[i] - b->rgba[i]));
    *max_diff = d;
    return d <= 1e-5;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_scene *s = test_scene("quad.pbrt");
    struct cv_error err = {{0}};
    const uint32_t one[] = {16, 0}, three[] = {4, 4, 8, 0};

    for (int smp = 0; smp < 2; smp++) {
        const char *name = smp ? "independent" : "sobol";
        struct cv_render_params p = {.seed = 1234, .sampler = smp ? CV_SAMPLER_INDEPENDENT
                                                                   : CV_SAMPLER_SOBOL};
        struct test_image a = {0}, b = {0}, c = {0}, d = {0};
        bool ok = test_render(gpu, s, &p, one, &a, &err) && test_render(gpu, s, &p, one, &b, &err) &&
                  test_render(gpu, s, &p, three, &c, &err);
        p.seed = 1235;
        ok = ok && test_render(gpu, s, &p, one, &d, &err);
        if (!tap_ok(ok, "%s: renders: %s", name, err.msg))
            continue;
        double diff = 0;
        bool eq = same(&a, &b, &diff);
        tap_ok(eq, "%s: same seed, same image (max diff %g)", name, diff);
        eq = same(&a, &c, &diff);
        tap_ok(eq, "%s: 4+4+8 spp in passes equals 16 spp (max diff %g)", name, diff);
        eq = same(&a, &d, &diff);
        tap_ok(!eq, "%s: another seed, another image (max diff %g)", name, diff);
        double ma = test_mean(&a, 0, NULL), md = test_mean(&d, 0, NULL);
        tap_ok(ma > 0 && fabs(ma / md - 1) < 0.05, "%s: both seeds agree on the mean (%.4f, %.4f)",
               name, ma, md);
        TAP_EQ_INT(a.counters.primary_rays, (uint64_t)a.w * a.h * 16, "primary rays counted");
        free(a.rgba);
        free(b.rgba);
        free(c.rgba);
        free(d.rgba);
    }

    /* AOVs: camera 5 above the floor, light 2 above it facing down */
    struct cv_render_params p = {.seed = 5, .aovs = true};
    struct cv_renderer *r = NULL;
    if (tap_ok(cv_renderer_create(gpu, s, &p, &r, &err) && cv_renderer_pass(r, 8, &err),
               "render with AOVs: %s", err.msg)) {
        uint32_t w, h;
        cv_renderer_size(r, &w, &h);
        TAP_EQ_INT(w * 1000 + h, 24 * 1000 + 16, "film is the scene's 24x16");
        TAP_EQ_INT(cv_renderer_spp_done(r), 8, "spp done");
        size_t n = (size_t)w * h;
        float *rgba = cv_xmalloc(n * 16), *alb = cv_xmalloc(n * 12), *nrm = cv_xmalloc(n * 12),
              *dep = cv_xmalloc(n * 4);
        tap_ok(cv_renderer_read(r, rgba, alb, nrm, dep, &err), "read back with AOVs: %s", err.msg);
        /* corner pixels see the floor; the centre pixel sees the light's back */
        size_t corner = 0, centre = (h / 2) * w + w / 2;
        /* fov 30 on the short side, aspect 1.5: the corner ray leaves at
         * tan = (0.402, 0.268), so the floor lies 5 * 1.11 = 5.55 away */
        tap_ok(dep[corner] > 5.45f && dep[corner] < 5.56f, "floor depth %.4f in (5.45, 5.56)",
               dep[corner]);
        tap_ok(fabsf(dep[centre] - 3.0f) < 0.01f, "light depth %.4f is 3", dep[centre]);
        tap_ok(fabsf(nrm[3 * corner + 2] - 1) < 1e-4f, "floor normal z %.4f is 1", nrm[3 * corner + 2]);
        tap_ok(fabsf(alb[3 * corner] - 0.5f) < 1e-4f, "floor albedo %.4f is 0.5", alb[3 * corner]);
        tap_ok(rgba[4 * corner + 3] == 1.0f && rgba[4 * corner] > 0, "pixel alpha 1, radiance %.4f",
               rgba[4 * corner]);
        GLuint res = cv_renderer_resolve(r, &err);
        tap_ok(res != 0, "resolve returns an SSBO");
        free(rgba);
        free(alb);
        free(nrm);
        free(dep);
    }
    cv_renderer_destroy(&r);
    tap_ok(r == NULL, "destroy clears the pointer");

    /* resolution override keeps the crop window of the scene */
    const char *crop = "LookAt 0 0 5 0 0 0 0 1 0\nCamera \"perspective\"\n"
                       "Film \"rgb\" \"integer xresolution\" 40 \"integer yresolution\" 20 "
                       "\"float cropwindow\" [0.25 0.75 0 0.5]\nWorldBegin\n";
    struct cv_scene *sc = NULL;
    struct cv_scene_load_params lp = {0};
    if (tap_ok(cv_scene_load_string("crop.pbrt", crop, strlen(crop), &lp, &sc, &err),
               "crop scene loads: %s", err.msg)) {
        uint32_t w = 0, h = 0;
        struct cv_render_params pc = {0};
        if (cv_renderer_create(gpu, sc, &pc, &r, &err)) {
            cv_renderer_size(r, &w, &h);
            cv_renderer_destroy(&r);
        }
        TAP_EQ_INT(w * 1000 + h, 20 * 1000 + 10, "scene crop 40x20 [.25,.75]x[0,.5] is 20x10");
        pc.width = 80;
        pc.height = 40;
        w = h = 0;
        if (cv_renderer_create(gpu, sc, &pc, &r, &err)) {
            cv_renderer_size(r, &w, &h);
            cv_renderer_destroy(&r);
        }
        TAP_EQ_INT(w * 1000 + h, 40 * 1000 + 20, "override 80x40 keeps the crop: 40x20");
        cv_scene_destroy(&sc);
    }

    /* rlpath is implemented now (tests/trace/rlpath_*): an unknown one is refused */
    struct cv_render_params bad = {.integrator = 99};
    tap_ok(!cv_renderer_create(gpu, s, &bad, &r, &err) && strstr(err.msg, "integrator"),
           "an unknown integrator is rejected: %s", err.msg);
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
