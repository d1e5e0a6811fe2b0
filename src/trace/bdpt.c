/* bdpt.c: see bdpt.h. */
#include <stdlib.h>

#include <epoxy/gl.h>

#include "base/mem.h"
#include "glsl/shared/bdpt.h"
#include "glsl/shared/trace.h"
#include "gpu/buffer.h"
#include "gpu/storage.h"
#include "trace/bdpt.h"

struct cv_bdpt {
    GLuint vertices;   /* CvBdptVertex[n_paths * CV_BDPT_VERTS(max_depth)] */
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

static bool ops_create(const struct cv_integrator_setup *s, void **state,
                       struct cv_program shade[CV_SHADE_PROGRAMS], struct cv_error *err)
{
    (void)shade;  /* the renderer builds the kernel: file[0] */
    struct cv_bdpt *b = cv_xcalloc(1, sizeof(*b));
    *state = b;
    uint64_t verts = (uint64_t)s->n_paths * CV_BDPT_VERTS((uint64_t)s->max_depth);
    b->vertices = cv_gpu_storage_buffer(s->gpu, verts * sizeof(CvBdptVertex),
                                        NULL, "bdpt subpath vertices", err);
    if (b->vertices)
        b->splat = cv_gpu_storage_buffer(s->gpu, (size_t)s->n_pixels * 3 * sizeof(float), NULL,
                                         "bdpt splat film", err);
    if (!b->vertices || !b->splat) {
        ops_destroy(state);
        return false;
    }
    return true;
}

static void ops_bind(const void *state)
{
    const struct cv_bdpt *b = state;
    cv_buffer_bind(b->vertices, CV_BIND_BDPT_VERTICES);
    cv_buffer_bind(b->splat, CV_BIND_BDPT_SPLAT);
}

/* Path slots when the renderer chooses: each keeps its two subpaths in
 * the store (CV_BDPT_VERTS vertices of 128 bytes), so fewer than the
 * wavefront's; a slot runs whole samples, so fewer suffice to fill the
 * GPU. */
#define CV_BDPT_MAX_PATHS (1u << 20)

const struct cv_integrator_ops cv_bdpt_ops = {
    .whole_samples = true,
    .max_paths = CV_BDPT_MAX_PATHS,
    .resolve_define = "CV_BDPT_SPLAT",
    .n_shade = 1,
    .file = {"trace/bdpt/bdpt.comp"},
    .create = ops_create,
    .bind = ops_bind,
    .destroy = ops_destroy,
};
