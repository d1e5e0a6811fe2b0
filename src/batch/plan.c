/* plan.c: see plan.h. Each decision is made here once: the film and camera
 * with the job's overrides (through scene/film.h's rules, the same as the
 * scene loader's), the sample count, depth and integrator with their
 * fallbacks to the scene, the time limit, and the colour settings, which
 * are checked against the OCIO config here rather than after the render. */
#include "config.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/file.h"
#include "base/limits.h"
#include "base/log.h"
#include "base/mem.h"
#include "batch/plan.h"
#include "color/ocio.h"
#include "glsl/shared/sdtree.h"
#include "manifest/job_hash.h"
#include "output/exr_write.h"
#include "scene/film.h"

/* rlpath.filter's values are sdtree's filter bits (render.h rl_sd_filter) */
_Static_assert(CV_RL_FILTER_SPATIAL == CV_SD_FILTER_SPATIAL &&
                   CV_RL_FILTER_DIRECTIONAL == CV_SD_FILTER_DIRECTIONAL &&
                   CV_RL_FILTER_BOTH == (CV_SD_FILTER_SPATIAL | CV_SD_FILTER_DIRECTIONAL),
               "rlpath.filter names sdtree's filter bits");

/* A job's problem at key k (else at the job): fails err with it. */
static bool fail_at(struct cv_error *err, const struct cv_plan_options *o,
                    const struct cv_job *job, enum cv_key_id k, const char *msg)
{
    const struct cv_key_at *at = &job->at[k];
    unsigned line = at->line ? at->line : job->line, col = at->line ? at->col : job->col;
    return cv_fail(err, "%s:%u:%u: job \"%s\": %s", o->manifest_path, line, col, job->name, msg);
}

static bool plan_camera(const struct cv_job *job, const struct cv_scene *scene,
                        const struct cv_plan_options *o, struct cv_render_plan *p,
                        struct cv_error *err)
{
    p->camera = scene->camera;
    p->width = scene->camera.film.x;
    p->height = scene->camera.film.y;
    if (job->camera.has_lookat) {
        double v[9];
        for (int i = 0; i < 3; i++) {
            v[i] = job->camera.eye[i];
            v[3 + i] = job->camera.at[i];
            v[6 + i] = job->camera.up[i];
        }
        if (!cv_camera_look_at(&p->camera, v, v + 3, v + 6))
            return fail_at(err, o, job, CV_K_CAMERA_LOOKAT,
                           "camera.lookat: up vector and viewing direction are parallel");
    }
    bool spherical = p->camera.type >= CV_CAMERA_EQUAL_AREA;
    if (job->camera.has_fov && spherical)
        return fail_at(err, o, job, CV_K_CAMERA_FOV,
                       "camera.fov: the scene's camera is spherical, which sees every direction");
    if (job->camera.has_fov)
        p->camera.lens.z = cv_camera_fov_scale(job->camera.fov);
    /* One crop rule for both homes of a crop window: the job's crop key
     * replaces the scene's Film "cropwindow" (pbrt's fractions, pixel
     * bounds by scene/film.h). The film stays full size: crop.xy are the
     * pixels rendered, film.zw their origin, so samples keep the keys of
     * their full-film pixels (a crop is the same pixels of the full
     * render). */
    double crop[4];
    for (int i = 0; i < 4; i++)
        crop[i] = job->has_crop ? job->crop[i] : scene->settings.crop[i];
    if (job->has_crop && !job->has_resolution)
        cv_camera_fit_film(&p->camera, crop, p->width, p->height);
    if (job->has_resolution) {
        p->width = job->width;
        p->height = job->height;
        const struct cv_key_at *at = &job->at[CV_K_RESOLUTION];
        char where[64] = "";  /* no line: set by --resolution */
        if (at->line)
            snprintf(where, sizeof(where), ":%u:%u", at->line, at->col);
        if (cv_camera_fit_film(&p->camera, crop, p->width, p->height) && !spherical)
            cv_warn("%s%s: job \"%s\": %sresolution %ux%u changes the scene's aspect ratio: "
                    "default screen window used", o->manifest_path, where, job->name,
                    at->line ? "" : "--", p->width, p->height);
    }
    if ((uint64_t)p->camera.crop.x * p->camera.crop.y > CV_MAX_FILM_PIXELS) {
        char msg[160];
        snprintf(msg, sizeof(msg),
                 "a film of %ux%u rendered pixels is too large (at most %u pixels, "
                 "such as 4096x4096)", p->camera.crop.x, p->camera.crop.y, CV_MAX_FILM_PIXELS);
        return fail_at(err, o, job, CV_K_RESOLUTION, msg);
    }
    return true;
}

