/* stages.c: the BVH build and rendering measurements, made through the bvh
 * stage (bvh/bvh.h: cv_bvh_build over GL buffers, cv_bvh_stats with GPU
 * phase times) and the trace stage (trace/render.h: cv_renderer_create,
 * cv_renderer_pass, cv_renderer_counters with rays by kind and pass GPU time,
 * cv_renderer_read). Both stages time their GPU work themselves (gpu/timer.h),
 * so this file adds no GPU timing around their calls. Where a stage header is not in the build, its part is
 * compiled out and the record says which measurements are unavailable. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "base/mem.h"
#include "batch/pass_size.h"
#include "bench/bench.h"
#include "gpu/buffer.h"
#include "gpu/program.h"

#if defined(__has_include)
#if __has_include("bvh/bvh.h")
#include "bvh/bvh.h"
#define BENCH_HAVE_BVH 1
#endif
#if __has_include("trace/render.h")
#include "scene/film.h"
#include "trace/render.h"
#define BENCH_HAVE_RENDER 1
#endif
#endif

#ifdef BENCH_HAVE_BVH
/* The BVH on its own, over the scene uploaded here, so that its phases are
 * measured apart from the renderer's set-up (which builds its own). */
static bool measure_bvh(struct cv_gpu *gpu, const struct cv_scene *scene,
                        const struct bench_run_params *p, struct bench_record *r,
                        struct cv_error *err)
{
    GLuint vb = cv_buffer_create((size_t)scene->n_vertices * sizeof(CvVertex), scene->vertices,
                                 "bench vertices", err);
    GLuint tb = vb ? cv_buffer_create((size_t)scene->n_triangles * sizeof(CvTriangle),
                                      scene->triangles, "bench triangles", err)
                   : 0;
    if (!vb || !tb) {
        cv_buffer_destroy(&vb);
        cv_error_prefix(err, "uploading the scene for the BVH");
        return false;
    }
    glFinish();
    double t0 = bench_now_ms();
    struct cv_bvh *bvh = NULL;
    bool ok = cv_bvh_build(gpu, vb, tb, scene->n_triangles, &p->knobs.bvh, &bvh, err);
    if (ok) {
        glFinish();
        bench_num(r, "bvh.build_wall_ms", bench_now_ms() - t0);
        bench_gpu_memory_sample(gpu);
        const struct cv_bvh_stats *st = cv_bvh_stats(bvh);
        for (int i = 0; i < CV_BVH_N_PHASES; i++) {
            const struct cv_bvh_phase *ph = &cv_bvh_phases[i];
            char key[96];
            snprintf(key, sizeof key, "bvh.phase.%s_ms", ph->name);
            if (ph->in_total)
                bench_num(r, key, cv_bvh_phase_ms(st, ph));
        }
        bench_num(r, "bvh.build_gpu_ms", st->ms_total);
        bench_num(r, "bvh.sah_cost", st->sah_cost);
        bench_num(r, "bvh.nodes", st->n_nodes);
        bench_num(r, "bvh.binary_nodes", st->n_binary_nodes);
        bench_num(r, "bvh.depth", st->depth);
        bench_num(r, "bvh.stack_need", st->stack_need);
        bench_num(r, "bvh.refs", st->n_refs);
        bench_num(r, "bvh.mb", (double)st->bytes / 1e6);
        bench_num(r, "bvh.scratch_mb", (double)st->scratch_bytes / 1e6);
        if (scene->n_triangles)
            bench_num(r, "bvh.bytes_per_triangle", (double)st->bytes / scene->n_triangles);
        if (st->ms_total > 0)
            bench_num(r, "bvh.mtriangles_per_s", scene->n_triangles / (st->ms_total * 1e3));
    } else {
        cv_error_prefix(err, "building the BVH");
    }
    cv_bvh_destroy(&bvh);
    cv_buffer_destroy(&tb);
    cv_buffer_destroy(&vb);
    return ok;
}
#endif

#ifdef BENCH_HAVE_RENDER
static int integrator_id(const char *name)
{
    return name ? cv_name_find(&cv_integrator_names, name) : CV_INTEGRATOR_PATH;
}

