/* manifest_edge_test.c: the less common paths through the manifest reader,
 * each from a small manifest written to a temporary folder: empty files,
 * extra documents, bad merge keys, colliding outputs, value forms
 * (durations, lookat, quoted numbers) and the cap on reported errors. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

static char dir[256];

static char *in_dir(const char *name)
{
    return cv_xasprintf("%s/%s", dir, name);
}

static void write_file(const char *name, const char *text)
{
    char *path = in_dir(name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    free(path);
}

/* Loads text as m.yaml; returns the manifest (or NULL) and the message. */
static struct cv_manifest *load(const char *text, struct cv_error *err)
{
    write_file("m.yaml", text);
    char *path = in_dir("m.yaml");
    struct cv_manifest *m = NULL;
    cv_error_clear(err);
    cv_manifest_load(path, &m, err);
    free(path);
    return m;
}

/* text must fail with a message holding want after "m.yaml:". */
static void fails(const char *what, const char *text, const char *want)
{
    struct cv_error err;
    struct cv_manifest *m = load(text, &err);
    bool ok = !m && strstr(err.msg, want) != NULL;
    if (!tap_ok(ok, "%s", what))
        tap_diag("got: %s\n# want: %s", err.msg, want);
    cv_manifest_destroy(&m);
}

#define HEAD "version: 1\njobs:\n"

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof(dir), "%s/cv-edge-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        tap_ok(false, "mkdtemp %s", dir);
        return tap_done();
    }
    write_file("s.pbrt", "WorldBegin\n");
    write_file("ocio.config", "ocio_profile_version: 2\n");

    struct cv_error err;
    struct cv_manifest *m = NULL;
    tap_ok(!cv_manifest_load("/nonexistent/m.yaml", &m, &err) && !m &&
               strstr(err.msg, "/nonexistent/m.yaml"),
           "a missing manifest names its path: %s", err.msg);

    fails("empty file", "", "m.yaml:1:1: the manifest is empty");
    fails("comment-only file", "# nothing\n", "m.yaml:1:1: the manifest is empty");
    fails("two documents", HEAD "  - {name: a, scene: s.pbrt}\n---\nversion: 1\n",
          "m.yaml:5:1: a manifest holds one YAML document; found a second one");
    fails("a list at the top", "- 1\n", "m.yaml:1:1: manifest: expected a mapping");
    fails("unsupported version", "version: 2\njobs:\n  - {name: a, scene: s.pbrt}\n",
          "m.yaml:1:10: unsupported manifest version 2; this cavalry reads version 1");
    fails("unknown top-level key", HEAD "  - {name: a, scene: s.pbrt}\ndefault: {spp: 2}\n",
          "m.yaml:4:1: unknown key \"default\" in the manifest; valid keys: version, defaults, "
          "jobs, x-* (did you mean \"defaults\"?)");
    fails("missing jobs", "version: 1\n", "m.yaml:1:1: missing required key \"jobs\"");
    fails("empty job list", "version: 1\njobs: []\n", "m.yaml:2:7: jobs: the list is empty");
    fails("a job that is not a mapping", HEAD "  - hero\n",
          "m.yaml:3:5: job: expected a mapping, got a plain scalar");
    fails("a job without scene", HEAD "  - name: a\n",
          "m.yaml:3:5: job \"a\" (line 3): missing required key \"scene\"");
    fails("duplicate key in a job", HEAD "  - name: a\n    scene: s.pbrt\n    name: b\n",
          "m.yaml:5:5: duplicate key \"name\" (first given at line 3)");
    fails("merge of a scalar", HEAD "  - name: a\n    scene: s.pbrt\n    <<: 3\n",
          "m.yaml:5:9: merge key \"<<\": expected a mapping or a sequence of mappings, got "
          "a plain scalar");
    fails("a mapping that merges itself",
          "version: 1\nx-a: &a {spp: 2, <<: *a}\njobs:\n  - {name: a, scene: s.pbrt, <<: *a}\n",
          "m.yaml:2:6: merge key \"<<\": this mapping merges itself");
    /* Thirty anchors each merging the previous one twice: 2^30 pairs if
     * expanded naively. It must be refused, and quickly. */
    char *bomb = cv_xstrdup("version: 1\nx-0: &a0 {spp: 2}\n");
    for (int i = 1; i < 30; i++) {
        char *next = cv_xasprintf("%sx-%d: &a%d {<<: [*a%d, *a%d]}\n", bomb, i, i, i - 1, i - 1);
        free(bomb);
        bomb = next;
    }
    char *bomb_jobs = cv_xasprintf("%sjobs:\n  - {name: a, scene: s.pbrt, <<: *a29}\n", bomb);
    fails("merge keys that expand exponentially", bomb_jobs,
          "merge keys nested too deeply or expanding too much");
    free(bomb);
    free(bomb_jobs);
    fails("name in defaults", "version: 1\ndefaults: {name: x}\njobs:\n  - {name: a, scene: s.pbrt}\n",
          "m.yaml:2:12: \"name\" cannot be given in defaults");
    fails("colliding outputs",
          "version: 1\ndefaults: {scene: s.pbrt, output: same}\njobs:\n  - name: a\n  - name: b\n",
          "m.yaml:2:35: job \"b\": output \"");
    fails("unknown placeholder in output", HEAD "  - {name: a, scene: s.pbrt, output: \"o/{nmae}\"}\n",
          "only {name} and {KEY} of a key of the job's matrix may be written in braces");
    fails("output naming a folder", HEAD "  - {name: a, scene: s.pbrt, output: out/}\n",
          "output: \"out/\" names a folder");
    fails("quoted number", HEAD "  - {name: a, scene: s.pbrt, spp: \"64\"}\n",
          "m.yaml:3:35: spp: expected an integer from 1 to 16777216, got \"64\"");
    fails("null value", HEAD "  - name: a\n    scene: s.pbrt\n    spp:\n",
          "spp: expected an integer from 1 to 16777216, got null");
    fails("spp past the renderer's limit", HEAD "  - {name: a, scene: s.pbrt, spp: 16777217}\n",
          "m.yaml:3:35: spp: expected an integer from 1 to 16777216, got \"16777217\"");
    fails("rlpath grid past the table's limit",
          HEAD "  - {name: a, scene: s.pbrt, rlpath: {grid: 257}}\n",
          "m.yaml:3:45: rlpath.grid: expected an integer from 1 to 256, got \"257\"");
    fails("rlpath directions past the table's limit",
          HEAD "  - {name: a, scene: s.pbrt, rlpath: {directions: 1025}}\n",
          "m.yaml:3:51: rlpath.directions: expected an integer from 1 to 1024, got \"1025\"");
    fails("rlpath train past the spp limit",
          HEAD "  - {name: a, scene: s.pbrt, rlpath: {train: 16777217}}\n",
          "m.yaml:3:46: rlpath.train: expected an integer from 0 to 16777216, got \"16777217\"");
    fails("negative rlpath train", HEAD "  - {name: a, scene: s.pbrt, rlpath: {train: -1}}\n",
          "rlpath.train: expected an integer from 0 to 16777216, got \"-1\"");
    fails("duration without a known unit", HEAD "  - {name: a, scene: s.pbrt, time_limit: 5min}\n",
          "time_limit: expected a duration > 0");
    fails("zero duration", HEAD "  - {name: a, scene: s.pbrt, time_limit: 0}\n",
          "time_limit: expected a duration > 0");
    fails("unknown format", HEAD "  - {name: a, scene: s.pbrt, formats: [exr, tiff]}\n",
          "m.yaml:3:45: formats: expected one of exr, png, got \"tiff\"");
    fails("no formats", HEAD "  - {name: a, scene: s.pbrt, formats: []}\n",
          "formats: expected at least one entry");
    fails("png bits 12", HEAD "  - {name: a, scene: s.pbrt, png: {bits: 12}}\n",
          "png.bits: expected 8 or 16");
    fails("missing colour config", HEAD "  - {name: a, scene: s.pbrt, color: {config: no.ocio}}\n",
          "m.yaml:3:46: job \"a\" (line 3): color config \"no.ocio\" not found");
    fails("unknown key in color", HEAD "  - {name: a, scene: s.pbrt, color: {veiw: Raw}}\n",
          "unknown key \"veiw\" in color; valid keys: config, display, view, look, exposure "
          "(did you mean \"view\"?)");
    fails("lookat with eye == target",
          HEAD "  - {name: a, scene: s.pbrt, camera: {lookat: [1,1,1, 1,1,1, 0,1,0]}}\n",
          "camera.lookat: eye and target are the same point");
    fails("fov 180", HEAD "  - {name: a, scene: s.pbrt, camera: {fov: 180}}\n",
          "camera.fov: expected degrees between 0 and 180");
    fails("a duration past the end of time",
          HEAD "  - {name: a, scene: s.pbrt, time_limit: 1e306h}\n",
          "time_limit: expected a duration > 0");
    tap_ok(!strcmp(cv_integrator_name(CV_INTEGRATOR_RLPATH), "rlpath") &&
               !cv_integrator_name(CV_INTEGRATOR_COUNT) &&
               !strcmp(cv_exr_compression_name(CV_EXR_DWAA), "dwaa") &&
               !strcmp(cv_format_ext(CV_FORMAT_PNG), "png") && !cv_format_ext(3) &&
               !strcmp(cv_aov_name(CV_AOV_DEPTH), "depth"),
           "names of settings");
    fails("nan is no number", HEAD "  - {name: a, scene: s.pbrt, color: {exposure: .nan}}\n",
          "color.exposure: expected a number from -64 to 64, got \".nan\"");

    m = load("version: 1\n"
             "x-t: &t {spp: 4, time_limit: 2h}\n"
             "jobs:\n"
             "  - {name: a, scene: s.pbrt, <<: *t}\n"
             "  - {name: b, scene: s.pbrt, time_limit: 30s, formats: png}\n"
             "  - name: c\n"
             "    scene: s.pbrt\n"
             "    color: {config: ocio.config, exposure: -1.5}\n"
             "    camera: {lookat: [0, 0, 5, 0, 0, 0, 0, 1, 0]}\n"
             "  - name: d\n"
             "    scene: s.pbrt\n"
             "    color: {config: \"ocio://default\"}\n"
             "    exr: {half: yes, compression: dwaa}\n",
             &err);
    if (tap_ok(m && m->n_jobs == 4, "x-* keys hold anchors; four jobs load")) {
        tap_ok(m->jobs[0].spp == 4 && m->jobs[0].time_limit == 7200.0, "2h is 7200 s");
        tap_ok(m->jobs[1].time_limit == 30.0 && m->jobs[1].formats == CV_FORMAT_PNG,
               "30s, and a lone format name");
        char *cfg = in_dir("ocio.config");
        tap_ok(!strcmp(m->jobs[2].color.config, cfg) && m->jobs[2].color.exposure == -1.5f,
               "colour config resolved next to the manifest");
        free(cfg);
        tap_ok(m->jobs[2].camera.has_lookat && m->jobs[2].camera.eye[2] == 5.0f &&
                   m->jobs[2].camera.up[1] == 1.0f,
               "flat lookat");
        tap_ok(!strcmp(m->jobs[3].color.config, "ocio://default"), "ocio:// URI kept as written");
        tap_ok(m->jobs[3].exr.half && m->jobs[3].exr.compression == CV_EXR_DWAA,
               "yes is true; dwaa");
        char *out = in_dir("d");
        tap_ok(!strcmp(m->jobs[3].output, out), "default output is {name} next to the manifest");
        free(out);
        char *bare = cv_job_output_path(&m->jobs[3], NULL);
        tap_ok(!strcmp(bare, m->jobs[3].output), "output path without extension");
        free(bare);
    } else {
        tap_diag("%s", err.msg);
    }
    cv_manifest_destroy(&m);

    /* So many errors that they cannot all fit: the message says how many
     * were left out instead of cutting a line in half. */
    char *big = cv_xstrdup(HEAD);
    for (int i = 0; i < 200; i++) {
        char *next = cv_xasprintf("%s  - {name: j%d, scene: s.pbrt, spp: 0}\n", big, i);
        free(big);
        big = next;
    }
    m = load(big, &err);
    const char *more = strstr(err.msg, "... and ");
    tap_ok(!m && more && strstr(more, " more errors") && strlen(err.msg) < CV_ERROR_MAX,
           "too many errors end with a count of the rest");
    free(big);

    /* A manifest in the working folder gives paths as written, without "./". */
    if (chdir(dir) == 0) {
        struct cv_manifest *local = NULL;
        write_file("m.yaml", HEAD "  - {name: a, scene: s.pbrt}\n");
        bool loaded = cv_manifest_load("m.yaml", &local, &err);
        tap_ok(loaded && !strcmp(local->jobs[0].scene, "s.pbrt") &&
                   !strcmp(local->jobs[0].output, "a"),
               "relative manifest: paths as written, without \"./\"");
        if (!loaded)
            tap_diag("%s", err.msg);
        cv_manifest_destroy(&local);
    }

    const char *files[] = {"m.yaml", "s.pbrt", "ocio.config"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(files); i++) {
        char *p = in_dir(files[i]);
        unlink(p);
        free(p);
    }
    rmdir(dir);
    return tap_done();
}
