/* scene_helpers.h: shared bits of the scene tests: a private temp folder,
 * writing small files into it, loading scene text from it, and capturing
 * the log so that warnings can be checked. */
#ifndef CV_TESTS_SCENE_HELPERS_H
#define CV_TESTS_SCENE_HELPERS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"
#include "scene/scene.h"

static char th_dir[512];
static FILE *th_log;

static inline void th_init(void)
{
    snprintf(th_dir, sizeof(th_dir), "%s/cv-scene-test.XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(th_dir)) {
        perror("mkdtemp");
        exit(1);
    }
    th_log = tmpfile();
    cv_log_set_stream(th_log);
}

static inline void th_cleanup(void)
{
    char cmd[600];
    snprintf(cmd, sizeof(cmd), "rm -rf '%s'", th_dir);
    if (system(cmd) != 0)
        fprintf(stderr, "# could not remove %s\n", th_dir);
    cv_log_set_stream(NULL);
    if (th_log)
        fclose(th_log);
}

static inline char *th_path(const char *rel)
{
    static char buf[4][1024];
    static int k;
    k = (k + 1) & 3;
    snprintf(buf[k], sizeof(buf[k]), "%s/%s", th_dir, rel);
    return buf[k];
}

static inline void th_write(const char *rel, const void *data, size_t len)
{
    FILE *f = fopen(th_path(rel), "wb");
    if (!f || fwrite(data, 1, len, f) != len) {
        perror(rel);
        exit(1);
    }
    fclose(f);
}

static inline void th_write_str(const char *rel, const char *s) { th_write(rel, s, strlen(s)); }

/* A PFM of w x h RGB texels given top row first (PFM stores rows bottom
 * up). */
static inline void th_write_pfm(const char *rel, int w, int h, const float *rgb)
{
    char hdr[64];
    int n = snprintf(hdr, sizeof(hdr), "PF\n%d %d\n-1.0\n", w, h);
    size_t row = (size_t)w * 3 * 4;
    unsigned char *buf = malloc((size_t)n + row * (size_t)h);
    memcpy(buf, hdr, (size_t)n);
    for (int y = 0; y < h; y++)
        memcpy(buf + n + row * (size_t)(h - 1 - y), rgb + (size_t)y * w * 3, row);
    th_write(rel, buf, (size_t)n + row * (size_t)h);
    free(buf);
}

/* Log text written since the last call. */
static inline const char *th_log_text(void)
{
    static char *buf;
    static long last;
    fflush(th_log);
    long end = ftell(th_log);
    free(buf);
    buf = calloc(1, (size_t)(end - last) + 1);
    fseek(th_log, last, SEEK_SET);
    size_t n = fread(buf, 1, (size_t)(end - last), th_log);
    buf[n] = 0;
    fseek(th_log, end, SEEK_SET);
    last = end;
    return buf;
}

/* Loads text as th_dir/main.pbrt. */
static inline struct cv_scene *th_load(const char *text, bool strict, struct cv_error *err)
{
    struct cv_scene_load_params p = {.strict = strict};
    struct cv_scene *s = NULL;
    th_log_text();
    if (!cv_scene_load_string(th_path("main.pbrt"), text, strlen(text), &p, &s, err))
        return NULL;
    return s;
}

#endif
