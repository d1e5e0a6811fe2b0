/* scene_upload.h: the flat scene's arrays as GPU buffers at their fixed
 * bindings (glsl/shared/bindings.h), the light-selection CDF by power, the
 * acceleration structure, and what the stage programs must be compiled
 * for (environment light, alpha cut-outs, textures). */
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
    GLuint env_dist;  /* environment-map distributions (glsl/shared/envmap.h) */
    GLuint media;     /* CvMedium[] (glsl/shared/medium.h) */
    bool has_media;   /* the scene names participating media */
    bool has_env;     /* an infinite light exists */
    bool has_alpha;   /* some material has an alpha cut-out */
    bool has_textures; /* the texture table is not empty */
    bool empty;       /* no triangles: no BVH, nothing to hit */
    bool basic_materials; /* only untextured diffuse and mirror: glsl/trace/bsdf_basic.glsl */
    struct cv_bvh *bvh;
    struct cv_gpu *gpu;  /* whose buffer pool the BVH's buffers return to */
};

/* Light selection CDF: cdf[i] = sum of pmf[0..i] with pmf proportional to
 * power (uniform when no light has power); cdf[n-1] = 1. Exposed for tests. */
void cv_light_cdf(const float *power, uint32_t n, float *cdf);

/* bvh: the BVH build's parameters; NULL: cv_bvh_default_params(). */
bool cv_scene_upload(struct cv_gpu *gpu, const struct cv_scene *s,
                     const struct cv_bvh_params *bvh, struct cv_scene_gpu *out,
                     struct cv_error *err);
/* Binds the scene buffers and the BVH at their fixed bindings. */
void cv_scene_bind(const struct cv_scene_gpu *g);
/* Deletes the buffers and the BVH; the struct is zeroed. */
void cv_scene_gpu_release(struct cv_scene_gpu *g);

/* cv_scene_upload into a new heap copy, for sharing one upload and one BVH
 * between the renderers of several jobs on one scene
 * (cv_renderer_create_shared). It holds no pointer to the scene, and nothing
 * derived from the camera or the render settings, so the jobs' camera and
 * resolution overrides do not change it. */
bool cv_scene_gpu_create(struct cv_gpu *gpu, const struct cv_scene *s,
                         const struct cv_bvh_params *bvh, struct cv_scene_gpu **out,
                         struct cv_error *err);
/* Accepts NULL; clears the pointer. The renderers using it must be
 * destroyed first. */
void cv_scene_gpu_destroy(struct cv_scene_gpu **g);

#endif
