/* job_hash.c: see job_hash.h. Changing what goes into the text changes every
 * hash, which makes --resume redo all jobs once: bump the first line's
 * version when doing so on purpose. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/job_hash.h"

#define FNV1A64_PRIME UINT64_C(0x100000001b3)

uint64_t cv_fnv1a64(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= FNV1A64_PRIME;
    }
    return h;
}

struct text {
    char *s;
    size_t len, cap;
};

static void add(struct text *t, const char *fmt, ...) CV_PRINTF(2, 3);
static void add(struct text *t, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    t->s = cv_xgrow(t->s, &t->cap, t->len + (size_t)n + 1, 1);
    va_start(ap, fmt);
    vsnprintf(t->s + t->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    t->len += (size_t)n;
}

static void add_str(struct text *t, const char *key, const char *v)
{
    /* Length-prefixed so that a value holding a newline cannot mimic a key. */
    if (v)
        add(t, "%s=%zu:%s\n", key, strlen(v), v);
    else
        add(t, "%s=-\n", key);
}

static void add_u32(struct text *t, const char *key, bool has, uint32_t v)
{
    if (has)
        add(t, "%s=%u\n", key, (unsigned)v);
    else
        add(t, "%s=-\n", key);
}

static void add_float(struct text *t, const char *key, bool has, double v)
{
    if (has)
        add(t, "%s=%.9g\n", key, v);
    else
        add(t, "%s=-\n", key);
}

static void add_vec(struct text *t, const char *key, const float *v)
{
    add(t, "%s=%.9g,%.9g,%.9g\n", key, v[0], v[1], v[2]);
}

char *cv_job_settings_text(const struct cv_job *job, long long scene_size,
                           long long scene_mtime)
{
    static const char *const integrators[] = {"-", "path", "rlpath"};
    static const char *const compressions[] = {"none", "zip", "piz", "dwaa"};
    struct text t = {0};
    add(&t, "cavalry-job-settings 1\n");
    add_str(&t, "scene", job->scene_as_written);
    add(&t, "scene.size=%lld\nscene.mtime=%lld\n", scene_size, scene_mtime);
    if (job->has_resolution)
        add(&t, "resolution=%ux%u\n", (unsigned)job->width, (unsigned)job->height);
    else
        add(&t, "resolution=-\n");
    add_u32(&t, "spp", job->has_spp, job->spp);
    add_float(&t, "time_limit", job->has_time_limit, job->time_limit);
    add(&t, "integrator=%s\n", integrators[job->integrator]);
    add_u32(&t, "max_depth", job->has_max_depth, job->max_depth);
    add_u32(&t, "seed", job->has_seed, job->seed);
    add_str(&t, "color.config", job->color.config);
    add_str(&t, "color.display", job->color.display);
    add_str(&t, "color.view", job->color.view);
    add_str(&t, "color.look", job->color.look);
    add_float(&t, "color.exposure", job->color.has_exposure, job->color.exposure);
    add(&t, "aovs=%u\n", job->aovs);
    add(&t, "exr.half=%d\nexr.compression=%s\n", job->exr.half,
        compressions[job->exr.compression]);
    add(&t, "png.bits=%u\n", job->png.bits);
    add_float(&t, "camera.fov", job->camera.has_fov, job->camera.fov);
    if (job->camera.has_lookat) {
        add_vec(&t, "camera.eye", job->camera.eye);
        add_vec(&t, "camera.at", job->camera.at);
        add_vec(&t, "camera.up", job->camera.up);
    } else {
        add(&t, "camera.lookat=-\n");
    }
    add_u32(&t, "rlpath.grid", job->rlpath.has_grid, job->rlpath.grid);
    add_u32(&t, "rlpath.directions", job->rlpath.has_directions, job->rlpath.directions);
    add_float(&t, "rlpath.mix", job->rlpath.has_mix, job->rlpath.mix);
    /* only when set off its default, so that the hashes of jobs written
     * before the key existed stay the same (resume keeps their images) */
    if (job->rlpath.guide_indirect)
        add(&t, "rlpath.guide=indirect\n");
    return t.s;
}

char *cv_job_settings_hash(const struct cv_job *job, long long scene_size,
                           long long scene_mtime)
{
    char *text = cv_job_settings_text(job, scene_size, scene_mtime);
    uint64_t h = cv_fnv1a64(CV_FNV1A64_BASIS, text, strlen(text));
    free(text);
    return cv_xasprintf("%016llx", (unsigned long long)h);
}
