/* matrix.c: see matrix.h. */
#include <stdlib.h>
#include <string.h>

#include "base/limits.h"
#include "base/mem.h"
#include "manifest/key_set.h"
#include "manifest/keys.h"
#include "manifest/matrix.h"
#include "manifest/yaml_view.h"

/* One key of the matrix: its row and its values with their labels. */
struct axis {
    const struct cv_key *key;
    yaml_node_t **values;
    char **labels;             /* borrowed from the document, or owned digits */
    bool *owned;
    size_t n;
};

static bool is_label(const char *s)
{
    if (!*s || !strcmp(s, ".") || !strcmp(s, ".."))
        return false;
    for (const char *p = s; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') ||
              *p == '.' || *p == '_' || *p == '-'))
            return false;
    return true;
}

static void bad_key(const struct cv_ypair *p, struct cv_diag *d)
{
    const char *valid[CV_K_COUNT];
    size_t n = 0;
    for (size_t i = 0; i < CV_K_COUNT; i++)
        if (cv_key_in_matrix(&cv_manifest_keys[i]))
            valid[n++] = cv_manifest_keys[i].name;
    const struct cv_key *k = cv_key_find(cv_ykey(p));
    if (k && !cv_key_in_matrix(k))
        cv_diag_add(d, cv_yline(p->key), cv_ycol(p->key),
                    "matrix: \"%s\" cannot vary in a matrix (%s)", k->name,
                    k->type == CV_KT_SECTION ? "a section: name its keys, e.g. \"color.exposure\""
                    : k == &cv_manifest_keys[CV_K_OUTPUT]
                        ? "the output template names the expanded jobs: write {KEY} in it"
                        : "each expanded job gets its own from the job's");
    else
        cv_yunknown_key(p, d, "matrix", valid, n);
}

/* Reads one key of the matrix into a; false after reporting. */
static bool read_axis(yaml_document_t *doc, const struct cv_ypair *p,
                      const struct cv_job_draft *job, struct cv_diag *d, struct axis *a)
{
    memset(a, 0, sizeof(*a));
    const struct cv_key *k = cv_key_find(cv_ykey(p));
    if (!k || !cv_key_in_matrix(k)) {
        bad_key(p, d);
        return false;
    }
    a->key = k;
    size_t id = (size_t)(k - cv_manifest_keys);
    if (cv_job_key_set(&job->job, k)) {
        cv_diag_add(d, cv_yline(p->key), cv_ycol(p->key),
                    "matrix: \"%s\" is also a key of the job (line %u): give it in one place",
                    k->name, job->job.at[id].line);
        return false;
    }
    yaml_node_t *v = p->value;
    bool is_map = v->type == YAML_MAPPING_NODE;
    struct cv_ypair *pairs = NULL;
    size_t n = 0;
    if (is_map)
        n = cv_ymap_pairs(doc, v, d, &pairs);
    else if (v->type == YAML_SEQUENCE_NODE)
        n = (size_t)(v->data.sequence.items.top - v->data.sequence.items.start);
    else {
        cv_diag_add(d, cv_yline(v), cv_ycol(v),
                    "matrix: %s: expected a list of values (or a mapping of label: value), got %s",
                    k->name, cv_ykind(v));
        return false;
    }
    if (n == 0) {
        cv_diag_add(d, cv_yline(v), cv_ycol(v), "matrix: %s: the list is empty", k->name);
        free(pairs);
        return false;
    }
    a->n = n;
    a->values = cv_xcalloc(n, sizeof(*a->values));
    a->labels = cv_xcalloc(n, sizeof(*a->labels));
    a->owned = cv_xcalloc(n, sizeof(*a->owned));
    bool ok = true;
    struct cv_key_set seen = {0};
    for (size_t i = 0; i < n; i++) {
        yaml_node_t *item, *at;
        if (is_map) {
            item = pairs[i].value;
            at = pairs[i].key;
            a->labels[i] = (char *)cv_ykey(&pairs[i]);
        } else {
            item = yaml_document_get_node(doc, v->data.sequence.items.start[i]);
            at = item;
            if (item->type == YAML_SCALAR_NODE) {
                a->labels[i] = (char *)item->data.scalar.value;
            } else {
                /* a list or mapping value is labelled by its place */
                a->labels[i] = cv_xasprintf("%zu", i);
                a->owned[i] = true;
            }
        }
        a->values[i] = item;
        struct cv_job scratch = {0};
        bool read = cv_job_read_value(doc, item, k, d, &scratch);
        cv_job_free(&scratch);
        if (!read) {
            ok = false;
            continue;
        }
        size_t first;
        if (!is_label(a->labels[i])) {
            cv_diag_add(d, cv_yline(at), cv_ycol(at),
                        "matrix: %s: \"%s\" cannot label a job name (letters, digits, '.', '_' "
                        "and '-'): give the values as a mapping of label: value",
                        k->name, a->labels[i]);
            ok = false;
        } else if (!cv_key_set_add(&seen, a->labels[i], i, &first)) {
            cv_diag_add(d, cv_yline(at), cv_ycol(at),
                        "matrix: %s: value \"%s\" is listed twice (first at line %zu): the "
                        "expanded jobs would have one name",
                        k->name, a->labels[i], cv_yline(a->values[first]));
            ok = false;
        }
    }
    cv_key_set_clear(&seen);
    free(pairs);
    return ok;
}

