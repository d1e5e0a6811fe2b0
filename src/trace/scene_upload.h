/* scene_upload.h: the flat scene's arrays as GPU buffers at their fixed
 * bindings (glsl/shared/bindings.h), the light-selection CDF by power, the
 * acceleration structure, and what the stage programs must be compiled
 * for (environment light, alpha cut-outs). */
#ifndef CV_TRACE_SCENE_UPLOAD_H
#define CV_TRACE_SCENE_UPLOAD_H

#include <stdbool.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "bvh/bvh.h"
#include "gpu/context.h"
#include "scene/scene.h"

struct cv_scene_gpu {
    GLuint vertices, triangles, tri_light, materials, textures, texels, lights, light_cdf;
    bool has_env;     /* an infinite light exists */
    bool has_alpha;   /* some material has an alpha cut-out */
    bool empty;       /* no triangles: no BVH, nothing to hit */
    struct cv_bvh *bvh;
};

/* Light selection CDF: cdf[i] = sum of pmf[0..i] with pmf proportional to
 * power (uniform when no light has power); cdf[n-1] = 1. Exposed for tests. */
void cv_light_cdf(const float *power, uint32_t n, float *cdf);

bool cv_scene_upload(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_scene_gpu *out,
                     struct cv_error *err);
/* Binds the scene buffers and the BVH at their fixed bindings. */
void cv_scene_bind(const struct cv_scene_gpu *g);
/* Deletes the buffers and the BVH; the struct is zeroed. */
void cv_scene_gpu_release(struct cv_scene_gpu *g);

#endif
