/* rlpath.c: see rlpath.h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <epoxy/gl.h>

#include "base/limits.h"
#include "base/mem.h"
#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/storage.h"
#include "trace/integrator.h"
#include "trace/rlpath.h"

_Static_assert(CV_RL_MAX_DIRECTIONS == CV_RL_MAX_BINS,
               "the manifest's direction limit is the table's bin limit");

struct cv_rlpath {
    CvRlParams params;
    uint32_t n_paths;
    uint32_t train;                     /* learns until this spp; 0: in every pass */
    struct cv_program rebuild;          /* a copy (see render.c) */
    GLuint ubo, table, guide, path;
    /* the shaders' views: the table as r32ui and as r32f, guide, path */
    struct cv_buffer_image images[4];
    GLuint guide_tex;   /* the guide as the shade stages read it (CV_TEXUNIT_RL_GUIDE) */
};

bool cv_rlpath_layout(const float bmin[3], const float bmax[3], uint32_t grid,
                      uint32_t directions, float mix, CvRlParams *out, struct cv_error *err)
{
    if (grid == 0)
        grid = CV_RL_DEFAULT_GRID;
    if (directions == 0)
        directions = CV_RL_DEFAULT_DIRECTIONS;
    if (mix < 0)
        mix = CV_RL_DEFAULT_MIX;
    if (!(mix <= 1))
        return cv_fail(err, "rlpath mix %g is not in [0, 1]", (double)mix);
    if (grid > CV_RL_MAX_GRID)
        return cv_fail(err, "rlpath grid %u is above %u cells per axis", grid, CV_RL_MAX_GRID);
    if (directions > CV_RL_MAX_BINS)
        return cv_fail(err, "rlpath directions %u is above %u", directions, CV_RL_MAX_BINS);
    uint32_t nz = (uint32_t)lround(sqrt(directions / 2.0));
    if (nz < 1)
        nz = 1;
    uint32_t np = (uint32_t)lround((double)directions / nz);
    if (np < 1)
        np = 1;
    if (nz * np > CV_RL_MAX_BINS)
        np = CV_RL_MAX_BINS / nz;

    double lo[3], ext[3], longest = 0;
    for (int a = 0; a < 3; a++) {
        double l = bmin[a], h = bmax[a];
        if (!isfinite(l) || !isfinite(h) || h < l)
            l = h = 0;                 /* empty scene: one cell does */
        ext[a] = h - l;
        lo[a] = l;
        if (ext[a] > longest)
            longest = ext[a];
    }
    if (longest <= 0)
        longest = 1;
    /* pad so that points on the bounds fall inside */
    double pad = 1e-3 * longest;
    uint32_t dims[3];
    float scale[3];
    for (int a = 0; a < 3; a++) {
        double e = ext[a] + 2 * pad;
        lo[a] -= pad;
        dims[a] = (uint32_t)ceil(grid * ext[a] / longest - 1e-9);
        if (dims[a] < 1)
            dims[a] = 1;
        if (dims[a] > grid)
            dims[a] = grid;
        scale[a] = (float)(dims[a] / e);
    }
    memset(out, 0, sizeof(*out));
    out->grid_min = (cv_vec4){(float)lo[0], (float)lo[1], (float)lo[2], mix};
    out->grid_scale = (cv_vec4){scale[0], scale[1], scale[2], CV_RL_FLOOR};
    out->dims = (cv_uvec4){dims[0], dims[1], dims[2], dims[0] * dims[1] * dims[2]};
    out->dirs = (cv_uvec4){nz, np, nz * np, out->dims.w * CV_RL_ORIENTS};
    out->learn = (cv_uvec4){1, 0, 0, 0};
    if (cv_rlpath_table_bytes(out) > ((uint64_t)1 << 30) ||
        cv_rlpath_guide_bytes(out) > ((uint64_t)1 << 30))
        return cv_fail(err, "rlpath table of %u cells x %u normal classes x %u directions is "
                       "above 1 GiB", out->dims.w, CV_RL_ORIENTS, out->dirs.z);
    return true;
}

uint64_t cv_rlpath_table_bytes(const CvRlParams *p)
{
    return (uint64_t)p->dirs.w * CV_RL_LEARN_TEXELS(p->dirs.z) * sizeof(uint32_t);
}

