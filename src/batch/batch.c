/* batch.c: the batch loop. Validate everything first (manifest, then every
 * scene the selected jobs name, then the render plan of every selected
 * job), then open one GPU context and run the jobs
 * in manifest order; a scene shared by several jobs is loaded, uploaded and
 * its BVH built once. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "base/log.h"
#include "base/mem.h"
#include "batch/batch.h"
#include "batch/plan.h"
#include "batch/job_lock.h"
#include "batch/run_job.h"
#include "batch/signals.h"
#include "manifest/manifest.h"
#include "manifest/shard.h"
#include "scene/scene.h"
#include "trace/scene_upload.h"

struct loaded_scene {
    const char *path;            /* borrowed from the first job naming it */
    struct cv_scene *scene;
    struct cv_scene_gpu *gpu_scene; /* uploaded at its first rendered job */
    size_t last_use;             /* index of the last selected job using it */
};

/* The selected jobs, their scenes and their render plans. */
struct selection {
    size_t *jobs;                /* selected job indices, manifest order */
    size_t n_jobs, cap_jobs;
    struct loaded_scene *scenes;
    size_t n_scenes, cap_scenes;
    size_t *scene_of;            /* per selected job: index into scenes */
    struct cv_render_plan *plans;  /* per selected job */
};

static void selection_free(struct selection *p)
{
    free(p->plans);
    for (size_t i = 0; i < p->n_scenes; i++)
        cv_scene_destroy(&p->scenes[i].scene);
    free(p->scenes);
    free(p->jobs);
    free(p->scene_of);
}

static bool select_jobs(const struct cv_manifest *m, const struct cv_batch_options *opt,
                        struct selection *p, struct cv_error *err)
{
    if (opt->only && !cv_manifest_find_job(m, opt->only))
        return cv_fail(err, "%s: no job named \"%s\"", m->path, opt->only);
    for (size_t i = 0; i < m->n_jobs; i++) {
        if (opt->only && strcmp(m->jobs[i].name, opt->only) != 0)
            continue;
        if (opt->shard_count && !cv_shard_select(m->n_jobs, opt->shard_index, opt->shard_count, i))
            continue;
        CV_PUSH(p->jobs, p->n_jobs, p->cap_jobs, i);
    }
    return true;
}

/* Loads every scene once; reports every broken scene, not just the first. */
static bool load_scenes(const struct cv_manifest *m, const struct cv_batch_options *opt,
                        struct selection *p, struct cv_error *err)
{
    p->scene_of = cv_xcalloc(p->n_jobs, sizeof(size_t));
    bool ok = true;
    char *all = NULL;
    for (size_t k = 0; k < p->n_jobs; k++) {
        const struct cv_job *job = &m->jobs[p->jobs[k]];
        size_t s = 0;
        while (s < p->n_scenes && strcmp(p->scenes[s].path, job->scene) != 0)
            s++;
        if (s == p->n_scenes) {
            struct loaded_scene ls = {.path = job->scene};
            struct cv_error e = {{0}};
            struct cv_scene_load_params lp = {.strict = opt->strict, .root = opt->scene_root};
            if (!cv_scene_load(job->scene, &lp, &ls.scene, &e)) {
                char *msg = cv_xasprintf("%s%s%s:%u:%u: job \"%s\": %s", all ? all : "",
                                         all ? "\n" : "", m->path, job->line, job->col, job->name,
                                         e.msg);
                free(all);
                all = msg;
                ok = false;
            }
            CV_PUSH(p->scenes, p->n_scenes, p->cap_scenes, ls);
        }
        p->scene_of[k] = s;
        p->scenes[s].last_use = k;
    }
    if (!ok) {
        cv_fail(err, "%s", all);
        free(all);
    }
    return ok;
}

/* The render plan of every selected job, before the GPU opens; reports
 * every job with a problem, not just the first. */
static bool make_plans(const struct cv_manifest *m, const struct cv_batch_options *opt,
                       struct selection *p, struct cv_error *err)
{
    p->plans = cv_xcalloc(p->n_jobs ? p->n_jobs : 1, sizeof(*p->plans));
    struct cv_plan_options po = {
        .manifest_path = m->path,
        .strict = opt->strict,
        .time_limit = opt->time_limit,
        .check_color = true,
        .stage_times = opt->stage_times,
    };
    bool ok = true;
    char *all = NULL;
    for (size_t k = 0; k < p->n_jobs; k++) {
        struct cv_error e = {{0}};
        if (cv_plan_make(&m->jobs[p->jobs[k]], p->scenes[p->scene_of[k]].scene, &po,
                         &p->plans[k], &e))
            continue;
        char *msg = cv_xasprintf("%s%s%s", all ? all : "", all ? "\n" : "", e.msg);
        free(all);
        all = msg;
        ok = false;
    }
    if (!ok) {
        cv_fail(err, "%s", all);
        free(all);
    }
    return ok;
}

static void print_plan(const struct cv_manifest *m, const struct selection *p,
                       const struct cv_batch_options *opt)
{
    for (size_t k = 0; k < p->n_jobs; k++) {
        const struct cv_job *job = &m->jobs[p->jobs[k]];
        const struct cv_render_plan *plan = &p->plans[k];
        uint32_t w = plan->width, h = plan->height, spp = plan->spp;
        bool skip = opt->resume && !opt->force && cv_job_outputs_current(plan);
        char formats[64] = "";
        for (unsigned i = 0; i < cv_format_names.count; i++)
            if (job->formats & (1u << i))
                snprintf(formats + strlen(formats), sizeof(formats) - strlen(formats), "%s%s",
                         formats[0] ? "," : "", cv_format_names.names[i]);
        /* a crop as oiiotool writes geometry: WxH+X+Y of the full film */
        const CvCamera *c = &plan->camera;
        char crop[64] = "";
        if (c->crop.x != w || c->crop.y != h)
            snprintf(crop, sizeof(crop), " crop %ux%u+%u+%u", c->crop.x, c->crop.y, c->film.z,
                     c->film.w);
        printf("%s: %s -> %s [%s] %ux%u%s, %u spp%s\n", job->name, job->scene_as_written,
               job->output, formats, w, h, crop, spp, skip ? " (up to date: skipped)" : "");
    }
}

