/* run_job.c: one job of a batch, as the product does it: from its plan
 * (batch/plan.h), render passes until the spp target, the time limit or a
 * signal, then colour and write each format atomically with metadata that
 * records the settings (for --resume) and whether the image is partial. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/clock.h"
#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "batch/matte_layers.h"
#include "batch/pass_size.h"
#include "batch/plan.h"
#include "batch/run_job.h"
#include "batch/signals.h"
#include "color/color.h"
#include "output/exr_read.h"
#include "output/exr_write.h"
#include "output/metadata.h"
#include "output/png_read.h"
#include "output/png_write.h"
#include "scene/camera_matrix.h"
#include "trace/render.h"

/* OpenEXR's capDate ("YYYY:MM:DD hh:mm:ss", local time) and utcOffset
 * [seconds, UTC = local time + utcOffset] of now. */
static void set_capture_date(struct cv_metadata *m)
{
    time_t now = time(NULL);
    struct tm local;
    char date[32];
    if (!localtime_r(&now, &local) ||
        strftime(date, sizeof(date), "%Y:%m:%d %H:%M:%S", &local) == 0)
        return;
    cv_metadata_set_string(m, "capDate", date);
    cv_metadata_set_float(m, "utcOffset", (double)-local.tm_gmtoff);
}

static struct cv_metadata *job_metadata(struct cv_gpu *gpu, const struct cv_render_plan *plan,
                                        const struct cv_job_result *res)
{
    const struct cv_job *job = plan->job;
    struct cv_metadata *m = cv_metadata_new();
    /* "software" (EXR) and "Software" (PNG, png_write.c) carry it */
    cv_metadata_set_string(m, "software", "cavalry-batch " PACKAGE_VERSION);
    /* OpenEXR's standard attributes (scene/camera_matrix.h: conventions) */
    float w2c[16], w2ndc[16];
    if (cv_camera_world_to_camera(&plan->camera, w2c))
        cv_metadata_set_m44f(m, "worldToCamera", w2c);
    if (cv_camera_world_to_ndc(&plan->camera, w2ndc))
        cv_metadata_set_m44f(m, "worldToNDC", w2ndc);
    set_capture_date(m);
    char host[256] = "";
    if (gethostname(host, sizeof(host) - 1) == 0 && host[0])
        cv_metadata_set_string(m, "cavalry.host", host);
    cv_metadata_set_string(m, "cavalry.version", PACKAGE_VERSION);
    cv_metadata_set_string(m, "cavalry.job", job->name);
    cv_metadata_set_string(m, "cavalry.scene", job->scene_as_written);
    cv_metadata_set_string(m, "cavalry.integrator", cv_integrator_name(plan->integrator));
    cv_metadata_set_int(m, "cavalry.spp", res->spp);  /* reached */
    cv_metadata_set_int(m, "cavalry.seed", plan->seed);
    cv_metadata_set_float(m, "cavalry.renderTime", res->seconds);
    cv_metadata_set_string(m, "cavalry.gpu", gpu->info.renderer);
    cv_metadata_set_int(m, "cavalry.sppTarget", plan->spp);
    cv_metadata_set_string(m, "cavalry.settingsHash", plan->settings_hash);
    cv_metadata_set_string(m, "cavalry.status", cv_job_status_name(res->stop));
    if (res->nonfinite > 0)   /* report_nonfinite */
        cv_metadata_set_int(m, "cavalry.nonfiniteSamples", (int64_t)res->nonfinite);
    /* the colour settings as the job gives them; the png's text has the
     * resolved config (write_png) */
    const struct cv_color_params *c = &plan->color;
    cv_metadata_set_string(m, "cavalry.ocioConfig", c->config_path && *c->config_path
                                                         ? c->config_path
                                                         : "$OCIO, else shipped cavalry.ocio");
    cv_metadata_set_string(m, "cavalry.ocioDisplay",
                           c->display && *c->display ? c->display : "(default)");
    cv_metadata_set_string(m, "cavalry.ocioView", c->view && *c->view ? c->view : "(default)");
    return m;
}

