/* yaml_view.h: typed reads from a libyaml document, reporting every misfit
 * to a cv_diag with the node's line:col. libyaml's document API already
 * resolves aliases (an alias is the anchored node itself); this file adds
 * the YAML 1.1 merge key ("<<: *base", "<<: [*a, *b]"), which libyaml
 * leaves to the application. */
#ifndef CV_MANIFEST_YAML_VIEW_H
#define CV_MANIFEST_YAML_VIEW_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <yaml.h>

#include "manifest/diag.h"

struct cv_ypair {
    yaml_node_t *key;     /* always a scalar */
    yaml_node_t *value;
};

/* 1-based position of a node. */
size_t cv_yline(const yaml_node_t *n);
size_t cv_ycol(const yaml_node_t *n);

/* Key of a pair as a NUL-terminated string (libyaml terminates scalars). */
const char *cv_ykey(const struct cv_ypair *p);

/* "a mapping", "a sequence", "null", "a string", ... for "expected X, got Y". */
const char *cv_ykind(const yaml_node_t *n);

/* The pairs of a mapping with merge keys applied: the mapping's own keys
 * win over merged ones, and among merged mappings the first listed wins
 * (YAML merge-key spec). Duplicate own keys and bad merge values are
 * reported. *pairs is newly allocated (free()); returns the count. */
size_t cv_ymap_pairs(yaml_document_t *doc, yaml_node_t *map, struct cv_diag *d,
                     struct cv_ypair **pairs);
/* The same, telling how many key comparisons its duplicate checks made
 * (expected linear in the number of pairs; the tests hold it to that). */
size_t cv_ymap_pairs_counted(yaml_document_t *doc, yaml_node_t *map, struct cv_diag *d,
                             struct cv_ypair **pairs, unsigned long *compares);

/* Each reader checks the node and reports "<what>: expected ..., got ..."
 * at the node on failure, returning false and leaving *out alone. */
bool cv_yread_string(yaml_node_t *n, struct cv_diag *d, const char *what, const char **out);
bool cv_yread_int(yaml_node_t *n, struct cv_diag *d, const char *what, long long min,
                  long long max, long long *out);
/* Finite number in [min, max]. */
bool cv_yread_float(yaml_node_t *n, struct cv_diag *d, const char *what, double min,
                    double max, double *out);
bool cv_yread_bool(yaml_node_t *n, struct cv_diag *d, const char *what, bool *out);
/* One of names[0..count); *out is the index. */
bool cv_yread_enum(yaml_node_t *n, struct cv_diag *d, const char *what,
                   const char *const *names, size_t count, int *out);
/* A duration (keys.h CV_KT_DURATION) from text: seconds > 0, with an
 * optional unit s, m or h; the manifest's reader and --time-limit share it. */
#define CV_DURATION_EXPECTED \
    "a duration > 0 in seconds, or with a unit s, m or h (\"90\", \"1.5m\", \"2h\")"
bool cv_duration_parse(const char *s, double *out);
/* Seconds > 0: a plain number, or a number followed by s, m or h. */
bool cv_yread_duration(yaml_node_t *n, struct cv_diag *d, const char *what, double *out);

/* Reports an unknown key with the list of valid ones. */
void cv_yunknown_key(const struct cv_ypair *p, struct cv_diag *d, const char *where,
                     const char *const *valid, size_t count);

#endif