enum cv_batch_status cv_batch_run(const char *manifest_path, const struct cv_batch_options *opt)
{
    struct cv_error err = {{0}};
    struct cv_manifest *m = NULL;
    /* From the start, so that a closed stdout or a signal while the scenes
     * load is handled as during a render. */
    cv_signals_install();
    if (!cv_manifest_load(manifest_path, &m, &err)) {
        cv_error_log("%s", err.msg);
        return CV_BATCH_INVALID;
    }
    struct selection sel = {0};
    enum cv_batch_status status = CV_BATCH_OK;
    if (!select_jobs(m, opt, &sel, &err) || !load_scenes(m, opt, &sel, &err) ||
        !make_plans(m, opt, &sel, &err)) {
        cv_error_log("%s", err.msg);
        status = CV_BATCH_INVALID;
        goto done;
    }
    if (opt->check_only) {
        printf("%s: valid: %zu job(s) selected, %zu scene(s)\n", manifest_path, sel.n_jobs,
               sel.n_scenes);
        goto done;
    }
    if (opt->dry_run) {
        print_plan(m, &sel, opt);
        goto done;
    }
    if (sel.n_jobs == 0) {
        cv_info("no job in this shard");
        goto done;
    }
    if (cv_signals_interrupted()) {
        status = CV_BATCH_INTERRUPTED;
        goto done;
    }

    struct cv_gpu *gpu = NULL;
    if (!cv_gpu_create(&opt->gpu, &gpu, &err)) {
        cv_error_log("%s", err.msg);
        status = CV_BATCH_NO_GPU;
        goto done;
    }
    struct cv_progress *progress =
        cv_progress_create(opt->progress, stderr, stdout);
    unsigned failed = 0;
    for (size_t k = 0; k < sel.n_jobs && !cv_signals_interrupted(); k++) {
        const struct cv_job *job = &m->jobs[sel.jobs[k]];
        struct loaded_scene *ls = &sel.scenes[sel.scene_of[k]];
        /* Several workers may share the manifest: a job is rendered only
         * under its lock, and with --resume checked again once locked, in
         * case another worker finished it meanwhile. */
        bool resume = opt->resume && !opt->force;
        const char *skip = resume && cv_job_outputs_current(&sel.plans[k]) ? "outputs up to date" : NULL;
        struct cv_job_lock *lock = NULL;
        struct cv_error jerr = {{0}};
        enum cv_lock_status locked = CV_LOCK_FAILED;
        if (!skip) {
            locked = cv_job_lock_take(job, &lock, &jerr);
            if (locked == CV_LOCK_BUSY)
                skip = "another process is rendering it";
            else if (locked == CV_LOCK_TAKEN && resume && cv_job_outputs_current(&sel.plans[k]))
                skip = "outputs up to date";
        }
        bool stop = false;
        if (skip) {
            cv_progress_job_ended(progress, job->name, CV_JOB_SKIPPED, 0, 0, skip);
        } else {
            cv_progress_job_started(progress, job->name, (unsigned)k + 1, (unsigned)sel.n_jobs,
                                    sel.plans[k].spp);
            struct cv_job_result res = {0};
            bool ready = locked == CV_LOCK_TAKEN; /* else jerr says why */
            if (!ready) {
                cv_error_prefix(&jerr, "job \"%s\": ", job->name);
            } else if (!ls->gpu_scene &&
                       !cv_scene_gpu_create(gpu, ls->scene, opt->bvh, &ls->gpu_scene, &jerr)) {
                cv_error_prefix(&jerr, "job \"%s\": uploading the scene: ", job->name);
                ready = false;
            }
            if (ready && cv_run_job(gpu, &sel.plans[k], ls->scene, ls->gpu_scene, progress,
                                    &res, &jerr)) {
                cv_progress_job_ended(progress, job->name, res.partial ? CV_JOB_PARTIAL : CV_JOB_DONE,
                                      res.spp, res.seconds, res.written);
            } else {
                failed++;
                cv_error_log("%s", jerr.msg);
                cv_progress_job_ended(progress, job->name, CV_JOB_FAILED, res.spp, res.seconds,
                                      jerr.msg);
                stop = opt->fail_fast;
            }
        }
        cv_job_lock_release(&lock);
        if (stop)
            break;
        /* Free a scene after the last job that uses it. */
        if (ls->last_use == k) {
            cv_scene_gpu_destroy(&ls->gpu_scene);
            cv_scene_destroy(&ls->scene);
        }
    }
    /* jobs left undone (--fail-fast, a signal) leave uploads behind */
    for (size_t i = 0; i < sel.n_scenes; i++)
        cv_scene_gpu_destroy(&sel.scenes[i].gpu_scene);
    cv_progress_summary(progress);
    cv_progress_destroy(&progress);
    cv_gpu_destroy(&gpu);
    if (cv_signals_interrupted())
        status = CV_BATCH_INTERRUPTED;
    else if (failed)
        status = CV_BATCH_JOBS_FAILED;
done:
    selection_free(&sel);
    cv_manifest_destroy(&m);
    return status;
}
