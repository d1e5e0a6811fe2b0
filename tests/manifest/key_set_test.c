/* key_set_test.c: the duplicate checks of the manifest reader are linear.
 * Counted, not timed: the key set's comparison counter, and that of
 * cv_ymap_pairs over a mapping of 40,000 keys, stay within a small constant
 * times the number of keys (comparing each key with all earlier ones, as the
 * reader once did, makes 800 million comparisons for 40,000 keys). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <yaml.h>

#include "base/mem.h"
#include "manifest/key_set.h"
#include "manifest/yaml_view.h"
#include "tests/tap.h"

enum { N = 40000 };

int main(void)
{
    char **keys = cv_xcalloc(N, sizeof(char *));
    for (size_t i = 0; i < N; i++)
        keys[i] = cv_xasprintf("output/shot_%05zu/beauty", i);

    struct cv_key_set s = {0};
    bool added = true;
    for (size_t i = 0; i < N; i++)
        added &= cv_key_set_add(&s, keys[i], i, NULL);
    tap_ok(added && s.n == N, "%d distinct keys added", N);
    unsigned long after_add = s.compares;
    tap_ok(after_add <= 2 * N, "adding %d keys made %lu comparisons (at most %d)", N, after_add,
           2 * N);
    size_t first = 0, misses = 0;
    for (size_t i = 0; i < N; i++) {
        char *again = cv_xstrdup(keys[i]);
        if (cv_key_set_add(&s, again, N + i, &first) || first != i)
            misses++;
        free(again);
    }
    tap_ok(misses == 0, "every key again is found with its first value (%zu misses)", misses);
    tap_ok(s.compares - after_add <= 2 * N, "finding %d keys made %lu comparisons", N,
           s.compares - after_add);
    tap_ok(!cv_key_set_has(&s, "output/shot_40000/beauty") && cv_key_set_has(&s, keys[7]),
           "membership");
    cv_key_set_clear(&s);
    tap_ok(!cv_key_set_has(&s, keys[7]) && s.n == 0, "a cleared set is empty");

    /* The same through the YAML view: a mapping of N keys, one repeated. */
    size_t cap = (size_t)N * 40 + 64, len = 0;
    char *text = cv_xmalloc(cap);
    for (size_t i = 0; i < N; i++)
        len += (size_t)snprintf(text + len, cap - len, "%s: %zu\n", keys[i], i);
    len += (size_t)snprintf(text + len, cap - len, "%s: again\n", keys[123]);
    yaml_parser_t parser;
    yaml_document_t doc;
    yaml_parser_initialize(&parser);
    yaml_parser_set_input_string(&parser, (const unsigned char *)text, len);
    if (!yaml_parser_load(&parser, &doc)) {
        tap_ok(false, "libyaml loads the mapping");
        return tap_done();
    }
    struct cv_diag d = {.file = "m.yaml"};
    struct cv_ypair *pairs = NULL;
    unsigned long compares = 0;
    size_t n = cv_ymap_pairs_counted(&doc, yaml_document_get_root_node(&doc), &d, &pairs,
                                     &compares);
    tap_ok(n == N, "cv_ymap_pairs keeps %d pairs (got %zu)", N, n);
    tap_ok(d.n == 1 && strstr(d.msgs[0].text, "m.yaml:40001:1: duplicate key") &&
               strstr(d.msgs[0].text, "(first given at line 124)"),
           "the repeated key is reported once, with its first line");
    tap_ok(compares <= 2 * N, "cv_ymap_pairs made %lu key comparisons for %d keys (at most %d)",
           compares, N + 1, 2 * N);
    free(pairs);
    cv_diag_free(&d);
    yaml_document_delete(&doc);
    yaml_parser_delete(&parser);
    free(text);
    for (size_t i = 0; i < N; i++)
        free(keys[i]);
    free(keys);
    return tap_done();
}
