/* metadata_test.c: the key/value list keeps order, replaces in place and
 * formats values as text the way PNG chunks carry them. */
#include <stdlib.h>
#include <string.h>

#include "output/metadata.h"
#include "tests/tap.h"

int main(void)
{
    struct cv_metadata *m = cv_metadata_new();
    cv_metadata_set_string(m, "scene", "a.pbrt");
    cv_metadata_set_int(m, "spp", 64);
    cv_metadata_set_float(m, "renderTime", 1.5);
    cv_metadata_set_bool(m, "partial", true);
    cv_metadata_set_string(m, "scene", "b.pbrt");
    TAP_EQ_INT(m->len, 4, "four keys after replacing one");
    tap_ok(strcmp(m->entries[0].key, "scene") == 0 && strcmp(m->entries[0].v.s, "b.pbrt") == 0,
           "replaced value keeps its place");
    const struct cv_meta_entry *e = cv_metadata_get(m, "spp");
    tap_ok(e && e->type == CV_META_INT && e->v.i == 64, "get int");
    tap_ok(cv_metadata_get(m, "nope") == NULL, "missing key is NULL");
    cv_metadata_set_int(m, "scene", -3);
    e = cv_metadata_get(m, "scene");
    tap_ok(e->type == CV_META_INT, "a key can change type");

    char *t = cv_meta_value_text(cv_metadata_get(m, "renderTime"));
    tap_ok(strcmp(t, "1.5") == 0, "float text %s", t);
    free(t);
    t = cv_meta_value_text(cv_metadata_get(m, "scene"));
    tap_ok(strcmp(t, "-3") == 0, "int text %s", t);
    free(t);
    t = cv_meta_value_text(cv_metadata_get(m, "partial"));
    tap_ok(strcmp(t, "1") == 0, "bool text %s", t);
    free(t);
    cv_metadata_set_float(m, "third", 1.0 / 3.0);
    t = cv_meta_value_text(cv_metadata_get(m, "third"));
    tap_ok((float)strtod(t, NULL) == (float)(1.0 / 3.0), "float text reads back as float32 (%s)", t);
    free(t);

    float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5f, -2, 3, 1};
    cv_metadata_set_m44f(m, "worldToCamera", id);
    e = cv_metadata_get(m, "worldToCamera");
    tap_ok(e && e->type == CV_META_M44F && e->v.m[12] == 0.5f, "get m44f");
    t = cv_meta_value_text(e);
    tap_ok(strcmp(t, "1 0 0 0 0 1 0 0 0 0 1 0 0.5 -2 3 1") == 0, "m44f text, row by row: %s", t);
    free(t);

    cv_metadata_destroy(&m);
    tap_ok(m == NULL, "destroy clears the pointer");
    cv_metadata_destroy(&m);
    cv_metadata_destroy(NULL);
    return tap_done();
}