/* pbrt-v4's integrators that render participating media, beside volpath
 * (cpu/render.cpp warns for the others, which ignore media). */
static const char *const media_integrators[] = {"simplevolpath", "bdpt", "mlt"};

/* The manifest's integrator, else the scene's where Cavalry has it, else
 * the one that renders the same image: volpath where the scene has
 * participating media and pbrt-v4's integrator renders them (volpath is
 * also pbrt-v4's default), else path; the scene's is then reported (an
 * error with --strict). Integrators that ignore media (path, rlpath, and
 * of pbrt-v4's sppm and the rest) render without them, with a warning, as
 * pbrt-v4 does. */
static bool plan_integrator(const struct cv_job *job, const struct cv_scene *scene,
                            const struct cv_plan_options *o, struct cv_render_plan *p,
                            struct cv_error *err)
{
    bool media = scene->n_media > 0;
    const char *asked = scene->settings.integrator;
    bool renders_media = !asked;
    for (size_t i = 0; asked && i < CV_ARRAY_SIZE(media_integrators); i++)
        renders_media |= strcmp(asked, media_integrators[i]) == 0;
    enum cv_integrator fallback =
        media && renders_media ? CV_INTEGRATOR_VOLPATH : CV_INTEGRATOR_PATH;
    const char *at = scene->settings.integrator_at ? scene->settings.integrator_at
                                                   : scene->path;
    p->integrator = fallback;
    p->substituted = NULL;
    if (job->has_integrator) {
        p->integrator = job->integrator;
    } else if (asked) {
        int id = cv_name_find(&cv_integrator_names, asked);
        /* sppm is for caustics, as bdpt: rendered with it, substituted;
         * but pbrt-v4's sppm ignores media, which bdpt renders: with
         * media it is an integrator Cavalry does not have */
        bool sppm = strcmp(asked, "sppm") == 0 && !media;
        if (sppm) {
            p->integrator = CV_INTEGRATOR_BDPT;
            p->substituted = asked;
            if (o->strict)
                return cv_fail(err, "%s: integrator \"sppm\" is not supported (--strict): "
                                    "job \"%s\" would render with \"bdpt\" (%s:%u:%u; set "
                                    "integrator there)", at, job->name, o->manifest_path,
                               job->line, job->col);
            cv_warn("%s: integrator \"sppm\" is not supported: job \"%s\" renders with "
                    "\"bdpt\", which converges to the same image", at, job->name);
        } else if (id >= 0) {
            p->integrator = (enum cv_integrator)id;
        } else {
            p->substituted = asked;
            const char *with = cv_integrator_name(fallback);
            if (o->strict)
                return cv_fail(err, "%s: integrator \"%s\" is not supported (--strict): job "
                                    "\"%s\" would render with \"%s\" (%s:%u:%u; set integrator "
                                    "there)", at, asked, job->name, with, o->manifest_path,
                               job->line, job->col);
            cv_warn("%s: integrator \"%s\" is not supported: job \"%s\" renders with \"%s\"",
                    at, asked, job->name, with);
        }
    }
    if (media && p->integrator != CV_INTEGRATOR_VOLPATH && p->integrator != CV_INTEGRATOR_BDPT)
        cv_warn("%s: the scene has participating media, which integrator \"%s\" ignores (as "
                "pbrt-v4's path does): job \"%s\"; use \"volpath\" to render them",
                job->has_integrator ? o->manifest_path : at,
                cv_integrator_name(p->integrator), job->name);
    return true;
}