static bool make_renderer(struct cv_gpu *gpu, const struct cv_scene *scene,
                          const struct bench_run_params *p, unsigned w, unsigned h,
                          struct cv_renderer **out, struct cv_error *err)
{
    struct cv_render_params rp;
    memset(&rp, 0, sizeof rp);
    CvCamera cam = scene->camera;
    if (w || h)
        cv_camera_fit_film(&cam, scene->settings.crop, w ? w : cam.film.x, h ? h : cam.film.y);
    rp.camera = &cam;
    rp.seed = p->seed ? p->seed : 1;
    int integrator = integrator_id(p->integrator);
    rp.integrator = (enum cv_integrator)integrator;
    rp.rl_grid = p->rl_grid;
    rp.rl_directions = p->rl_directions;
    rp.rl_mix = p->rl_mix;
    rp.rl_guide_indirect = p->rl_guide_indirect;
    int method = p->rl_method ? cv_name_find(&cv_rl_method_names, p->rl_method)
                              : CV_RL_METHOD_QLEARN;
    rp.rl_sdtree = method == CV_RL_METHOD_SDTREE;
    rp.rl_train = p->rl_train;
    /* as the manifest's rlpath.fallback: false keeps guiding after training */
    if (p->rl_no_fallback)
        rp.rl_choice = CV_RL_CHOICE_GUIDED;
    rp.spp = p->spp;
    rp.paths_per_pixel = p->paths_per_pixel;
    rp.stage_times = p->knobs.stage_times;
    rp.bdpt_slots = p->knobs.bdpt_slots;
    rp.misses = p->knobs.misses;
    rp.bvh = &p->knobs.bvh;
    if (integrator < 0)
        return cv_fail(err, "unknown integrator \"%s\" (path, rlpath)", p->integrator);
    if (method < 0)
        return cv_fail(err, "unknown rlpath method \"%s\" (qlearn, sdtree)", p->rl_method);
    return cv_renderer_create(gpu, scene, &rp, out, err);
}

/* Where program builds took the time up to the first pass (gpu/program.h):
 * what a cold start spends that a warm one does not. */
static void record_programs(const struct cv_gpu *gpu, struct bench_record *r)
{
    struct cv_program_build_stats b;
    struct cv_program_disk_stats d;
    cv_program_build_stats(gpu, &b);
    cv_program_cache_stats(gpu, &d);
    bench_num(r, "program.parallel", b.parallel);
    bench_num(r, "program.build_ms", b.build_ms);
    bench_num(r, "program.assemble_ms", b.assemble_ms);
    bench_num(r, "program.cache_lookup_ms", b.load_ms);
    bench_num(r, "program.compile_ms", b.compile_ms);
    bench_num(r, "program.link_ms", b.link_ms);
    bench_num(r, "program.wait_ms", b.wait_ms);
    bench_num(r, "program.store_ms", b.store_ms);
    bench_num(r, "program.compiled", b.compiled);
    bench_num(r, "program.cache_hits", b.cache_hits);
    bench_num(r, "program.requested", b.requested);
    bench_num(r, "program.unused", b.unused);
    bench_num(r, "program.disk_cache", d.enabled);
    bench_str(r, "program.slowest", b.slowest);
    bench_num(r, "program.slowest_ms", b.slowest_ms);
}

static bool measure_render(struct cv_gpu *gpu, const struct cv_scene *scene,
                           const struct bench_run_params *p, struct bench_record *r,
                           struct cv_error *err)
{
    double t0 = bench_now_ms();
    struct cv_renderer *ren = NULL;
    if (!make_renderer(gpu, scene, p, p->width, p->height, &ren, err))
        return false;
    glFinish();
    bench_num(r, "render.create_wall_ms", bench_now_ms() - t0);
    bench_gpu_memory_sample(gpu);
    uint32_t w, h;
    cv_renderer_size(ren, &w, &h);
    bench_num(r, "render.width", w);
    bench_num(r, "render.height", h);
    bench_num(r, "render.spp", p->spp);
    bench_str(r, "render.integrator", p->integrator ? p->integrator : "path");

