/* bdpt.c: see bdpt.h. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <epoxy/gl.h>

#include "base/mem.h"
#include "glsl/shared/bdpt.h"
#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/storage.h"
#include "trace/bdpt.h"
#include "trace/scene_defines.h"

#define KERNEL "trace/bdpt/bdpt.comp"
/* defines of the kernel at most, with the NULL: the scene's, the
 * mattes' (render.c: stride, Cryptomatte, transparent film), a strategy's
 * two */
#define CV_MAX_DEFINES (CV_SCENE_DEFINES_MAX + 6)

struct cv_bdpt {
    GLuint vertices;   /* CvBdptVertex[wave_paths * CV_BDPT_VERTS(max_depth)] */
    GLuint splat;      /* float bits [3 * n_pixels], starts at 0 */
};

static void ops_destroy(void **state)
{
    struct cv_bdpt *b = *state;
    if (b) {
        cv_buffer_destroy(&b->vertices);
        cv_buffer_destroy(&b->splat);
        free(b);
    }
    *state = NULL;
}

/* The kernel's defines: the scene's, and a strategy alone where the
 * parameters ask for one (render.h: bdpt_s, bdpt_t). */
struct kernel_defines {
    const char *list[CV_MAX_DEFINES];
    char only_s[32], only_t[32];
};

static const char *const *kernel_defines(struct kernel_defines *k, const struct cv_render_params *p,
                                         const char *const *defines)
{
    int n = 0;
    while (defines[n])
        k->list[n] = defines[n], n++;
    if (p->bdpt_t > 0) {
        snprintf(k->only_s, sizeof(k->only_s), "CV_BDPT_ONLY_S=%uu", p->bdpt_s);
        snprintf(k->only_t, sizeof(k->only_t), "CV_BDPT_ONLY_T=%uu", p->bdpt_t);
        k->list[n++] = k->only_s;
        k->list[n++] = k->only_t;
    }
    k->list[n] = NULL;
    return k->list;
}

static void ops_prefetch(struct cv_gpu *gpu, const struct cv_render_params *p,
                         const char *const *defines)
{
    struct kernel_defines k;
    cv_program_request(gpu, KERNEL, kernel_defines(&k, p, defines));
}

static bool ops_create(const struct cv_integrator_setup *s, void **state,
                       struct cv_program shade[CV_SHADE_PROGRAMS], struct cv_error *err)
{
    struct kernel_defines k;
    struct cv_program *prog = cv_program_get(s->gpu, KERNEL, kernel_defines(&k, s->params, s->defines),
                                             err);
    if (!prog)
        return false;
    shade[0] = *prog;
    struct cv_bdpt *b = cv_xcalloc(1, sizeof(*b));
    *state = b;
    /* one wave's subpaths (integrator.h): the film's slots beyond it run
     * in further dispatches of each round, so the store's size depends on
     * neither the film nor, beyond one buffer, the depth */
    uint64_t verts = (uint64_t)s->wave_paths * CV_BDPT_VERTS((uint64_t)s->max_depth);
    b->vertices = cv_gpu_storage_buffer(s->gpu, verts * sizeof(CvBdptVertex),
                                        NULL, "bdpt subpath vertices", err);
    size_t splat_floats = CV_BDPT_SPLAT_HEADER + (size_t)s->n_pixels * 3;
    if (b->vertices)
        b->splat = cv_gpu_storage_buffer(s->gpu, splat_floats * sizeof(float), NULL,
                                         "bdpt splat film", err);
    if (!b->vertices || !b->splat) {
        ops_destroy(state);
        return false;
    }
    /* pbrt-v4's Bounds3::BoundingSphere of the scene */
    float sphere[4] = {0, 0, 0, 0}, r2 = 0;
    for (int i = 0; i < 3; i++) {
        sphere[i] = 0.5f * (s->scene->bounds_min[i] + s->scene->bounds_max[i]);
        float d = s->scene->bounds_max[i] - sphere[i];
        r2 += d * d;
    }
    sphere[3] = r2 > 0 ? sqrtf(r2) : 0;
    glNamedBufferSubData(b->splat, 0, sizeof(sphere), sphere);
    return true;
}

static void ops_bind(const void *state)
{
    const struct cv_bdpt *b = state;
    cv_buffer_bind(b->vertices, CV_BIND_BDPT_VERTICES);
    cv_buffer_bind(b->splat, CV_BIND_BDPT_SPLAT);
}

/* Path slots when the renderer chooses, and slots a wave: each keeps its
 * two subpaths in the store (CV_BDPT_VERTS vertices of 128 bytes), so
 * fewer than the wavefront's; a slot runs whole samples, so fewer suffice
 * to fill the GPU. */
#define CV_BDPT_MAX_PATHS (1u << 20)

static uint64_t slot_bytes(uint32_t max_depth)
{
    return CV_BDPT_VERTS((uint64_t)max_depth) * sizeof(CvBdptVertex);
}

const struct cv_integrator_ops cv_bdpt_ops = {
    .slot_bytes = slot_bytes,
    .whole_samples = true,
    .media = true,
    .max_paths = CV_BDPT_MAX_PATHS,
    .resolve_define = "CV_BDPT_SPLAT",
    .n_shade = 1,
    .create = ops_create,
    .prefetch = ops_prefetch,
    .bind = ops_bind,
    .destroy = ops_destroy,
};
