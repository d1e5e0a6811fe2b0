/* render.c: see render.h. The stages follow pbrt-v4's wavefront
 * integrator: generate camera rays; per iteration: reset the queues,
 * intersect (closest), escaped rays, surface hits (emission, NEE, BSDF
 * sampling; path shades diffuse hits and the others with two programs,
 * rlpath has its own shade stage and then its table update),
 * shadow rays; a path that ends starts its slot's next sample in the stage
 * that ends it (path regeneration, glsl/shared/trace.h); the film
 * accumulates in place. Queue counts stay on the GPU: the last work group
 * of the intersect and shade stages turns them into the next stages'
 * indirect dispatch arguments (glsl/trace/queue_args.glsl). The host reads
 * one count back per CV_CHUNK iterations, a chunk behind the GPU, only to
 * learn when the pass is over. */
#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/limits.h"
#include "base/log.h"
#include "base/mem.h"
#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/memory.h"
#include "gpu/program.h"
#include "gpu/storage.h"
#include "trace/filter_table.h"
#include "trace/render.h"
#include "trace/rlpath.h"
#include "trace/scene_upload.h"

/* Iterations queued between looks at whether the pass is over. Small, so
 * that a pass ends soon after its last path (every queued iteration after
 * that is a few empty dispatches); large enough that the look, a chunk
 * behind, never leaves the GPU idle. */
#define CV_CHUNK 4

enum stage {
    ST_GENERATE,
    ST_INTERSECT,
    ST_ESCAPED,
    ST_SHADE,
    ST_SHADE_B,
    ST_SHADOW,
    ST_RESOLVE,
    ST_COUNT
};

/* CAVALRY_STAGE_TIMES' row beyond the stages: rlpath's table rebuild. */
enum { PROF_RLPATH = ST_COUNT, PROF_COUNT };

/* CAVALRY_STAGE_TIMES also times the intersect stage of each iteration of a
 * pass by its index, with the rays it traced, up to this many iterations:
 * the traversal rate against the wave's size. */
#define PROF_ITERS 64

/* A pair of CAVALRY_STAGE_TIMES queries: the stage (or PROF_*) it times and
 * the pass's iteration it ran in (UINT8_MAX: past PROF_ITERS). */
struct prof_pair {
    uint8_t stage, iter;
};

struct cv_renderer {
    struct cv_gpu *gpu;
    const struct cv_scene_gpu *scene;  /* borrowed, or owned_scene */
    struct cv_scene_gpu *owned_scene;  /* cv_renderer_create's own upload */
    /* copies: the cache's entries move as it grows (ids stay valid) */
    struct cv_program prog[ST_COUNT];
    uint32_t n_pixels, crop_w, crop_h;
    uint32_t paths_per_pixel;      /* K of glsl/shared/trace.h */
    size_t n_paths;                /* path slots: n_pixels * paths_per_pixel */
    uint32_t max_depth;
    bool aovs;
    bool escaped_stage;            /* misses go through escaped.comp */
    uint32_t spp_done;
    uint64_t iterations;           /* over all passes, for the counters */
    CvPassParams pass;
    GLuint ubo, queues, rays, hits, shadow, film, resolved;
    GLuint alive[2];               /* rays-out count at the end of a chunk, by chunk parity */
    GLuint queues_copy;            /* cv_renderer_counters' read-back staging */
    GLuint *queries;               /* GL_TIMESTAMP pairs (pass start, end), not yet read */
    size_t n_queries, cap_queries;
    double gpu_ms;
    struct cv_rlpath *rl;          /* CV_RENDER_RLPATH, else NULL */
    /* CAVALRY_STAGE_TIMES: GPU time per stage, from timestamp pairs around
     * every dispatch (a diagnostic: the queries cost time themselves) */
    struct {
        bool on;
        GLuint *queries;           /* before, after pairs */
        struct prof_pair *pairs;
        size_t n, cap, cap_pairs;
        double ms[PROF_COUNT];
        GLuint counts;             /* rays in of the pass's iterations 0..PROF_ITERS-1 */
        double iter_ms[PROF_ITERS];
        uint64_t iter_rays[PROF_ITERS];
        uint32_t iter;             /* the iteration of the pairs marked now */
    } prof;
};

