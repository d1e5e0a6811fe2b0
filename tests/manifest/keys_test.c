/* keys_test.c: the manifest key table (manifest/keys.h) against the reader
 * that walks it. For every key, from a value of its type: the job reads it
 * (and says where), `defaults` merges it into a job (or refuses it, for
 * job-only keys) with the same settings as the job's own, and the settings
 * text changes with it exactly when the row says the key is hashed. The
 * rows themselves: named, documented for --list-keys, in sections that
 * come first. cavalry-manifest(5) is checked against the same rows by
 * man_lint_test.sh. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "manifest/job_hash.h"
#include "manifest/job_parse.h"
#include "manifest/keys.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

static char dir[256];

static void write_file(const char *name, const char *text)
{
    char *path = cv_xasprintf("%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    free(path);
}

static struct cv_manifest *load(const char *text, struct cv_error *err)
{
    write_file("m.yaml", text);
    char *path = cv_xasprintf("%s/m.yaml", dir);
    struct cv_manifest *m = NULL;
    cv_error_clear(err);
    cv_manifest_load(path, &m, err);
    free(path);
    return m;
}

/* A valid value of row k other than its default, as YAML flow text. */
static char *example(const struct cv_key *k)
{
    switch (k->type) {
    case CV_KT_STRING:
        if (k == &cv_manifest_keys[CV_K_NAME])
            return cv_xstrdup("other");
        if (k == &cv_manifest_keys[CV_K_SCENE])
            return cv_xstrdup("t.pbrt");
        if (k == &cv_manifest_keys[CV_K_OUTPUT])
            return cv_xstrdup("\"renders/{name}\"");
        if (k == &cv_manifest_keys[CV_K_COLOR_CONFIG])
            return cv_xstrdup("c.ocio");
        if (k == &cv_manifest_keys[CV_K_ENV_FILE])  /* any file that exists */
            return cv_xstrdup("t.pbrt");
        return cv_xstrdup("x1");
    case CV_KT_U32: return cv_xasprintf("%.0f", k->max);
    case CV_KT_FLOAT: return cv_xasprintf("%g", (k->min + k->max) / 2);
    case CV_KT_DURATION: return cv_xstrdup("2m");
    case CV_KT_BOOL: return cv_xstrdup(k->def != 0 ? "false" : "true");
    case CV_KT_ENUM: return cv_xstrdup(k->names->names[k->names->count - 1]);
    case CV_KT_BITS: return cv_xasprintf("[%s]", k->names->names[k->names->count - 1]);
    case CV_KT_RESOLUTION: return cv_xstrdup("[3, 2]");
    case CV_KT_LOOKAT: return cv_xstrdup("[[0, 0, 0], [0, 0, 1], [0, 1, 0]]");
    case CV_KT_CROP: return cv_xstrdup("[0.25, 0.75, 0, 0.5]");
    /* a key that is not hashed, as the matrix row is not: its values
     * enter the hash as the keys they set */
    case CV_KT_MATRIX: return cv_xstrdup("{formats: [exr, png]}");
    case CV_KT_ROTATE: return cv_xstrdup("[90, 0, 1, 0]");
    case CV_KT_LIGHT_SCALES: return cv_xstrdup("{0: 2, 3: 0.5}");
    case CV_KT_SECTION: break;
    }
    return NULL;
}

/* "key: value", or "section: {key: value}" */
static char *entry(const struct cv_key *k, const char *value)
{
    const char *leaf = cv_key_leaf(k);
    if (leaf == k->name)
        return cv_xasprintf("%s: %s", k->name, value);
    return cv_xasprintf("%.*s: {%s: %s}", (int)(leaf - k->name - 1), k->name, leaf, value);
}

static char *settings(const struct cv_job *j)
{
    return cv_job_settings_text(j, 1, 2);
}

