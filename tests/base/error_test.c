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

    int *v = NULL;
    size_t n = 0, cap = 0;
    for (int i = 0; i < 1000; i++)
        CV_PUSH(v, n, cap, i);
    tap_ok(n == 1000 && v[999] == 999 && cap >= 1000, "CV_PUSH grows");
    free(v);
    return tap_done();
}