    /* First pass: reading the counters waits for the GPU, so the time after
     * it is when the first complete image exists. */
    struct cv_render_counters c1, c;
    double p0 = bench_now_ms();
    bool ok = cv_renderer_pass(ren, 1, err) && cv_renderer_counters(ren, &c1, err);
    if (ok) {
        bench_num(r, "render.first_pass_from_start_ms", bench_now_ms());
        bench_num(r, "render.first_pass_gpu_ms", c1.gpu_ms);
        record_programs(gpu, r);
        bench_gpu_memory_sample(gpu);
    }
    /* The rest in passes sized as cavalry-batch sizes them, or of pass_spp
     * (each waits for its counters, as the batch's progress does). */
    uint32_t n = 1, passes = 1, max_pass = 1;
    double tp = p0;
    while (ok && cv_renderer_spp_done(ren) < p->spp) {
        double now = bench_now_ms();
        n = p->pass_spp ? p->pass_spp : cv_next_pass_spp(n, (now - tp) * 1e-3, 0);
        tp = now;
        if (n > p->spp - cv_renderer_spp_done(ren))
            n = p->spp - cv_renderer_spp_done(ren);
        ok = cv_renderer_pass(ren, n, err) && cv_renderer_counters(ren, &c, err);
        passes++;
        max_pass = n > max_pass ? n : max_pass;
    }
    ok = ok && cv_renderer_counters(ren, &c, err);
    if (ok) {
        bench_num(r, "render.time_to_spp_wall_ms", bench_now_ms() - p0);
        bench_num(r, "render.time_to_spp_gpu_ms", c.gpu_ms);
        bench_num(r, "render.passes", passes);
        bench_num(r, "render.iterations", (double)c.iterations);
        /* the renderer's own: a learning pass may run as several */
        bench_num(r, "render.gpu_passes", (double)c.passes);
        /* where misses started their slots' next samples in the last pass,
         * and the share of rays that missed (trace/render.h: enum cv_misses) */
        bench_num(r, "render.escaped_stage", c.escaped_stage);
        /* rlpath: the passes after training ran path's programs
         * (trace/guide_choice.h) */
        bench_num(r, "render.unguided", c.unguided);
        /* ... and the figures it chose by, where it measured them (z: the
         * cost difference over its standard error; an infinite one, of a
         * spread of 0, as +-1e300) */
        if (c.choice_measured) {
            bench_num(r, "render.choice_err_guided", c.choice_err[0]);
            bench_num(r, "render.choice_err_path", c.choice_err[1]);
            bench_num(r, "render.choice_ms_guided", c.choice_ms[0]);
            bench_num(r, "render.choice_ms_path", c.choice_ms[1]);
            bench_num(r, "render.choice_z",
                      isinf(c.choice_z) ? copysign(1e300, c.choice_z) : c.choice_z);
        }
        bench_num(r, "render.missed_share",
                  (double)c.missed_rays / (double)(c.primary_rays + c.secondary_rays));
        uint32_t ppp = (uint32_t)(c.path_slots / ((uint64_t)w * h));
        bench_num(r, "render.paths_per_pixel", ppp);
        bench_gpu_memory_sample(gpu);
        /* llvmpipe answers GL_TIME_ELAPSED with near-zero times; there the
         * CPU is the device and the wall clock is the honest measure. */
        double secs = c.gpu_ms * 1e-3;
        if (gpu->info.software) {
            secs = (bench_now_ms() - p0) * 1e-3;
            bench_str(r, "render.rate_clock", "wall (software renderer)");
        } else {
            bench_str(r, "render.rate_clock", "gpu (GL_TIME_ELAPSED)");
        }
        if (secs > 0) {
            bench_num(r, "render.primary_rays_per_s", (double)c.primary_rays / secs);
            bench_num(r, "render.secondary_rays_per_s", (double)c.secondary_rays / secs);
            bench_num(r, "render.shadow_rays_per_s", (double)c.shadow_rays / secs);
            bench_num(r, "render.rays_per_s",
                      (double)(c.primary_rays + c.secondary_rays + c.shadow_rays) / secs);
            bench_num(r, "render.samples_per_s", (double)w * h * p->spp / secs);
        }
        /* Traversal alone (stage_times, CAVALRY_STAGE_TIMES): the intersect stage traces
         * camera and bounce rays together, so its rate counts both. */
        if (!gpu->info.software && c.intersect_ms > 0 && c.shadow_ms > 0) {
            bench_num(r, "render.stage.intersect_ms", c.intersect_ms);
            bench_num(r, "render.stage.shadow_ms", c.shadow_ms);
            bench_num(r, "render.traversal.closest_rays_per_s",
                      (double)(c.primary_rays + c.secondary_rays) / (c.intersect_ms * 1e-3));
            bench_num(r, "render.traversal.shadow_rays_per_s",
                      (double)c.shadow_rays / (c.shadow_ms * 1e-3));
            bench_num(r, "render.stage.intersect_first_ms", c.intersect_first_ms);
            /* With no pass longer than a slot's one sample, no path is
             * regenerated: each pass's first iteration traces all its
             * camera rays and the others bounce rays alone. */
            double bounce_ms = c.intersect_ms - c.intersect_first_ms;
            if (max_pass <= ppp && bounce_ms > 0 && c.intersect_first_ms > 0) {
                bench_num(r, "render.traversal.camera_only_rays_per_s",
                          (double)c.primary_rays / (c.intersect_first_ms * 1e-3));
                bench_num(r, "render.traversal.secondary_only_rays_per_s",
                          (double)c.secondary_rays / (bounce_ms * 1e-3));
                /* the bounce rays of a full wave, before paths end */
                if (c.first_bounce_ms > 0)
                    bench_num(r, "render.traversal.first_bounce_rays_per_s",
                              (double)c.first_bounce_rays / (c.first_bounce_ms * 1e-3));
            }
        }
        bench_num(r, "render.primary_rays", (double)c.primary_rays);
        bench_num(r, "render.secondary_rays", (double)c.secondary_rays);
        bench_num(r, "render.shadow_rays", (double)c.shadow_rays);
    }
    cv_renderer_destroy(&ren);
    return ok;
}
#endif