static bool has_name(char **pairs, size_t n_pairs, int which, const char *display,
                     const char *name)
{
    for (size_t i = 0; i < n_pairs; i++)
        if ((!display || strcmp(pairs[2 * i], display) == 0) &&
            strcmp(pairs[2 * i + which], name) == 0)
            return true;
    return false;
}

/* Opens the config and builds the processor as the colour pass will, so
 * that a bad name fails now, at the key that holds it. */
static bool plan_color(const struct cv_job *job, const struct cv_plan_options *o,
                       struct cv_render_plan *p, struct cv_error *err)
{
    const struct cv_job_color *c = &job->color;
    p->color = (struct cv_color_params){
        .config_path = c->config,
        .display = c->display,
        .view = c->view,
        .look = c->look,
        .exposure = c->has_exposure ? c->exposure : 0.0f,
    };
    if (!o->check_color || !(job->formats & CV_FORMAT_PNG))
        return true;
    struct cv_error e = {{0}};
    char **pairs = NULL;
    size_t n_pairs = 0;
    enum cv_key_id culprit = CV_K_COUNT;
    if (!cv_ocio_list_views(c->config, &pairs, &n_pairs, &e)) {
        culprit = CV_K_COLOR_CONFIG;
    } else if (c->display && *c->display && !has_name(pairs, n_pairs, 0, NULL, c->display)) {
        culprit = CV_K_COLOR_DISPLAY;
    } else if (c->view && *c->view &&
               !has_name(pairs, n_pairs, 1, c->display && *c->display ? c->display : NULL,
                         c->view)) {
        culprit = CV_K_COLOR_VIEW;
    }
    cv_ocio_free_names(&pairs);
    /* The processor's own message lists the valid names; the checks above
     * only find the key to point at. */
    struct cv_ocio *ocio = NULL;
    if (culprit != CV_K_COLOR_CONFIG && !cv_ocio_create(&p->color, &ocio, &e)) {
        if (culprit == CV_K_COUNT) /* names that exist but not together, or a look */
            culprit = c->look ? CV_K_COLOR_LOOK
                      : c->view ? CV_K_COLOR_VIEW
                      : c->display ? CV_K_COLOR_DISPLAY
                      : CV_K_COLOR_CONFIG;
    } else if (culprit != CV_K_COLOR_CONFIG) {
        culprit = CV_K_COUNT;  /* the processor builds: OCIO knows better */
    }
    cv_ocio_destroy(&ocio);
    return culprit == CV_K_COUNT || fail_at(err, o, job, culprit, e.msg);
}

/* The folder of out can be made and written: the nearest folder that
 * exists is a folder we may write, and no component on the way is a file.
 * Makes nothing (--check leaves no trace). */
static bool check_out_dir(const char *out, char *msg, size_t n)
{
    char *dir = cv_path_dirname(out);
    bool ok = true;
    for (;;) {
        struct stat st;
        if (stat(dir, &st) == 0) {
            if (!S_ISDIR(st.st_mode)) {
                snprintf(msg, n, "output folder of \"%s\" cannot be made: \"%s\" is not a folder",
                         out, dir);
                ok = false;
            } else if (access(dir, W_OK | X_OK) != 0) {
                snprintf(msg, n, "output folder of \"%s\" cannot be written: %s: %s", out, dir,
                         strerror(errno));
                ok = false;
            }
            break;
        }
        if (errno != ENOENT) {
            snprintf(msg, n, "output folder of \"%s\" cannot be made: %s: %s", out, dir,
                     strerror(errno));
            ok = false;
            break;
        }
        char *up = cv_path_dirname(dir);
        bool top = strcmp(up, dir) == 0;
        free(dir);
        dir = up;
        if (top)
            break;
    }
    free(dir);
    return ok;
}

/* Each output file: its folder can be made, and it is none of the job's
 * inputs (the scene and every file it reads), compared in one spelling. */
