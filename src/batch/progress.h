/* progress.h: what a batch tells the person or the farm tool watching it.
 * On a terminal, a live line per job (spp, rays/s, ETA); with --progress=json
 * one JSON object per line on stdout, each with its UTC time (batch_started,
 * phase, progress, job_started, job_finished, job_partial, job_failed,
 * job_skipped, error, batch_finished; cavalry-batch(1) lists their fields);
 * with --progress=openjd the "openjd_progress: N" and "openjd_status: ..."
 * lines of Open Job Description; at the end a summary table. */
#ifndef CV_BATCH_PROGRESS_H
#define CV_BATCH_PROGRESS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

enum cv_progress_mode {
    CV_PROGRESS_AUTO = 0,  /* bar on a terminal, else none */
    CV_PROGRESS_BAR,
    CV_PROGRESS_JSON,
    CV_PROGRESS_NONE,
    CV_PROGRESS_OPENJD,
    CV_PROGRESS_WIRE,      /* a worker's calls, to its parent (progress_wire.h);
                            * not a --progress name */
};

enum cv_job_outcome {
    CV_JOB_DONE,
    CV_JOB_PARTIAL,      /* interrupted: image written, marked partial */
    CV_JOB_FAILED,
    CV_JOB_SKIPPED,      /* --resume found its outputs */
};

/* The stages a batch and each job go through, in order; a phase event
 * says one begins, so that a long scene load or BVH build is not silence. */
enum cv_phase {
    CV_PHASE_MANIFEST_READ,
    CV_PHASE_SCENE_LOAD,       /* parse a scene file (before any job starts) */
    CV_PHASE_GPU_OPEN,         /* create the GPU context (once a batch) */
    CV_PHASE_BVH_BUILD,        /* upload a scene and build its BVH (its first job) */
    CV_PHASE_PROGRAM_COMPILE,  /* link the job's GPU programs (or take them from the cache) */
    CV_PHASE_RENDER,           /* render passes */
    CV_PHASE_COLOUR,           /* the OCIO display pass of a PNG */
    CV_PHASE_WRITE,            /* write one output file */
    CV_PHASE_COUNT
};

/* A finished job as the events and the table report it. */
struct cv_job_report {
    enum cv_job_outcome outcome;
    uint32_t spp;
    double seconds;            /* [s] the whole job: for the first job of a scene its
                                * parse and BVH build too, then compile, render, write */
    double scene_seconds;      /* [s] the scene's parse and BVH build when this job
                                * paid for them; 0 for later jobs sharing the scene */
    double render_seconds;     /* [s] the render passes alone */
    const char *const *outputs;  /* files written; n_outputs of them */
    size_t n_outputs;
    const char *detail;        /* why skipped, the error; NULL: none */
};

struct cv_progress;

/* Returns false for an unknown mode name; names lists them for messages. */
bool cv_progress_mode_parse(const char *name, enum cv_progress_mode *mode);
extern const char cv_progress_mode_names[];
const char *cv_phase_name(enum cv_phase phase);

struct cv_progress *cv_progress_create(enum cv_progress_mode mode, FILE *tty, FILE *json);
void cv_progress_destroy(struct cv_progress **p);

/* The selected jobs, in the order they will run. */
void cv_progress_batch_started(struct cv_progress *p, const char *manifest,
                               const char *const *jobs, size_t n_jobs);
/* A phase begins; job NULL for the batch's own; what: the file it reads or
 * writes, or NULL. p NULL: nothing (--check, --dry-run). */
void cv_progress_phase(struct cv_progress *p, const char *job, enum cv_phase phase,
                       const char *what);
/* Problems that stop the batch: one "file:line:col: message" (or a plain
 * message) per line, each its own error event. */
void cv_progress_error(struct cv_progress *p, const char *lines);

void cv_progress_job_started(struct cv_progress *p, const char *job, unsigned index,
                             unsigned total, uint32_t target_spp);
/* rays_per_s may be 0 when unknown; percent in [0, 100] of the job (samples
 * or time limit, whichever ends it first); eta_s < 0 when unknown. */
void cv_progress_update(struct cv_progress *p, const char *job, uint32_t spp, uint32_t target_spp,
                        double rays_per_s, double elapsed_s, double percent, double eta_s);
void cv_progress_job_ended(struct cv_progress *p, const char *job,
                           const struct cv_job_report *r);
/* Prints the summary table (to the terminal stream unless in json mode,
 * where it becomes a batch_finished object naming the jobs never started). */
void cv_progress_summary(struct cv_progress *p);

/* Where the next events come from: worker, the worker process of a
 * multi-GPU batch (batch/workers.h), -1 in a single process; gpu, the EGL
 * device index, -1 when unknown. Events about a job then carry "gpu" and
 * "worker" (each when not -1), and so do a worker's batch phases and errors;
 * a bar or OpenJD status names them. In mode CV_PROGRESS_WIRE the device
 * goes to the parent. */
void cv_progress_source(struct cv_progress *p, int worker, int gpu);

/* Appends s to out as a JSON string literal (with quotes). */
void cv_json_string(FILE *out, const char *s);

#endif