bool bench_gpu_stages(struct cv_gpu *gpu, struct cv_scene *scene,
                      const struct bench_run_params *p, struct bench_record *r,
                      struct cv_error *err)
{
    /* Rendering first, so that "first pass from start" is what a user of the
     * batch sees (load, renderer set-up with its own BVH, one pass); the BVH
     * is then measured on its own. */
#ifdef BENCH_HAVE_RENDER
    if (!measure_render(gpu, scene, p, r, err))
        return false;
#else
    (void)p;
    bench_unavailable(r, "render", "trace/render.h is not in this build");
#endif
#ifdef BENCH_HAVE_BVH
    return measure_bvh(gpu, scene, p, r, err);
#else
    (void)gpu, (void)scene, (void)err;
    bench_unavailable(r, "bvh", "bvh/bvh.h is not in this build");
    return true;
#endif
}

bool bench_converge(struct cv_gpu *gpu, struct cv_scene *scene,
                    const struct bench_run_params *p, const float *ref_rgb,
                    unsigned ref_w, unsigned ref_h, unsigned ref_spp, FILE *csv,
                    struct cv_error *err)
{
#ifdef BENCH_HAVE_RENDER
    unsigned want_w = ref_rgb ? ref_w : p->width, want_h = ref_rgb ? ref_h : p->height;
    struct cv_renderer *ren = NULL;
    uint32_t w = 0, h = 0;
    float *rgba = NULL, *own_ref = NULL;
    bool ok = true;
    if (!ref_rgb) {
        /* A long render of the same scene is the reference. */
        ok = make_renderer(gpu, scene, p, want_w, want_h, &ren, err);
        if (ok) {
            cv_renderer_size(ren, &w, &h);
            rgba = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
            own_ref = cv_xmalloc((size_t)w * h * 3 * sizeof(float));
        }
        for (unsigned s = 0; s < ref_spp && ok; s++)
            ok = cv_renderer_pass(ren, 1, err);
        ok = ok && cv_renderer_read(ren, rgba, NULL, NULL, NULL, err);
        for (size_t i = 0; ok && i < (size_t)w * h; i++)
            memcpy(own_ref + 3 * i, rgba + 4 * i, 3 * sizeof(float));
        cv_renderer_destroy(&ren);
        ref_rgb = own_ref;
        ref_w = w, ref_h = h;
    }
    ok = ok && make_renderer(gpu, scene, p, want_w, want_h, &ren, err);
    if (ok) {
        cv_renderer_size(ren, &w, &h);
        if (w != ref_w || h != ref_h)
            ok = cv_fail(err, "the render is %ux%u but the reference %ux%u (crop window?)",
                         w, h, ref_w, ref_h);
    }
    if (ok && !rgba)
        rgba = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
    if (ok)
        fprintf(csv, "spp,seconds,wall_seconds,gpu_seconds,relmse\n");
    double wall_ms = 0, mark = bench_now_ms();
    size_t n = (size_t)w * h;
    for (unsigned s = 1, next = 1; s <= p->spp && ok; s++) {
        ok = cv_renderer_pass(ren, 1, err);
        if (!ok || s != next)
            continue;
        next *= 2;
        struct cv_render_counters c;
        /* Counters wait for the GPU: the wall time up to here is render time;
         * read-back and the error sum are not counted. */
        if (!(ok = cv_renderer_counters(ren, &c, err)))
            break;
        wall_ms += bench_now_ms() - mark;
        if (!(ok = cv_renderer_read(ren, rgba, NULL, NULL, NULL, err)))
            break;
        double sum = 0;
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) {
                double ref = ref_rgb[3 * i + k], d = (double)rgba[4 * i + k] - ref;
                sum += d * d / (ref * ref + 1e-2);
            }
        /* "seconds" is GPU time, except on a software renderer whose timer
         * queries read near zero: there the CPU is the device. */
        double secs = gpu->info.software ? wall_ms * 1e-3 : c.gpu_ms * 1e-3;
        fprintf(csv, "%u,%.6g,%.6g,%.6g,%.6g\n", s, secs, wall_ms * 1e-3, c.gpu_ms * 1e-3,
                n ? sum / (3.0 * (double)n) : 0.0);
        fflush(csv);
        mark = bench_now_ms();
    }
    free(rgba);
    free(own_ref);
    cv_renderer_destroy(&ren);
    return ok;
#else
    (void)gpu, (void)scene, (void)p, (void)ref_rgb, (void)ref_w, (void)ref_h, (void)ref_spp;
    (void)csv;
    return cv_fail(err, "convergence needs the renderer (trace/render.h), which is not in "
                   "this build");
#endif
}
