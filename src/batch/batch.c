/* batch.c: the batch loop. Validate everything first (manifest, then every
 * scene the selected jobs name, then the render plan of every selected
 * job), then open one GPU context and run the jobs
 * in manifest order; a scene shared by several jobs is loaded, uploaded and
 * its BVH built once. */
#include <fnmatch.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "batch/batch.h"
#include "batch/plan.h"
#include "batch/job_lock.h"
#include "batch/run_job.h"
#include "batch/signals.h"
#include "batch/workers.h"
#include "gpu/program.h"
#include "manifest/manifest.h"
#include "manifest/shard.h"
#include "scene/scene.h"
#include "trace/scene_upload.h"

struct loaded_scene {
    const char *path;            /* borrowed from the first job naming it */
    struct cv_scene *scene;
    struct cv_scene_gpu *gpu_scene; /* uploaded at its first rendered job */
    size_t last_use;             /* index of the last selected job using it */
    double load_seconds;         /* [s] parsing it: reported with its first job */
};

/* The selected jobs, their scenes and their render plans. */
struct selection {
    size_t *jobs;                /* selected job indices, manifest order */
    size_t n_jobs, cap_jobs;
    struct loaded_scene *scenes;
    size_t n_scenes, cap_scenes;
    size_t *scene_of;            /* per selected job: index into scenes */
    struct cv_render_plan *plans;  /* per selected job */
    struct cv_env_files env_files; /* env.file images, each loaded once */
};

static void selection_free(struct selection *p)
{
    free(p->plans);
    cv_env_files_clear(&p->env_files);
    for (size_t i = 0; i < p->n_scenes; i++)
        cv_scene_destroy(&p->scenes[i].scene);
    free(p->scenes);
    free(p->jobs);
    free(p->scene_of);
}

/* A pattern selects a job by its name; a job expanded from a matrix also
 * by the name of the job as written, so that --only NAME takes them all. */
static bool only_matches(const char *pattern, const struct cv_job *job)
{
    return fnmatch(pattern, job->name, 0) == 0 ||
           (job->matrix_of && fnmatch(pattern, job->matrix_of, 0) == 0);
}

/* --only patterns (any may match; each must match some job, or it is
 * likely a typo), then the shard. */
static bool select_jobs(const struct cv_manifest *m, const struct cv_batch_options *opt,
                        struct selection *p, struct cv_error *err)
{
    for (size_t k = 0; k < opt->n_only; k++) {
        size_t i = 0;
        while (i < m->n_jobs && !only_matches(opt->only[k], &m->jobs[i]))
            i++;
        if (i == m->n_jobs)
            return cv_fail(err, "%s: no job %s \"%s\"", m->path,
                           strpbrk(opt->only[k], "*?[") ? "matches" : "named", opt->only[k]);
    }
    for (size_t i = 0; i < m->n_jobs; i++) {
        bool wanted = opt->n_only == 0;
        for (size_t k = 0; k < opt->n_only && !wanted; k++)
            wanted = only_matches(opt->only[k], &m->jobs[i]);
        if (!wanted)
            continue;
        if (opt->shard_count && !opt->all_shards &&
            !cv_shard_select(m->n_jobs, opt->shard_index, opt->shard_count, i))
            continue;
        CV_PUSH(p->jobs, p->n_jobs, p->cap_jobs, i);
    }
    return true;
}

/* The command line's overrides, on the selected jobs before their plans. */
static bool override_jobs(struct cv_manifest *m, const struct cv_batch_options *opt,
                          const struct selection *p, struct cv_error *err)
{
    char *dir = cv_path_dirname(m->path);
    if (!strcmp(dir, "."))  /* as manifest.c resolves them */
        dir[0] = '\0';
    bool ok = true;
    for (size_t k = 0; k < p->n_jobs && ok; k++)
        ok = cv_plan_override_job(&m->jobs[p->jobs[k]], dir, &opt->overrides, err);
    free(dir);
    return ok;
}