/* A NaN or infinite sample is a bug (a 0/0 in a pdf, a table gone bad, a
 * sum that overflowed): the renderer leaves it out, as pbrt-v4's film
 * does, so that one sample cannot poison its pixel (a NaN pixel shows as
 * black in most viewers and spreads through every filter downstream), and
 * it is reported here, in the log, the job's events (detail) and the
 * image's metadata, never passed over in silence. */
static void report_nonfinite(const char *job, struct cv_job_result *res, const char *what,
                             uint64_t count)
{
    char msg[160];
    snprintf(msg, sizeof(msg), "%llu %s NaN or infinite and left out", (unsigned long long)count,
             what);
    cv_warn("job \"%s\": %s (a bug, or values past the float range: please report it "
            "with the scene)", job, msg);
    if (res->warning) {
        char *both = cv_xmalloc(strlen(res->warning) + strlen(msg) + 3);
        sprintf(both, "%s; %s", res->warning, msg);
        free(res->warning);
        res->warning = both;
    } else {
        res->warning = cv_xstrdup(msg);
    }
}

/* The last line of report_nonfinite's defence: a pixel that came out of
 * the resolve NaN or infinite (its sums overflowed, say) is written as 0
 * and counted. Returns the count. */
static uint64_t zero_nonfinite(float *v, size_t n)
{
    uint64_t bad = 0;
    for (size_t i = 0; i < n; i++)
        if (!isfinite(v[i])) {
            v[i] = 0;
            bad++;
        }
    return bad;
}

static void note_written(struct cv_job_result *res, const char *path)
{
    if (res->n_outputs < CV_ARRAY_SIZE(res->outputs))
        res->outputs[res->n_outputs++] = cv_xstrdup(path);
}

void cv_job_result_clear(struct cv_job_result *r)
{
    for (size_t i = 0; i < r->n_outputs; i++)
        free(r->outputs[i]);
    r->n_outputs = 0;
    free(r->warning);
    r->warning = NULL;
}

static bool write_exr(struct cv_renderer *r, const struct cv_render_plan *plan,
                      const struct cv_scene *scene, uint32_t w, uint32_t h,
                      const struct cv_metadata *meta, struct cv_progress *progress,
                      struct cv_job_result *res, struct cv_error *err)
{
    const struct cv_job *job = plan->job;
    size_t n = (size_t)w * h;
    float *rgba = cv_xmalloc(n * 4 * sizeof(float));
    float *albedo = job->aovs & CV_AOV_ALBEDO ? cv_xmalloc(n * 3 * sizeof(float)) : NULL;
    float *normal = job->aovs & CV_AOV_NORMAL ? cv_xmalloc(n * 3 * sizeof(float)) : NULL;
    float *depth = job->aovs & CV_AOV_DEPTH ? cv_xmalloc(n * sizeof(float)) : NULL;
    bool ok = cv_renderer_read(r, rgba, albedo, normal, depth, err);
    uint64_t bad = ok ? zero_nonfinite(rgba, n * 4) : 0;
    if (bad)
        report_nonfinite(job->name, res, "image values were", bad);
    struct cv_matte_layers mattes = {0};
    ok = ok && cv_matte_layers_make(r, scene, job->aovs, &mattes, err);
    struct cv_image_layer layers[3 + CV_MATTE_MAX_LAYERS];
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
    for (size_t i = 0; ok && i < mattes.n_layers; i++)
        layers[n_layers++] = mattes.layers[i];
    char *path = cv_job_output_path(job, "exr");
    if (ok) {
        cv_progress_phase(progress, job->name, CV_PHASE_WRITE, path);
        ok = cv_exr_write(path, &(struct cv_exr_params){
                                    .rgba = rgba,
                                    .width = w,
                                    .height = h,
                                    /* a crop: the data window in the full film */
                                    .full_width = plan->camera.film.x,
                                    .full_height = plan->camera.film.y,
                                    .x0 = plan->camera.film.z,
                                    .y0 = plan->camera.film.w,
                                    .use_float = !job->exr.half,
                                    .compression = job->exr.compression,
                                    .layers = layers,
                                    .n_layers = n_layers,
                                    .meta = meta,
                                    .meta_exr = mattes.meta,
                                },
                          err);
    }
    if (ok)
        note_written(res, path);
    cv_matte_layers_free(&mattes);
    free(path);
    free(rgba);
    free(albedo);
    free(normal);
    free(depth);
    return ok;
}

