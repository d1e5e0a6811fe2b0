/* stages.c: the BVH build and rendering measurements, made through the bvh
 * and trace stages' public headers. Those stages land separately; until a
 * header is in the build its part is compiled out and the record says which
 * measurements are unavailable and why.
 *
 * What this file expects of them (the interface the bench is written to):
 *   bvh/bvh.h:
 *     bool cv_bvh_build(struct cv_gpu *, const struct cv_scene *,
 *                       struct cv_bvh **out, struct cv_error *);
 *     void cv_bvh_stats(const struct cv_bvh *, struct cv_bvh_stats *out);
 *       struct cv_bvh_stats { unsigned n_phases;
 *           struct { const char *name; double gpu_ms; } phase[];
 *           double sah_cost; double bytes; (GPU bytes of nodes+indices)
 *           unsigned n_nodes; };
 *     void cv_bvh_destroy(struct cv_bvh **);
 *   trace/render.h:
 *     bool cv_renderer_create(struct cv_gpu *, const struct cv_scene *,
 *                             const struct cv_bvh *,
 *                             const struct cv_render_params *,
 *                             struct cv_renderer **out, struct cv_error *);
 *       struct cv_render_params { unsigned width, height; ... };
 *     bool cv_renderer_pass(struct cv_renderer *, struct cv_error *);
 *       (adds one sample per pixel; asynchronous)
 *     void cv_renderer_counters(const struct cv_renderer *,
 *                               struct cv_render_counters *out);
 *       struct cv_render_counters { uint64_t primary_rays, secondary_rays,
 *           shadow_rays, samples; }   (totals since creation)
 *     bool cv_renderer_read_rgb(struct cv_renderer *, float *rgb, struct cv_error *);
 *       (the mean image so far, width*height*3 floats)
 *     void cv_renderer_destroy(struct cv_renderer **);
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "base/mem.h"
#include "bench/bench.h"

#if defined(__has_include)
#if __has_include("bvh/bvh.h")
#include "bvh/bvh.h"
#define BENCH_HAVE_BVH 1
#endif
#if __has_include("trace/render.h") && defined(BENCH_HAVE_BVH)
#include "trace/render.h"
#define BENCH_HAVE_RENDER 1
#endif
#endif

#ifdef BENCH_HAVE_BVH
static bool build_bvh(struct cv_gpu *gpu, struct cv_scene *scene, struct bench_record *r,
                      struct cv_bvh **out, struct cv_error *err)
{
    /* No timer query around the build: the BVH stage times its phases with
     * its own GL_TIME_ELAPSED queries, and GL forbids nesting them. */
    double t0 = bench_now_ms();
    if (!cv_bvh_build(gpu, scene, out, err)) {
        cv_error_prefix(err, "building the BVH");
        return false;
    }
    glFinish();
    bench_num(r, "bvh.build_wall_ms", bench_now_ms() - t0);
    bench_gpu_memory_sample(gpu);
    struct cv_bvh_stats st;
    memset(&st, 0, sizeof st);
    cv_bvh_stats(*out, &st);
    double gpu_ms = 0;
    for (unsigned i = 0; i < st.n_phases; i++) {
        gpu_ms += st.phase[i].gpu_ms;
        char key[96];
        snprintf(key, sizeof key, "bvh.phase.%s_ms", st.phase[i].name);
        bench_num(r, key, st.phase[i].gpu_ms);
    }
    bench_num(r, "bvh.build_gpu_ms", gpu_ms);
    bench_num(r, "bvh.sah_cost", st.sah_cost);
    bench_num(r, "bvh.nodes", st.n_nodes);
    bench_num(r, "bvh.bytes_per_triangle",
              scene->n_triangles ? (double)st.bytes / scene->n_triangles : 0);
    return true;
}
#endif

#ifdef BENCH_HAVE_RENDER
static bool render(struct cv_gpu *gpu, struct cv_scene *scene, struct cv_bvh *bvh,
                   const struct bench_run_params *p, struct bench_record *r,
                   struct cv_error *err)
{
    struct cv_render_params rp;
    memset(&rp, 0, sizeof rp);
    rp.width = p->width ? p->width : scene->settings.width;
    rp.height = p->height ? p->height : scene->settings.height;
    struct cv_renderer *ren = NULL;
    if (!cv_renderer_create(gpu, scene, bvh, &rp, &ren, err))
        return false;
    bench_num(r, "render.width", rp.width);
    bench_num(r, "render.height", rp.height);
    bench_num(r, "render.spp", p->spp);
    double t0 = bench_now_ms(), gpu_ms = 0;
    double *pass_ms = cv_xcalloc(p->spp ? p->spp : 1, sizeof(double));
    bool ok = true;
    for (unsigned s = 0; s < p->spp && ok; s++) {
        struct bench_timer tm;
        bench_timer_begin(&tm);
        ok = cv_renderer_pass(ren, err);
        pass_ms[s] = bench_timer_end(&tm);    /* waits: the pass is complete */
        gpu_ms += pass_ms[s];
        bench_gpu_memory_sample(gpu);
        if (s == 0) {
            bench_num(r, "render.first_pass_from_start_ms", bench_now_ms());
            bench_num(r, "render.first_pass_gpu_ms", pass_ms[0]);
        }
    }
    if (ok) {
        glFinish();
        bench_num(r, "render.time_to_spp_wall_ms", bench_now_ms() - t0);
        bench_num(r, "render.time_to_spp_gpu_ms", gpu_ms);
        struct cv_render_counters c;
        memset(&c, 0, sizeof c);
        cv_renderer_counters(ren, &c);
        double secs = gpu_ms * 1e-3;
        if (secs > 0) {
            bench_num(r, "render.primary_rays_per_s", (double)c.primary_rays / secs);
            bench_num(r, "render.secondary_rays_per_s", (double)c.secondary_rays / secs);
            bench_num(r, "render.shadow_rays_per_s", (double)c.shadow_rays / secs);
            bench_num(r, "render.rays_per_s",
                      (double)(c.primary_rays + c.secondary_rays + c.shadow_rays) / secs);
            bench_num(r, "render.samples_per_s", (double)c.samples / secs);
        }
    }
    free(pass_ms);
    cv_renderer_destroy(&ren);
    return ok;
}
#endif

