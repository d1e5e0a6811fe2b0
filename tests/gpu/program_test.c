/* program_test.c: the GLSL loader. Includes resolve with their line numbers,
 * driver logs of both styles map back to glsl/<file>:<line>, and a broken
 * shader's error names its file and line when compiled by the real driver. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

int main(void)
{
    struct cv_error err = {{0}};
    char *names_a[] = {"main.comp", "lib/x.glsl", NULL};
    char *m = cv_glsl_map_log("1:4(12): error: `y' undeclared\n", names_a);
    tap_ok(strcmp(m, "glsl/lib/x.glsl:4:12: error: `y' undeclared\n") == 0, "Mesa style: %s", m);
    free(m);
    m = cv_glsl_map_log("0(42) : error C1008: undefined variable \"y\"\n", names_a);
    tap_ok(strcmp(m, "glsl/main.comp:42: error C1008: undefined variable \"y\"\n") == 0,
           "NVIDIA style: %s", m);
    free(m);
    m = cv_glsl_map_log("0:100004(2): error: x\n", names_a);
    tap_ok(strcmp(m, "glsl/lib/x.glsl:4:2: error: x\n") == 0, "file taken from the line: %s", m);
    free(m);
    m = cv_glsl_map_log("7(3) : out of range file\n", names_a);
    tap_ok(strcmp(m, "7(3) : out of range file\n") == 0, "unknown file numbers stay");
    free(m);

    /* Assembly from the test's own glsl tree. */
    char *dir = cv_xasprintf("%s/gpu", getenv("CV_TEST_DATA") ? getenv("CV_TEST_DATA") : "tests/data");
    setenv("CAVALRY_DATA_DIR", dir, 1);
    free(dir);
    const char *defs[] = {"FOO=1", "BAR", NULL};
    char *src = NULL, **names = NULL;
    bool ok = cv_glsl_assemble("broken.comp", defs, &src, &names, &err);
    tap_ok(ok, "assembles: %s", ok ? "" : err.msg);
    if (ok) {
        tap_ok(strncmp(src, "#version 450\n#define FOO 1\n#define BAR\n#line 2 0\n", 48) == 0,
               "version first, then defines, then #line");
        tap_ok(names[1] && strcmp(names[1], "inc/fine.glsl") == 0 && names[2] &&
                   strcmp(names[2], "inc/bad.glsl") == 0 && !names[3],
               "include table");
        tap_ok(strstr(src, "#line 200001 2\n// bad.glsl") != NULL && strstr(src, "#line 5 0\n") != NULL,
               "#line directives around includes");
        for (char **n = names; *n; n++)
            free(*n);
        free(names);
        free(src);
    }
    tap_ok(!cv_glsl_assemble("missing.comp", NULL, &src, &names, &err) &&
               strstr(err.msg, "missing.comp"),
           "missing shader names the file: %s", err.msg);

    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_program *p = cv_program_get(gpu, "broken.comp", NULL, &err);
    tap_ok(p == NULL, "broken shader fails");
    tap_ok(strstr(err.msg, "glsl/inc/bad.glsl:4") != NULL && !strstr(err.msg, "broken.comp:4"),
           "every error line names glsl/inc/bad.glsl:4");
    tap_diag("%s", err.msg);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
