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
};

/* Whether the scene has an environment (an infinite light) to override. */
bool cv_scene_has_env(const struct cv_scene *s);

/* lights and power (n_lights each, allocated by the caller) get the scene's
 * lights and their sampling powers with r applied; a light's power scales
 * with its radiance, so that light selection follows the new brightness. */
void cv_scene_relight(const struct cv_scene *s, const struct cv_relight *r, CvLight *lights,
                      float *power);

#endif