static const char *const stage_names[PROF_COUNT] = {
    "generate", "intersect", "escaped", "shade", "shade-b", "shadow", "resolve", "rlpath-rebuild",
};

static void prof_mark(struct cv_renderer *r, int stage)
{
    if (!r->prof.on)
        return;
    GLuint q;
    glGenQueries(1, &q);
    glQueryCounter(q, GL_TIMESTAMP);
    if (r->prof.n % 2 == 0) {  /* a pair begins: note its stage and iteration */
        size_t k = r->prof.n / 2;
        struct prof_pair pair = {(uint8_t)stage, (uint8_t)r->prof.iter};
        CV_PUSH(r->prof.pairs, k, r->prof.cap_pairs, pair);
    }
    CV_PUSH(r->prof.queries, r->prof.n, r->prof.cap, q);
}

/* Milliseconds between two GL_TIMESTAMP queries (waits for both). */
static double timestamps_ms(GLuint begin, GLuint end)
{
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(begin, GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(end, GL_QUERY_RESULT, &t1);
    return t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0;
}

static void prof_collect(struct cv_renderer *r)
{
    for (size_t i = 0; i + 1 < r->prof.n; i += 2) {
        int s = r->prof.pairs[i / 2].stage, it = r->prof.pairs[i / 2].iter;
        double ms = timestamps_ms(r->prof.queries[i], r->prof.queries[i + 1]);
        r->prof.ms[s] += ms;
        if (s == ST_INTERSECT && it < PROF_ITERS)
            r->prof.iter_ms[it] += ms;
    }
    if (r->prof.n)
        glDeleteQueries((GLsizei)r->prof.n, r->prof.queries);
    r->prof.n = 0;
}

static const char *const stage_files[ST_COUNT] = {
    "trace/generate.comp", "trace/intersect.comp", "trace/escaped.comp", "trace/shade.comp",
    "trace/shade.comp",    "trace/shadow.comp",    "trace/resolve.comp",
};

/* The film: the scene's, or the override with the scene's crop window. */
static void setup_camera(struct cv_renderer *r, const struct cv_scene *s,
                         const struct cv_render_params *p)
{
    const CvCamera *c = &s->camera;
    uint32_t w = p->width ? p->width : c->film.x, h = p->height ? p->height : c->film.y;
    uint32_t x0 = c->film.z, y0 = c->film.w, cw = c->crop.x, ch = c->crop.y;
    cv_vec4 screen = c->screen;
    if (w != c->film.x || h != c->film.y) {
        const float *cr = s->settings.crop;
        x0 = (uint32_t)ceil(w * (double)cr[0]);
        y0 = (uint32_t)ceil(h * (double)cr[2]);
        uint32_t x1 = (uint32_t)ceil(w * (double)cr[1]), y1 = (uint32_t)ceil(h * (double)cr[3]);
        cw = x1 > x0 ? x1 - x0 : 1;
        ch = y1 > y0 ? y1 - y0 : 1;
        double old_aspect = (double)c->film.x / c->film.y, aspect = (double)w / h;
        if (fabs(old_aspect - aspect) > 1e-6 * aspect) {
            /* pbrt's default screen window for the new aspect ratio */
            if (aspect > 1)
                screen = (cv_vec4){(float)-aspect, (float)aspect, -1, 1};
            else
                screen = (cv_vec4){-1, 1, (float)(-1 / aspect), (float)(1 / aspect)};
            cv_warn("film %ux%u changes the scene's aspect ratio: default screen window used", w, h);
        }
    }
    r->crop_w = cw;
    r->crop_h = ch;
    r->n_pixels = cw * ch;
    CvPassParams *u = &r->pass;
    u->frame = (cv_uvec4){r->n_pixels, cw, ch, 0};
    u->film = (cv_uvec4){w, h, x0, y0};
    for (int i = 0; i < 3; i++)
        u->cam_to_world[i] = c->to_world[i];
    u->screen = screen;
    u->lens = (cv_vec4){c->lens.x, c->lens.y, c->lens.z, c->crop.z == CV_CAMERA_ORTHOGRAPHIC ? 1.0f : 0.0f};
}

static void setup_filter(struct cv_renderer *r, const struct cv_render_settings *st)
{
    CvPassParams *u = &r->pass;
    float rx = st->filter_radius[0], ry = st->filter_radius[1];
    uint32_t type = 0;
    switch (st->filter) {
    case CV_FILTER_BOX:
        type = 0;
        if (rx <= 0) rx = 0.5f;
        if (ry <= 0) ry = 0.5f;
        break;
    case CV_FILTER_TRIANGLE:
        type = 1;
        if (rx <= 0) rx = 2;
        if (ry <= 0) ry = 2;
        break;
    case CV_FILTER_GAUSSIAN:
        type = 2;
        if (rx <= 0) rx = 1.5f;
        if (ry <= 0) ry = 1.5f;
        break;
    }
    u->misc.y = type;
    u->pixel_filter = (cv_vec4){rx, ry, st->filter_sigma, 0};
    float tx[CV_FILTER_TABLE + 4] = {0}, ty[CV_FILTER_TABLE + 4] = {0};
    if (type == 2) {
        cv_gaussian_filter_table(rx, st->filter_sigma, tx, CV_FILTER_TABLE);
        cv_gaussian_filter_table(ry, st->filter_sigma, ty, CV_FILTER_TABLE);
    }
    memcpy(u->filter_x, tx, sizeof(u->filter_x));
    memcpy(u->filter_y, ty, sizeof(u->filter_y));
}

static GLuint make(struct cv_gpu *gpu, size_t bytes, const char *label, bool *ok,
                   struct cv_error *err)
{
    if (!*ok)
        return 0;
    GLuint b = cv_gpu_storage_buffer(gpu, bytes, NULL, label, err);
    if (!b)
        *ok = false;
    return b;
}

/* Bytes a path slot takes: its rays (two halves), hits (two), shadow ray
 * and film entry. */
#define PATH_BYTES (2 * sizeof(CvRayItem) + 2 * sizeof(CvHitItem) + sizeof(CvShadowItem) + \
                    sizeof(CvFilmPixel))

