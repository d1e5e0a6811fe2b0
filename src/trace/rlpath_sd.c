/* rlpath_sd.c: rlpath's sdtree method (rlpath.method: sdtree), after
 * Müller, Gross and Novák, "Practical Path Guiding" (2017): training
 * passes of doubling length (1, 2, 4, ... spp; the last runs to
 * rlpath.train), in which the shade and escaped stages record each guided
 * bounce with the radiance its path then found (glsl/trace/rlpath/
 * sdtree.glsl); after each training pass the records are read back (cost
 * class: once per training pass, a wait for the GPU), and at the end of
 * each training iteration the host builds the next guide from that
 * iteration's records alone (trace/sdtree.c: earlier, smaller iterations
 * learned from a worse guide) and uploads it. An iteration keeps at most
 * SD_MAX_RECORDS_PER_ITERATION records, a uniform share of its paths' (the
 * shaders hash each path against a threshold set here from the records the
 * passes before wanted): the build's cost grows with the records, not with
 * the image or the iteration's length. Passes after training
 * sample the last tree, frozen. The renderer owns one through
 * cv_rlpath_sd_ops (cv_integrator_for). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "base/limits.h"
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

/* Records a training iteration keeps at most (the record buffer's
 * capacity: two texels each; those past it in a pass are dropped): the
 * host build's time is linear in it (bench/sdtree_build). */
#define SD_MAX_RECORDS_PER_ITERATION (1u << 20)
#define SD_RECORDS_PER_SLOT 64u

/* The buffers the shaders see as images, in cv_rlpath_sd.images. */
enum { SD_VERTS, SD_OUT, SD_COUNT, SD_TREE, SD_IMAGES };

struct cv_rlpath_sd {
    CvSdParams params;
    uint32_t train;        /* training ends at this spp; 0: never */
    uint32_t start, len;   /* the training iteration: first spp, length */
    uint32_t end;          /* ... and where it ends */
    uint32_t cap;          /* records per pass */
    float bmin[3], bmax[3];
    struct cv_sdtree_opts opts;
    struct cv_program flush;   /* a copy (see render.c) */
    uint32_t n_paths;
    GLuint ubo, verts, out, count, tree;
    GLuint staging;        /* the records' way back, as large as out */
    struct cv_buffer_image images[SD_IMAGES];   /* the shaders' views of them */
    size_t tree_texels;    /* the tree buffer's capacity */
    struct cv_sd_record *recs;   /* the iteration's records so far */
    size_t n_recs;
    uint32_t builds;
    uint32_t last_spp;     /* spp done when the last training pass ended */
    double wanted_per_spp; /* records the paths of one spp offer (the last pass's) */
};

/* Where the training iteration that starts at spp s with length len ends:
 * after len spp, or at the end of training if the next, twice as long,
 * would not fit before it (the last tree learns from the longest). */
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
    struct cv_buffer_image *im = &sd->images[SD_TREE];
    cv_buffer_image_destroy(im);
    cv_buffer_destroy(&sd->tree);
    /* the caller writes the tree before any lookup */
    sd->tree = cv_buffer_create(cap * 16, NULL, "rlpath sdtree", err);
    if (!sd->tree ||
        !cv_buffer_image_create(im, sd->tree, cap, CV_IMAGE_SD_TREE, GL_RGBA32F, GL_READ_ONLY, err))
        return false;
    sd->tree_texels = cap;
    cv_buffer_image_bind(im);
    return true;
}

static bool tree_upload(struct cv_rlpath_sd *sd, const float (*t)[4], size_t n,
                        struct cv_error *err)
{
    return tree_reserve(sd, n, err) && cv_buffer_upload(sd->tree, 0, n * 16, t, err);
}

/* The next pass's share of paths that keep their records: the capacity
 * left in the iteration over what its remaining spp would offer, so that
 * the kept records spread over all of them; and that capacity. */
static void keep_for_next_pass(struct cv_rlpath_sd *sd, uint32_t spp_done)
{
    uint32_t left = sd->cap - (uint32_t)sd->n_recs;
    double offered = sd->wanted_per_spp * (sd->end > spp_done ? sd->end - spp_done : 1);
    /* a little below, so that a pass offering more than the last does not
     * overrun the capacity (whose last paths would then be dropped) */
    double share = offered > 0.95 * left ? 0.95 * left / offered : 1.0;
    sd->params.learn.y = left;
    sd->params.keep.x = share >= 1.0 ? CV_SD_KEEP_ALL : (uint32_t)(share * 0x1p32);
    sd->params.keep.y++;   /* the pass's hashes differ from the last's */
}

