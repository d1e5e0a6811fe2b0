/* passes_test.c: the renderer's contract beyond radiance: the same seed
 * gives the same image, another seed another; progressive passes continue
 * the sample sequence (4 + 4 + 8 spp equals 16 spp in one pass); counters;
 * the AOVs (depth, normal, albedo of a floor under an area light); the
 * resolution override and crop; renderers sharing one scene upload
 * (cv_renderer_create_shared) render what a renderer of its own renders;
 * several paths in flight per pixel; shadow rays that outlive their path
 * keep their sample's filter weight; rejected parameters. */
#include "config.h"

#include "gpu/buf.h"
#include "tests/trace/trace_test_util.h"
#include "trace/scene_upload.h"

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

    /* Path slots (glsl/shared/trace.h): with 3 a pixel, passes of 1, 2, 4
     * and 9 spp start 1, 2, 3 and 3 slots, the second and third wrapping
     * past the last slot, and must add up as 16 spp in one pass; against 1
     * slot a pixel, the same paths summed in another order. The default
     * gives this 24x16 film 8 slots a pixel, so the tests above cover
     * that. */
    {
        const uint32_t uneven[] = {1, 2, 4, 9, 0};
        struct cv_render_params p1 = {.seed = 77, .paths_per_pixel = 1}, p3 = p1;
        p3.paths_per_pixel = 3;
        struct test_image a = {0}, b = {0}, c = {0};
        bool ok = test_render(gpu, s, &p3, one, &a, &err) &&
                  test_render(gpu, s, &p3, uneven, &b, &err) &&
                  test_render(gpu, s, &p1, one, &c, &err);
        if (tap_ok(ok, "3 and 1 paths a pixel render: %s", err.msg)) {
            double diff = 0;
            bool eq = same(&a, &b, &diff);
            tap_ok(eq, "3 paths a pixel: 1+2+4+9 spp equals 16 (max diff %g)", diff);
            size_t n = (size_t)a.w * a.h * 4;
            double rel = 0;
            for (size_t i = 0; i < n; i++)
                rel = fmax(rel, fabs((double)a.rgba[i] - c.rgba[i]) / fmax(fabs(c.rgba[i]), 1e-3));
            tap_ok(rel < 1e-5, "3 paths a pixel render 1's image but for rounding (max rel %g)",
                   rel);
            TAP_EQ_INT(a.counters.path_slots, (uint64_t)a.w * a.h * 3, "3 slots a pixel");
            TAP_EQ_INT(c.counters.primary_rays, a.counters.primary_rays, "the same camera rays");
            TAP_EQ_INT(c.counters.secondary_rays, a.counters.secondary_rays,
                       "the same bounce rays");
            TAP_EQ_INT(c.counters.shadow_rays, a.counters.shadow_rays, "the same shadow rays");
        }
        free(a.rgba);
        free(b.rgba);
        free(c.rgba);
        struct cv_render_params huge = {.seed = 1, .paths_per_pixel = 1u << 23};
        struct cv_renderer *rh = NULL;
        tap_ok(!cv_renderer_create(gpu, s, &huge, &rh, &err) && strstr(err.msg, "2^24"),
               "more than 2^24 paths are refused: %s", err.msg);
        err.msg[0] = '\0';
    }

    /* A shadow ray outlives its path when the path ends at the vertex
     * that sent it (Russian roulette): the slot has moved on to its next
     * sample when the shadow stage adds the light, so the ray carries its
     * sample's filter weight. Mitchell's negative lobes give samples of
     * either sign; a closed grey sphere ends most paths by roulette. With 4
     * slots a pixel, a pass's last sample in each slot has no next one, so
     * had the shadow stage taken the slot's weight, 8 + 8 spp would differ
     * from 16 in one pass, and the pixels would be biased. Each slot adds its samples in
     * their order whatever the passes, so the sums keep their bits. */
    {
        const char *box = "LookAt 0 0 0 0 0 1 0 1 0\nCamera \"perspective\" \"float fov\" [ 60 ]\n"
                          "Integrator \"path\" \"integer maxdepth\" [ 12 ]\n"
                          "Film \"rgb\" \"integer xresolution\" [ 16 ] \"integer yresolution\" [ 12 ]\n"
                          "PixelFilter \"mitchell\"\nWorldBegin\n"
                          "LightSource \"point\" \"point3 from\" [ 0 1 0.5 ] \"rgb I\" [ 2 2 2 ]\n"
                          "Material \"diffuse\" \"rgb reflectance\" [ 0.8 0.8 0.8 ]\n"
                          "Shape \"sphere\" \"float radius\" 2\n";
        const uint32_t halves[] = {8, 8, 0};
        struct cv_scene *sb = NULL;
        struct cv_scene_load_params lp = {0};
        struct cv_render_params pm = {.seed = 31, .paths_per_pixel = 4};
        struct test_image a = {0}, b = {0};
        bool ok = cv_scene_load_string("sphere.pbrt", box, strlen(box), &lp, &sb, &err) &&
                  test_render(gpu, sb, &pm, one, &a, &err) &&
                  test_render(gpu, sb, &pm, halves, &b, &err);
        if (tap_ok(ok, "mitchell filter in a closed sphere renders: %s", err.msg)) {
            double diff = 0;
            same(&a, &b, &diff);
            tap_ok(memcmp(a.rgba, b.rgba, (size_t)a.w * a.h * 4 * sizeof(float)) == 0,
                   "shadow rays of ended paths: 8+8 spp is 16 spp bit for bit (max diff %g)",
                   diff);
        }
        free(a.rgba);
        free(b.rgba);
        cv_scene_destroy(&sb);
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
        const struct cv_buf *res = cv_renderer_resolve(r, &err);
        tap_ok(res && res->params.storable && res->params.size == (size_t)w * h * 16,
               "resolve returns a storage buffer of a vec4 a pixel (%zu bytes)",
               res ? res->params.size : 0);
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
        CvCamera cam = test_camera(sc, 80, 40);
        pc.camera = &cam;
        w = h = 0;
        if (cv_renderer_create(gpu, sc, &pc, &r, &err)) {
            cv_renderer_size(r, &w, &h);
            cv_renderer_destroy(&r);
        }
        TAP_EQ_INT(w * 1000 + h, 40 * 1000 + 20, "override 80x40 keeps the crop: 40x20");
        cv_scene_destroy(&sc);
    }

    /* Shared upload: a renderer with another film and camera and an rlpath
     * renderer use it first, passes interleaved; the last one must match a
     * renderer that uploaded the scene itself, bit for bit (same passes, so
     * that the film sums in the same order on any driver). */
    {
        struct cv_render_params ps = {.seed = 1234};
        struct test_image own = {0};
        struct cv_scene_gpu *gs = NULL;
        struct cv_renderer *ra = NULL, *rb = NULL, *rc = NULL;
        struct cv_scene moved = *s;
        moved.camera.to_world[0].w += 0.5f;
        CvCamera small = test_camera(&moved, 12, 8);
        struct cv_render_params pa = {.seed = 99, .camera = &small};
        struct cv_render_params pb = {.seed = 1234, .integrator = CV_INTEGRATOR_RLPATH, .rl_mix = -1};
        bool ok = test_render(gpu, s, &ps, one, &own, &err) &&
                  cv_scene_gpu_create(gpu, s, NULL, &gs, &err) &&
                  cv_renderer_create_shared(gpu, gs, &moved, &pa, &ra, &err) &&
                  cv_renderer_create_shared(gpu, gs, s, &pb, &rb, &err) &&
                  cv_renderer_pass(ra, 4, &err) && cv_renderer_pass(rb, 4, &err) &&
                  cv_renderer_create_shared(gpu, gs, s, &ps, &rc, &err) &&
                  cv_renderer_pass(ra, 4, &err) && cv_renderer_pass(rc, 16, &err);
        if (tap_ok(ok, "three renderers on one upload: %s", err.msg)) {
            uint32_t w, h;
            cv_renderer_size(ra, &w, &h);
            TAP_EQ_INT(w * 1000 + h, 12 * 1000 + 8, "the override film is its renderer's own");
            size_t bytes = (size_t)own.w * own.h * 4 * sizeof(float);
            float *px = cv_xmalloc(bytes);
            ok = cv_renderer_read(rc, px, NULL, NULL, NULL, &err);
            tap_ok(ok && memcmp(px, own.rgba, bytes) == 0,
                   "shared upload renders the own upload's image bit for bit %s", err.msg);
            free(px);
        }
        cv_renderer_destroy(&ra);
        cv_renderer_destroy(&rb);
        cv_renderer_destroy(&rc);
        cv_scene_gpu_destroy(&gs);
        tap_ok(gs == NULL, "cv_scene_gpu_destroy clears the pointer");
        free(own.rgba);
    }

    /* rlpath is implemented now (tests/trace/rlpath_*): an unknown one is refused */
    struct cv_render_params bad = {.integrator = (enum cv_integrator)99};
    tap_ok(!cv_renderer_create(gpu, s, &bad, &r, &err) && strstr(err.msg, "integrator"),
           "an unknown integrator is rejected: %s", err.msg);
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