/* Path slots per pixel (render.h: paths_per_pixel). */
static bool choose_paths_per_pixel(struct cv_gpu *gpu, const struct cv_render_params *p,
                                   uint32_t n_pixels, uint32_t *out, struct cv_error *err)
{
    /* o.w and d.w hold slots as floats (trace.h) */
    uint64_t max_paths = 1u << 24;
    if (p->paths_per_pixel) {
        if ((uint64_t)n_pixels * p->paths_per_pixel > max_paths)
            return cv_fail(err, "%u paths per pixel over %u pixels: more than 2^24 paths",
                           p->paths_per_pixel, n_pixels);
        *out = p->paths_per_pixel;
        return true;
    }
    /* Only for speed, so never into a probed storage size, nor into memory
     * that scenes or other jobs might want. */
    uint64_t cap = CV_WAVE_PATHS < max_paths ? CV_WAVE_PATHS : max_paths;
    uint64_t known = cv_gpu_storage_known(gpu);
    if (known && known / (2 * sizeof(CvRayItem)) < cap)
        cap = known / (2 * sizeof(CvRayItem));
    uint64_t total = 0, avail = 0;
    if (cv_gpu_memory(gpu, &total, &avail) && avail / 8 / PATH_BYTES < cap)
        cap = avail / 8 / PATH_BYTES;
    uint32_t k = CV_MAX_PATHS_PER_PIXEL;
    while (k > 1 && (uint64_t)n_pixels * k > cap)
        k--;
    *out = k;
    return true;
}

static bool check_params(const struct cv_scene *scene, const struct cv_render_params *p,
                         struct cv_error *err)
{
    if (p->integrator != CV_RENDER_PATH && p->integrator != CV_RENDER_RLPATH)
        return cv_fail(err, "unknown integrator %d", p->integrator);
    if (p->sampler != CV_SAMPLER_SOBOL && p->sampler != CV_SAMPLER_INDEPENDENT)
        return cv_fail(err, "unknown sampler %d", (int)p->sampler);
    if (scene->camera.film.x == 0 || scene->camera.film.y == 0)
        return cv_fail(err, "scene has no film resolution");
    return true;
}