/* Loads every scene once; reports every broken scene, not just the first. */
static bool load_scenes(const struct cv_manifest *m, const struct cv_batch_options *opt,
                        struct cv_progress *progress, struct selection *p,
                        struct cv_error *err)
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
            cv_progress_phase(progress, NULL, CV_PHASE_SCENE_LOAD, job->scene);
            double t0 = cv_seconds();
            bool loaded = cv_scene_load(job->scene, &lp, &ls.scene, &e);
            ls.load_seconds = cv_seconds() - t0;
            if (!loaded) {
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
        .bdpt_slots = opt->bdpt_slots,
        .misses = opt->misses,
        .env_files = &p->env_files,
    };
    p->env_files.params = (struct cv_scene_load_params){.strict = opt->strict,
                                                        .root = opt->scene_root};
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
        printf("%s: %s -> %s [%s] %ux%u%s, %u spp", job->name, job->scene_as_written,
               job->output, formats, w, h, crop, spp);
        /* the job's time_limit or --time-limit, as the render applies it */
        if (plan->time_limit > 0)
            printf(", at most %g s", plan->time_limit);
        /* an expanded job: "(matrix of shot: seed=3, camera.fov=wide)" */
        if (job->matrix_of)
            printf(" (matrix of %s:", job->matrix_of);
        for (size_t i = 0; job->matrix_of && i < job->n_axes; i++)
            printf("%s %s=%s", i ? "," : "", cv_manifest_keys[job->axes[i].key].name,
                   job->axes[i].label);
        printf("%s%s\n", job->matrix_of ? ")" : "", skip ? " (up to date: skipped)" : "");
    }
}

/* The shard of --shard-count that renders manifest job i; 0 without. */
static unsigned shard_of(const struct cv_manifest *m, const struct cv_batch_options *opt,
                         size_t i)
{
    for (unsigned s = 0; s < opt->shard_count; s++)
        if (cv_shard_select(m->n_jobs, s, opt->shard_count, i))
            return s;
    return 0;
}

/* --dry-run --json: what a farm submitter builds its task list from. */
static void print_plan_json(const struct cv_manifest *m, const struct selection *p,
                            const struct cv_batch_options *opt)
{
    printf("{\"manifest\":");
    cv_json_string(stdout, m->path);
    printf(",\"shard_count\":%u,\"jobs\":[", opt->shard_count ? opt->shard_count : 1);
    for (size_t k = 0; k < p->n_jobs; k++) {
        const struct cv_job *job = &m->jobs[p->jobs[k]];
        const struct cv_render_plan *plan = &p->plans[k];
        printf("%s\n {\"name\":", k ? "," : "");
        cv_json_string(stdout, job->name);
        printf(",\"scene\":");
        cv_json_string(stdout, job->scene);
        printf(",\"outputs\":[");
        for (unsigned i = 0, n = 0; i < cv_format_names.count; i++) {
            unsigned bit = 1u << i;
            if (!(job->formats & bit))
                continue;
            char *path = cv_job_output_path(job, cv_format_ext(bit));
            printf("%s", n++ ? "," : "");
            cv_json_string(stdout, path);
            free(path);
        }
        printf("],\"resolution\":[%u,%u],\"spp\":%u,\"integrator\":\"%s\",\"seed\":%u,",
               plan->width, plan->height, plan->spp, cv_integrator_name(plan->integrator),
               plan->seed);
        if (plan->time_limit > 0)
            printf("\"time_limit\":%.3f,", plan->time_limit);
        else
            printf("\"time_limit\":null,");
        /* the job as written and the label of each matrix value */
        if (job->matrix_of) {
            printf("\"matrix_of\":");
            cv_json_string(stdout, job->matrix_of);
            printf(",\"matrix\":{");
            for (size_t i = 0; i < job->n_axes; i++) {
                printf("%s", i ? "," : "");
                cv_json_string(stdout, cv_manifest_keys[job->axes[i].key].name);
                printf(":");
                cv_json_string(stdout, job->axes[i].label);
            }
            printf("},");
        }
        printf("\"shard\":%u,\"settings_hash\":\"%s\",\"up_to_date\":%s}",
               shard_of(m, opt, p->jobs[k]),
               plan->settings_hash,
               opt->resume && !opt->force && cv_job_outputs_current(plan) ? "true" : "false");
    }
    printf("\n]}\n");
}

/* A problem that stops the batch: to the log, and as error events. */
static void report_error(struct cv_progress *progress, const char *msg)
{
    cv_error_log("%s", msg);
    cv_progress_error(progress, msg);
}

