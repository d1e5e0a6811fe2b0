/* run_job.c: one job of a batch, as the product does it: apply the job's
 * overrides to the scene, render passes until the spp target, the time
 * limit or a signal, then write each format atomically with metadata that
 * records the settings (for --resume) and whether the image is partial. */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "batch/pass_size.h"
#include "batch/run_job.h"
#include "batch/signals.h"
#include "color/color.h"
#include "gpu/buffer.h"
#include "output/exr_read.h"
#include "output/exr_write.h"
#include "output/metadata.h"
#include "output/png_read.h"
#include "output/png_write.h"
#include "trace/render.h"

/* Passes aim at this much wall time: short enough for a responsive
 * progress line and a quick stop on SIGTERM, long enough that the readback
 * per pass costs nothing measurable. */
#define CV_DEFAULT_SPP 16

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int i = 0; i < 3; i++)
            v[i] /= l;
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* The job's camera and resolution overrides, on a shallow copy of the
 * scene (the arrays stay shared and read-only). */
static bool apply_overrides(const struct cv_job *job, struct cv_scene *s, struct cv_error *err)
{
    CvCamera *cam = &s->camera;
    if (job->camera.has_lookat) {
        /* pbrt's LookAt: camera space is left-handed, looking down +z. */
        float dir[3], right[3], up[3], new_up[3];
        for (int i = 0; i < 3; i++) {
            dir[i] = job->camera.at[i] - job->camera.eye[i];
            up[i] = job->camera.up[i];
        }
        normalize3(dir);
        normalize3(up);
        cross3(up, dir, right);
        float rl = sqrtf(right[0] * right[0] + right[1] * right[1] + right[2] * right[2]);
        if (rl < 1e-6f)
            return cv_fail(err, "job \"%s\": camera lookat: up vector and viewing direction are "
                                "parallel", job->name);
        normalize3(right);
        cross3(dir, right, new_up);
        float *rows[3] = {&cam->to_world[0].x, &cam->to_world[1].x, &cam->to_world[2].x};
        for (int r = 0; r < 3; r++) {
            rows[r][0] = right[r];
            rows[r][1] = new_up[r];
            rows[r][2] = dir[r];
            rows[r][3] = job->camera.eye[r];
        }
    }
    if (job->camera.has_fov)
        cam->lens.z = tanf(job->camera.fov * (float)M_PI / 360.0f);
    if (job->has_resolution) {
        uint32_t w = job->width, h = job->height;
        s->settings.width = w;
        s->settings.height = h;
        /* pbrt's default screen window follows the aspect ratio; a new
         * resolution gets the default window for its own aspect. */
        float aspect = (float)w / (float)h;
        if (aspect > 1)
            cam->screen = (CV_VEC4){-aspect, aspect, -1, 1};
        else
            cam->screen = (CV_VEC4){-1, 1, -1 / aspect, 1 / aspect};
        const float *c = s->settings.crop;
        uint32_t x0 = (uint32_t)ceilf(w * c[0]), x1 = (uint32_t)ceilf(w * c[1]);
        uint32_t y0 = (uint32_t)ceilf(h * c[2]), y1 = (uint32_t)ceilf(h * c[3]);
        if (x1 <= x0 || y1 <= y0) {
            x0 = y0 = 0;
            x1 = w;
            y1 = h;
        }
        cam->film = (CV_UVEC4){w, h, x0, y0};
        cam->crop.x = x1 - x0;
        cam->crop.y = y1 - y0;
    }
    return true;
}

static int integrator_of(const struct cv_job *job, const struct cv_scene *s)
{
    if (job->integrator == CV_INTEGRATOR_RLPATH)
        return CV_RENDER_RLPATH;
    if (job->integrator == CV_INTEGRATOR_UNSET && s->settings.integrator &&
        strcmp(s->settings.integrator, "path") != 0)
        cv_warn("job \"%s\": scene asks for integrator \"%s\"; rendering with \"path\"", job->name,
                s->settings.integrator);
    return CV_RENDER_PATH;
}

static struct cv_metadata *job_metadata(struct cv_gpu *gpu, const struct cv_job *job,
                                        const struct cv_job_result *res, int integrator)
{
    struct cv_metadata *m = cv_metadata_new();
    cv_metadata_set_string(m, "software", "cavalry-batch " PACKAGE_VERSION);
    cv_metadata_set_string(m, "cavalry.job", job->name);
    cv_metadata_set_string(m, "cavalry.scene", job->scene_as_written);
    cv_metadata_set_string(m, "cavalry.integrator",
                           integrator == CV_RENDER_RLPATH ? "rlpath" : "path");
    cv_metadata_set_int(m, "cavalry.spp", res->spp);
    cv_metadata_set_int(m, "cavalry.seed", job->has_seed ? job->seed : 0);
    cv_metadata_set_float(m, "cavalry.renderTime", res->seconds);
    cv_metadata_set_string(m, "cavalry.gpu", gpu->info.renderer);
    cv_metadata_set_string(m, "cavalry.settingsHash", job->settings_hash);
    cv_metadata_set_string(m, "cavalry.status", res->partial ? "partial" : "complete");
    return m;
}

