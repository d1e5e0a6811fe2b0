/* manifest.c: cv_manifest_load and friends (see manifest.h). The flow is
 * parse (libyaml document) -> read the top level, defaults and each job
 * (job_parse.c) -> expand each job's matrix (matrix.c) -> merge defaults ->
 * resolve paths and check the files they name -> hash. Every stage keeps going after a problem so that one run shows
 * the user all of them. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <yaml.h>

#include "base/file.h"
#include "base/mem.h"
#include "manifest/diag.h"
#include "manifest/job_hash.h"
#include "manifest/job_parse.h"
#include "manifest/key_set.h"
#include "manifest/manifest.h"
#include "manifest/matrix.h"
#include "manifest/yaml_scan.h"
#include "manifest/yaml_view.h"

static const char *const top_keys[] = {"version", "defaults", "jobs", "x-*"};

/* libyaml reader errors (bad UTF-8) carry a byte offset, not a mark. */
static void offset_to_mark(const char *data, size_t len, size_t offset, size_t *line,
                           size_t *col)
{
    *line = 1;
    *col = 1;
    for (size_t i = 0; i < offset && i < len; i++) {
        if (data[i] == '\n') {
            ++*line;
            *col = 1;
        } else {
            ++*col;
        }
    }
}

static void syntax_error(yaml_parser_t *p, const char *data, size_t len, struct cv_diag *d)
{
    size_t line = p->problem_mark.line + 1, col = p->problem_mark.column + 1;
    const char *problem = p->problem ? p->problem : "malformed YAML";
    if (p->error == YAML_READER_ERROR) {
        offset_to_mark(data, len, p->problem_offset, &line, &col);
        cv_diag_add(d, line, col, "YAML error: %s", problem);
    } else if (p->context) {
        cv_diag_add(d, line, col, "YAML syntax error: %s (%s at line %zu, column %zu)", problem,
                    p->context, p->context_mark.line + 1, p->context_mark.column + 1);
    } else {
        cv_diag_add(d, line, col, "YAML syntax error: %s", problem);
    }
}

/* The label that {key} stands for in job's output template: the job's
 * name, or the label of its value of that matrix key; NULL when the job's
 * matrix has no such key. */
static const char *template_value(const struct cv_job *j, const char *key, size_t len)
{
    if (len == 4 && !strncmp(key, "name", 4))
        return j->name ? j->name : "";
    for (size_t i = 0; i < j->n_axes; i++) {
        const char *k = cv_manifest_keys[j->axes[i].key].name;
        if (strlen(k) == len && !strncmp(k, key, len))
            return j->axes[i].label;
    }
    return NULL;
}

/* The output template with {name} and each {KEY} of the job's matrix
 * replaced (keys.c checked the braces' spelling); NULL with the first
 * placeholder the job cannot fill in *missing. */
static char *expand_output(const char *tmpl, const struct cv_job *j, char *missing, size_t n)
{
    size_t cap = strlen(tmpl) + 1, len = 0;
    char *out = cv_xmalloc(cap);
    for (const char *p = tmpl; *p;) {
        const char *end = *p == '{' ? strchr(p, '}') : NULL;
        const char *v = end ? template_value(j, p + 1, (size_t)(end - p - 1)) : NULL;
        if (end && !v) {
            snprintf(missing, n, "%.*s", (int)(end - p + 1), p);
            free(out);
            return NULL;
        }
        size_t add = v ? strlen(v) : 1;
        out = cv_xgrow(out, &cap, len + add + 1, 1);
        memcpy(out + len, v ? v : p, add);
        len += add;
        p = v ? end + 1 : p + 1;
    }
    out[len] = '\0';
    return out;
}

static bool is_ocio_uri(const char *s)
{
    return !strncmp(s, "ocio://", 7);
}

/* Resolves and checks one merged job; draft index i is only for messages. */
/* Makes *path (as written) relative to the manifest's folder dir, and
 * says where it was written if no file is there. */
static void resolve_file(const char *dir, char **path, struct cv_key_at at, const char *what,
                         const char *label, struct cv_diag *d)
{
    char *full = cv_path_join(dir, *path);
    struct stat st;
    if (stat(full, &st) != 0)
        cv_diag_add(d, at.line, at.col, "%s: %s \"%s\" not found (%s: %s)", label, what, *path,
                    full, strerror(errno));
    free(*path);
    *path = full;
}

