/* matte_layers.h: a job's ID AOVs (object_id, material_id) and Cryptomatte
 * layers (crypto_object, crypto_material) as EXR layers with their header
 * attributes, from the renderer's matte slots (trace/render.h) and the
 * scene's object and material names (scene/scene.h). */
#ifndef CV_BATCH_MATTE_LAYERS_H
#define CV_BATCH_MATTE_LAYERS_H

#include <stdbool.h>

#include "base/error.h"
#include "output/cryptomatte.h"
#include "output/exr_write.h"
#include "scene/scene.h"
#include "trace/render.h"

#define CV_MATTE_MAX_LAYERS (2 + 2 * CV_CRYPTO_LAYERS)

struct cv_matte_layers {
    struct cv_image_layer layers[CV_MATTE_MAX_LAYERS];
    size_t n_layers;
    float *data[CV_MATTE_MAX_LAYERS];      /* owned, one per layer */
    char layer_names[CV_MATTE_MAX_LAYERS][32];
    struct cv_metadata *meta;              /* the EXR's attributes for them */
};

/* Fills out for the CV_AOV_* bits of aovs that are mattes; nothing (and
 * no read-back) when there are none. */
bool cv_matte_layers_make(struct cv_renderer *r, const struct cv_scene *scene, unsigned aovs,
                          struct cv_matte_layers *out, struct cv_error *err);
void cv_matte_layers_free(struct cv_matte_layers *m);

/* The name under which material i is a matte: its MakeNamedMaterial name,
 * else "file:line" of its Material directive, else "material<i>".
 * Borrowed from the scene, or written into buf. */
const char *cv_material_matte_name(const struct cv_scene *scene, uint32_t i, char *buf,
                                   size_t n);

#endif
