/* rlpath_sd.c: rlpath's sdtree method (rlpath.method: sdtree), after
 * Müller, Gross and Novák, "Practical Path Guiding" (2017): training
 * iterations of 1 spp, then of 8, 16, 32, ... spp (the last runs to
 * rlpath.train), in which every guided bounce's record, once its path has
 * found its radiance, is splatted by the shaders into the statistics of
 * the tree being trained (glsl/trace/rlpath/sdtree.glsl); at the end of
 * each iteration the host reads back only those statistics (the tree's
 * size, through a copy; cost class: once per training iteration, a wait
 * for the GPU),
 * refines the tree from them (trace/sdtree.c: the next sampling quadtrees
 * learn from that iteration alone, as earlier, shorter iterations learned
 * from a worse guide) and uploads it. Passes after training sample the
 * last tree, frozen. The renderer owns one through cv_rlpath_sd_ops
 * (cv_integrator_for). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <epoxy/gl.h>

#include "base/limits.h"
#include "base/clock.h"
#include "base/log.h"
#include "base/mem.h"
#include "glsl/shared/sdtree.h"
#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "trace/integrator.h"
#include "trace/rlpath.h"
#include "trace/rlpath_sd.h"
#include "trace/sdtree.h"

/* The buffers the shaders see as images, in cv_rlpath_sd.images. */
enum { SD_VERTS, SD_COUNTS, SD_FLUX, SD_STATS, SD_IMAGES };

/* The splat of the records of every slot's path at the end of each
 * learning pass (one path a slot: learn_path_a_slot): requested with the
 * renderer's programs, first waited for there. */
static const char FLUSH[] = "trace/rlpath/sd_flush.comp";

struct cv_rlpath_sd {
    CvSdParams params;
    uint32_t train;        /* training ends at this spp; 0: never */
    uint32_t start, len;   /* the training iteration: first spp, length */
    uint32_t end;          /* ... and where it ends */
    struct cv_sdtree_opts opts;
    struct cv_sdtree *guide;   /* the host's copy of the table's trees */
    struct cv_gpu *gpu;
    uint32_t n_paths;
    GLuint ubo, verts, counts, tree;
    /* the statistics, and the copy the host reads them through (a buffer
     * the host reads is moved to its memory by the NVIDIA driver, and the
     * shaders' adds would then cross the bus: gpu/buffer.h) */
    GLuint stats, stats_copy;
    struct cv_buffer_image images[SD_IMAGES];   /* the shaders' views of them */
    GLuint tree_tex;       /* the tree as a buffer texture (CV_TEXUNIT_SD_TREE) */
    size_t tree_texels;    /* the tree buffer's capacity */
    size_t stat_words;     /* the statistics buffer's capacity */
    uint32_t builds;
    double table_s;        /* the last guide_upload's host table, wall seconds */
    double tree_s;         /* ... and its table's upload */
};

/* The second training iteration's samples per pixel; the first takes
 * one, as Müller et al.'s, and each later one twice the one before.
 * Iterations of 2 and 4 spp between cost more time than their trees saved:
 * each iteration makes the GPU wait for the host at its end, and each of
 * its passes runs to the end of its longest path, one path a slot
 * (bench/RESULTS.md, "sdtree's training iterations"). */
enum { SECOND_ITERATION_SPP = 8 };

/* Where the training iteration that starts at spp s with length len ends:
 * after len spp, or at the end of training if an iteration twice as long
 * would not fit after it (the last tree learns from the longest). After
 * the first iteration the next is SECOND_ITERATION_SPP, not twice its one
 * spp: a training of 3 to 8 spp runs as 1 and the rest, where a test
 * with that length would run it as one iteration. */
static uint32_t iteration_end(uint32_t train, uint32_t s, uint32_t len)
{
    if (train == 0)
        return s + len;
    if ((uint64_t)s + 3ull * len > train)
        return train > s ? train : s + 1;
    return s + len;
}

/* (Re)creates the tree buffer for at least n texels. */
static bool tree_reserve(struct cv_rlpath_sd *sd, size_t n, struct cv_error *err)
{
    if (n <= sd->tree_texels && sd->tree)
        return true;
    size_t cap = sd->tree_texels ? sd->tree_texels : 256;
    while (cap < n)
        cap *= 2;
    if (sd->tree_tex)
        glDeleteTextures(1, &sd->tree_tex);
    sd->tree_tex = 0;
    cv_buffer_destroy(&sd->tree);
    /* the caller writes the tree before any lookup: not zero-filled, which
     * would cost host time in proportion to its size (gpu/buffer.h) */
    sd->tree = cv_buffer_create_uninit(cap * 16, "rlpath sdtree", err);
    if (!sd->tree || !(sd->tree_tex = cv_buffer_texture(sd->tree, GL_RGBA32F, cap, err)))
        return false;
    sd->tree_texels = cap;
    glBindTextureUnit(CV_TEXUNIT_SD_TREE, sd->tree_tex);
    return true;
}