static bool write_png(struct cv_gpu *gpu, struct cv_renderer *r, const struct cv_render_plan *plan,
                      uint32_t w, uint32_t h, struct cv_metadata *meta,
                      struct cv_progress *progress, struct cv_job_result *res,
                      struct cv_error *err)
{
    const struct cv_job *job = plan->job;
    struct cv_color_pass *pass = NULL;
    cv_progress_phase(progress, job->name, CV_PHASE_COLOUR, NULL);
    if (!cv_color_pass_create(gpu, &plan->color, &pass, err))
        return false;
    size_t n = (size_t)w * h;
    const struct cv_buf *linear = cv_renderer_resolve_display(r, err);
    float *px = cv_xmalloc(n * 4 * sizeof(float));
    bool ok = linear && cv_color_pass_run(pass, linear, w, h, px, err);
    char *path = cv_job_output_path(job, "png");
    if (ok) {
        cv_metadata_set_string(meta, "cavalry.colour", cv_color_pass_description(pass));
        cv_metadata_set_string(meta, "cavalry.ocioConfig", cv_color_pass_config_source(pass));
        /* Without alpha it is 1 everywhere: write RGB. With it, RGBA with
         * straight colour (cv_renderer_resolve_display: the alpha divided
         * out before the view transform, as Blender writes PNG). */
        if (!job->alpha)
            for (size_t i = 0; i < n; i++)
                memmove(&px[i * 3], &px[i * 4], 3 * sizeof(float));
        cv_progress_phase(progress, job->name, CV_PHASE_WRITE, path);
        ok = cv_png_write(path, &(struct cv_png_params){
                                    .pixels = px,
                                    .width = w,
                                    .height = h,
                                    .channels = job->alpha ? 4 : 3,
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
    cv_color_pass_destroy(&pass);
    return ok;
}

bool cv_run_job(struct cv_gpu *gpu, const struct cv_render_plan *plan,
                const struct cv_scene *scene, const struct cv_scene_gpu *gs,
                struct cv_progress *progress, struct cv_job_result *res, struct cv_error *err)
{
    const struct cv_job *job = plan->job;
    double t0 = cv_seconds();
    memset(res, 0, sizeof(*res));
    struct cv_render_params rp = cv_plan_render_params(plan);
    struct cv_renderer *r = NULL;
    /* the job's light overrides: its own light records on the shared
     * upload and BVH (plan.h: relit) */
    struct cv_scene_gpu *relit = NULL;
    if (plan->relit) {
        uint32_t n = scene->n_lights ? scene->n_lights : 1;
        const struct cv_scene *env = plan->relight.env;
        CvLight *lights = cv_xcalloc(n, sizeof(CvLight));
        float *power = cv_xcalloc(n, sizeof(float));
        CvTexture *env_tex = env ? cv_xcalloc(env->n_textures, sizeof(CvTexture)) : NULL;
        cv_scene_relight(scene, &plan->relight, lights, power, env_tex);
        bool made = cv_scene_gpu_relight(gpu, gs, scene, lights, power, env, env_tex, &relit, err);
        free(lights);
        free(power);
        free(env_tex);
        if (!made)
            return false;
        gs = relit;
    }
    cv_progress_phase(progress, job->name, CV_PHASE_PROGRAM_COMPILE, NULL);
    if (!cv_renderer_create_shared(gpu, gs, scene, &rp, &r, err)) {
        cv_scene_gpu_destroy(&relit);
        return false;
    }

    uint32_t target = plan->spp;
    double limit = plan->time_limit;
    bool ok = true;
    uint32_t pass_spp = 1;
    uint64_t rays_total = 0;
    double t_render = cv_seconds();
    cv_progress_phase(progress, job->name, CV_PHASE_RENDER, NULL);
    while (cv_renderer_spp_done(r) < target) {
        uint32_t done = cv_renderer_spp_done(r);
        uint32_t n = pass_spp < target - done ? pass_spp : target - done;
        double tp = cv_seconds();
        struct cv_render_counters c;
        if (!cv_renderer_pass(r, n, err) || !cv_renderer_counters(r, &c, err)) {
            ok = false;
            break;
        }
        double now = cv_seconds(), dt = now - tp;
        rays_total = c.primary_rays + c.secondary_rays + c.shadow_rays;
        res->nonfinite = c.nonfinite_samples;
        double elapsed = now - t_render;
        done = cv_renderer_spp_done(r);
        double rate = elapsed > 0 ? rays_total / elapsed : 0;
        /* Done is whichever comes first: the samples or the time limit. */
        double frac = (double)done / target, eta = done ? elapsed / done * (target - done) : -1;
        if (limit > 0) {
            frac = fmax(frac, (now - t0) / limit);
            eta = eta < 0 ? limit - (now - t0) : fmin(eta, limit - (now - t0));
            eta = fmax(eta, 0);
        }
        cv_progress_update(progress, job->name, done, target, rate, elapsed,
                           fmin(frac, 1.0) * 100.0, eta);
        if (cv_signals_interrupted()) {
            res->partial = done < target;
            res->stop = done < target ? CV_STOP_SIGNAL : CV_STOP_COMPLETE;
            break;
        }
        /* the limit counts from the job's start, program build included */
        if (limit > 0 && now - t0 >= limit && done < target) {
            cv_info("job \"%s\": time limit %.1fs reached at %u of %u spp", job->name, limit,
                    done, target);
            res->partial = true;
            res->stop = CV_STOP_TIME_LIMIT;
            break;
        }
        pass_spp = cv_next_pass_spp(n, dt, limit > 0 ? fmax(limit - (now - t0), 1e-9) : 0);
    }
    res->spp = cv_renderer_spp_done(r);
    res->render_seconds = cv_seconds() - t_render;
    uint32_t w, h;
    cv_renderer_size(r, &w, &h);
    if (ok && res->spp == 0)
        ok = cv_fail(err, "job \"%s\": stopped before the first pass finished", job->name);
    if (ok && res->nonfinite > 0)
        report_nonfinite(job->name, res, "radiance samples were", res->nonfinite);
    if (ok) {
        char *first = cv_job_output_path(job, NULL);
        ok = cv_mkdir_parents(first, err);
        free(first);
    }
    if (ok) {
        res->seconds = cv_seconds() - t0;
        struct cv_metadata *meta = job_metadata(gpu, plan, res);
        if (job->formats & CV_FORMAT_EXR)
            ok = write_exr(r, plan, scene, w, h, meta, progress, res, err);
        if (ok && (job->formats & CV_FORMAT_PNG))
            ok = write_png(gpu, r, plan, w, h, meta, progress, res, err);
        cv_metadata_destroy(&meta);
    }
    cv_renderer_destroy(&r);
    cv_scene_gpu_destroy(&relit);
    res->seconds = cv_seconds() - t0;
    if (!ok)
        cv_error_prefix(err, "job \"%s\"", job->name);
    return ok;
}

const char *cv_job_status_name(enum cv_job_stop stop)
{
    static const char *const names[] = {
        [CV_STOP_COMPLETE] = "complete",
        [CV_STOP_SIGNAL] = "partial",
        [CV_STOP_TIME_LIMIT] = "time-limit",
    };
    return names[stop];
}

/* Decodes the whole image (every pixel; every PNG chunk's CRC): a cut or
 * damaged file is not up to date, whatever its header says. */
static bool output_decodes(const char *path, bool exr)
{
    struct cv_error err;
    if (!exr)
        return cv_png_check(path, &err);
    float *rgba = NULL;
    uint32_t w, h;
    bool ok = cv_exr_read_rgba(path, &rgba, &w, &h, &err);
    free(rgba);
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
    ok = ok && strcmp(got, hash) == 0 &&
         strcmp(status, cv_job_status_name(CV_STOP_COMPLETE)) == 0 && output_decodes(path, exr);
    free(got);
    free(status);
    return ok;
}

bool cv_job_outputs_current(const struct cv_render_plan *plan)
{
    const struct cv_job *job = plan->job;
    for (unsigned i = 0; i < cv_format_names.count; i++) {
        unsigned bit = 1u << i;
        if (!(job->formats & bit))
            continue;
        char *path = cv_job_output_path(job, cv_format_ext(bit));
        bool current = output_current(path, bit == CV_FORMAT_EXR, plan->settings_hash);
        free(path);
        if (!current)
            return false;
    }
    return true;
}
