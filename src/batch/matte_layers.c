/* matte_layers.c: see matte_layers.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "batch/matte_layers.h"
#include "manifest/enums.h"

const char *cv_material_matte_name(const struct cv_scene *scene, uint32_t i, char *buf, size_t n)
{
    if (scene->material_names && scene->material_names[i])
        return scene->material_names[i];
    if (scene->material_at && scene->material_at[i])
        return scene->material_at[i];
    snprintf(buf, n, "material%u", i);
    return buf;
}

static float *add_layer(struct cv_matte_layers *m, const char *name, uint32_t channels,
                        size_t pixels)
{
    size_t i = m->n_layers++;
    snprintf(m->layer_names[i], sizeof(m->layer_names[i]), "%s", name);
    m->data[i] = cv_xcalloc(pixels * channels, sizeof(float));
    static const char *const rgba[4] = {"R", "G", "B", "A"};
    m->layers[i] = (struct cv_image_layer){
        .name = m->layer_names[i],
        .n_channels = channels,
        .data = m->data[i],
        /* ids must keep every bit: never half */
        .pixel = CV_EXR_PIXEL_FLOAT,
    };
    if (channels == 1)
        m->layers[i].channels[0] = "id";
    else
        for (uint32_t c = 0; c < channels; c++)
            m->layers[i].channels[c] = rgba[c];
    return m->data[i];
}

/* 1 + the id of sample 0's first hit, 0 where it escaped: the pixel's
 * first slot holds sample 0 (glsl/shared/trace.h) */
static void id_layer(struct cv_matte_layers *m, const struct cv_matte_slots *s,
                     const char *name, uint32_t word)
{
    float *out = add_layer(m, name, 1, s->n_pixels);
    for (uint32_t i = 0; i < s->n_pixels; i++)
        out[i] = (float)s->words[(size_t)i * s->stride + word];
}

static void crypto_type(struct cv_matte_layers *m, const struct cv_matte_slots *s,
                        const struct cv_crypto_type *t)
{
    float *layers[CV_CRYPTO_LAYERS];
    for (unsigned l = 0; l < CV_CRYPTO_LAYERS; l++) {
        char name[32];
        snprintf(name, sizeof(name), "%s%02u", t->layer, l);
        layers[l] = add_layer(m, name, 4, s->n_pixels);
    }
    cv_crypto_layers(s, t, layers);
    cv_crypto_metadata(m->meta, t);
}

bool cv_matte_layers_make(struct cv_renderer *r, const struct cv_scene *scene, unsigned aovs,
                          struct cv_matte_layers *out, struct cv_error *err)
{
    memset(out, 0, sizeof(*out));
    unsigned want = aovs & (CV_AOV_OBJECT_ID | CV_AOV_MATERIAL_ID | CV_AOV_CRYPTO_OBJECT |
                            CV_AOV_CRYPTO_MATERIAL);
    if (!want)
        return true;
    struct cv_matte_slots s;
    if (!cv_renderer_read_matte_slots(r, &s, err))
        return false;
    out->meta = cv_metadata_new();
    const char *const *objects = (const char *const *)scene->object_names;
    char (*buf)[32] = cv_xcalloc(scene->n_materials ? scene->n_materials : 1, sizeof(*buf));
    const char **materials = cv_xcalloc(scene->n_materials ? scene->n_materials : 1,
                                        sizeof(*materials));
    for (uint32_t i = 0; i < scene->n_materials; i++)
        materials[i] = cv_material_matte_name(scene, i, buf[i], sizeof(buf[i]));
    if (want & CV_AOV_OBJECT_ID) {
        id_layer(out, &s, "object_id", CV_MATTE_OBJECT_ID);
        char *json = cv_id_names_json(objects, scene->n_objects);
        cv_metadata_set_string(out->meta, "cavalry.objectIds", json);
        free(json);
    }
    if (want & CV_AOV_MATERIAL_ID) {
        id_layer(out, &s, "material_id", CV_MATTE_MATERIAL_ID);
        char *json = cv_id_names_json(materials, scene->n_materials);
        cv_metadata_set_string(out->meta, "cavalry.materialIds", json);
        free(json);
    }
    if (want & CV_AOV_CRYPTO_OBJECT)
        crypto_type(out, &s, &(struct cv_crypto_type){.layer = "CryptoObject",
                                                      .names = objects,
                                                      .n_names = scene->n_objects,
                                                      .first_word = CV_MATTE_CRYPTO_OBJECT});
    if (want & CV_AOV_CRYPTO_MATERIAL)
        crypto_type(out, &s, &(struct cv_crypto_type){.layer = "CryptoMaterial",
                                                      .names = materials,
                                                      .n_names = scene->n_materials,
                                                      .first_word = CV_MATTE_CRYPTO_MATERIAL});
    free(materials);
    free(buf);
    cv_matte_slots_free(&s);
    return true;
}

void cv_matte_layers_free(struct cv_matte_layers *m)
{
    for (size_t i = 0; i < m->n_layers; i++)
        free(m->data[i]);
    cv_metadata_destroy(&m->meta);
    memset(m, 0, sizeof(*m));
}