/* (Re)creates the statistics buffer and its two views for at least n
 * words. */
static bool stats_reserve(struct cv_rlpath_sd *sd, size_t n, struct cv_error *err)
{
    if (n <= sd->stat_words && sd->stats)
        return true;
    size_t cap = sd->stat_words ? sd->stat_words : 1024;
    while (cap < n)
        cap *= 2;
    cv_buffer_image_destroy(&sd->images[SD_FLUX]);
    cv_buffer_image_destroy(&sd->images[SD_STATS]);
    cv_buffer_destroy(&sd->stats);
    cv_buffer_destroy(&sd->stats_copy);
    /* guide_upload zeroes the words the tree uses, all the shaders touch */
    if (!(sd->stats = cv_buffer_create_uninit(cap * 4, "rlpath sdtree statistics", err)) ||
        !(sd->stats_copy = cv_buffer_create_uninit(cap * 4, "rlpath sdtree statistics read-back",
                                                   err)) ||
        !cv_buffer_image_create(&sd->images[SD_FLUX], sd->stats, cap, CV_IMAGE_SD_FLUX, GL_R32F,
                                GL_READ_WRITE, err) ||
        !cv_buffer_image_create(&sd->images[SD_STATS], sd->stats, cap, CV_IMAGE_SD_STATS,
                                GL_R32UI, GL_READ_WRITE, err))
        return false;
    sd->stat_words = cap;
    cv_buffer_image_bind(&sd->images[SD_FLUX]);
    cv_buffer_image_bind(&sd->images[SD_STATS]);
    return true;
}

/* Uploads the guide's table, with its grid block's place in the
 * parameters, and zeroes the statistics of its training tree (its words
 * alone: the buffer may be larger). */
static bool guide_upload(struct cv_rlpath_sd *sd, struct cv_error *err)
{
    float(*t)[4] = NULL;
    size_t n = 0, words = cv_sdtree_stat_words(sd->guide);
    double t0 = cv_seconds();
    cv_sdtree_table(sd->guide, &sd->opts, &t, &n);
    sd->table_s = cv_seconds() - t0;
    sd->params.grid.x = (uint32_t)(n - CV_SD_GRID_TEXELS);
    sd->params.grid.y = (uint32_t)t[0][3];   /* the top blocks' levels */
    glNamedBufferSubData(sd->ubo, 0, sizeof(sd->params), &sd->params);
    double t1 = cv_seconds();
    bool ok = tree_reserve(sd, n, err) && cv_buffer_upload(sd->tree, 0, n * 16, t, err);
    sd->tree_s = cv_seconds() - t1;
    ok = ok && stats_reserve(sd, words, err);
    free(t);
    if (ok)
        cv_buffer_zero_range(sd->stats, 0, words * 4);
    return ok;
}

bool cv_rlpath_sd_create(struct cv_gpu *gpu, const float bmin[3], const float bmax[3],
                         uint32_t n_paths, float mix, uint32_t train, struct cv_rlpath_sd **out,
                         struct cv_error *err)
{
    struct cv_rlpath_sd *sd = cv_xcalloc(1, sizeof(*sd));
    sd->gpu = gpu;
    sd->n_paths = n_paths;
    sd->opts = cv_sdtree_defaults;
    if (mix >= 0)   /* the job's share, in training too */
        sd->opts.mix = sd->opts.train_mix = mix;
    sd->train = cv_rlpath_train_spp(train);
    sd->start = 0;
    sd->len = 1;
    sd->end = iteration_end(sd->train, 0, 1);
    /* the empty guide: one leaf, whose classes do not guide */
    sd->guide = cv_sdtree_create(bmin, bmax);
    struct cv_sd_frame f = cv_sdtree_frame(sd->guide, &sd->opts);
    sd->params.learn = (cv_uvec4){1, f.filter, n_paths, 0};
    sd->params.cube = (cv_vec4){f.cube[0], f.cube[1], f.cube[2], f.cube[3]};
    /* the counts zeroed: no slot has a path waiting; the records are
     * written before they are read (shared/sdtree.h), so nothing touches
     * their storage here */
    size_t slots = n_paths ? n_paths : 1, rtexels = slots * CV_SD_RECORD_TEXELS;
    bool ok = (sd->ubo = cv_buffer_create(sizeof(sd->params), &sd->params, "rlpath sd params", err)) &&
              (sd->verts = cv_buffer_create_uninit(rtexels * 16, "rlpath sd path records", err)) &&
              (sd->counts = cv_buffer_create(slots * 4, NULL, "rlpath sd records waiting", err)) &&
              cv_buffer_image_create(&sd->images[SD_VERTS], sd->verts, rtexels, CV_IMAGE_SD_VERTS,
                                     GL_RGBA32F, GL_READ_WRITE, err) &&
              cv_buffer_image_create(&sd->images[SD_COUNTS], sd->counts, slots,
                                     CV_IMAGE_SD_COUNTS, GL_R32UI, GL_READ_WRITE, err) &&
              guide_upload(sd, err);
    if (!ok) {
        cv_error_prefix(err, "rlpath sdtree for %u path slots: ", n_paths);
        cv_rlpath_sd_destroy(&sd);
        return false;
    }
    *out = sd;
    return true;
}