static bool plan_outputs(const struct cv_job *job, const struct cv_scene *scene,
                         const struct cv_plan_options *o, struct cv_error *err)
{
    if ((job->formats & CV_FORMAT_EXR) && !cv_exr_compression_supported(job->exr.compression)) {
        char msg[160];
        snprintf(msg, sizeof(msg), "EXR compression \"%s\" needs OpenEXR 3.2 or later, "
                 "which this one is not", cv_exr_compression_name(job->exr.compression));
        return fail_at(err, o, job, CV_K_EXR_COMPRESSION, msg);
    }
    char *scene_norm = cv_path_normalize(job->scene);
    bool ok = true;
    for (unsigned i = 0; ok && i < cv_format_names.count; i++) {
        unsigned bit = 1u << i;
        if (!(job->formats & bit))
            continue;
        char *path = cv_job_output_path(job, cv_format_ext(bit));
        char *norm = cv_path_normalize(path);
        char msg[1024];
        if (!check_out_dir(path, msg, sizeof(msg))) {
            ok = fail_at(err, o, job, CV_K_OUTPUT, msg);
        } else {
            const char *input = strcmp(norm, scene_norm) == 0 ? job->scene : NULL;
            for (size_t k = 0; !input && k < scene->n_inputs; k++) {
                char *in = cv_path_normalize(scene->inputs[k]);
                if (strcmp(in, norm) == 0)
                    input = scene->inputs[k];
                free(in);
            }
            if (input) {
                snprintf(msg, sizeof(msg), "output \"%s\" would overwrite \"%s\", which the "
                         "job's scene reads", path, input);
                ok = fail_at(err, o, job, CV_K_OUTPUT, msg);
            }
        }
        free(norm);
        free(path);
    }
    free(scene_norm);
    return ok;
}

/* env.* and lights.* against the scene: an environment to change, lights
 * that exist. */
static bool plan_lights(const struct cv_job *job, const struct cv_scene *scene,
                        const struct cv_plan_options *o, struct cv_render_plan *p,
                        struct cv_error *err)
{
    struct cv_relight *r = &p->relight;
    *r = (struct cv_relight){.env_scale = 1};
    const struct cv_job_env *env = &job->env;
    if ((env->file || env->has_scale || env->has_rotate) && !cv_scene_has_env(scene))
        return fail_at(err, o, job,
                       env->file        ? CV_K_ENV_FILE
                       : env->has_scale ? CV_K_ENV_SCALE
                                        : CV_K_ENV_ROTATE,
                       "the scene has no environment light (LightSource \"infinite\") "
                       "to change");
    if (env->file) {
        struct cv_error e = {{0}};
        if (!o->env_files)
            return fail_at(err, o, job, CV_K_ENV_FILE, "env.file: no image cache in this run");
        if (!cv_env_files_get(o->env_files, env->file, &r->env, &e))
            return fail_at(err, o, job, CV_K_ENV_FILE, e.msg);
        r->env_equal_area = cv_scene_env_equal_area(scene, r->env);
        const CvTexture *t = &r->env->textures[r->env->lights[0].tex];
        if (r->env_equal_area && t->width != t->height) {
            char msg[320];
            snprintf(msg, sizeof(msg),
                     "env.file: \"%s\" is %ux%u; the scene's environment is an equal-area "
                     "map (pbrt-v4), which is square", env->file, t->width, t->height);
            return fail_at(err, o, job, CV_K_ENV_FILE, msg);
        }
    }
    if (env->has_scale)
        r->env_scale = env->scale;
    if (env->has_rotate) {
        r->env_rotate = true;
        memcpy(r->rotate, env->rotate, sizeof(r->rotate));
    }
    const struct cv_light_scales *ls = &job->lights.scale;
    for (uint32_t i = 0; job->lights.has_scale && i < ls->n; i++) {
        if (ls->v[i].light >= scene->n_light_sources) {
            char msg[256];
            snprintf(msg, sizeof(msg),
                     "lights.scale: the scene has no light %u: it has %u light directives "
                     "(LightSource, AreaLightSource), named 0 to %u in file order "
                     "(cavalry-batch --dump-scene lists them)",
                     ls->v[i].light, scene->n_light_sources,
                     scene->n_light_sources ? scene->n_light_sources - 1 : 0);
            return fail_at(err, o, job, CV_K_LIGHTS_SCALE, msg);
        }
        r->scales[r->n_scales++] = (struct cv_relight_scale){ls->v[i].light, ls->v[i].scale};
    }
    p->relit = r->env || env->has_scale || env->has_rotate || r->n_scales > 0;
    return true;
}