static void test_key(const struct cv_key *k)
{
    size_t id = (size_t)(k - cv_manifest_keys);
    char *value = example(k), *e = entry(k, value);
    struct cv_error err = {{0}};
    /* the job's own: line 3 */
    bool replaces = id == CV_K_NAME || id == CV_K_SCENE;
    char *own_text = cv_xasprintf("version: 1\njobs:\n  - {%s%s%s}\n",
                                  id == CV_K_NAME ? "" : "name: j, ",
                                  id == CV_K_SCENE ? "" : "scene: s.pbrt, ", e);
    struct cv_manifest *own = load(own_text, &err);
    const struct cv_job *oj = own ? &own->jobs[0] : NULL;
    tap_ok(oj && cv_job_key_set(oj, k) && oj->at[id].line == 3 && oj->at[id].col > 5,
           "%s: read from the job, at its line (%s)", k->name, err.msg);

    struct cv_manifest *plain = load("version: 1\njobs:\n  - {name: j, scene: s.pbrt}\n", &err);
    const struct cv_job *pj = plain ? &plain->jobs[0] : NULL;
    /* output always holds the resolved path, its template's or the default's */
    if (!replaces)
        tap_ok(pj && (id == CV_K_OUTPUT || !cv_job_key_set(pj, k)) && pj->at[id].line == 0,
               "%s: unset where not written", k->name);
    char *t_own = oj ? settings(oj) : NULL, *t_plain = pj ? settings(pj) : NULL;
    bool differs = t_own && t_plain && strcmp(t_own, t_plain) != 0;
    tap_ok(differs == (k->hash != CV_HASH_NO), "%s: %s the settings hash", k->name,
           k->hash != CV_HASH_NO ? "changes" : "does not change");

    /* from defaults: line 2 */
    char *def_text = cv_xasprintf("version: 1\ndefaults: {%s}\njobs:\n  - {name: j%s}\n", e,
                                  id == CV_K_SCENE ? "" : ", scene: s.pbrt");
    struct cv_manifest *merged = load(def_text, &err);
    if (k->merge == CV_MERGE_JOB_ONLY) {
        tap_ok(!merged && strstr(err.msg, "cannot be given in defaults"),
               "%s: refused in defaults: %s", k->name, err.msg);
    } else {
        const struct cv_job *mj = merged ? &merged->jobs[0] : NULL;
        char *t_merged = mj ? settings(mj) : NULL;
        tap_ok(mj && cv_job_key_set(mj, k) && mj->at[id].line == 2 && t_own && t_merged &&
                   strcmp(t_own, t_merged) == 0,
               "%s: merged from defaults, with the job's own settings (%s)", k->name, err.msg);
        free(t_merged);
    }
    free(t_own);
    free(t_plain);
    free(def_text);
    free(own_text);
    free(value);
    free(e);
    cv_manifest_destroy(&own);
    cv_manifest_destroy(&plain);
    cv_manifest_destroy(&merged);
}

static void test_rows(void)
{
    bool named = true, ordered = true, unique = true, stored = true;
    for (size_t i = 0; i < CV_K_COUNT; i++) {
        const struct cv_key *k = &cv_manifest_keys[i];
        if (!k->name || !k->help) {
            named = false;
            continue;
        }
        for (size_t j = 0; j < i; j++)
            if (!strcmp(cv_manifest_keys[j].name, k->name))
                unique = false;
        const char *dot = strrchr(k->name, '.');
        if (dot) {
            char *section = cv_xasprintf("%.*s", (int)(dot - k->name), k->name);
            const struct cv_key *s = cv_key_find(section);
            if (!s || s->type != CV_KT_SECTION || s > k)
                ordered = false;
            free(section);
        }
        bool needs_flag = k->type != CV_KT_STRING && k->type != CV_KT_SECTION;
        if (needs_flag != (k->has != 0) || (k->type != CV_KT_SECTION && k->offset == 0 &&
                                            i != CV_K_NAME))
            stored = false;
    }
    tap_ok(named, "every row has a name and a help line");
    tap_ok(unique, "key names are unique");
    tap_ok(ordered, "every nested key follows its section");
    tap_ok(stored, "every value has a place in struct cv_job and a has_ flag where it needs one");
    tap_ok(cv_key_find("color.view") == &cv_manifest_keys[CV_K_COLOR_VIEW] &&
               !cv_key_find("view") && !strcmp(cv_key_leaf(&cv_manifest_keys[CV_K_COLOR_VIEW]),
                                               "view"),
           "keys are found by their dotted names");
}

int main(void)
{
    snprintf(dir, sizeof(dir), "%s/cv-keys-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir))
        return tap_skip_all("cannot make a temporary folder");
    write_file("s.pbrt", "WorldBegin\n");
    write_file("t.pbrt", "WorldBegin\n");
    write_file("c.ocio", "ocio_profile_version: 2\n");
    test_rows();
    for (size_t i = 0; i < CV_K_COUNT; i++)
        if (cv_manifest_keys[i].type != CV_KT_SECTION)
            test_key(&cv_manifest_keys[i]);
    char *cmd = cv_xasprintf("rm -rf '%s'", dir);
    if (system(cmd) != 0)
        tap_diag("could not remove %s", dir);
    free(cmd);
    return tap_done();
}