bool cv_rlpath_sd_create(struct cv_gpu *gpu, const float bmin[3], const float bmax[3],
                         uint32_t n_paths, uint32_t n_pixels, float mix, uint32_t train,
                         struct cv_rlpath_sd **out,
                         struct cv_error *err)
{
    struct cv_rlpath_sd *sd = cv_xcalloc(1, sizeof(*sd));
    struct cv_program *fp = cv_program_get(gpu, "trace/rlpath/sd_flush.comp", NULL, err);
    if (!fp) {
        free(sd);
        return false;
    }
    sd->flush = *fp;
    sd->n_paths = n_paths;
    memcpy(sd->bmin, bmin, sizeof(sd->bmin));
    memcpy(sd->bmax, bmax, sizeof(sd->bmax));
    sd->opts = cv_sdtree_defaults;
    if (mix >= 0)
        sd->opts.mix = mix;
    sd->train = cv_rlpath_train_spp(train);
    sd->start = 0;
    sd->len = 1;
    sd->end = iteration_end(sd->train, 0, 1);
    uint64_t cap = (uint64_t)(n_paths ? n_paths : 1) * SD_RECORDS_PER_SLOT;
    sd->cap = cap < SD_MAX_RECORDS_PER_ITERATION ? (uint32_t)cap : SD_MAX_RECORDS_PER_ITERATION;
    sd->params.learn = (cv_uvec4){1, sd->cap, n_paths, 0};
    /* what the first pass's paths offer is not known yet: at most every
     * pixel's path recording at every vertex it may (a smaller share than
     * needed, rather than the first paths flushed only) */
    sd->wanted_per_spp = (double)(n_pixels ? n_pixels : n_paths) * CV_SD_MAX_RECORDS;
    keep_for_next_pass(sd, 0);
    /* zero: no slot has a path waiting */
    size_t vbytes = (size_t)(n_paths ? n_paths : 1) * CV_SD_SLOT_TEXELS * 16;
    /* the empty table: one leaf, whose classes do not guide */
    float(*empty)[4] = NULL;
    size_t n_empty = 0;
    cv_sdtree_build(bmin, bmax, NULL, 0, &sd->opts, &empty, &n_empty, NULL);
    bool ok = (sd->ubo = cv_buffer_create(sizeof(sd->params), &sd->params, "rlpath sd params", err)) &&
              (sd->verts = cv_buffer_create(vbytes, NULL, "rlpath sd path records", err)) &&
              (sd->out = cv_buffer_create((size_t)sd->cap * 32, NULL, "rlpath sd records", err)) &&
              (sd->count = cv_buffer_create(16, NULL, "rlpath sd record count", err)) &&
              (sd->staging = cv_buffer_create_uninit((size_t)sd->cap * 32,
                                                     "rlpath sd records read-back", err)) &&
              cv_buffer_image_create(&sd->images[SD_VERTS], sd->verts, vbytes / 16,
                                     CV_IMAGE_SD_VERTS, GL_RGBA32F, GL_READ_WRITE, err) &&
              cv_buffer_image_create(&sd->images[SD_OUT], sd->out, (size_t)sd->cap * 2,
                                     CV_IMAGE_SD_OUT, GL_RGBA32F, GL_WRITE_ONLY, err) &&
              cv_buffer_image_create(&sd->images[SD_COUNT], sd->count, 4, CV_IMAGE_SD_COUNT,
                                     GL_R32UI, GL_READ_WRITE, err) &&
              tree_upload(sd, (const float(*)[4])empty, n_empty, err);
    free(empty);
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
}

uint32_t cv_rlpath_sd_learn_until(const struct cv_rlpath_sd *sd)
{
    /* training over: the renderer no longer learns from train on */
    if (sd->train && sd->start >= sd->train)
        return sd->train;
    return sd->end;
}

void cv_rlpath_sd_set_learning(struct cv_rlpath_sd *sd, bool learning)
{
    if ((sd->params.learn.x != 0) == learning)
        return;
    sd->params.learn.x = learning;
    glNamedBufferSubData(sd->ubo, 0, sizeof(sd->params), &sd->params);
}