bool cv_renderer_create(struct cv_gpu *gpu, const struct cv_scene *scene,
                        const struct cv_render_params *p, struct cv_renderer **out,
                        struct cv_error *err)
{
    /* bad parameters fail before the upload and BVH build */
    if (!check_params(scene, p, err))
        return false;
    struct cv_scene_gpu *gs = NULL;
    if (!cv_scene_gpu_create(gpu, scene, &gs, err)) {
        cv_error_prefix(err, "uploading the scene: ");
        return false;
    }
    if (!cv_renderer_create_shared(gpu, gs, scene, p, out, err)) {
        cv_scene_gpu_destroy(&gs);
        return false;
    }
    (*out)->owned_scene = gs;
    return true;
}

/* out = the nd defines plus `a` and `b` where not NULL, NULL-terminated;
 * out has room for nd + 3 entries. */
static void defines_plus(const char **out, const char *const *defines, int nd, const char *a,
                         const char *b)
{
    memcpy(out, defines, (size_t)nd * sizeof(*out));
    if (a)
        out[nd++] = a;
    if (b)
        out[nd++] = b;
    out[nd] = NULL;
}

bool cv_renderer_create_shared(struct cv_gpu *gpu, const struct cv_scene_gpu *gs,
                               const struct cv_scene *scene, const struct cv_render_params *p,
                               struct cv_renderer **out, struct cv_error *err)
{
    if (!check_params(scene, p, err))
        return false;

    struct cv_renderer *r = cv_xcalloc(1, sizeof(*r));
    r->gpu = gpu;
    r->aovs = p->aovs;
    const char *times = getenv("CAVALRY_STAGE_TIMES");
    r->prof.on = times && *times && strcmp(times, "0") != 0;
    r->max_depth = p->max_depth ? p->max_depth
                                : (scene->settings.max_depth ? scene->settings.max_depth : 5);
    setup_camera(r, scene, p);
    setup_filter(r, &scene->settings);
    if ((uint64_t)r->crop_w * r->crop_h > (1u << 24)) {
        uint32_t w = r->crop_w, h = r->crop_h;
        free(r);
        return cv_fail(err, "film of %ux%u pixels is too large", w, h);
    }
    if (!choose_paths_per_pixel(gpu, p, r->n_pixels, &r->paths_per_pixel, err)) {
        free(r);
        return false;
    }
    r->n_paths = (size_t)r->n_pixels * r->paths_per_pixel;
    r->pass.wave = (cv_uvec4){(uint32_t)r->n_paths, r->paths_per_pixel, 0, 0};
    r->pass.seed = (cv_uvec4){(uint32_t)p->seed, (uint32_t)(p->seed >> 32),
                              p->sampler == CV_SAMPLER_INDEPENDENT ? 1u : 0u, r->max_depth};
    /* misc.z: lights to sample at each vertex; 0 turns next-event
     * estimation off, and with it the MIS weights of emission hits */
    r->pass.misc = (cv_uvec4){0, r->pass.misc.y, p->no_nee ? 0 : scene->n_lights, 0};

    r->scene = gs;

