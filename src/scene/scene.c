/* scene.c: cv_scene_load / cv_scene_destroy: parse, build, finish. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"
#include "scene/parse.h"
#include "scene/scene.h"

static void scene_free(struct cv_scene *s)
{
    for (size_t i = 0; i < s->n_inputs; i++)
        free(s->inputs[i]);
    free(s->inputs);
    free(s->vertices);
    free(s->triangles);
    free(s->tri_light);
    free(s->tri_object);
    free(s->curves);
    free(s->curve_xforms);
    free(s->motions);
    for (uint32_t i = 0; i < s->n_objects; i++)
        free(s->object_names[i]);
    free(s->object_names);
    for (uint32_t i = 0; i < s->n_materials; i++) {
        free(s->material_names[i]);
        free(s->material_at ? s->material_at[i] : NULL);
    }
    free(s->material_names);
    free(s->material_at);
    free(s->materials);
    free(s->textures);
    free(s->measured);
    free(s->texels);
    free(s->lights);
    free(s->media);
    for (uint32_t i = 0; i < s->n_media; i++)
        free(s->medium_sources[i].at);
    free(s->medium_sources);
    free(s->medium_grids);
    free(s->bssrdf);
    free(s->bssrdf_keys);
    free(s->conductor_fresnel);
    free(s->light_power);
    for (uint32_t i = 0; i < s->n_light_sources; i++) {
        free(s->light_sources[i].type);
        free(s->light_sources[i].at);
    }
    free(s->light_sources);
    free(s->light_source);
    free(s->settings.integrator);
    free(s->settings.integrator_at);
    free(s->settings.sampler);
    free(s->settings.film_filename);
    free(s->path);
    free(s);
}

bool cv_scene_load(const char *path, const struct cv_scene_load_params *params,
                   struct cv_scene **out, struct cv_error *err)
{
    struct cv_scene *s = cv_xcalloc(1, sizeof(*s));
    struct cv_builder b;
    cv_b_init(&b, s, params && params->strict);
    bool ok = (!params || !params->root || cv_b_set_root(&b, params->root, err)) &&
              cv_parse_file(&b, path, err) && cv_b_finish(&b, err);
    cv_b_free(&b);
    if (!ok) {
        scene_free(s);
        return false;
    }
    s->path = cv_xstrdup(path);
    *out = s;
    return true;
}

bool cv_scene_load_string(const char *name, const char *text, size_t len,
                          const struct cv_scene_load_params *params, struct cv_scene **out,
                          struct cv_error *err)
{
    struct cv_scene *s = cv_xcalloc(1, sizeof(*s));
    struct cv_builder b;
    cv_b_init(&b, s, params && params->strict);
    bool ok = (!params || !params->root || cv_b_set_root(&b, params->root, err)) &&
              cv_parse_string(&b, name, text, len, err) && cv_b_finish(&b, err);
    cv_b_free(&b);
    if (!ok) {
        scene_free(s);
        return false;
    }
    s->path = cv_xstrdup(name);
    *out = s;
    return true;
}

void cv_scene_destroy(struct cv_scene **scene)
{
    if (!scene || !*scene)
        return;
    scene_free(*scene);
    *scene = NULL;
}

uint32_t cv_scene_static_triangles(const struct cv_scene *s)
{
    return s->n_motions ? s->motions[0].first : s->n_triangles;
}