bool cv_rlpath_sd_build(struct cv_rlpath_sd *sd, struct cv_sd_record *rec, size_t n,
                        struct cv_error *err)
{
    float(*t)[4] = NULL;
    size_t nt = 0;
    struct cv_sdtree_stats st;
    cv_sdtree_build(sd->bmin, sd->bmax, rec, n, &sd->opts, &t, &nt, &st);
    bool ok = tree_upload(sd, (const float(*)[4])t, nt, err);
    free(t);
    sd->builds++;
    cv_log(CV_LOG_DEBUG, "rlpath sdtree %u: %zu records, %u spatial leaves (%u of their "
           "classes guide), %u quadtree nodes, depth %u", sd->builds, n, st.spatial_leaves,
           st.guiding, st.quad_nodes, st.max_quad_depth);
    return ok;
}

bool cv_rlpath_sd_pass_done(struct cv_rlpath_sd *sd, uint32_t spp_done, struct cv_error *err)
{
    if (!sd->params.learn.x)
        return true;
    /* the records of each slot's last path, then the pass's (the stages
     * wrote them through images) */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    cv_program_dispatch_1d(&sd->flush, sd->n_paths);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    uint32_t wanted = 0;
    if (!cv_buffer_read(sd->count, 0, sizeof(wanted), &wanted, err))
        return false;
    uint32_t left = sd->cap - (uint32_t)sd->n_recs;
    uint32_t n = wanted < left ? wanted : left;
    if (n) {
        if (!sd->recs)   /* the iteration's capacity, once */
            sd->recs = cv_xcalloc(sd->cap, sizeof(*sd->recs));
        if (!cv_buffer_read_staged(sd->out, 0, (size_t)n * 32, sd->staging, sd->recs + sd->n_recs,
                                   err))
            return false;
        sd->n_recs += n;
    }
    const uint32_t zero = 0;
    glNamedBufferSubData(sd->count, 0, sizeof(zero), &zero);
    /* what the pass's paths offered: the counter holds the kept share's */
    uint32_t pass_spp = spp_done - sd->last_spp;
    double share = sd->params.keep.x == CV_SD_KEEP_ALL ? 1.0 : sd->params.keep.x * 0x1p-32;
    if (pass_spp > 0 && share > 0)
        sd->wanted_per_spp = wanted / share / pass_spp;
    sd->last_spp = spp_done;
    bool ok = true;
    if (spp_done >= sd->end) {
        /* the iteration is over: the next guide learns from its records alone */
        ok = cv_rlpath_sd_build(sd, sd->recs, sd->n_recs, err);
        sd->n_recs = 0;
        sd->start = sd->end;
        sd->len *= 2;
        sd->end = iteration_end(sd->train, sd->start, sd->len);
    }
    keep_for_next_pass(sd, spp_done);
    glNamedBufferSubData(sd->ubo, 0, sizeof(sd->params), &sd->params);
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
    cv_buffer_destroy(&sd->ubo);
    cv_buffer_destroy(&sd->verts);
    cv_buffer_destroy(&sd->out);
    cv_buffer_destroy(&sd->count);
    cv_buffer_destroy(&sd->staging);
    cv_buffer_destroy(&sd->tree);
    free(sd->recs);
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
                             s->n_pixels, p->rl_mix, p->rl_train, &sd, err))
        return false;
    *state = sd;
    return true;
}

static void ops_bind(const void *state) { cv_rlpath_sd_bind(state); }

static void ops_prefetch(struct cv_gpu *gpu, const struct cv_render_params *p,
                         const char *const *defines)
{
    (void)p;
    (void)defines;
    cv_program_request(gpu, "trace/rlpath/sd_flush.comp", NULL);
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

/* the records of a path slot's path in flight (glsl/shared/sdtree.h) */
static uint64_t ops_slot_bytes(uint32_t max_depth)
{
    (void)max_depth;
    return (uint64_t)CV_SD_SLOT_TEXELS * 16;
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
    .n_shade = 3,
    .file = {"trace/rlpath/sd_shade.comp", "trace/rlpath/sd_shade.comp",
             "trace/rlpath/sd_shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1", "CV_SHADE_BIN=2"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B, CV_ARGS_HITS_C},
    .bins = {1u, 2u, 4u},
    .create = ops_create,
    .bind = ops_bind,
    .destroy = ops_destroy,
    .learn_spp = ops_learn_spp,
    .set_learning = ops_set_learning,
    .pass_done = ops_pass_done,
    .slot_bytes = ops_slot_bytes,
    .prefetch = ops_prefetch,
};