    const char *defines[8];
    int nd = 0;
    if (r->scene->empty)
        defines[nd++] = "CV_EMPTY_SCENE";
    if (r->aovs)
        defines[nd++] = "CV_AOVS";
    if (r->scene->has_alpha)
        defines[nd++] = "CV_HAS_ALPHA";
    if (r->scene->basic_materials)
        defines[nd++] = "CV_BSDF_BASIC";
    /* Code for what the scene lacks stays out of the kernels: on an H100
     * (veach-bidir, 256 spp) the two shade stages took 1089 ms with the
     * texture and environment code and 265 ms without it (the texture
     * loops' arrays live in local memory; fewer registers). */
    if (!r->scene->has_env)
        defines[nd++] = "CV_NO_ENV";
    if (!r->scene->has_textures)
        defines[nd++] = "CV_NO_TEXTURES";
    defines[nd] = NULL;
    bool rl = p->integrator == CV_RENDER_RLPATH;
    /* Misses need an escaped stage for an environment light or for
     * rlpath's learning; otherwise the intersect stage starts their pixels'
     * next samples itself (intersect.comp). */
    r->escaped_stage = rl || r->scene->has_env;
    const char *escaped[9];
    defines_plus(escaped, defines, nd, rl ? "CV_RLPATH" : NULL, NULL);
    /* hits binned by material for the shade stages (intersect.comp) */
    const char *intersect[10];
    defines_plus(intersect, defines, nd, "CV_HIT_BINS",
                 r->escaped_stage ? "CV_ESCAPED_QUEUE" : NULL);
    /* path shades each bin with its own program (shade.comp); rlpath's one
     * shade program takes both bins in one dispatch */
    const char *shade_a[9], *shade_b[9];
    defines_plus(shade_a, defines, nd, "CV_SHADE_BIN=0", NULL);
    defines_plus(shade_b, defines, nd, "CV_SHADE_BIN=1", NULL);
    const char *const no_defines[1] = {NULL};
    for (int s = 0; s < ST_COUNT; s++) {
        /* rlpath's shade stage replaces these, with the same defines */
        if ((s == ST_SHADE || s == ST_SHADE_B) && rl)
            continue;
        if (s == ST_ESCAPED && !r->escaped_stage)
            continue;
        const char *const *d = defines;
        if (s == ST_GENERATE)
            d = no_defines;
        else if (s == ST_ESCAPED)
            d = escaped;
        else if (s == ST_INTERSECT)
            d = intersect;
        else if (s == ST_SHADE)
            d = shade_a;
        else if (s == ST_SHADE_B)
            d = shade_b;
        struct cv_program *pr = cv_program_get(gpu, stage_files[s], d, err);
        if (pr)
            r->prog[s] = *pr;
        if (!pr) {
            cv_renderer_destroy(&r);
            return false;
        }
    }

    if (rl) {
        CvRlParams rp;
        if (!cv_rlpath_layout(scene->bounds_min, scene->bounds_max, p->rl_grid, p->rl_directions,
                              p->rl_mix, &rp, err) ||
            !cv_rlpath_create(gpu, &rp, (uint32_t)r->n_paths, defines, p->rl_guide_indirect,
                              &r->rl, err)) {
            cv_renderer_destroy(&r);
            return false;
        }
        r->prog[ST_SHADE] = *cv_rlpath_shade_program(r->rl);
    }

    size_t n = r->n_paths;
    bool ok = true;
    r->ubo = make(gpu, sizeof(CvPassParams), "trace pass params", &ok, err);
    r->queues = make(gpu, sizeof(CvTraceQueues), "trace queues", &ok, err);
    r->rays = make(gpu, 2 * n * sizeof(CvRayItem), "trace rays", &ok, err);
    r->hits = make(gpu, 2 * n * sizeof(CvHitItem), "trace hits and escaped rays", &ok, err);
    r->shadow = make(gpu, n * sizeof(CvShadowItem), "trace shadow rays", &ok, err);
    r->film = make(gpu, n * sizeof(CvFilmPixel), "trace film", &ok, err);
    r->resolved = make(gpu, (size_t)r->n_pixels * 4 * sizeof(float), "trace resolved", &ok, err);
    if (r->prof.on)
        r->prof.counts = make(gpu, PROF_ITERS * sizeof(uint32_t), "trace stage-time ray counts",
                              &ok, err);
    r->alive[0] = make(gpu, sizeof(uint32_t), "trace pass end check 0", &ok, err);
    r->alive[1] = make(gpu, sizeof(uint32_t), "trace pass end check 1", &ok, err);
    r->queues_copy = make(gpu, sizeof(CvTraceQueues), "trace queues read-back", &ok, err);
    if (!ok) {
        cv_error_prefix(err, "allocating the film and queues for %ux%u, %u paths a pixel: ",
                        r->crop_w, r->crop_h, r->paths_per_pixel);
        cv_renderer_destroy(&r);
        return false;
    }
    *out = r;
    return true;
}

static void bind_all(struct cv_renderer *r)
{
    cv_scene_bind(r->scene);
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_PASS, r->ubo);
    cv_buffer_bind(r->queues, CV_BIND_QUEUES);
    cv_buffer_bind(r->rays, CV_BIND_RAYS);
    cv_buffer_bind(r->hits, CV_BIND_HITS);
    cv_buffer_bind(r->shadow, CV_BIND_SHADOW);
    cv_buffer_bind(r->film, CV_BIND_FILM);
    cv_buffer_bind(r->resolved, CV_BIND_RESOLVED);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, r->queues);
    if (r->rl)
        cv_rlpath_bind(r->rl);
}