enum cv_batch_status cv_batch_run(const char *manifest_path, const struct cv_batch_options *opt)
{
    struct cv_error err = {{0}};
    struct cv_manifest *m = NULL;
    /* From the start, so that a closed stdout or a signal while the scenes
     * load is handled as during a render. */
    cv_signals_install();
    /* --check and --dry-run print their own report: the stream carries only
     * errors then (JSON ones with --dry-run --json). */
    bool report_only = opt->check_only || opt->dry_run;
    enum cv_progress_mode mode = opt->progress;
    if (opt->dry_run && opt->json)
        mode = CV_PROGRESS_JSON;
    struct cv_progress *progress = cv_progress_create(mode, stderr, stdout);
    struct cv_progress *events = report_only ? NULL : progress;  /* NULL: none */
    struct selection sel = {0};
    enum cv_batch_status status = CV_BATCH_OK;
    if (events)
        cv_progress_phase(events, NULL, CV_PHASE_MANIFEST_READ,
                          strcmp(manifest_path, "-") ? manifest_path : CV_MANIFEST_STDIN);
    if (!cv_manifest_load(manifest_path, &m, &err)) {
        report_error(progress, err.msg);
        status = CV_BATCH_INVALID;
        goto done;
    }
    bool selected = select_jobs(m, opt, &sel, &err);
    if (selected && events) {
        const char **names = cv_xcalloc(sel.n_jobs ? sel.n_jobs : 1, sizeof(char *));
        for (size_t k = 0; k < sel.n_jobs; k++)
            names[k] = m->jobs[sel.jobs[k]].name;
        cv_progress_batch_started(events, m->path, names, sel.n_jobs);
        free(names);
    }
    if (!selected || !override_jobs(m, opt, &sel, &err) ||
        !load_scenes(m, opt, events, &sel, &err) ||
        !make_plans(m, opt, &sel, &err)) {
        report_error(progress, err.msg);
        status = CV_BATCH_INVALID;
        goto done;
    }
    if (opt->check_only) {
        printf("%s: valid: %zu job(s) selected, %zu scene(s)\n", m->path, sel.n_jobs,
               sel.n_scenes);
        goto done;
    }
    if (opt->dry_run) {
        if (opt->json)
            print_plan_json(m, &sel, opt);
        else
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
    cv_progress_phase(progress, NULL, CV_PHASE_GPU_OPEN, NULL);
    if (!cv_gpu_create(&opt->gpu, &gpu, &err)) {
        report_error(progress, err.msg);
        status = CV_BATCH_NO_GPU;
        goto done;
    }
    cv_progress_source(progress, -1, gpu->info.device_index);
    cv_program_set_serial(gpu, opt->serial_compile);
    unsigned failed = 0;
    /* In manifest order; a worker of a multi-GPU batch gets its jobs from
     * the parent instead (workers.h), still in that order. */
    size_t k, next = 0;
    while (!cv_signals_interrupted() && cv_batch_next_job(opt->worker, sel.n_jobs, &next, &k)) {
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
            cv_progress_job_ended(progress, job->name,
                                  &(struct cv_job_report){.outcome = CV_JOB_SKIPPED,
                                                          .detail = skip});
        } else {
            cv_progress_job_started(progress, job->name, (unsigned)k + 1, (unsigned)sel.n_jobs,
                                    sel.plans[k].spp);
            /* A job's seconds include its scene's upload and BVH build
             * (for the first job of the scene) and its program compile. */
            double t0 = cv_seconds(), scene_seconds = 0;
            struct cv_job_result res = {0};
            bool ready = locked == CV_LOCK_TAKEN; /* else jerr says why */
            if (!ready) {
                cv_error_prefix(&jerr, "job \"%s\": ", job->name);
            } else if (!ls->gpu_scene) {
                cv_progress_phase(progress, job->name, CV_PHASE_BVH_BUILD, ls->path);
                /* the driver compiles the job's programs during the build */
                struct cv_render_params rp = cv_plan_render_params(&sel.plans[k]);
                cv_renderer_prefetch(gpu, ls->scene, &rp);
                bool built = cv_scene_gpu_create(gpu, ls->scene, opt->bvh, &ls->gpu_scene, &jerr);
                scene_seconds = ls->load_seconds + (cv_seconds() - t0);
                if (!built) {
                    cv_error_prefix(&jerr, "job \"%s\": uploading the scene: ", job->name);
                    ready = false;
                }
            }
            ready = ready && cv_run_job(gpu, &sel.plans[k], ls->scene, ls->gpu_scene, progress,
                                        &res, &jerr);
            struct cv_job_report rep = {
                .outcome = !ready ? CV_JOB_FAILED : res.partial ? CV_JOB_PARTIAL : CV_JOB_DONE,
                .spp = res.spp,
                .seconds = cv_seconds() - t0 + ls->load_seconds * (scene_seconds > 0),
                .scene_seconds = scene_seconds,
                .render_seconds = res.render_seconds,
                .outputs = (const char *const *)res.outputs,
                .n_outputs = res.n_outputs,
                .detail = ready ? res.warning : jerr.msg,
            };
            if (!ready) {
                failed++;
                cv_error_log("%s", jerr.msg);
                stop = opt->fail_fast;
            }
            cv_progress_job_ended(progress, job->name, &rep);
            cv_job_result_clear(&res);
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
    cv_gpu_destroy(&gpu);
    if (cv_signals_interrupted())
        status = CV_BATCH_INTERRUPTED;
    else if (failed)
        status = CV_BATCH_JOBS_FAILED;
done:
    if (!report_only)
        cv_progress_summary(progress);
    cv_progress_destroy(&progress);
    selection_free(&sel);
    cv_manifest_destroy(&m);
    return status;
}
