/* yaml_view.c: see yaml_view.h. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/key_set.h"
#include "manifest/yaml_view.h"

/* Merge chains deeper than this are certainly a mistake (or a cycle). */
#define MAX_MERGE_DEPTH 32

size_t cv_yline(const yaml_node_t *n)
{
    return n->start_mark.line + 1;
}

size_t cv_ycol(const yaml_node_t *n)
{
    return n->start_mark.column + 1;
}

const char *cv_ykey(const struct cv_ypair *p)
{
    return (const char *)p->key->data.scalar.value;
}

static bool is_null(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE || n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE)
        return false;
    const char *v = (const char *)n->data.scalar.value;
    return !v[0] || !strcmp(v, "~") || !strcmp(v, "null") || !strcmp(v, "Null") ||
           !strcmp(v, "NULL");
}

static bool is_quoted(const yaml_node_t *n)
{
    return n->type == YAML_SCALAR_NODE && n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE;
}

const char *cv_ykind(const yaml_node_t *n)
{
    switch (n->type) {
    case YAML_MAPPING_NODE:
        return "a mapping";
    case YAML_SEQUENCE_NODE:
        return "a sequence";
    case YAML_SCALAR_NODE:
        if (is_null(n))
            return "null";
        return is_quoted(n) ? "a quoted string" : "a plain scalar";
    default:
        return "nothing";
    }
}

static const char *scalar(const yaml_node_t *n)
{
    return (const char *)n->data.scalar.value;
}

static bool is_merge_key(const yaml_node_t *k)
{
    return k->type == YAML_SCALAR_NODE && k->data.scalar.style == YAML_PLAIN_SCALAR_STYLE &&
           !strcmp(scalar(k), "<<");
}

/* Merging walks shared nodes, so a few lines of anchors can ask for an
 * exponential amount of work ("<<: [*a, *a]" chained); a mapping can even
 * merge itself. The walk keeps the chain of mappings being merged to catch
 * cycles and a budget of pairs visited to stop the explosion. */
#define MERGE_BUDGET 100000

struct merge_walk {
    yaml_document_t *doc;
    struct cv_diag *d;
    yaml_node_t *chain[MAX_MERGE_DEPTH];
    int depth;
    long budget;
    bool reported;
    unsigned long compares;  /* key comparisons of the duplicate checks */
};

/* Appends the pairs of map, its own first, to the empty list *out. */
static void collect(struct merge_walk *w, yaml_node_t *map, struct cv_ypair **out, size_t *n,
                    size_t *cap);

/* Appends the pairs of one merge source whose keys are not in seen yet. */
static void merge_from(struct merge_walk *w, yaml_node_t *src, struct cv_key_set *seen,
                       struct cv_ypair **out, size_t *n, size_t *cap)
{
    if (src->type != YAML_MAPPING_NODE) {
        cv_diag_add(w->d, cv_yline(src), cv_ycol(src),
                    "merge key \"<<\": expected a mapping or a sequence of mappings, got %s",
                    cv_ykind(src));
        return;
    }
    for (int i = 0; i < w->depth; i++) {
        if (w->chain[i] == src) {
            cv_diag_add(w->d, cv_yline(src), cv_ycol(src),
                        "merge key \"<<\": this mapping merges itself");
            return;
        }
    }
    struct cv_ypair *sub = NULL;
    size_t sn = 0, scap = 0;
    collect(w, src, &sub, &sn, &scap);
    for (size_t i = 0; i < sn; i++)
        if (cv_key_set_add(seen, cv_ykey(&sub[i]), *n, NULL))
            CV_PUSH(*out, *n, *cap, sub[i]);
    free(sub);
}

