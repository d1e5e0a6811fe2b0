/* progress.h: what a batch tells the person or the farm tool watching it.
 * On a terminal, a live line per job (spp, rays/s, ETA); with --progress=json
 * one JSON object per line on stdout (job_started, progress, job_finished,
 * job_failed, job_skipped, batch_finished); at the end a summary table. */
#ifndef CV_BATCH_PROGRESS_H
#define CV_BATCH_PROGRESS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

enum cv_progress_mode {
    CV_PROGRESS_AUTO = 0,  /* bar on a terminal, else none */
    CV_PROGRESS_BAR,
    CV_PROGRESS_JSON,
    CV_PROGRESS_NONE,
};

enum cv_job_outcome {
    CV_JOB_DONE,
    CV_JOB_PARTIAL,      /* interrupted: image written, marked partial */
    CV_JOB_FAILED,
    CV_JOB_SKIPPED,      /* --resume found its outputs */
};

struct cv_progress;

/* Returns false for an unknown mode name. */
bool cv_progress_mode_parse(const char *name, enum cv_progress_mode *mode);
struct cv_progress *cv_progress_create(enum cv_progress_mode mode, FILE *tty, FILE *json);
void cv_progress_destroy(struct cv_progress **p);

void cv_progress_job_started(struct cv_progress *p, const char *job, unsigned index,
                             unsigned total, uint32_t target_spp);
/* rays_per_s may be 0 when unknown; eta_s < 0 when unknown. */
void cv_progress_update(struct cv_progress *p, const char *job, uint32_t spp, uint32_t target_spp,
                        double rays_per_s, double elapsed_s, double eta_s);
void cv_progress_job_ended(struct cv_progress *p, const char *job, enum cv_job_outcome outcome,
                           uint32_t spp, double seconds, const char *detail);
/* Prints the summary table (to the terminal stream unless in json mode,
 * where it becomes a batch_finished object). */
void cv_progress_summary(struct cv_progress *p);

/* Appends s to out as a JSON string literal (with quotes). */
void cv_json_string(FILE *out, const char *s);

#endif
