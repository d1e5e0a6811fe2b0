/* progress_wire.h: the line protocol between a worker process and the
 * parent of a multi-GPU batch (batch/workers.h). A worker's cv_progress
 * (mode CV_PROGRESS_WIRE) writes one line per call instead of showing it;
 * the parent parses the line and makes the same call on its own cv_progress,
 * so that one stream (bar, JSON or OpenJD) shows every worker. The worker's
 * log lines and its requests for a job travel on the same line stream, so
 * the parent sees them in the order they were made.
 *
 * A line is a verb and its fields, separated by tabs. Strings escape \\, tab,
 * newline and carriage return as \\\\, \\t, \\n and \\r; \\N is NULL. A list
 * is its count, then its items. Parent and workers are one binary: the
 * format makes no promise between versions. */
#ifndef CV_BATCH_PROGRESS_WIRE_H
#define CV_BATCH_PROGRESS_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

enum cv_wire_verb {
    CV_WIRE_BATCH_STARTED,   /* manifest, [jobs] */
    CV_WIRE_PHASE,           /* job, phase, what */
    CV_WIRE_ERROR,           /* lines */
    CV_WIRE_JOB_STARTED,     /* job, index, total, target_spp */
    CV_WIRE_UPDATE,          /* job, spp, target_spp, rays_per_s, elapsed_s, percent, eta_s */
    CV_WIRE_JOB_ENDED,       /* job, outcome, spp, seconds, scene_seconds, render_seconds,
                              * detail, [outputs] */
    CV_WIRE_GPU,             /* the EGL device index the worker opened (-1: none) */
    CV_WIRE_LOG,             /* one line of the worker's log, its "error: " prefix included */
    CV_WIRE_CLAIM,           /* the worker asks for a job; the parent answers (workers.c) */
    CV_WIRE_VERB_COUNT
};

/* Writes one line and flushes it. The arguments follow the verb's fields
 * above: const char * for a string (NULL allowed), unsigned for a count or
 * enum, int for a device, double for seconds and rates, and for a list a
 * const char *const * then a size_t. Returns false when the write failed. */
bool cv_wire_send(FILE *out, enum cv_wire_verb verb, ...);

/* A parsed line; its strings point into the line, which it unescapes in
 * place. */
struct cv_wire_msg {
    enum cv_wire_verb verb;
    char **field;            /* every field after the verb; owned (cv_wire_msg_clear) */
    size_t n_fields;
};

/* Parses one line without its newline. False for an unknown verb or fields
 * that do not match the verb's. */
bool cv_wire_parse(char *line, struct cv_wire_msg *msg);
void cv_wire_msg_clear(struct cv_wire_msg *msg);

/* Field i of a parsed message as its type; the list at field i (its count)
 * is field i + 1 onwards. */
const char *cv_wire_str(const struct cv_wire_msg *m, size_t i);
unsigned cv_wire_uint(const struct cv_wire_msg *m, size_t i);
int cv_wire_int(const struct cv_wire_msg *m, size_t i);
double cv_wire_double(const struct cv_wire_msg *m, size_t i);
const char *const *cv_wire_list(const struct cv_wire_msg *m, size_t i, size_t *n);

#endif