static void collect(struct merge_walk *w, yaml_node_t *map, struct cv_ypair **out, size_t *n,
                    size_t *cap)
{
    if (w->depth >= MAX_MERGE_DEPTH || w->budget <= 0) {
        if (!w->reported)
            cv_diag_add(w->d, cv_yline(map), cv_ycol(map),
                        "merge keys nested too deeply or expanding too much");
        w->reported = true;
        return;
    }
    w->chain[w->depth++] = map;
    yaml_node_t *merges[64];
    size_t n_merges = 0;
    struct cv_key_set seen = {0}; /* keys in *out, valued by their index */
    for (yaml_node_pair_t *p = map->data.mapping.pairs.start; p < map->data.mapping.pairs.top;
         p++) {
        yaml_node_t *k = yaml_document_get_node(w->doc, p->key);
        yaml_node_t *v = yaml_document_get_node(w->doc, p->value);
        w->budget--;
        if (!k || !v)
            continue;
        if (is_merge_key(k)) {
            if (v->type == YAML_SEQUENCE_NODE) {
                for (yaml_node_item_t *it = v->data.sequence.items.start;
                     it < v->data.sequence.items.top; it++)
                    if (n_merges < CV_ARRAY_SIZE(merges))
                        merges[n_merges++] = yaml_document_get_node(w->doc, *it);
            } else if (n_merges < CV_ARRAY_SIZE(merges)) {
                merges[n_merges++] = v;
            }
            continue;
        }
        if (k->type != YAML_SCALAR_NODE || is_null(k)) {
            cv_diag_add(w->d, cv_yline(k), cv_ycol(k), "expected a string key, got %s",
                        cv_ykind(k));
            continue;
        }
        size_t first;
        if (!cv_key_set_add(&seen, scalar(k), *n, &first)) {
            cv_diag_add(w->d, cv_yline(k), cv_ycol(k),
                        "duplicate key \"%s\" (first given at line %zu)", scalar(k),
                        cv_yline((*out)[first].key));
            continue;
        }
        struct cv_ypair pair = {k, v};
        CV_PUSH(*out, *n, *cap, pair);
    }
    for (size_t i = 0; i < n_merges; i++)
        if (merges[i])
            merge_from(w, merges[i], &seen, out, n, cap);
    w->compares += seen.compares;
    cv_key_set_clear(&seen);
    w->depth--;
}

size_t cv_ymap_pairs_counted(yaml_document_t *doc, yaml_node_t *map, struct cv_diag *d,
                             struct cv_ypair **pairs, unsigned long *compares)
{
    size_t n = 0, cap = 0;
    struct merge_walk w = {.doc = doc, .d = d, .budget = MERGE_BUDGET};
    *pairs = NULL;
    collect(&w, map, pairs, &n, &cap);
    if (compares)
        *compares = w.compares;
    return n;
}

size_t cv_ymap_pairs(yaml_document_t *doc, yaml_node_t *map, struct cv_diag *d,
                     struct cv_ypair **pairs)
{
    return cv_ymap_pairs_counted(doc, map, d, pairs, NULL);
}

static void expected(yaml_node_t *n, struct cv_diag *d, const char *what, const char *exp)
{
    if (n->type == YAML_SCALAR_NODE && !is_null(n))
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected %s, got \"%s\"", what, exp,
                    scalar(n));
    else
        cv_diag_add(d, cv_yline(n), cv_ycol(n), "%s: expected %s, got %s", what, exp,
                    cv_ykind(n));
}

bool cv_yread_string(yaml_node_t *n, struct cv_diag *d, const char *what, const char **out)
{
    if (n->type != YAML_SCALAR_NODE || is_null(n) || !scalar(n)[0]) {
        expected(n, d, what, "a non-empty string");
        return false;
    }
    *out = scalar(n);
    return true;
}

bool cv_yread_int(yaml_node_t *n, struct cv_diag *d, const char *what, long long min,
                  long long max, long long *out)
{
    char exp[96];
    snprintf(exp, sizeof(exp), "an integer from %lld to %lld", min, max);
    if (n->type != YAML_SCALAR_NODE || is_null(n) || is_quoted(n)) {
        expected(n, d, what, exp);
        return false;
    }
    const char *s = scalar(n);
    char *end;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (end == s || *end || errno == ERANGE || v < min || v > max) {
        expected(n, d, what, exp);
        return false;
    }
    *out = v;
    return true;
}

/* Parses a finite decimal number; strtod alone would take "nan", "inf" and
 * hex floats, none of which belong in a manifest. */
static bool parse_number(const char *s, double *out, const char **rest)
{
    const char *p = s;
    if (*p == '+' || *p == '-')
        p++;
    if (!((*p >= '0' && *p <= '9') || (*p == '.' && p[1] >= '0' && p[1] <= '9')))
        return false;
    if (p[0] == '0' && (p[1] == 'x' || p[1] == 'X'))
        return false;
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || errno == ERANGE || !isfinite(v))
        return false;
    *out = v;
    *rest = end;
    return true;
}

