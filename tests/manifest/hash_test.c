/* hash_test.c: the settings hash is FNV-1a 64 as published, is stable from
 * one load to the next, changes when a render setting (spp, exposure) or the
 * scene file changes, and ignores what does not change pixels (name, output,
 * formats). Manifests are written to a temporary folder. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/mem.h"
#include "manifest/job_hash.h"
#include "manifest/manifest.h"
#include "tests/tap.h"

static char dir[256];

static void write_file(const char *name, const char *text)
{
    char *path = cv_xasprintf("%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    free(path);
}

/* Hash of the only job of a manifest body (after "version: 1"); NULL if the
 * manifest does not load. */
static char *hash_of(const char *jobs)
{
    write_file("m.yaml", jobs);
    char *path = cv_xasprintf("%s/m.yaml", dir);
    struct cv_manifest *m = NULL;
    struct cv_error err = {0};
    char *h = NULL;
    if (cv_manifest_load(path, &m, &err))
        h = cv_xstrdup(m->jobs[0].settings_hash);
    else
        tap_diag("%s", err.msg);
    cv_manifest_destroy(&m);
    free(path);
    return h;
}

static bool same(const char *a, const char *b)
{
    return a && b && !strcmp(a, b);
}

static bool differ(const char *a, const char *b)
{
    return a && b && strcmp(a, b) != 0;
}

#define BASE "version: 1\njobs:\n  - scene: s.pbrt\n"

int main(void)
{
    TAP_EQ_INT(cv_fnv1a64(CV_FNV1A64_BASIS, "", 0), 0xcbf29ce484222325ull, "FNV-1a 64 of \"\"");
    TAP_EQ_INT(cv_fnv1a64(CV_FNV1A64_BASIS, "a", 1), 0xaf63dc4c8601ec8cull, "FNV-1a 64 of \"a\"");
    TAP_EQ_INT(cv_fnv1a64(CV_FNV1A64_BASIS, "foobar", 6), 0x85944171f73967e8ull,
               "FNV-1a 64 of \"foobar\"");

    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof(dir), "%s/cv-hash-XXXXXX", tmp && tmp[0] ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        tap_ok(false, "mkdtemp %s", dir);
        return tap_done();
    }
    write_file("s.pbrt", "WorldBegin\n");

    char *h1 = hash_of(BASE "    name: a\n    spp: 16\n    color: {exposure: 1}\n");
    char *h2 = hash_of(BASE "    name: a\n    spp: 16\n    color: {exposure: 1}\n");
    tap_ok(h1 && strlen(h1) == 16 && strspn(h1, "0123456789abcdef") == 16,
           "hash is 16 hex digits: %s", h1 ? h1 : "(none)");
    tap_ok(same(h1, h2), "same manifest, same hash");
    char *spp = hash_of(BASE "    name: a\n    spp: 17\n    color: {exposure: 1}\n");
    tap_ok(differ(h1, spp), "spp 16 -> 17 changes the hash");
    char *exposure = hash_of(BASE "    name: a\n    spp: 16\n    color: {exposure: 2}\n");
    tap_ok(differ(h1, exposure), "exposure changes the hash");
    char *unset = hash_of(BASE "    name: a\n    color: {exposure: 1}\n");
    tap_ok(differ(h1, unset), "spp unset differs from spp 16");
    char *renamed = hash_of(BASE "    name: b\n    spp: 16\n    color: {exposure: 1}\n"
                                 "    output: elsewhere/{name}\n    formats: [png]\n");
    tap_ok(same(h1, renamed), "name, output and formats do not change the hash");
    char *via_defaults = hash_of("version: 1\ndefaults: {spp: 16, color: {exposure: 1}}\n"
                                 "jobs:\n  - scene: s.pbrt\n    name: a\n");
    tap_ok(same(h1, via_defaults), "the same settings through defaults hash the same");

    write_file("s.pbrt", "WorldBegin\nShape \"sphere\"\n");
    char *scene = hash_of(BASE "    name: a\n    spp: 16\n    color: {exposure: 1}\n");
    tap_ok(differ(h1, scene), "a changed scene file changes the hash");

    struct cv_job job = {0};
    char *text = cv_job_settings_text(&job, 10, 20);
    tap_ok(strstr(text, "spp=-\n") && strstr(text, "scene.size=10\n") &&
               strstr(text, "scene.mtime=20\n"),
           "canonical text marks unset values and holds the scene's size and mtime");
    free(text);

    free(h1), free(h2), free(spp), free(exposure), free(unset), free(renamed);
    free(via_defaults), free(scene);
    char *p = cv_xasprintf("%s/m.yaml", dir);
    unlink(p);
    free(p);
    p = cv_xasprintf("%s/s.pbrt", dir);
    unlink(p);
    free(p);
    rmdir(dir);
    return tap_done();
}