void cv_rlpath_sd_bind(const struct cv_rlpath_sd *sd)
{
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_SDTREE, sd->ubo);
    for (size_t i = 0; i < CV_ARRAY_SIZE(sd->images); i++)
        cv_buffer_image_bind(&sd->images[i]);
    glBindTextureUnit(CV_TEXUNIT_SD_TREE, sd->tree_tex);
}

uint32_t cv_rlpath_sd_learn_until(const struct cv_rlpath_sd *sd)
{
    /* training over: the renderer no longer learns from train on */
    if (sd->train && sd->start >= sd->train)
        return sd->train;
    return sd->end;
}

void cv_rlpath_sd_set_block_log2(struct cv_rlpath_sd *sd, uint32_t levels)
{
    sd->opts.block_log2 = levels;
}

void cv_rlpath_sd_set_filter(struct cv_rlpath_sd *sd, uint32_t filter)
{
    sd->opts.filter = filter & (CV_SD_FILTER_SPATIAL | CV_SD_FILTER_DIRECTIONAL);
    sd->params.learn.y = sd->opts.filter;
    glNamedBufferSubData(sd->ubo, 0, sizeof(sd->params), &sd->params);
}

void cv_rlpath_sd_set_learning(struct cv_rlpath_sd *sd, bool learning)
{
    if ((sd->params.learn.x != 0) == learning)
        return;
    sd->params.learn.x = learning;
    glNamedBufferSubData(sd->ubo, 0, sizeof(sd->params), &sd->params);
}

static double cpu_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void log_guide(const struct cv_rlpath_sd *sd, const struct cv_sdtree_stats *st,
                      double host_s, float mix)
{
    cv_log(CV_LOG_DEBUG, "rlpath sdtree %u: %llu records, %u spatial leaves (%u of their "
           "classes guide, share %g), %u sampling and %u training quadtree nodes, depth %u, host "
           "refine %.3f ms; spatial leaf depth min %u mean %.2f max %u, by records %.2f",
           sd->builds, (unsigned long long)st->records, st->spatial_leaves, st->guiding, (double)mix,
           st->quad_nodes, st->train_nodes, st->max_quad_depth, 1e3 * host_s,
           st->min_spatial_depth, st->mean_spatial_depth, st->max_spatial_depth,
           st->record_spatial_depth);
}

bool cv_rlpath_sd_build(struct cv_rlpath_sd *sd, const struct cv_sd_record *rec, size_t n,
                        struct cv_error *err)
{
    struct cv_sdtree_stats st;
    double t0 = cpu_seconds();
    cv_sdtree_learn_records(sd->guide, rec, n, &sd->opts, &st);
    double dt = cpu_seconds() - t0;
    sd->builds++;
    log_guide(sd, &st, dt, sd->opts.mix);
    return guide_upload(sd, err);
}