static void stage_indirect(struct cv_renderer *r, int s, uint32_t slot)
{
    prof_mark(r, s);
    cv_program_dispatch_indirect(&r->prog[s], CV_ARGS_BYTES(slot), 0);
    prof_mark(r, s);
}

/* One iteration: a bounce of every path in flight; the slots whose paths
 * end start their next samples on the way. */
static void iterate(struct cv_renderer *r, uint32_t it)
{
    r->pass.misc.x = it;
    glNamedBufferSubData(r->ubo, (GLintptr)offsetof(CvPassParams, misc), sizeof(cv_uvec4),
                         &r->pass.misc);
    if (r->prof.on && it < PROF_ITERS) {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glCopyNamedBufferSubData(r->queues, r->prof.counts,
                                 (GLintptr)(sizeof(uint32_t) * CV_Q_RAYS_IN),
                                 (GLintptr)(sizeof(uint32_t) * it), sizeof(uint32_t));
    }
    r->prof.iter = it < PROF_ITERS ? it : UINT8_MAX;  /* no row: its rays are not counted */
    stage_indirect(r, ST_INTERSECT, CV_ARGS_RAYS);
    if (r->escaped_stage)
        stage_indirect(r, ST_ESCAPED, CV_ARGS_ESCAPED);
    if (r->rl) {
        stage_indirect(r, ST_SHADE, CV_ARGS_HITS_ALL);
    } else {
        /* The bins' programs share no data (each pixel's hit is in one
         * bin; queue slots come from atomics), so the first needs no
         * barrier before the second and the two may overlap. */
        prof_mark(r, ST_SHADE);
        glUseProgram(r->prog[ST_SHADE].id);
        glDispatchComputeIndirect(CV_ARGS_BYTES(CV_ARGS_HITS));
        prof_mark(r, ST_SHADE);
        stage_indirect(r, ST_SHADE_B, CV_ARGS_HITS_B);
    }
    if (r->rl) {
        prof_mark(r, PROF_RLPATH);
        cv_rlpath_update(r->rl);
        prof_mark(r, PROF_RLPATH);
    }
    stage_indirect(r, ST_SHADOW, CV_ARGS_SHADOW);
}

bool cv_renderer_pass(struct cv_renderer *r, uint32_t spp, struct cv_error *err)
{
    if (spp == 0)
        return true;
    if ((uint64_t)r->spp_done + spp > CV_MAX_SPP)
        return cv_fail(err, "more than %u samples per pixel", CV_MAX_SPP);
    /* timestamps rather than GL_TIME_ELAPSED: llvmpipe reports 0 elapsed
     * time for compute work */
    GLuint query[2] = {0, 0};
    glGenQueries(2, query);
    glQueryCounter(query[0], GL_TIMESTAMP);
    bind_all(r);
    /* the slots that have a sample in this pass (generate.comp) */
    uint32_t slots = r->paths_per_pixel, started = spp < slots ? spp : slots;
    r->pass.frame.w = r->spp_done;
    r->pass.misc.x = 0;
    r->pass.misc.w = r->spp_done + spp;
    r->pass.wave.z = r->n_pixels * started;
    glNamedBufferSubData(r->ubo, 0, sizeof(CvPassParams), &r->pass);
    prof_mark(r, ST_GENERATE);
    cv_program_dispatch_1d(&r->prog[ST_GENERATE], r->pass.wave.z);
    prof_mark(r, ST_GENERATE);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);

    /* Every path ends within max_depth + 1 iterations and a slot runs at
     * most ceil(spp / slots) of them, so this bounds the pass even if a
     * count were never read back as 0. */
    uint64_t limit = (uint64_t)((spp + slots - 1) / slots) * (r->max_depth + 1) + CV_CHUNK;
    uint64_t it = 0;
    uint32_t alive = 1;
    for (uint32_t chunk = 0; it < limit; chunk++) {
        for (int k = 0; k < CV_CHUNK && it < limit; k++, it++)
            iterate(r, (uint32_t)it);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        /* the rays the next iteration would trace (queue_args.glsl) */
        glCopyNamedBufferSubData(r->queues, r->alive[chunk & 1],
                                 (GLintptr)(sizeof(uint32_t) * CV_Q_RAYS_IN), 0,
                                 sizeof(uint32_t));
        /* the previous chunk's count: waits for that chunk while this one runs */
        if (chunk > 0) {
            if (!cv_buffer_read(r->alive[(chunk - 1) & 1], 0, sizeof(alive), &alive, err))
                return false;
            if (alive == 0)
                break;
        }
    }
    glQueryCounter(query[1], GL_TIMESTAMP);
    if (r->prof.on) {
        /* a diagnostic: this read-back waits for the pass */
        uint32_t counts[PROF_ITERS], n = it < PROF_ITERS ? (uint32_t)it : PROF_ITERS;
        if (!cv_buffer_read(r->prof.counts, 0, n * sizeof(uint32_t), counts, err))
            return false;
        for (uint32_t i = 0; i < n; i++)
            r->prof.iter_rays[i] += counts[i];
    }
    CV_PUSH(r->queries, r->n_queries, r->cap_queries, query[0]);
    CV_PUSH(r->queries, r->n_queries, r->cap_queries, query[1]);
    if (!cv_gl_check(err, "rendering a pass of %u spp", spp))
        return false;
    r->iterations += it;
    r->spp_done += spp;
    return true;
}