bool bench_gpu_stages(struct cv_gpu *gpu, struct cv_scene *scene,
                      const struct bench_run_params *p, struct bench_record *r,
                      struct cv_error *err)
{
#ifdef BENCH_HAVE_BVH
    struct cv_bvh *bvh = NULL;
    if (!build_bvh(gpu, scene, r, &bvh, err))
        return false;
#ifdef BENCH_HAVE_RENDER
    bool ok = render(gpu, scene, bvh, p, r, err);
    cv_bvh_destroy(&bvh);
    return ok;
#else
    cv_bvh_destroy(&bvh);
    bench_unavailable(r, "render", "trace/render.h is not in this build");
    return true;
#endif
#else
    (void)gpu, (void)scene, (void)p, (void)err;
    bench_unavailable(r, "bvh", "bvh/bvh.h is not in this build");
    bench_unavailable(r, "render", "trace/render.h is not in this build");
    return true;
#endif
}

#ifdef BENCH_HAVE_RENDER
static bool make_renderer(struct cv_gpu *gpu, struct cv_scene *scene, struct cv_bvh *bvh,
                          unsigned w, unsigned h, struct cv_renderer **out,
                          struct cv_error *err)
{
    struct cv_render_params rp;
    memset(&rp, 0, sizeof rp);
    rp.width = w;
    rp.height = h;
    return cv_renderer_create(gpu, scene, bvh, &rp, out, err);
}
#endif

bool bench_converge(struct cv_gpu *gpu, struct cv_scene *scene,
                    const struct bench_run_params *p, const float *ref_rgb,
                    unsigned ref_w, unsigned ref_h, unsigned ref_spp, FILE *csv,
                    struct cv_error *err)
{
#ifdef BENCH_HAVE_RENDER
    struct cv_bvh *bvh = NULL;
    if (!cv_bvh_build(gpu, scene, &bvh, err))
        return false;
    if (!ref_rgb) {
        ref_w = p->width ? p->width : scene->settings.width;
        ref_h = p->height ? p->height : scene->settings.height;
    }
    size_t n = (size_t)ref_w * ref_h * 3;
    float *img = cv_xmalloc(n * sizeof(float)), *own_ref = NULL;
    struct cv_renderer *ren = NULL;
    bool ok = true;
    if (!ref_rgb) {
        /* A long render of the same scene is the reference. */
        own_ref = cv_xmalloc(n * sizeof(float));
        ok = make_renderer(gpu, scene, bvh, ref_w, ref_h, &ren, err);
        for (unsigned s = 0; s < ref_spp && ok; s++)
            ok = cv_renderer_pass(ren, err);
        ok = ok && cv_renderer_read_rgb(ren, own_ref, err);
        cv_renderer_destroy(&ren);
        ref_rgb = own_ref;
    }
    ok = ok && make_renderer(gpu, scene, bvh, ref_w, ref_h, &ren, err);
    if (ok)
        fprintf(csv, "spp,seconds,gpu_seconds,relmse\n");
    double gpu_ms = 0, render_wall_ms = 0;
    for (unsigned s = 1, next = 1; s <= p->spp && ok; s++) {
        double w0 = bench_now_ms();
        struct bench_timer tm;
        bench_timer_begin(&tm);
        ok = cv_renderer_pass(ren, err);
        gpu_ms += bench_timer_end(&tm);
        render_wall_ms += bench_now_ms() - w0;
        if (!ok || s != next)
            continue;
        next *= 2;
        /* Read-back and error are not render time: only passes count. */
        if (!(ok = cv_renderer_read_rgb(ren, img, err)))
            break;
        double sum = 0;
        for (size_t i = 0; i < n; i++) {
            double d = (double)img[i] - ref_rgb[i];
            sum += d * d / ((double)ref_rgb[i] * ref_rgb[i] + 1e-2);
        }
        fprintf(csv, "%u,%.6g,%.6g,%.6g\n", s, render_wall_ms * 1e-3, gpu_ms * 1e-3,
                sum / (double)n);
        fflush(csv);
    }
    free(img);
    free(own_ref);
    cv_renderer_destroy(&ren);
    cv_bvh_destroy(&bvh);
    return ok;
#else
    (void)gpu, (void)scene, (void)p, (void)ref_rgb, (void)ref_w, (void)ref_h, (void)ref_spp;
    (void)csv;
    return cv_fail(err, "convergence needs the BVH and the renderer (bvh/bvh.h, "
                   "trace/render.h), which are not in this build");
#endif
}
