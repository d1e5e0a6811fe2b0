/* plan.c: see plan.h. Each decision is made here once: the film and camera
 * with the job's overrides (through scene/film.h's rules, the same as the
 * scene loader's), the sample count, depth and integrator with their
 * fallbacks to the scene, the time limit, and the colour settings, which
 * are checked against the OCIO config here rather than after the render. */
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "batch/plan.h"
#include "color/ocio.h"
#include "scene/film.h"

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
    if (job->camera.has_fov)
        p->camera.lens.z = cv_camera_fov_scale(job->camera.fov);
    if (job->has_resolution) {
        p->width = job->width;
        p->height = job->height;
        if (cv_camera_fit_film(&p->camera, scene->settings.crop, p->width, p->height))
            cv_warn("%s:%u:%u: job \"%s\": resolution %ux%u changes the scene's aspect ratio: "
                    "default screen window used", o->manifest_path,
                    job->at[CV_K_RESOLUTION].line, job->at[CV_K_RESOLUTION].col, job->name,
                    p->width, p->height);
    }
    if ((uint64_t)p->camera.crop.x * p->camera.crop.y > (1u << 24)) {
        char msg[128];
        snprintf(msg, sizeof(msg), "a film of %ux%u rendered pixels is too large",
                 p->camera.crop.x, p->camera.crop.y);
        return fail_at(err, o, job, CV_K_RESOLUTION, msg);
    }
    return true;
}

/* The manifest's integrator, else the scene's where Cavalry has it, else
 * path: the scene's is then reported (an error with --strict). */
static bool plan_integrator(const struct cv_job *job, const struct cv_scene *scene,
                            const struct cv_plan_options *o, struct cv_render_plan *p,
                            struct cv_error *err)
{
    p->integrator = CV_INTEGRATOR_PATH;
    p->substituted = NULL;
    if (job->has_integrator) {
        p->integrator = job->integrator;
        return true;
    }
    const char *asked = scene->settings.integrator;
    if (!asked || strcmp(asked, cv_integrator_name(CV_INTEGRATOR_PATH)) == 0)
        return true;
    p->substituted = asked;
    const char *at = scene->settings.integrator_at ? scene->settings.integrator_at
                                                   : scene->path;
    if (o->strict)
        return cv_fail(err, "%s: integrator \"%s\" is not supported (--strict): job \"%s\" "
                            "would render with \"path\" (%s:%u:%u; set integrator there)",
                       at, asked, job->name, o->manifest_path, job->line, job->col);
    cv_warn("%s: integrator \"%s\" is not supported: job \"%s\" renders with \"path\"", at,
            asked, job->name);
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

bool cv_plan_make(const struct cv_job *job, const struct cv_scene *scene,
                  const struct cv_plan_options *o, struct cv_render_plan *out,
                  struct cv_error *err)
{
    memset(out, 0, sizeof(*out));
    out->job = job;
    out->spp = job->has_spp ? job->spp : scene->settings.spp;
    out->max_depth = job->has_max_depth ? job->max_depth : scene->settings.max_depth;
    out->seed = job->has_seed ? job->seed : 0;
    out->stage_times = o->stage_times;
    out->time_limit = job->has_time_limit ? job->time_limit : 0;
    if (o->time_limit > 0 && (out->time_limit == 0 || o->time_limit < out->time_limit))
        out->time_limit = o->time_limit;
    return plan_camera(job, scene, o, out, err) && plan_integrator(job, scene, o, out, err) &&
           plan_color(job, o, out, err);
}

struct cv_render_params cv_plan_render_params(const struct cv_render_plan *plan)
{
    const struct cv_job *job = plan->job;
    return (struct cv_render_params){
        .camera = &plan->camera,
        .max_depth = plan->max_depth,
        .seed = plan->seed,
        .integrator = plan->integrator,
        .aovs = job->aovs != 0,
        .sampler = CV_SAMPLER_SOBOL,
        .rl_grid = job->rlpath.has_grid ? job->rlpath.grid : 0,
        .rl_directions = job->rlpath.has_directions ? job->rlpath.directions : 0,
        .rl_mix = job->rlpath.has_mix ? job->rlpath.mix : -1.0f,   /* negative: the default */
        .rl_guide_indirect = job->rlpath.guide == CV_RL_GUIDE_INDIRECT,
        .stage_times = plan->stage_times,
    };
}