/* One file's size and mtime into hash h; a missing file enters as such. */
static uint64_t hash_stamp(uint64_t h, const char *what, const char *path)
{
    struct stat st;
    char line[128];
    if (path && stat(path, &st) == 0)
        snprintf(line, sizeof(line), "%s=%lld,%lld\n", what, (long long)st.st_size,
                 (long long)st.st_mtim.tv_sec);
    else
        snprintf(line, sizeof(line), "%s=-\n", what);
    return cv_fnv1a64(h, line, strlen(line));
}

/* The settings hash that --resume compares (plan.h: settings_hash). Files
 * enter by size and mtime, as the scene file does in the job's own hash:
 * cheap at every --resume, and a touched file re-renders rather than a
 * changed one being missed. */
static void plan_hash(const struct cv_job *job, const struct cv_scene *scene,
                      struct cv_render_plan *p)
{
    uint64_t h = CV_FNV1A64_BASIS;
    const char *head = "cavalry " PACKAGE_VERSION "\n";
    h = cv_fnv1a64(h, head, strlen(head));
    h = cv_fnv1a64(h, job->settings_hash, strlen(job->settings_hash));
    for (size_t i = 0; i < scene->n_inputs; i++)
        h = hash_stamp(h, "input", scene->inputs[i]);
    if (job->env.file)  /* its name is in the job's hash; its contents enter here */
        h = hash_stamp(h, "env", job->env.file);
    if (job->formats & CV_FORMAT_PNG) {
        const char *cfg = cv_ocio_config_file(job->color.config);
        if (!cfg) {
            h = cv_fnv1a64(h, cv_ocio_shipped_config, strlen(cv_ocio_shipped_config));
        } else {
            h = cv_fnv1a64(h, cfg, strlen(cfg));
            h = hash_stamp(h, "ocio", cfg);
        }
    }
    snprintf(p->settings_hash, sizeof(p->settings_hash), "%016llx", (unsigned long long)h);
}

bool cv_plan_make(const struct cv_job *job, const struct cv_scene *scene,
                  const struct cv_plan_options *o, struct cv_render_plan *out,
                  struct cv_error *err)
{
    memset(out, 0, sizeof(*out));
    out->job = job;
    /* AOV layers live only in the EXR: never dropped without a word */
    if (job->aovs && !(job->formats & CV_FORMAT_EXR))
        return fail_at(err, o, job, CV_K_AOVS,
                       "aovs need the exr format (PNG has no layers): add exr to formats");
    out->spp = job->has_spp ? job->spp : scene->settings.spp;
    out->max_depth = job->has_max_depth ? job->max_depth : scene->settings.max_depth;
    out->seed = job->has_seed ? job->seed : 0;
    out->stage_times = o->stage_times;
    out->bdpt_slots = o->bdpt_slots;
    out->misses = o->misses;
    out->time_limit = job->has_time_limit ? job->time_limit : 0;
    if (o->time_limit > 0 && (out->time_limit == 0 || o->time_limit < out->time_limit))
        out->time_limit = o->time_limit;
    if (job->settings_hash)
        plan_hash(job, scene, out);
    return plan_camera(job, scene, o, out, err) && plan_integrator(job, scene, o, out, err) &&
           plan_lights(job, scene, o, out, err) && plan_color(job, o, out, err) &&
           plan_outputs(job, scene, o, err);
}

