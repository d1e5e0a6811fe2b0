/* relight.h: a job's overrides of the scene's lights (cavalry-manifest(5):
 * env.scale, env.rotate, lights.scale) applied to copies of the loaded
 * scene's light arrays, so that jobs on one scene share its load, upload and
 * BVH and differ only in the few light records the GPU reads
 * (trace/scene_upload.h: cv_scene_gpu_relight). */
#ifndef CV_SCENE_RELIGHT_H
#define CV_SCENE_RELIGHT_H

#include <stdbool.h>
#include <stdint.h>

#include "base/limits.h"
#include "scene/scene.h"

struct cv_relight {
    float env_scale;                 /* on every infinite light's radiance; 1: none */
    bool env_rotate;
    float rotate[4];                 /* [degrees], world axis x, y, z: turns the
                                      * environment after the scene's transform */
    uint32_t n_scales;
    struct cv_relight_scale {
        uint32_t source;             /* index into cv_scene.light_sources */
        float scale;                 /* on the radiance of its every light */
    } scales[CV_MAX_LIGHT_SCALES];
    /* env.file: the image (scene/env_file.h) every infinite light shows
     * instead of its own map or colour (a colour stays on as the map's
     * scale, as pbrt's L); NULL: none. */
    const struct cv_scene *env;
    bool env_equal_area;             /* read it as pbrt-v4's equal-area map (square),
                                      * else as a latitude-longitude one */
};

/* Whether the scene has an environment (an infinite light) to override. */
bool cv_scene_has_env(const struct cv_scene *s);

/* How env.file's image env is read on scene s: as the scene's environment
 * map is (equal-area or latitude-longitude); where the scene's environment
 * is a colour, a square image as equal-area (pbrt-v4), any other as
 * latitude-longitude (pbrt-v3). */
bool cv_scene_env_equal_area(const struct cv_scene *s, const struct cv_scene *env);

/* lights and power (n_lights each, allocated by the caller) get the scene's
 * lights and their sampling powers with r applied; a light's power scales
 * with its radiance, so that light selection follows the new brightness.
 * With r->env, env_textures (r->env->n_textures, else unused) gets the
 * image's texture records as the relit lights index them: after the
 * scene's own (index s->n_textures + i), texels after the scene's (offset
 * s->n_texels + the image's own). */
void cv_scene_relight(const struct cv_scene *s, const struct cv_relight *r, CvLight *lights,
                      float *power, CvTexture *env_textures);

#endif