bool cv_rlpath_sd_splat(struct cv_rlpath_sd *sd, const struct cv_sd_record *rec, size_t n,
                        bool cas, uint32_t **stats, size_t *words, struct cv_error *err)
{
    *stats = NULL;
    *words = cv_sdtree_stat_words(sd->guide);
    const char *defines[] = {"CV_SD_CAS", NULL};
    struct cv_program *fp = cv_program_get(sd->gpu, FLUSH, cas ? defines : NULL, err);
    if (!fp)
        return false;
    cv_buffer_zero(sd->stats);
    size_t per = (size_t)sd->n_paths * CV_SD_MAX_RECORDS;
    size_t rtexels = (size_t)sd->n_paths * CV_SD_RECORD_TEXELS;
    float(*v)[4] = cv_xcalloc(rtexels, sizeof(*v));
    uint32_t *count = cv_xcalloc(sd->n_paths, sizeof(*count));
    bool ok = true;
    cv_rlpath_sd_bind(sd);
    for (size_t at = 0; ok && at < n; at += per) {
        memset(v, 0, rtexels * sizeof(*v));
        memset(count, 0, sd->n_paths * sizeof(*count));
        for (size_t i = at; i < n && i < at + per; i++) {
            size_t slot = (i - at) / CV_SD_MAX_RECORDS, k = (i - at) % CV_SD_MAX_RECORDS;
            float *r0 = v[CV_SD_RECORD_TEXEL(slot, k, 0, (size_t)sd->n_paths)];
            float *r1 = v[CV_SD_RECORD_TEXEL(slot, k, 1, (size_t)sd->n_paths)];
            count[slot] = (uint32_t)(k + 1);
            memcpy(r0, rec[i].p, sizeof(rec[i].p));
            r0[3] = rec[i].pdf;
            r1[0] = rec[i].u;
            r1[1] = rec[i].v;
            r1[2] = rec[i].beta;
            r1[3] = rec[i].L;
        }
        ok = cv_buffer_upload(sd->verts, 0, rtexels * 16, v, err) &&
             cv_buffer_upload(sd->counts, 0, sd->n_paths * sizeof(*count), count, err);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        if (ok)
            cv_program_dispatch_1d(fp, sd->n_paths);
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    }
    free(v);
    free(count);
    *stats = cv_xcalloc(*words, sizeof(**stats));
    return ok && cv_buffer_read(sd->stats, 0, *words * sizeof(**stats), *stats, err) &&
           cv_gl_check(err, "rlpath sdtree splat of %zu records", n);
}

/* The records of each slot's path of the pass into the statistics (the
 * stages wrote them through images). */
static bool flush(struct cv_rlpath_sd *sd, struct cv_error *err)
{
    struct cv_program *fp = cv_program_get(sd->gpu, FLUSH, NULL, err);
    if (!fp)
        return false;
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    cv_program_dispatch_1d(fp, sd->n_paths);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    return true;
}

/* The end of a training iteration, its last pass flushed from t0 on: the
 * statistics back, the tree refined and uploaded with zeroed statistics. */
static bool iteration_done(struct cv_rlpath_sd *sd, double t0, struct cv_error *err)
{
    size_t words = cv_sdtree_stat_words(sd->guide);
    uint32_t *stats = cv_xmalloc(words * sizeof(*stats));
    if (!cv_buffer_read_staged(sd->stats, 0, words * sizeof(*stats), sd->stats_copy, stats,
                               err)) {
        free(stats);
        return false;
    }
    double t1 = cv_seconds(), c0 = cpu_seconds();
    struct cv_sdtree_stats st;
    /* a tree that another training iteration samples guides less */
    struct cv_sdtree_opts o = sd->opts;
    if (sd->train != 0 && sd->end < sd->train)
        o.mix = o.train_mix;
    cv_sdtree_refine(sd->guide, stats, &o, &st);
    double dt = cpu_seconds() - c0, t2 = cv_seconds();
    free(stats);
    sd->builds++;
    log_guide(sd, &st, dt, o.mix);
    bool ok = guide_upload(sd, err);
    double t3 = cv_seconds();
    /* where the GPU waits between iterations (wall time; the upload's is
     * its queueing) */
    cv_log(CV_LOG_DEBUG, "rlpath sdtree %u: iteration end %.3f ms: the pass's tail, the flush "
           "and the read-back of %zu words %.3f ms, refine %.3f ms, table %.3f ms, upload "
           "%.3f ms (the table's %.3f ms)", sd->builds, 1e3 * (t3 - t0), words, 1e3 * (t1 - t0),
           1e3 * (t2 - t1), 1e3 * sd->table_s, 1e3 * (t3 - t2 - sd->table_s), 1e3 * sd->tree_s);
    return ok;
}