static void note_written(struct cv_job_result *res, const char *path)
{
    size_t n = strlen(res->written);
    snprintf(res->written + n, sizeof(res->written) - n, "%s%s", n ? " " : "", path);
}

static enum cv_exr_compression exr_compression(const struct cv_job *job)
{
    switch (job->exr.compression) {
    case CV_JOB_EXR_NONE: return CV_EXR_NONE;
    case CV_JOB_EXR_PIZ: return CV_EXR_PIZ;
    case CV_JOB_EXR_DWAA: return CV_EXR_DWAA;
    case CV_JOB_EXR_ZIP: break;
    }
    return CV_EXR_ZIP;
}

static bool write_exr(struct cv_renderer *r, const struct cv_job *job, uint32_t w, uint32_t h,
                      const struct cv_metadata *meta, struct cv_job_result *res,
                      struct cv_error *err)
{
    size_t n = (size_t)w * h;
    float *rgba = cv_xmalloc(n * 4 * sizeof(float));
    float *albedo = job->aovs & CV_AOV_ALBEDO ? cv_xmalloc(n * 3 * sizeof(float)) : NULL;
    float *normal = job->aovs & CV_AOV_NORMAL ? cv_xmalloc(n * 3 * sizeof(float)) : NULL;
    float *depth = job->aovs & CV_AOV_DEPTH ? cv_xmalloc(n * sizeof(float)) : NULL;
    bool ok = cv_renderer_read(r, rgba, albedo, normal, depth, err);
    struct cv_image_layer layers[3];
    size_t n_layers = 0;
    if (albedo)
        layers[n_layers++] = (struct cv_image_layer){
            .name = "albedo", .n_channels = 3, .channels = {"R", "G", "B"}, .data = albedo};
    if (normal)
        layers[n_layers++] = (struct cv_image_layer){
            .name = "N", .n_channels = 3, .channels = {"X", "Y", "Z"}, .data = normal};
    if (depth)
        layers[n_layers++] = (struct cv_image_layer){
            .name = NULL, .n_channels = 1, .channels = {"Z"}, .data = depth,
            .pixel = CV_EXR_PIXEL_FLOAT};
    char *path = cv_job_output_path(job, "exr");
    if (ok) {
        ok = cv_exr_write(path, &(struct cv_exr_params){
                                    .rgba = rgba,
                                    .width = w,
                                    .height = h,
                                    .use_float = !job->exr.half,
                                    .compression = exr_compression(job),
                                    .layers = layers,
                                    .n_layers = n_layers,
                                    .meta = meta,
                                },
                          err);
    }
    if (ok)
        note_written(res, path);
    free(path);
    free(rgba);
    free(albedo);
    free(normal);
    free(depth);
    return ok;
}

static bool write_png(struct cv_gpu *gpu, struct cv_renderer *r, const struct cv_job *job,
                      uint32_t w, uint32_t h, struct cv_metadata *meta,
                      struct cv_job_result *res, struct cv_error *err)
{
    struct cv_color_params cp = {
        .config_path = job->color.config,
        .display = job->color.display,
        .view = job->color.view,
        .look = job->color.look,
        .exposure = job->color.has_exposure ? job->color.exposure : 0.0f,
    };
    struct cv_color_pass *pass = NULL;
    if (!cv_color_pass_create(gpu, &cp, &pass, err))
        return false;
    size_t n = (size_t)w * h;
    GLuint linear = cv_renderer_resolve(r, err);
    GLuint display = linear ? cv_buffer_create(n * 4 * sizeof(float), NULL, "display", err) : 0;
    float *px = display ? cv_xmalloc(n * 4 * sizeof(float)) : NULL;
    bool ok = display && cv_color_pass_run(pass, linear, display, w, h, err) &&
              cv_buffer_read(display, 0, n * 4 * sizeof(float), px, err);
    char *path = cv_job_output_path(job, "png");
    if (ok) {
        cv_metadata_set_string(meta, "cavalry.colour", cv_color_pass_description(pass));
        /* Alpha is 1 everywhere: write RGB. */
        for (size_t i = 0; i < n; i++)
            memmove(&px[i * 3], &px[i * 4], 3 * sizeof(float));
        ok = cv_png_write(path, &(struct cv_png_params){
                                    .pixels = px,
                                    .width = w,
                                    .height = h,
                                    .channels = 3,
                                    .bit_depth = job->png.bits,
                                    .encoding = cv_color_pass_encoding(pass),
                                    .meta = meta,
                                },
                          err);
    }
    if (ok)
        note_written(res, path);
    free(path);
    free(px);
    cv_buffer_destroy(&display);
    cv_color_pass_destroy(&pass);
    return ok;
}