uint32_t cv_renderer_spp_done(const struct cv_renderer *r)
{
    return r->spp_done;
}

void cv_renderer_size(const struct cv_renderer *r, uint32_t *width, uint32_t *height)
{
    *width = r->crop_w;
    *height = r->crop_h;
}

bool cv_renderer_counters(struct cv_renderer *r, struct cv_render_counters *c,
                          struct cv_error *err)
{
    for (size_t i = 0; i + 1 < r->n_queries; i += 2)
        r->gpu_ms += timestamps_ms(r->queries[i], r->queries[i + 1]);
    glDeleteQueries((GLsizei)r->n_queries, r->queries);
    r->n_queries = 0;
    prof_collect(r);
    CvTraceQueues q;
    /* Staged, or the queues' atomics and indirect arguments would live in
     * host memory from the first pass on (gpu/buffer.h; H100, 1024 spp:
     * veach-bidir 4.64 -> 4.14 s, cornell-box 2.38 -> 1.99 s, the 4 M
     * scene's 64 spp 347 -> 306 ms). */
    if (!cv_buffer_read_staged(r->queues, 0, sizeof(q), r->queues_copy, &q, err))
        return false;
    uint64_t extend = (uint64_t)q.stats[CV_STAT_EXTEND].y << 32 | q.stats[CV_STAT_EXTEND].x;
    c->primary_rays = (uint64_t)r->n_pixels * r->spp_done;
    c->path_slots = r->n_paths;
    c->secondary_rays = extend > c->primary_rays ? extend - c->primary_rays : 0;
    c->iterations = r->iterations;
    c->shadow_rays = (uint64_t)q.stats[CV_STAT_SHADOW].y << 32 | q.stats[CV_STAT_SHADOW].x;
    c->gpu_ms = r->gpu_ms;
    c->intersect_first_ms = r->prof.on ? r->prof.iter_ms[0] : 0;
    c->intersect_ms = r->prof.on ? r->prof.ms[ST_INTERSECT] : 0;
    c->shadow_ms = r->prof.on ? r->prof.ms[ST_SHADOW] : 0;
    c->first_bounce_ms = r->prof.on ? r->prof.iter_ms[1] : 0;
    c->first_bounce_rays = r->prof.on ? r->prof.iter_rays[1] : 0;
    return cv_gl_check(err, "reading render counters");
}

GLuint cv_renderer_resolve(struct cv_renderer *r, struct cv_error *err)
{
    glNamedBufferSubData(r->ubo, 0, sizeof(CvPassParams), &r->pass);
    bind_all(r);
    cv_program_dispatch_1d(&r->prog[ST_RESOLVE], r->n_pixels);
    if (!cv_gl_check(err, "resolving the film"))
        return 0;
    return r->resolved;
}