bool cv_rlpath_sd_pass_done(struct cv_rlpath_sd *sd, uint32_t spp_done, struct cv_error *err)
{
    if (!sd->params.learn.x)
        return true;
    double t0 = cv_seconds();
    if (!flush(sd, err))
        return false;
    /* a pass inside an iteration: the next adds to the same statistics */
    if (spp_done < sd->end)
        return true;
    bool ok = iteration_done(sd, t0, err);
    sd->start = sd->end;
    sd->len = sd->len < SECOND_ITERATION_SPP / 2 ? SECOND_ITERATION_SPP : 2 * sd->len;
    sd->end = iteration_end(sd->train, sd->start, sd->len);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return ok && cv_gl_check(err, "rlpath sdtree after %u spp", spp_done);
}

void cv_rlpath_sd_destroy(struct cv_rlpath_sd **sdp)
{
    if (!sdp || !*sdp)
        return;
    struct cv_rlpath_sd *sd = *sdp;
    for (size_t i = 0; i < CV_ARRAY_SIZE(sd->images); i++)
        cv_buffer_image_destroy(&sd->images[i]);
    if (sd->tree_tex)
        glDeleteTextures(1, &sd->tree_tex);
    cv_buffer_destroy(&sd->ubo);
    cv_buffer_destroy(&sd->verts);
    cv_buffer_destroy(&sd->counts);
    cv_buffer_destroy(&sd->stats);
    cv_buffer_destroy(&sd->stats_copy);
    cv_buffer_destroy(&sd->tree);
    cv_sdtree_destroy(&sd->guide);
    free(sd);
    *sdp = NULL;
}

static bool ops_create(const struct cv_integrator_setup *s, void **state,
                       struct cv_program shade[CV_SHADE_PROGRAMS], struct cv_error *err)
{
    const struct cv_render_params *p = s->params;
    struct cv_rlpath_sd *sd = NULL;
    (void)shade;   /* the renderer's (cv_rlpath_sd_ops.file) */
    if (p->rl_mix > 1 || isnan(p->rl_mix))
        return cv_fail(err, "rlpath mix %g is not in [0, 1]", (double)p->rl_mix);
    if (!cv_rlpath_sd_create(s->gpu, s->scene->bounds_min, s->scene->bounds_max, s->n_paths,
                             p->rl_mix, p->rl_train, &sd, err))
        return false;
    if (p->rl_sd_filter_set)
        cv_rlpath_sd_set_filter(sd, p->rl_sd_filter);
    *state = sd;
    return true;
}

static void ops_bind(const void *state) { cv_rlpath_sd_bind(state); }

static void ops_prefetch(struct cv_gpu *gpu, const struct cv_render_params *p,
                         const char *const *defines)
{
    (void)p;
    (void)defines;
    cv_program_request(gpu, FLUSH, NULL);
}

static uint32_t ops_learn_spp(const void *state) { return cv_rlpath_sd_learn_until(state); }

static void ops_set_learning(void *state, bool learning)
{
    cv_rlpath_sd_set_learning(state, learning);
}

static bool ops_pass_done(void *state, uint32_t spp_done, struct cv_error *err)
{
    return cv_rlpath_sd_pass_done(state, spp_done, err);
}

/* the records of a path slot's path in flight and their count
 * (glsl/shared/sdtree.h) */
static uint64_t ops_slot_bytes(uint32_t max_depth)
{
    (void)max_depth;
    return (uint64_t)CV_SD_RECORD_TEXELS * 16 + 4;
}

static void ops_destroy(void **state)
{
    struct cv_rlpath_sd *sd = *state;
    cv_rlpath_sd_destroy(&sd);
    *state = NULL;
}

const struct cv_integrator_ops cv_rlpath_sd_ops = {
    .escaped_stage = true,   /* misses end paths that recorded */
    .escaped_define = "CV_RLPATH_SD",
    .shadow_define = "CV_RLPATH_SD",   /* shadow rays add to the records */
    .image_stages = true,               /* ... which the next stages read */
    .learn_path_a_slot = true,
    .n_shade = 3,
    .file = {"trace/rlpath/sd_shade.comp", "trace/rlpath/sd_shade.comp",
             "trace/rlpath/sd_shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1", "CV_SHADE_BIN=2"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B, CV_ARGS_HITS_C},
    .bins = {1u, 2u, 4u},
    .guides = true,
    .create = ops_create,
    .bind = ops_bind,
    .destroy = ops_destroy,
    .learn_spp = ops_learn_spp,
    .set_learning = ops_set_learning,
    .train_spp = cv_rlpath_job_train_spp,
    .frozen_programs = true,
    .pass_done = ops_pass_done,
    .slot_bytes = ops_slot_bytes,
    .prefetch = ops_prefetch,
};
