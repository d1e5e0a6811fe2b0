/* matrix_test.c: manifest/matrix.c through cv_manifest_load: a job's matrix
 * becomes its jobs in product order (first key slowest), each holding its
 * values as if written in the job (where they were written, for messages),
 * its name and labels, its templated output and its own settings hash;
 * defaults stay under the matrix's values; values of every kind (mappings
 * with labels, lookat lists, sections' keys, the light keys) expand; a job
 * without a matrix is untouched. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

static char dir[256];

static struct cv_manifest *load(const char *text, struct cv_error *err)
{
    char *path = cv_xasprintf("%s/m.yaml", dir);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    struct cv_manifest *m = NULL;
    cv_error_clear(err);
    cv_manifest_load(path, &m, err);
    free(path);
    return m;
}

static const char *tail(const char *path)
{
    size_t n = strlen(dir);
    return strncmp(path, dir, n) == 0 ? path + n + 1 : path;
}

int main(void)
{
    snprintf(dir, sizeof(dir), "%s/cv-matrix-XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir))
        return tap_skip_all("cannot make a temporary folder");
    char *scene = cv_xasprintf("%s/s.pbrt", dir);
    FILE *f = fopen(scene, "w");
    if (f) {
        fputs("WorldBegin\n", f);
        fclose(f);
    }
    free(scene);

    struct cv_error err = {{0}};
    struct cv_manifest *m = load("version: 1\n"                              /* 1 */
                                 "defaults: {scene: s.pbrt, spp: 8, seed: 9}\n" /* 2 */
                                 "jobs:\n"                                   /* 3 */
                                 "  - name: a\n"                             /* 4 */
                                 "    output: o/{color.exposure}/{name}\n"   /* 5 */
                                 "    matrix:\n"                             /* 6 */
                                 "      color.exposure: {dark: -1, bright: 1}\n" /* 7 */
                                 "      seed: [3, 4, 5]\n"                   /* 8 */
                                 "  - name: b\n"                             /* 9 */
                                 "    matrix:\n"                             /* 10 */
                                 "      camera.lookat: [[[0, 0, 5], [0, 0, 0], [0, 1, 0]],\n"
                                 "                      [0, 5, 0, 0, 0, 0, 0, 0, 1]]\n"
                                 "      env.rotate: [[90, 0, 1, 0]]\n"       /* 13 */
                                 "      lights.scale: {off: {0: 0}}\n"       /* 14 */
                                 "  - name: c\n",                            /* 15 */
                                 &err);
    if (!tap_ok(m != NULL, "the manifest loads: %s", err.msg))
        return tap_done();
    tap_ok(m->n_jobs == 6 + 2 + 1, "2 x 3 + 2 x 1 x 1 + 1 jobs (%zu)", m->n_jobs);
    static const char *const names[] = {"a_dark_3",   "a_dark_4",   "a_dark_5",
                                        "a_bright_3", "a_bright_4", "a_bright_5",
                                        "b_0_0_off",  "b_1_0_off",  "c"};
    bool in_order = m->n_jobs == 9;
    for (size_t i = 0; in_order && i < 9; i++)
        in_order = !strcmp(m->jobs[i].name, names[i]);
    tap_ok(in_order, "names in product order, the first key slowest");

    const struct cv_job *j = cv_manifest_find_job(m, "a_bright_4");
    tap_ok(j && j->has_seed && j->seed == 4 && j->color.has_exposure && j->color.exposure == 1,
           "a_bright_4 holds its values");
    tap_ok(j && j->has_spp && j->spp == 8, "defaults apply to expanded jobs");
    tap_ok(j && j->at[CV_K_SEED].line == 8 && j->at[CV_K_SEED].col == 17 &&
               j->at[CV_K_COLOR_EXPOSURE].line == 7,
           "a value's place is where the matrix lists it (%u:%u)", j ? j->at[CV_K_SEED].line : 0,
           j ? j->at[CV_K_SEED].col : 0);
    tap_ok(j && !strcmp(tail(j->output), "o/bright/a_bright_4"), "output template: %s",
           j ? j->output : "-");
    tap_ok(j && !strcmp(j->matrix_of, "a") && j->n_axes == 2 &&
               j->axes[0].key == CV_K_COLOR_EXPOSURE && !strcmp(j->axes[0].label, "bright") &&
               j->axes[1].key == CV_K_SEED && !strcmp(j->axes[1].label, "4"),
           "the job as written and its labels by key");
    bool distinct = true;
    for (size_t i = 0; i < 6; i++)
        for (size_t k = 0; k < i; k++)
            distinct &= strcmp(m->jobs[i].settings_hash, m->jobs[k].settings_hash) != 0;
    tap_ok(distinct, "every expanded job has its own settings hash");

    const struct cv_job *b = cv_manifest_find_job(m, "b_1_0_off");
    tap_ok(b && b->camera.has_lookat && b->camera.eye[1] == 5 && b->camera.up[2] == 1,
           "a flat lookat list as a value");
    tap_ok(b && b->env.has_rotate && b->env.rotate[0] == 90 && b->env.rotate[2] == 1,
           "env.rotate as a value");
    tap_ok(b && b->lights.has_scale && b->lights.scale.n == 1 && b->lights.scale.v[0].light == 0 &&
               b->lights.scale.v[0].scale == 0,
           "lights.scale by label");
    const struct cv_job *c = cv_manifest_find_job(m, "c");
    tap_ok(c && !c->matrix_of && c->n_axes == 0 && c->seed == 9, "a job without a matrix as it was");

    /* a matrix value and the same value written in the job: one hash */
    cv_manifest_destroy(&m);
    m = load("version: 1\ndefaults: {scene: s.pbrt}\njobs:\n"
             "  - {name: x, output: x, matrix: {env.scale: [2]}}\n"
             "  - {name: y, output: y, env: {scale: 2}}\n",
             &err);
    tap_ok(m && m->n_jobs == 2 && !strcmp(m->jobs[0].settings_hash, m->jobs[1].settings_hash),
           "a value from the matrix hashes as the same value written in the job (%s)", err.msg);
    cv_manifest_destroy(&m);

    char *cmd = cv_xasprintf("rm -rf '%s'", dir);
    if (system(cmd) != 0)
        tap_diag("could not remove %s", dir);
    free(cmd);
    return tap_done();
}