bool cv_renderer_read(struct cv_renderer *r, float *rgba, float *albedo3, float *normal3,
                      float *depth1, struct cv_error *err)
{
    if ((albedo3 || normal3 || depth1) && !r->aovs)
        return cv_fail(err, "AOVs requested from a renderer made without them");
    size_t n = r->n_pixels, k = r->paths_per_pixel;
    if (rgba) {
        if (!cv_renderer_resolve(r, err))
            return false;
        if (!cv_buffer_read(r->resolved, 0, n * 4 * sizeof(float), rgba, err))
            return false;
    }
    if (!albedo3 && !normal3 && !depth1)
        return true;
    CvFilmPixel *aov = cv_xmalloc(n * k * sizeof(CvFilmPixel));
    bool ok = cv_buffer_read(r->film, 0, n * k * sizeof(CvFilmPixel), aov, err);
    /* a pixel's sums are those of its slots, in slot order (resolve.comp) */
    for (size_t i = 0; ok && i < n; i++) {
        for (size_t s = 1; s < k; s++) {
            const CvFilmPixel *f = &aov[s * n + i];
            aov[i].L.w += f->L.w;
            aov[i].albedo.x += f->albedo.x;
            aov[i].albedo.y += f->albedo.y;
            aov[i].albedo.z += f->albedo.z;
            aov[i].albedo.w += f->albedo.w;
            aov[i].normal.x += f->normal.x;
            aov[i].normal.y += f->normal.y;
            aov[i].normal.z += f->normal.z;
        }
        float w = aov[i].L.w, inv = w > 0 ? 1 / w : 0;
        if (albedo3) {
            albedo3[3 * i + 0] = aov[i].albedo.x * inv;
            albedo3[3 * i + 1] = aov[i].albedo.y * inv;
            albedo3[3 * i + 2] = aov[i].albedo.z * inv;
        }
        if (normal3) {
            float x = aov[i].normal.x, y = aov[i].normal.y, z = aov[i].normal.z;
            float len = sqrtf(x * x + y * y + z * z), s = len > 0 ? 1 / len : 0;
            normal3[3 * i + 0] = x * s;
            normal3[3 * i + 1] = y * s;
            normal3[3 * i + 2] = z * s;
        }
        if (depth1)
            depth1[i] = aov[i].albedo.w * inv;
    }
    free(aov);
    return ok;
}

void cv_renderer_destroy(struct cv_renderer **rp)
{
    if (!rp || !*rp)
        return;
    struct cv_renderer *r = *rp;
    if (r->prof.on) {
        prof_collect(r);
        double total = 0;
        for (int s = 0; s < PROF_COUNT; s++)
            total += r->prof.ms[s];
        for (int s = 0; s < PROF_COUNT; s++)
            if (r->prof.ms[s] > 0)
                cv_info("stage %-13s %10.1f ms %5.1f %%", stage_names[s], r->prof.ms[s],
                        total > 0 ? 100 * r->prof.ms[s] / total : 0);
        for (int i = 0; i < PROF_ITERS; i++)
            if (r->prof.iter_rays[i] > 0 && r->prof.iter_ms[i] > 0)
                cv_info("intersect iteration %2d %12" PRIu64 " rays %8.2f ms %6.3f G rays/s", i,
                        r->prof.iter_rays[i], r->prof.iter_ms[i],
                        (double)r->prof.iter_rays[i] / (r->prof.iter_ms[i] * 1e6));
        free(r->prof.queries);
        free(r->prof.pairs);
    }
    if (r->n_queries)
        glDeleteQueries((GLsizei)r->n_queries, r->queries);
    free(r->queries);
    GLuint *bufs[] = {&r->ubo,  &r->queues,   &r->rays,     &r->hits,    &r->shadow,
                      &r->film, &r->resolved, &r->alive[0], &r->alive[1], &r->queues_copy,
                      &r->prof.counts};
    for (size_t i = 0; i < CV_ARRAY_SIZE(bufs); i++)
        cv_buffer_destroy(bufs[i]);
    cv_scene_gpu_destroy(&r->owned_scene);
    cv_rlpath_destroy(&r->rl);
    free(r);
    *rp = NULL;
}