bool cv_yread_float(yaml_node_t *n, struct cv_diag *d, const char *what, double min,
                    double max, double *out)
{
    char exp[96];
    snprintf(exp, sizeof(exp), "a number from %g to %g", min, max);
    double v;
    const char *rest;
    if (n->type != YAML_SCALAR_NODE || is_null(n) || is_quoted(n) ||
        !parse_number(scalar(n), &v, &rest) || *rest || v < min || v > max) {
        expected(n, d, what, exp);
        return false;
    }
    *out = v;
    return true;
}

bool cv_yread_bool(yaml_node_t *n, struct cv_diag *d, const char *what, bool *out)
{
    static const char *const yes[] = {"true", "True", "TRUE", "yes", "Yes", "YES", "on", "On", "ON"};
    static const char *const no[] = {"false", "False", "FALSE", "no", "No", "NO", "off", "Off", "OFF"};
    if (n->type == YAML_SCALAR_NODE && !is_quoted(n)) {
        for (size_t i = 0; i < CV_ARRAY_SIZE(yes); i++) {
            if (!strcmp(scalar(n), yes[i])) {
                *out = true;
                return true;
            }
            if (!strcmp(scalar(n), no[i])) {
                *out = false;
                return true;
            }
        }
    }
    expected(n, d, what, "true or false");
    return false;
}

bool cv_yread_enum(yaml_node_t *n, struct cv_diag *d, const char *what,
                   const char *const *names, size_t count, int *out)
{
    if (n->type == YAML_SCALAR_NODE) {
        for (size_t i = 0; i < count; i++) {
            if (!strcmp(scalar(n), names[i])) {
                *out = (int)i;
                return true;
            }
        }
    }
    char exp[256] = "one of ";
    for (size_t i = 0; i < count; i++) {
        strncat(exp, names[i], sizeof(exp) - strlen(exp) - 1);
        if (i + 1 < count)
            strncat(exp, ", ", sizeof(exp) - strlen(exp) - 1);
    }
    expected(n, d, what, exp);
    return false;
}

bool cv_duration_parse(const char *s, double *out)
{
    double v;
    const char *rest;
    if (!parse_number(s, &v, &rest))
        return false;
    double unit = 1.0;
    if (!strcmp(rest, "") || !strcmp(rest, "s"))
        unit = 1.0;
    else if (!strcmp(rest, "m"))
        unit = 60.0;
    else if (!strcmp(rest, "h"))
        unit = 3600.0;
    else
        unit = 0.0;
    if (unit == 0.0 || !(v > 0.0) || !isfinite(v * unit))
        return false;
    *out = v * unit;
    return true;
}

bool cv_yread_duration(yaml_node_t *n, struct cv_diag *d, const char *what, double *out)
{
    if (n->type != YAML_SCALAR_NODE || is_null(n) || !cv_duration_parse(scalar(n), out)) {
        expected(n, d, what, CV_DURATION_EXPECTED);
        return false;
    }
    return true;
}

/* Edit distance, for "did you mean"; keys are short so O(n*m) is nothing. */
static size_t distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 31 || lb > 31)
        return 99;
    size_t row[32];
    for (size_t j = 0; j <= lb; j++)
        row[j] = j;
    for (size_t i = 1; i <= la; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= lb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (row[j] + 1 < best)
                best = row[j] + 1;
            if (row[j - 1] + 1 < best)
                best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[lb];
}

void cv_yunknown_key(const struct cv_ypair *p, struct cv_diag *d, const char *where,
                     const char *const *valid, size_t count)
{
    char list[512] = "";
    const char *close = NULL;
    size_t best = 3;
    for (size_t i = 0; i < count; i++) {
        if (i)
            strncat(list, ", ", sizeof(list) - strlen(list) - 1);
        strncat(list, valid[i], sizeof(list) - strlen(list) - 1);
        size_t dist = distance(cv_ykey(p), valid[i]);
        if (dist < best) {
            best = dist;
            close = valid[i];
        }
    }
    if (close)
        cv_diag_add(d, cv_yline(p->key), cv_ycol(p->key),
                    "unknown key \"%s\" in %s; valid keys: %s (did you mean \"%s\"?)",
                    cv_ykey(p), where, list, close);
    else
        cv_diag_add(d, cv_yline(p->key), cv_ycol(p->key),
                    "unknown key \"%s\" in %s; valid keys: %s", cv_ykey(p), where, list);
}
