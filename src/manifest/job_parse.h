/* job_parse.h: turns one job mapping (or the `defaults` mapping) of the
 * manifest into a cv_job whose has_ flags say what it set, and merges the
 * defaults under a job. Paths stay as written here; manifest.c resolves
 * them once the defaults are merged. */
#ifndef CV_MANIFEST_JOB_PARSE_H
#define CV_MANIFEST_JOB_PARSE_H

#include <stdbool.h>
#include <stddef.h>

#include <yaml.h>

#include "manifest/diag.h"
#include "manifest/manifest.h"

struct cv_ypos {
    size_t line, col;          /* 1-based; 0 when not given */
};

/* A job while being read: after cv_job_parse, job.output holds the output
 * template and job.color.config the config as written; job.scene is NULL.
 * job.at holds where each key was written. */
struct cv_job_draft {
    struct cv_job job;
    struct cv_ypos at;         /* the job's mapping */
    yaml_node_t *matrix;       /* its matrix's value (manifest/matrix.h); NULL: none */
};

/* Reads map into *out (zeroed first). In defaults `name` is not a valid key.
 * Every problem goes to d; the draft keeps whatever was valid. */
void cv_job_parse(yaml_document_t *doc, yaml_node_t *map, bool is_defaults,
                  struct cv_diag *d, struct cv_job_draft *out);

/* Reads v as the value of row k into j, as if written at k in the job
 * (a matrix value): sets its has_ flag and where it was written. */
bool cv_job_read_value(yaml_document_t *doc, yaml_node_t *v, const struct cv_key *k,
                       struct cv_diag *d, struct cv_job *j);

/* A deep copy of src into dst (strings and matrix labels duplicated). */
void cv_job_copy(struct cv_job *dst, const struct cv_job *src);

/* Fills everything job did not set from defaults (strings are copied),
 * following each key's merge rule. */
void cv_job_merge(struct cv_job_draft *job, const struct cv_job_draft *defaults);

/* Whether the job holds a value of row k (a has_ flag, or a string). */
bool cv_job_key_set(const struct cv_job *job, const struct cv_key *k);

/* Stores the default of every output setting (keys.h: fill_default) the
 * job left unset. */
void cv_job_fill_defaults(struct cv_job *job);

/* Frees the strings of a job, not the struct itself. */
void cv_job_free(struct cv_job *job);

#endif
