/* program_test.c: the GLSL loader. Includes resolve with their line numbers,
 * driver logs of both styles map back to glsl/<file>:<line>, and a broken
 * shader's error names its file and line when compiled by the real driver,
 * and lines continued by a backslash reach the driver joined, keeping the
 * line numbers after them.
 * Requests (compiling ahead, gpu/program.h): a program requested and never
 * got is no error, a failure is reported at the first get with its
 * file:line, and the build statistics count what happened. */
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
    /* Lines continued by a backslash reach the driver joined (NVIDIA's
     * compiler does not join a #define's), padded with empty lines so the
     * lines after them keep their numbers. */
    ok = cv_glsl_assemble("continued.comp", NULL, &src, &names, &err);
    tap_ok(ok, "assembles continued.comp: %s", ok ? "" : err.msg);
    if (ok) {
        tap_ok(!strstr(src, "\\\n"), "no backslash-newline reaches the driver");
        tap_ok(strstr(src, "\n#define SUM3     (1.0 +      2.0 + 3.0)\n\n\nlayout") != NULL,
               "a continued #define is one line, then one empty line per line joined");
        tap_ok(strstr(src, "\n#define PAIR_SUM     (4.0 + 5.0)\n\n#line 5 0\n") != NULL,
               "and in an included file, where the #line back names the line after it");
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
    p = cv_program_get(gpu, "continued.comp", NULL, &err);
    tap_ok(p == NULL && strstr(err.msg, "glsl/continued.comp:9") != NULL &&
               strstr(err.msg, "undeclared_after_define") != NULL,
           "an error after continued #defines names glsl/continued.comp:9");
    tap_ok(!strstr(err.msg, "SUM") && !strstr(err.msg, "continued.glsl"),
           "and no other error: the joined #defines compiled");
    tap_diag("%s", err.msg);

    struct cv_program_build_stats st;
    cv_program_build_stats(gpu, &st);
    tap_diag("%s compilation", st.parallel ? "parallel" : "serial");
    unsigned failed0 = st.failed;
    const char *prefetched[] = {"PREFETCHED", NULL};
    const char *never[] = {"NEVER_USED", NULL};
    cv_program_request(gpu, "good.comp", NULL);
    cv_program_request(gpu, "broken.comp", prefetched);
    cv_program_request(gpu, "missing.comp", NULL);
    cv_program_request(gpu, "good.comp", never);
    cv_program_build_stats(gpu, &st);
    tap_ok(st.unused == (st.parallel ? 4u : 0u) && st.requested == st.unused,
           "four requests, none got yet: no error (requested %u, unused %u)", st.requested,
           st.unused);
    err.msg[0] = '\0';
    p = cv_program_get(gpu, "good.comp", NULL, &err);
    tap_ok(p && p->local_size[0] == 8, "a requested program is got: %s", p ? "" : err.msg);
    tap_ok(p == cv_program_get(gpu, "good.comp", NULL, &err), "and got again from memory");
    p = cv_program_get(gpu, "broken.comp", prefetched, &err);
    tap_ok(p == NULL && strstr(err.msg, "glsl/inc/bad.glsl:4") != NULL,
           "a requested broken program fails at its get, naming glsl/inc/bad.glsl:4");
    err.msg[0] = '\0';
    p = cv_program_get(gpu, "broken.comp", prefetched, &err);
    tap_ok(p == NULL && strstr(err.msg, "glsl/inc/bad.glsl:4") != NULL,
           "and at every later get");
    p = cv_program_get(gpu, "missing.comp", NULL, &err);
    tap_ok(p == NULL && strstr(err.msg, "missing.comp") != NULL,
           "a requested missing file fails at its get: %s", err.msg);
    cv_program_build_stats(gpu, &st);
    tap_ok(st.unused == (st.parallel ? 1u : 0u),
           "one program requested and never got (%u)", st.unused);
    tap_ok(st.failed == failed0 + 2, "two more failed builds counted (%u)", st.failed - failed0);
    /* the suite's disk cache may hold good.comp from an earlier run */
    tap_ok(st.compiled + st.cache_hits >= 1 && st.slowest[0] && st.build_ms >= st.slowest_ms,
           "totals: %u compiled, %u from the disk cache, %.1f ms, slowest %s", st.compiled,
           st.cache_hits, st.build_ms, st.slowest);
    cv_gpu_destroy(&gpu);

    /* The same without compiling ahead: requests do nothing. */
    gpu = test_gpu_open(CV_BACKEND_AUTO);
    cv_program_set_serial(gpu, true);
    cv_program_request(gpu, "good.comp", NULL);
    cv_program_build_stats(gpu, &st);
    tap_ok(!st.parallel && st.requested == 0 && st.unused == 0, "serial: a request does nothing");
    p = cv_program_get(gpu, "good.comp", NULL, &err);
    tap_ok(p && p->local_size[0] == 8, "serial: built at its get");
    cv_gpu_destroy(&gpu);
    return tap_done();
}
