/* matrix.h: a job's `matrix:` (cavalry-manifest(5), "Matrix"): a mapping
 * of job keys to lists of their values, which expands the job into one job
 * per combination (the cartesian product, the first key varying slowest).
 * Each expanded job is an ordinary job from here on: its own name
 * (the job's name, then "_" and the label of each value, in the matrix's
 * order), settings hash, shard and lock. Values are read and checked once,
 * where they are written, before any job is made. */
#ifndef CV_MANIFEST_MATRIX_H
#define CV_MANIFEST_MATRIX_H

#include <stddef.h>

#include <yaml.h>

#include "manifest/diag.h"
#include "manifest/job_parse.h"

/* Expands job (as parsed, before defaults are merged; job->matrix not
 * NULL) into new drafts appended to *jobs (*n entries, *cap allocated; the
 * array may move). The job itself is left as it was; the caller frees it.
 * Problems go to d; with any, the job is appended once, unexpanded, so that
 * later checks still see it. */
void cv_matrix_expand(yaml_document_t *doc, const struct cv_job_draft *job, struct cv_diag *d,
                      struct cv_job_draft **jobs, size_t *n, size_t *cap);

#endif
