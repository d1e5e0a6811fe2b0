/* yaml_caps_test.c: a manifest past the reader's limits on nesting depth,
 * anchors and aliases fails with one clear message at the node's line:col,
 * and one at the limit still loads; 40,000 top-level keys are read, and a
 * duplicate among them found. Only the public reader is used, so the test
 * holds for any implementation (the comparison count of the duplicate check
 * is key_set_test's business). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

/* The limits as cavalry-manifest(5) documents them. */
enum { MAX_DEPTH = 64, MAX_ANCHORS = 1000, MAX_ALIASES = 10000 };

static char path[256];

/* Grows a string with printf-style pieces. */
struct text {
    char *s;
    size_t n, cap;
};

static void add(struct text *t, const char *piece)
{
    size_t k = strlen(piece);
    if (t->n + k + 1 > t->cap) {
        t->cap = (t->n + k + 1) * 2;
        t->s = cv_xrealloc(t->s, t->cap);
    }
    memcpy(t->s + t->n, piece, k + 1);
    t->n += k;
}

static struct cv_manifest *load(const char *text, struct cv_error *err)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    struct cv_manifest *m = NULL;
    cv_error_clear(err);
    cv_manifest_load(path, &m, err);
    return m;
}

/* The job list as "jobs: [{name: a, scene: s.pbrt, output: o, extra: X}]"
 * where X is nested `depth` levels deep. */
static char *nested(int depth)
{
    struct text t = {0};
    add(&t, "version: 1\njobs:\n  - name: a\n    scene: s.pbrt\n    x: ");
    for (int i = 0; i < depth; i++)
        add(&t, "[");
    for (int i = 0; i < depth; i++)
        add(&t, "]");
    add(&t, "\n");
    return t.s;
}

/* n anchors defined and each used `uses` times. */
static char *anchored(int n, int uses)
{
    struct text t = {0};
    char buf[64];
    add(&t, "version: 1\nx-anchors:\n");
    for (int i = 0; i < n; i++) {
        snprintf(buf, sizeof(buf), "  - &a%d %d\n", i, i);
        add(&t, buf);
    }
    add(&t, "x-uses:\n");
    for (int u = 0; u < uses; u++)
        for (int i = 0; i < n; i++) {
            snprintf(buf, sizeof(buf), "  - *a%d\n", i);
            add(&t, buf);
        }
    add(&t, "jobs: []\n");
    return t.s;
}

static void expect(const char *what, char *text, const char *want)
{
    struct cv_error err;
    struct cv_manifest *m = load(text, &err);
    bool ok = !m && strstr(err.msg, want) != NULL;
    if (!tap_ok(ok, "%s", what))
        tap_diag("got: %.300s\n# want: %s", m ? "(loaded)" : err.msg, want);
    cv_manifest_destroy(&m);
    free(text);
}

/* Under the limit: whatever the reader says, it is not about the limit. */
static void within(const char *what, char *text, const char *not_want)
{
    struct cv_error err;
    struct cv_manifest *m = load(text, &err);
    bool ok = m || !strstr(err.msg, not_want);
    if (!tap_ok(ok, "%s", what))
        tap_diag("got: %.300s", err.msg);
    cv_manifest_destroy(&m);
    free(text);
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    char dir[200];
    snprintf(dir, sizeof(dir), "%s/cv-caps-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir))
        return tap_ok(false, "mkdtemp"), tap_done();
    snprintf(path, sizeof(path), "%s/m.yaml", dir);

    /* The document's mapping, jobs, the job, then x's depth brackets. */
    expect("nesting past the limit: clear error at its line:col", nested(MAX_DEPTH + 10),
           "m.yaml:5:69: ");
    expect("nesting past the limit: says what the limit is",
           nested(MAX_DEPTH + 10), "nested deeper than");
    expect("100,000 levels of nesting: refused, no crash", nested(100000), "nested deeper than");
    within("nesting at the limit is not refused for depth", nested(MAX_DEPTH - 3),
           "nested deeper");
    expect("too many anchors", anchored(MAX_ANCHORS + 1, 0), "anchors (&name)");
    within("anchors at the limit", anchored(MAX_ANCHORS, 0), "anchors (&name)");
    expect("too many aliases", anchored(100, MAX_ALIASES / 100 + 1), "aliases (*name)");
    within("aliases at the limit", anchored(100, MAX_ALIASES / 100), "aliases (*name)");

    /* 40,000 top-level keys (x-* keys are the user's own) with the last one
     * repeating the first: a duplicate at the last line. */
    struct text t = {0};
    char buf[64];
    add(&t, "version: 1\njobs: []\n");
    for (int i = 0; i < 40000; i++) {
        snprintf(buf, sizeof(buf), "x-key%05d: %d\n", i, i);
        add(&t, buf);
    }
    add(&t, "x-key00000: again\n");
    expect("40,000 keys: the duplicate of the first is found at the last line", t.s,
           "m.yaml:40003:1: duplicate key \"x-key00000\" (first given at line 3)");

    unlink(path);
    rmdir(dir);
    return tap_done();
}