uint64_t cv_rlpath_guide_bytes(const CvRlParams *p)
{
    return (uint64_t)p->dirs.w * CV_RL_GUIDE_TEXELS(p->dirs.z) * 4 * sizeof(float);
}

/* The rebuild program's defines (the shade programs are the renderer's:
 * cv_rlpath_ops.file). */
static const char *const rebuild_indirect[2] = {"CV_RL_GUIDE_INDIRECT", NULL};
static const char *const *rebuild_defines(bool guide_indirect)
{
    return guide_indirect ? rebuild_indirect : NULL;
}

static void rlpath_prefetch(struct cv_gpu *gpu, bool guide_indirect)
{
    cv_program_request(gpu, "trace/rlpath/rebuild.comp", rebuild_defines(guide_indirect));
}

bool cv_rlpath_create(struct cv_gpu *gpu, const CvRlParams *layout, uint32_t n_paths,
                      bool guide_indirect, struct cv_rlpath **out, struct cv_error *err)
{
    struct cv_rlpath *rl = cv_xcalloc(1, sizeof(*rl));
    rl->params = *layout;
    rl->n_paths = n_paths;
    rlpath_prefetch(gpu, guide_indirect);
    struct cv_program *p = cv_program_get(gpu, "trace/rlpath/rebuild.comp",
                                          rebuild_defines(guide_indirect), err);
    if (p)
        rl->rebuild = *p;
    if (!p) {
        cv_rlpath_destroy(&rl);
        return false;
    }
    /* every path starts with nothing to learn: all state words CV_RL_NONE */
    size_t path_bytes = (size_t)(n_paths ? n_paths : 1) * 2 * sizeof(uint32_t);
    void *none = cv_xmalloc(path_bytes);
    memset(none, 0xff, path_bytes);
    rl->ubo = cv_buffer_create(sizeof(CvRlParams), &rl->params, "rlpath params", err);
    if (rl->ubo)
        rl->table = cv_gpu_storage_buffer(gpu, (size_t)cv_rlpath_table_bytes(layout), NULL,
                                          "rlpath learning table", err);
    /* zero: every key's guiding weight 0 until its first rebuild */
    if (rl->table)
        rl->guide = cv_gpu_storage_buffer(gpu, (size_t)cv_rlpath_guide_bytes(layout), NULL,
                                          "rlpath guide table", err);
    if (rl->guide)
        rl->path = cv_buffer_create(path_bytes, none, "rlpath path state", err);
    free(none);
    size_t table_texels = (size_t)cv_rlpath_table_bytes(layout) / 4;
    bool ok = rl->path &&
              cv_buffer_image_create(&rl->images[0], rl->table, table_texels, CV_IMAGE_RL_Q,
                                     GL_R32UI, GL_READ_WRITE, err) &&
              cv_buffer_image_create(&rl->images[1], rl->table, table_texels, CV_IMAGE_RL_QF,
                                     GL_R32F, GL_READ_WRITE, err) &&
              cv_buffer_image_create(&rl->images[2], rl->guide,
                                     (size_t)cv_rlpath_guide_bytes(layout) / 16,
                                     CV_IMAGE_RL_GUIDE, GL_RGBA32F, GL_READ_WRITE, err) &&
              cv_buffer_image_create(&rl->images[3], rl->path, path_bytes / 8, CV_IMAGE_RL_PATH,
                                     GL_RG32UI, GL_READ_WRITE, err) &&
              (rl->guide_tex = cv_buffer_texture(rl->guide, GL_RGBA32F,
                                                 (size_t)cv_rlpath_guide_bytes(layout) / 16, err));
    if (!ok) {
        cv_error_prefix(err, "rlpath table of %u keys x %u directions: ", layout->dirs.w,
                        layout->dirs.z);
        cv_rlpath_destroy(&rl);
        return false;
    }
    *out = rl;
    return true;
}

void cv_rlpath_bind(const struct cv_rlpath *rl)
{
    glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_RLPATH, rl->ubo);
    for (size_t i = 0; i < CV_ARRAY_SIZE(rl->images); i++)
        cv_buffer_image_bind(&rl->images[i]);
    glBindTextureUnit(CV_TEXUNIT_RL_GUIDE, rl->guide_tex);
}

uint32_t cv_rlpath_train_spp(uint32_t train)
{
    return train == 0 ? CV_RL_DEFAULT_TRAIN : train == CV_RL_TRAIN_ALWAYS ? 0 : train;
}