bool cv_run_job(struct cv_gpu *gpu, const struct cv_job *job, const struct cv_scene *scene,
                const struct cv_scene_gpu *gs, const struct cv_batch_options *opt, struct cv_progress *progress,
                struct cv_job_result *res, struct cv_error *err)
{
    double t0 = now_seconds();
    memset(res, 0, sizeof(*res));
    struct cv_scene s = *scene;
    if (!apply_overrides(job, &s, err))
        return false;
    int integrator = integrator_of(job, &s);
    struct cv_render_params rp = {
        .max_depth = job->has_max_depth ? job->max_depth : 0,
        .seed = job->has_seed ? job->seed : 0,
        .integrator = integrator,
        .aovs = job->aovs != 0,
        .sampler = CV_SAMPLER_SOBOL,
        .rl_grid = job->rlpath.has_grid ? job->rlpath.grid : 0,
        .rl_directions = job->rlpath.has_directions ? job->rlpath.directions : 0,
        .rl_mix = job->rlpath.has_mix ? job->rlpath.mix : 0.0f,
        .rl_guide_indirect = job->rlpath.guide_indirect,
    };
    struct cv_renderer *r = NULL;
    if (!cv_renderer_create_shared(gpu, gs, &s, &rp, &r, err))
        return false;

    uint32_t target = job->has_spp ? job->spp : s.settings.spp ? s.settings.spp : CV_DEFAULT_SPP;
    double limit = job->has_time_limit ? job->time_limit : 0;
    if (opt->time_limit > 0 && (limit == 0 || opt->time_limit < limit))
        limit = opt->time_limit;

    bool ok = true;
    uint32_t pass_spp = 1;
    uint64_t rays_total = 0;
    double t_render = now_seconds();
    while (cv_renderer_spp_done(r) < target) {
        uint32_t done = cv_renderer_spp_done(r);
        uint32_t n = pass_spp < target - done ? pass_spp : target - done;
        double tp = now_seconds();
        struct cv_render_counters c;
        if (!cv_renderer_pass(r, n, err) || !cv_renderer_counters(r, &c, err)) {
            ok = false;
            break;
        }
        double now = now_seconds(), dt = now - tp;
        rays_total = c.primary_rays + c.secondary_rays + c.shadow_rays;
        double elapsed = now - t_render;
        done = cv_renderer_spp_done(r);
        double rate = elapsed > 0 ? rays_total / elapsed : 0;
        double eta = done ? elapsed / done * (target - done) : -1;
        cv_progress_update(progress, job->name, done, target, rate, elapsed, eta);
        if (cv_signals_interrupted()) {
            res->partial = done < target;
            break;
        }
        if (limit > 0 && now - t0 >= limit) {
            cv_info("job \"%s\": time limit %.1fs reached at %u spp", job->name, limit, done);
            break;
        }
        pass_spp = cv_next_pass_spp(n, dt, limit > 0 ? fmax(limit - (now - t0), 1e-9) : 0);
    }
    res->spp = cv_renderer_spp_done(r);
    uint32_t w, h;
    cv_renderer_size(r, &w, &h);
    if (ok && res->spp == 0)
        ok = cv_fail(err, "job \"%s\": stopped before the first pass finished", job->name);
    if (ok) {
        char *first = cv_job_output_path(job, NULL);
        ok = cv_mkdir_parents(first, err);
        free(first);
    }
    if (ok) {
        res->seconds = now_seconds() - t0;
        struct cv_metadata *meta = job_metadata(gpu, job, res, integrator);
        if (job->formats & CV_FORMAT_EXR)
            ok = write_exr(r, job, w, h, meta, res, err);
        if (ok && (job->formats & CV_FORMAT_PNG))
            ok = write_png(gpu, r, job, w, h, meta, res, err);
        cv_metadata_destroy(&meta);
    }
    cv_renderer_destroy(&r);
    res->seconds = now_seconds() - t0;
    if (!ok)
        cv_error_prefix(err, "job \"%s\"", job->name);
    return ok;
}

static bool output_current(const char *path, bool exr, const char *hash)
{
    if (!cv_path_exists(path))
        return false;
    struct cv_error err;
    char *got = NULL, *status = NULL;
    bool ok = exr ? cv_exr_read_attribute_string(path, "cavalry.settingsHash", &got, &err) &&
                        cv_exr_read_attribute_string(path, "cavalry.status", &status, &err)
                  : cv_png_read_text(path, "cavalry.settingsHash", &got, &err) &&
                        cv_png_read_text(path, "cavalry.status", &status, &err);
    ok = ok && strcmp(got, hash) == 0 && strcmp(status, "complete") == 0;
    free(got);
    free(status);
    return ok;
}

bool cv_job_outputs_current(const struct cv_job *job)
{
    static const struct {
        unsigned bit;
        const char *ext;
    } formats[] = {{CV_FORMAT_EXR, "exr"}, {CV_FORMAT_PNG, "png"}};
    for (size_t i = 0; i < CV_ARRAY_SIZE(formats); i++) {
        if (!(job->formats & formats[i].bit))
            continue;
        char *path = cv_job_output_path(job, formats[i].ext);
        bool current = output_current(path, formats[i].bit == CV_FORMAT_EXR, job->settings_hash);
        free(path);
        if (!current)
            return false;
    }
    return true;
}