static void axis_free(struct axis *a)
{
    for (size_t i = 0; i < a->n; i++)
        if (a->owned[i])
            free(a->labels[i]);
    free(a->values);
    free(a->labels);
    free(a->owned);
}

static void push(struct cv_job_draft **jobs, size_t *n, size_t *cap, const struct cv_job_draft *dr)
{
    CV_PUSH(*jobs, *n, *cap, *dr);
}

void cv_matrix_expand(yaml_document_t *doc, const struct cv_job_draft *job, struct cv_diag *d,
                      struct cv_job_draft **jobs, size_t *n, size_t *cap)
{
    yaml_node_t *m = job->matrix;
    struct cv_ypair *pairs = NULL;
    size_t np = 0;
    bool ok = true;
    if (m->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(m), cv_ycol(m),
                    "matrix: expected a mapping of keys to lists of values, got %s", cv_ykind(m));
        ok = false;
    } else {
        np = cv_ymap_pairs(doc, m, d, &pairs);
        if (np == 0) {
            cv_diag_add(d, cv_yline(m), cv_ycol(m), "matrix: expected at least one key");
            ok = false;
        }
    }
    struct axis *axes = cv_xcalloc(np ? np : 1, sizeof(*axes));
    size_t count = 1;
    for (size_t i = 0; i < np; i++) {
        ok &= read_axis(doc, &pairs[i], job, d, &axes[i]);
        if (axes[i].n && count <= CV_MAX_MATRIX_JOBS)
            count *= axes[i].n;   /* no overflow: both factors are bounded first */
    }
    if (ok && count > CV_MAX_MATRIX_JOBS) {
        cv_diag_add(d, cv_yline(m), cv_ycol(m),
                    "matrix: expands the job into more than %u jobs (the product of its lists' "
                    "lengths); split it into several jobs",
                    CV_MAX_MATRIX_JOBS);
        ok = false;
    }
    if (!ok) {
        struct cv_job_draft copy = *job;
        cv_job_copy(&copy.job, &job->job);
        copy.matrix = NULL;
        push(jobs, n, cap, &copy);
    }
    size_t *digit = cv_xcalloc(np ? np : 1, sizeof(size_t));
    for (size_t c = 0; ok && c < count; c++) {
        struct cv_job_draft dr = *job;
        dr.matrix = NULL;
        cv_job_copy(&dr.job, &job->job);
        struct cv_job *j = &dr.job;
        j->axes = cv_xcalloc(np, sizeof(*j->axes));
        j->n_axes = np;
        size_t len = j->name ? strlen(j->name) : 0;
        for (size_t i = 0; i < np; i++) {
            const struct axis *a = &axes[i];
            /* checked in read_axis: the diag sees no new problem here */
            struct cv_diag quiet = {.file = d->file};
            cv_job_read_value(doc, a->values[digit[i]], a->key, &quiet, j);
            cv_diag_free(&quiet);
            j->axes[i] = (struct cv_job_axis){(enum cv_key_id)(a->key - cv_manifest_keys),
                                              cv_xstrdup(a->labels[digit[i]])};
            len += 1 + strlen(a->labels[digit[i]]);
        }
        if (j->name) {
            char *name = cv_xmalloc(len + 1), *o = name;
            o += sprintf(o, "%s", j->name);
            for (size_t i = 0; i < np; i++)
                o += sprintf(o, "_%s", j->axes[i].label);
            j->matrix_of = j->name;
            j->name = name;
        }
        push(jobs, n, cap, &dr);
        /* next combination: the last key varies fastest */
        for (size_t i = np; i-- > 0;) {
            if (++digit[i] < axes[i].n)
                break;
            digit[i] = 0;
        }
    }
    free(digit);
    for (size_t i = 0; i < np; i++)
        axis_free(&axes[i]);
    free(axes);
    free(pairs);
}
