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
    GLuint tri_object; /* uint[]: each triangle's ID-matte object (scene.h) */
    /* tri_object as an r32ui buffer texture (CV_TEXUNIT_TRI_OBJECT); 0
     * where the scene has no triangles or more than a buffer texture holds
     * (GL_MAX_TEXTURE_BUFFER_SIZE: jobs with ID mattes then fail) */
    GLuint tri_object_tex;
    GLuint light_cdf_tex; /* light_cdf as an r32f buffer texture (CV_TEXUNIT_LIGHT_CDF) */
    GLuint media;     /* CvMedium[] (glsl/shared/medium.h), or 0 */
    GLuint media_tex; /* that buffer as an rgba32f buffer texture (CV_TEXUNIT_MEDIA) */
    bool has_media;   /* the scene names participating media */
    GLuint medium_grids; /* float[]: grid media's samples and majorants, or 0 */
    GLuint medium_grids_tex; /* that buffer as an rgba32f buffer texture (CV_TEXUNIT_MEDIUM_GRIDS) */
    /* Where one buffer texture does not hold the grid store: its pages
     * 1 .. n - 1 (n_grid_pages of them in all), each a buffer and its
     * texture (CV_TEXUNIT_MEDIUM_GRID_PAGES up), medium_grids being page 0;
     * and the defines that the kernels then need ("CV_MEDIUM_GRID_PAGES=n",
     * "CV_MEDIUM_GRID_PAGE_TEXELS=t"; empty strings with one page). */
    uint32_t n_grid_pages;
    GLuint *grid_pages, *grid_pages_tex;
    char grid_pages_define[40], grid_page_texels_define[48];
    bool has_medium_grids; /* some medium is a grid (CV_MEDIUM_GRIDS) */
    bool has_medium_cloud; /* some medium is a cloud (CV_MEDIUM_CLOUDS; its data is in the grids) */
    bool has_env;     /* an infinite light exists */
    bool spherical_camera; /* the camera is spherical (CV_SPHERICAL_CAMERA) */
    bool alpha_emitters; /* some area light is cut out (CV_ALPHA_EMITTERS) */
    bool has_alpha;   /* some material has an alpha cut-out */
    bool has_textures; /* the texture table is not empty */
    bool empty;       /* no triangles and no curves: nothing to hit */
    GLuint curves;    /* the curves and their tree (src/bvh/curve_bvh.h), or 0 */
    GLuint curves_tex; /* that buffer as an rgba32f buffer texture (CV_TEXUNIT_CURVES) */
    bool has_curves;  /* compile the stages with CV_HAS_CURVES */
    bool no_triangles; /* no static triangles: no triangle BVH (CV_NO_TRIANGLES) */
    GLuint motion;    /* the moving shapes and their trees (src/bvh/motion_bvh.h), or 0 */
    GLuint motion_tex; /* that buffer as an rgba32f buffer texture (CV_TEXUNIT_MOTION) */
    bool has_motion;  /* compile the stages with CV_HAS_MOTION */
    bool basic_materials; /* only untextured diffuse and mirror: glsl/trace/bsdf_basic.glsl */
    bool has_hair;    /* some material is hair (else CV_NO_HAIR) */
    GLuint bssrdf;    /* float[]: the BSSRDF tables (glsl/shared/bssrdf.h), or 0 */
    GLuint bssrdf_tex; /* that buffer as an r32f buffer texture (CV_TEXUNIT_BSSRDF) */
    bool has_subsurface; /* some material is subsurface (CV_HAS_SUBSURFACE) */
    bool has_coat_closed; /* some coated diffuse may take the closed form (else CV_NO_COAT_CLOSED) */
    uint32_t shade_bins; /* bit b: some material is in shade bin b (trace/shade_bins.h) */
    bool walk_coat_closed; /* one in the coated walk's bin may take the closed form too */
    uint32_t textured_bins; /* bit b: shade bin b's kernel reads textures (a material's,
                             * trace/shade_bins.h, or a light's: then every bit) */
    bool walk_only; /* no mix in the coated walk's bin (trace/shade_bins.h: CV_BSDF_WALK_ONLY) */
    uint32_t guided_bins; /* bit b: a material of shade bin b that rlpath's guide may serve
                             (trace/shade_bins.h: cv_shade_bins_guided) */
    GLuint measured;  /* the measured BRDFs' tables (glsl/shared/measured.h), or 0 */
    GLuint measured_tex; /* that buffer as an r32ui buffer texture (CV_TEXUNIT_MEASURED) */
    bool has_measured; /* some material is measured (else CV_NO_MEASURED) */
    GLuint conductor_fresnel; /* float[]: conductors' Fresnel tables (glsl/shared/conductor_fresnel.h), or 0 */
    GLuint conductor_fresnel_tex; /* that buffer as an rgba32f buffer texture (CV_TEXUNIT_CONDUCTOR_FRESNEL) */
    bool has_conductor_fresnel; /* some conductor has a table (CV_CONDUCTOR_TABLES) */
    struct cv_bvh *bvh;
    struct cv_gpu *gpu;  /* whose buffer pool the BVH's buffers return to */
    /* A relit copy (cv_scene_gpu_relight): its lights and light_cdf are its
     * own, and with a new environment image its textures, texels and
     * env_dist too; every other buffer and the BVH are base's; NULL
     * otherwise. */
    const struct cv_scene_gpu *base;
};

/* Light selection CDF: cdf[i] = sum of pmf[0..i] with pmf proportional to
 * power (uniform when no light has power); cdf[n-1] = 1. Exposed for tests. */
void cv_light_cdf(const float *power, uint32_t n, float *cdf);

/* Sets g's feature flags (has_env ... basic_materials, empty) from s: what
 * cv_scene_upload sets, without touching the GPU. */
void cv_scene_gpu_features(const struct cv_scene *s, struct cv_scene_gpu *g);

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

/* A copy of base, the upload of s, with its own light records and
 * light-selection CDF from lights and power (s->n_lights each; a job's
 * overrides, scene/relight.h). With env (an environment image,
 * scene/env_file.h), env_textures (env->n_textures records, as
 * cv_scene_relight made them) follow the scene's textures and env's texels
 * the scene's (copied on the GPU), and the environment distributions are
 * built from env's image. Everything else, the BVH included, stays base's,
 * which must outlive it. Costs an upload of the lights (and of the image
 * with its distribution): per job, not per pass. Destroy with
 * cv_scene_gpu_destroy. */
bool cv_scene_gpu_relight(struct cv_gpu *gpu, const struct cv_scene_gpu *base,
                          const struct cv_scene *s, const CvLight *lights, const float *power,
                          const struct cv_scene *env, const CvTexture *env_textures,
                          struct cv_scene_gpu **out, struct cv_error *err);

#endif