static void resolve_job(struct cv_job_draft *dr, size_t i, const char *dir, struct cv_diag *d)
{
    struct cv_job *j = &dr->job;
    char label[160];
    if (j->name)
        snprintf(label, sizeof(label), "job \"%s\" (line %zu)", j->name, dr->at.line);
    else
        snprintf(label, sizeof(label), "job %zu (line %zu)", i + 1, dr->at.line);
    const struct cv_key_at *at = j->at;
    if (!j->name && !at[CV_K_NAME].line)
        cv_diag_add(d, dr->at.line, dr->at.col, "job %zu: missing required key \"name\"", i + 1);

    cv_job_fill_defaults(j);

    const char *tmpl = j->output ? j->output : cv_manifest_keys[CV_K_OUTPUT].def_text;
    char missing[80];
    char *expanded = expand_output(tmpl, j, missing, sizeof(missing));
    if (!expanded) {
        const struct cv_key_at *oat = &at[CV_K_OUTPUT];
        cv_diag_add(d, oat->line ? oat->line : dr->at.line, oat->line ? oat->col : dr->at.col,
                    "%s: output \"%s\": %s is not a key of the job's matrix", label, tmpl,
                    missing);
        expanded = cv_xstrdup(tmpl);
    }
    free(j->output);
    j->output = cv_path_join(dir, expanded);
    free(expanded);

    struct stat st = {0};
    bool scene_ok = false;
    if (!j->scene_as_written) {
        cv_diag_add(d, dr->at.line, dr->at.col,
                    "%s: missing required key \"scene\" (give it in the job or in defaults)",
                    label);
    } else {
        j->scene = cv_path_join(dir, j->scene_as_written);
        if (stat(j->scene, &st) != 0)
            cv_diag_add(d, at[CV_K_SCENE].line, at[CV_K_SCENE].col,
                        "%s: scene file \"%s\" not found (%s: %s)", label, j->scene_as_written,
                        j->scene, strerror(errno));
        else if (!S_ISREG(st.st_mode))
            cv_diag_add(d, at[CV_K_SCENE].line, at[CV_K_SCENE].col,
                        "%s: scene \"%s\" is not a regular file", label, j->scene_as_written);
        else
            scene_ok = true;
    }
    if (scene_ok)
        j->settings_hash = cv_job_settings_hash_stat(j, &st);

    if (j->env.file)
        resolve_file(dir, &j->env.file, at[CV_K_ENV_FILE], "environment image", label, d);
    if (j->color.config && !is_ocio_uri(j->color.config))
        resolve_file(dir, &j->color.config, at[CV_K_COLOR_CONFIG], "color config", label, d);
}

/* Names and output files must be unique: two jobs writing one file would
 * silently overwrite each other on a farm. Sets of the names and outputs
 * seen keep it linear in the number of jobs. */
static void check_unique(struct cv_job_draft *jobs, size_t n, const char *file,
                         struct cv_diag *d)
{
    struct cv_key_set names = {0}, outputs = {0};
    /* outputs compared in one spelling: out/a, ./out/a, out//a, out/../out/a */
    char **norm = cv_xcalloc(n ? n : 1, sizeof(char *));
    for (size_t i = 0; i < n; i++)
        norm[i] = jobs[i].job.output ? cv_path_normalize(jobs[i].job.output) : NULL;
    for (size_t i = 0; i < n; i++) {
        struct cv_job_draft *a = &jobs[i];
        if (!a->job.name)
            continue;
        size_t k;
        if (!cv_key_set_add(&names, a->job.name, i, &k)) {
            struct cv_job_draft *b = &jobs[k];
            cv_diag_add(d, a->job.at[CV_K_NAME].line, a->job.at[CV_K_NAME].col,
                        "duplicate job name \"%s\" (first defined at %s:%u:%u)",
                        a->job.name, file, b->job.at[CV_K_NAME].line,
                        b->job.at[CV_K_NAME].col);
        } else if (norm[i] && !cv_key_set_add(&outputs, norm[i], i, &k)) {
            struct cv_job_draft *b = &jobs[k];
            const struct cv_key_at *oat = &a->job.at[CV_K_OUTPUT];
            bool given = oat->line != 0;
            cv_diag_add(d, given ? oat->line : a->at.line, given ? oat->col : a->at.col,
                        "job \"%s\": output \"%s\" is also the output of job \"%s\" "
                        "(line %zu); put {name} in the output template",
                        a->job.name, a->job.output, b->job.name, b->at.line);
        }
    }
    cv_key_set_clear(&names);
    cv_key_set_clear(&outputs);
    for (size_t i = 0; i < n; i++)
        free(norm[i]);
    free(norm);
}