uint32_t cv_rlpath_job_train_spp(const struct cv_render_params *p)
{
    return cv_rlpath_train_spp(p->rl_train);
}

void cv_rlpath_set_learning(struct cv_rlpath *rl, bool learning)
{
    if ((rl->params.learn.x != 0) == learning)
        return;
    rl->params.learn.x = learning;
    glNamedBufferSubData(rl->ubo, 0, sizeof(CvRlParams), &rl->params);
}

void cv_rlpath_update(const struct cv_rlpath *rl)
{
    /* the escaped and shade stages' adds to the table */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    cv_rlpath_dispatch_rebuild(&rl->rebuild, &rl->params);
}

void cv_rlpath_dispatch_rebuild(const struct cv_program *rebuild, const CvRlParams *p)
{
    /* one workgroup per key; keys past one dimension's 65535 go to y */
    uint32_t keys = p->dirs.w, gx = keys < 4096 ? keys : 4096, gy = (keys + gx - 1) / gx;
    if (keys == 0)
        return;
    glUseProgram(rebuild->id);
    glDispatchCompute(gx, gy, 1);
    /* the shade stage reads the CDFs and weights through the buffer
     * texture (tests through the image too) */
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void cv_rlpath_destroy(struct cv_rlpath **rlp)
{
    if (!rlp || !*rlp)
        return;
    struct cv_rlpath *rl = *rlp;
    for (size_t i = 0; i < CV_ARRAY_SIZE(rl->images); i++)
        cv_buffer_image_destroy(&rl->images[i]);
    if (rl->guide_tex)
        glDeleteTextures(1, &rl->guide_tex);
    cv_buffer_destroy(&rl->ubo);
    cv_buffer_destroy(&rl->table);
    cv_buffer_destroy(&rl->guide);
    cv_buffer_destroy(&rl->path);
    free(rl);
    *rlp = NULL;
}

static bool ops_create(const struct cv_integrator_setup *s, void **state,
                       struct cv_program shade[CV_SHADE_PROGRAMS], struct cv_error *err)
{
    const struct cv_render_params *p = s->params;
    CvRlParams rp;
    struct cv_rlpath *rl = NULL;
    if (!cv_rlpath_layout(s->scene->bounds_min, s->scene->bounds_max, p->rl_grid,
                          p->rl_directions, p->rl_mix, &rp, err) ||
        !cv_rlpath_create(s->gpu, &rp, s->n_paths, p->rl_guide_indirect, &rl, err))
        return false;
    rl->train = cv_rlpath_train_spp(p->rl_train);
    (void)shade;   /* both are the renderer's (cv_rlpath_ops.file) */
    *state = rl;
    return true;
}

static void ops_bind(const void *state)
{
    cv_rlpath_bind(state);
}

static void ops_after_shade(const void *state)
{
    cv_rlpath_update(state);
}

static uint32_t ops_learn_spp(const void *state)
{
    return ((const struct cv_rlpath *)state)->train;
}

static void ops_set_learning(void *state, bool learning)
{
    cv_rlpath_set_learning(state, learning);
}

static void ops_prefetch(struct cv_gpu *gpu, const struct cv_render_params *p,
                         const char *const *defines)
{
    (void)defines;
    rlpath_prefetch(gpu, p->rl_guide_indirect);
}

static void ops_destroy(void **state)
{
    struct cv_rlpath *rl = *state;
    cv_rlpath_destroy(&rl);
    *state = NULL;
}

const struct cv_integrator_ops cv_rlpath_ops = {
    .escaped_stage = true,   /* misses learn too */
    .escaped_define = "CV_RLPATH",
    /* path's three bins (trace/integrator.c, trace/shade_bins.h) */
    .n_shade = 3,
    .file = {"trace/rlpath/shade.comp", "trace/rlpath/shade.comp", "trace/rlpath/shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1", "CV_SHADE_BIN=2"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B, CV_ARGS_HITS_C},
    .bins = {1u, 2u, 4u},
    .guides = true,
    .create = ops_create,
    .bind = ops_bind,
    .after_shade = ops_after_shade,
    .after_shade_name = "rlpath-rebuild",
    .destroy = ops_destroy,
    .prefetch = ops_prefetch,
    .learn_spp = ops_learn_spp,
    .train_spp = cv_rlpath_job_train_spp,
    .set_learning = ops_set_learning,
};
