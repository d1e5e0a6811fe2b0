/* error_test.c: error messages keep their context when prefixed, and file
 * helpers report the path that failed. */
#include <string.h>

#include "base/error.h"
#include "base/file.h"
#include "base/mem.h"
#include "tests/tap.h"

int main(void)
{
    struct cv_error err = {0};
    tap_ok(!cv_fail(&err, "%s:%d:%d: bad", "a.pbrt", 3, 7), "cv_fail returns false");
    cv_error_prefix(&err, "loading %s", "scene");
    tap_ok(strcmp(err.msg, "loading scene: a.pbrt:3:7: bad") == 0, "prefix: %s", err.msg);

    char *data;
    size_t len;
    tap_ok(!cv_read_file("/nonexistent/x.pbrt", &data, &len, &err), "missing file fails");
    tap_ok(strstr(err.msg, "/nonexistent/x.pbrt") != NULL, "message names the file: %s", err.msg);

    char *d = cv_path_dirname("dir/sub/file.ply");
    tap_ok(strcmp(d, "dir/sub") == 0, "dirname");
    char *j = cv_path_join(d, "m.ply");
    tap_ok(strcmp(j, "dir/sub/m.ply") == 0, "join");
    free(d);
    free(j);

    char tmpl[] = "/tmp/cv-mkdir-XXXXXX";
    char *base = mkdtemp(tmpl);
    char *deep = cv_xasprintf("%s/a/b/c/out.exr", base);
    tap_ok(cv_mkdir_parents(deep, &err), "mkdir parents: %s", err.msg);
    char *made = cv_path_dirname(deep);
    tap_ok(cv_path_exists(made), "folders made");
    tap_ok(cv_mkdir_parents(deep, &err), "again: nothing to do");
    char *under_file = cv_xasprintf("%s/a/b/c/f/x.exr", base);
    char *file = cv_xasprintf("%s/a/b/c/f", base);
    FILE *ff = fopen(file, "w");
    if (ff)
        fclose(ff);
    tap_ok(!cv_mkdir_parents(under_file, &err) && strstr(err.msg, "not a folder"),
           "a file in the way: %s", err.msg);
    free(deep);
    free(made);
    free(under_file);
    free(file);

    int *v = NULL;
    size_t n = 0, cap = 0;
    for (int i = 0; i < 1000; i++)
        CV_PUSH(v, n, cap, i);
    tap_ok(n == 1000 && v[999] == 999 && cap >= 1000, "CV_PUSH grows");
    free(v);
    return tap_done();
}