static void read_version(yaml_node_t *v, struct cv_diag *d)
{
    long long version;
    if (!cv_yread_int(v, d, "version", 0, 1000000, &version))
        return;
    if (version != CV_MANIFEST_VERSION)
        cv_diag_add(d, cv_yline(v), cv_ycol(v),
                    "unsupported manifest version %lld; this cavalry reads version %d", version,
                    CV_MANIFEST_VERSION);
}

/* Reads the document into drafts; returns the count, *jobs allocated. */
static size_t read_document(yaml_document_t *doc, yaml_node_t *root, struct cv_diag *d,
                            struct cv_job_draft *defaults, struct cv_job_draft **jobs)
{
    *jobs = NULL;
    memset(defaults, 0, sizeof(*defaults));
    if (root->type != YAML_MAPPING_NODE) {
        cv_diag_add(d, cv_yline(root), cv_ycol(root),
                    "manifest: expected a mapping with version, defaults and jobs, got %s",
                    cv_ykind(root));
        return 0;
    }
    struct cv_ypair *pairs;
    size_t np = cv_ymap_pairs(doc, root, d, &pairs);
    yaml_node_t *version = NULL, *def = NULL, *list = NULL;
    for (size_t i = 0; i < np; i++) {
        const char *k = cv_ykey(&pairs[i]);
        if (!strcmp(k, "version"))
            version = pairs[i].value;
        else if (!strcmp(k, "defaults"))
            def = pairs[i].value;
        else if (!strcmp(k, "jobs"))
            list = pairs[i].value;
        else if (strncmp(k, "x-", 2) != 0) /* x-*: room for anchors, ignored */
            cv_yunknown_key(&pairs[i], d, "the manifest", top_keys, CV_ARRAY_SIZE(top_keys));
    }
    free(pairs);

    if (version)
        read_version(version, d);
    else
        cv_diag_add(d, cv_yline(root), cv_ycol(root),
                    "missing required key \"version\" (write \"version: %d\" at the top)",
                    CV_MANIFEST_VERSION);
    if (def)
        cv_job_parse(doc, def, true, d, defaults);
    if (!list) {
        cv_diag_add(d, cv_yline(root), cv_ycol(root),
                    "missing required key \"jobs\" (a list of jobs)");
        return 0;
    }
    if (list->type != YAML_SEQUENCE_NODE) {
        cv_diag_add(d, cv_yline(list), cv_ycol(list), "jobs: expected a list of jobs, got %s",
                    cv_ykind(list));
        return 0;
    }
    size_t n = (size_t)(list->data.sequence.items.top - list->data.sequence.items.start);
    if (n == 0) {
        cv_diag_add(d, cv_yline(list), cv_ycol(list), "jobs: the list is empty");
        return 0;
    }
    /* a job with a matrix becomes its expansions (manifest/matrix.h) */
    size_t count = 0, cap = 0;
    for (size_t i = 0; i < n; i++) {
        yaml_node_t *item = yaml_document_get_node(doc, list->data.sequence.items.start[i]);
        struct cv_job_draft dr;
        cv_job_parse(doc, item, false, d, &dr);
        if (dr.matrix) {
            cv_matrix_expand(doc, &dr, d, jobs, &count, &cap);
            cv_job_free(&dr.job);
        } else {
            CV_PUSH(*jobs, count, cap, dr);
        }
    }
    return count;
}