struct cv_render_params cv_plan_render_params(const struct cv_render_plan *plan)
{
    const struct cv_job *job = plan->job;
    return (struct cv_render_params){
        .camera = &plan->camera,
        .max_depth = plan->max_depth,
        .seed = plan->seed,
        .integrator = plan->integrator,
        .aovs = (job->aovs & (CV_AOV_ALBEDO | CV_AOV_NORMAL | CV_AOV_DEPTH)) != 0,
        .alpha = job->alpha,
        .id_mattes = (job->aovs & (CV_AOV_OBJECT_ID | CV_AOV_MATERIAL_ID)) != 0,
        .cryptomatte = (job->aovs & (CV_AOV_CRYPTO_OBJECT | CV_AOV_CRYPTO_MATERIAL)) != 0,
        .sampler = CV_SAMPLER_SOBOL,
        .rl_grid = job->rlpath.has_grid ? job->rlpath.grid : 0,
        .rl_directions = job->rlpath.has_directions ? job->rlpath.directions : 0,
        .rl_mix = job->rlpath.has_mix ? job->rlpath.mix : -1.0f,   /* negative: the default */
        .rl_guide_indirect = job->rlpath.guide == CV_RL_GUIDE_INDIRECT,
        .rl_train = job->rlpath.train == 0 ? CV_RL_TRAIN_ALWAYS : job->rlpath.train,
        .spp = plan->spp,
        .rl_sdtree = job->rlpath.method == CV_RL_METHOD_SDTREE,
        .rl_sd_filter_set = job->rlpath.has_filter,
        .rl_sd_filter = job->rlpath.filter,   /* the values are the bits */
        .rl_choice = job->rlpath.has_fallback && !job->rlpath.fallback ? CV_RL_CHOICE_GUIDED
                                                                       : CV_RL_CHOICE_MEASURE,
        .stage_times = plan->stage_times,
        .bdpt_slots = plan->bdpt_slots,
        .misses = plan->misses,
    };
}

static bool in_range(enum cv_key_id id, const char *flag, uint32_t v, struct cv_error *err)
{
    const struct cv_key *k = &cv_manifest_keys[id];
    if (v < k->min || v > k->max)
        return cv_fail(err, "%s: %u is not in [%.0f, %.0f] (as the manifest's %s)", flag, v,
                       k->min, k->max, k->name);
    return true;
}

bool cv_plan_overrides_check(const struct cv_plan_overrides *ov, struct cv_error *err)
{
    if (ov->spp && !in_range(CV_K_SPP, "--spp", ov->spp, err))
        return false;
    if (ov->width || ov->height)
        return in_range(CV_K_RESOLUTION, "--resolution", ov->width, err) &&
               in_range(CV_K_RESOLUTION, "--resolution", ov->height, err);
    return true;
}

/* Writes n values of row id into job through the key table, as the reader
 * does for a manifest value; it comes from no line of the manifest. */
static void set_u32s(struct cv_job *job, enum cv_key_id id, const uint32_t *v, size_t n)
{
    const struct cv_key *k = &cv_manifest_keys[id];
    memcpy((char *)job + k->offset, v, n * sizeof(*v));
    *(bool *)((char *)job + k->has) = true;
    job->at[id] = (struct cv_key_at){0, 0};
}

bool cv_plan_override_job(struct cv_job *job, const char *manifest_dir,
                          const struct cv_plan_overrides *ov, struct cv_error *err)
{
    bool rehash = false;
    if (ov->spp) {
        set_u32s(job, CV_K_SPP, &ov->spp, 1);
        rehash = true;
    }
    if (ov->width && ov->height) {
        const uint32_t wh[2] = {ov->width, ov->height};
        set_u32s(job, CV_K_RESOLUTION, wh, 2);
        rehash = true;
    }
    if (ov->output_dir) {
        /* The output as resolved is "<manifest folder>/<template>", or the
         * template alone when it is absolute or the folder is the working one. */
        size_t n = strlen(manifest_dir);
        const char *rel = NULL;
        if (!n && job->output[0] != '/')
            rel = job->output;
        else if (n && !strncmp(job->output, manifest_dir, n) && job->output[n] == '/')
            rel = job->output + n + 1;
        if (rel) {
            char *moved = cv_path_join(ov->output_dir, rel);
            free(job->output);
            job->output = moved;
        }
    }
    if (!rehash)
        return true;
    struct stat st;
    if (stat(job->scene, &st) != 0)
        return cv_fail(err, "%s: %s", job->scene, strerror(errno));
    free(job->settings_hash);
    job->settings_hash = cv_job_settings_hash_stat(job, &st);
    return true;
}