/* Parses data (owned: freed here) read from path. */
static bool load_data(const char *path, char *data, size_t len, struct cv_manifest **out,
                      struct cv_error *err);

bool cv_manifest_load(const char *path, struct cv_manifest **out, struct cv_error *err)
{
    *out = NULL;
    char *data;
    size_t len;
    if (!strcmp(path, "-")) {
        if (!cv_read_stdin(CV_MANIFEST_STDIN, &data, &len, err))
            return false;
        path = CV_MANIFEST_STDIN;
    } else if (!cv_read_file(path, &data, &len, err)) {
        return false;
    }
    return load_data(path, data, len, out, err);
}

static bool load_data(const char *path, char *data, size_t len, struct cv_manifest **out,
                      struct cv_error *err)
{
    struct cv_diag d = {.file = path};
    if (!cv_yaml_scan(data, len, &d)) {
        free(data);
        return cv_diag_finish(&d, err);
    }
    yaml_parser_t parser;
    yaml_document_t doc;
    if (!yaml_parser_initialize(&parser)) {
        free(data);
        return cv_fail(err, "%s: cannot initialise the YAML parser", path);
    }
    yaml_parser_set_input_string(&parser, (const unsigned char *)data, len);
    if (!yaml_parser_load(&parser, &doc)) {
        syntax_error(&parser, data, len, &d);
        yaml_parser_delete(&parser);
        free(data);
        return cv_diag_finish(&d, err);
    }
    yaml_node_t *root = yaml_document_get_root_node(&doc);
    if (!root) {
        cv_diag_add(&d, 1, 1, "the manifest is empty (expected version, defaults and jobs)");
    } else {
        /* A second document would be ignored silently; say so instead. */
        yaml_document_t extra;
        if (!yaml_parser_load(&parser, &extra)) {
            syntax_error(&parser, data, len, &d);
        } else {
            yaml_node_t *r2 = yaml_document_get_root_node(&extra);
            if (r2)
                cv_diag_add(&d, cv_yline(r2), cv_ycol(r2),
                            "a manifest holds one YAML document; found a second one");
            yaml_document_delete(&extra);
        }
    }

    struct cv_job_draft defaults, *drafts = NULL;
    size_t n = root ? read_document(&doc, root, &d, &defaults, &drafts) : 0;
    if (!root)
        memset(&defaults, 0, sizeof(defaults));
    /* "./scenes/a.pbrt" helps no one: keep paths of a manifest in the
     * working folder as written. */
    char *dir = cv_path_dirname(path);
    if (!strcmp(dir, "."))
        dir[0] = '\0';
    for (size_t i = 0; i < n; i++) {
        cv_job_merge(&drafts[i], &defaults);
        resolve_job(&drafts[i], i, dir, &d);
    }
    check_unique(drafts, n, path, &d);
    free(dir);
    cv_job_free(&defaults.job);
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    free(data);

    if (!cv_diag_finish(&d, err)) {
        for (size_t i = 0; i < n; i++)
            cv_job_free(&drafts[i].job);
        free(drafts);
        return false;
    }
    struct cv_manifest *m = cv_xcalloc(1, sizeof(*m));
    m->path = cv_xstrdup(path);
    m->n_jobs = n;
    m->jobs = cv_xcalloc(n, sizeof(*m->jobs));
    for (size_t i = 0; i < n; i++)
        m->jobs[i] = drafts[i].job;
    free(drafts);
    *out = m;
    return true;
}

void cv_manifest_destroy(struct cv_manifest **m)
{
    if (!m || !*m)
        return;
    for (size_t i = 0; i < (*m)->n_jobs; i++)
        cv_job_free(&(*m)->jobs[i]);
    free((*m)->jobs);
    free((*m)->path);
    free(*m);
    *m = NULL;
}

char *cv_job_output_path(const struct cv_job *job, const char *ext)
{
    if (!ext)
        return cv_xstrdup(job->output);
    return cv_xasprintf("%s.%s", job->output, ext);
}

const struct cv_job *cv_manifest_find_job(const struct cv_manifest *m, const char *name)
{
    for (size_t i = 0; i < m->n_jobs; i++)
        if (!strcmp(m->jobs[i].name, name))
            return &m->jobs[i];
    return NULL;
}
