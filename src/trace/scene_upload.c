/* scene_upload.c: see scene_upload.h. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "trace/scene_upload.h"

void cv_light_cdf(const float *power, uint32_t n, float *cdf)
{
    double total = 0;
    for (uint32_t i = 0; i < n; i++)
        total += power && power[i] > 0 ? power[i] : 0;
    double acc = 0;
    for (uint32_t i = 0; i < n; i++) {
        acc += total > 0 ? (power[i] > 0 ? power[i] : 0) / total : 1.0 / n;
        cdf[i] = (float)acc;
    }
    if (n)
        cdf[n - 1] = 1;
}

static bool up(GLuint *b, size_t bytes, const void *data, const char *label, struct cv_error *err)
{
    *b = cv_buffer_create(bytes, data, label, err);
    return *b != 0;
}

bool cv_scene_upload(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_scene_gpu *out,
                     struct cv_error *err)
{
    struct cv_scene_gpu g = {0};
    for (uint32_t i = 0; i < s->n_lights; i++)
        if (s->lights[i].type == CV_LIGHT_INFINITE || s->lights[i].type == CV_LIGHT_INFINITE_MAP)
            g.has_env = true;
    for (uint32_t i = 0; i < s->n_materials; i++)
        if (s->materials[i].alpha_tex >= 0 || s->materials[i].alpha < 1)
            g.has_alpha = true;
    float *cdf = cv_xcalloc(s->n_lights ? s->n_lights : 1, sizeof(float));
    cv_light_cdf(s->light_power, s->n_lights, cdf);
    bool ok = up(&g.vertices, s->n_vertices * sizeof(CvVertex), s->vertices, "scene vertices", err) &&
              up(&g.triangles, s->n_triangles * sizeof(CvTriangle), s->triangles, "scene triangles", err) &&
              up(&g.tri_light, s->n_triangles * sizeof(int32_t), s->tri_light, "scene triangle lights", err) &&
              up(&g.materials, s->n_materials * sizeof(CvMaterial), s->materials, "scene materials", err) &&
              up(&g.textures, s->n_textures * sizeof(CvTexture), s->textures, "scene textures", err) &&
              up(&g.texels, (size_t)s->n_texels * 8, s->texels, "scene texels", err) &&
              up(&g.lights, s->n_lights * sizeof(CvLight), s->lights, "scene lights", err) &&
              up(&g.light_cdf, s->n_lights * sizeof(float), cdf, "scene light cdf", err);
    free(cdf);
    if (!ok) {
        cv_scene_gpu_release(&g);
        return false;
    }
    g.empty = s->n_triangles == 0;
    if (!g.empty && !cv_bvh_build(gpu, g.vertices, g.triangles, s->n_triangles, NULL, &g.bvh, err)) {
        cv_error_prefix(err, "building the BVH: ");
        cv_scene_gpu_release(&g);
        return false;
    }
    *out = g;
    return true;
}

void cv_scene_bind(const struct cv_scene_gpu *g)
{
    cv_buffer_bind(g->vertices, CV_BIND_VERTICES);
    cv_buffer_bind(g->triangles, CV_BIND_TRIANGLES);
    cv_buffer_bind(g->tri_light, CV_BIND_TRI_LIGHT);
    cv_buffer_bind(g->materials, CV_BIND_MATERIALS);
    cv_buffer_bind(g->textures, CV_BIND_TEXTURES);
    cv_buffer_bind(g->texels, CV_BIND_TEXELS);
    cv_buffer_bind(g->lights, CV_BIND_LIGHTS);
    cv_buffer_bind(g->light_cdf, CV_BIND_LIGHT_CDF);
    if (g->bvh)
        cv_bvh_bind(g->bvh);
}

void cv_scene_gpu_release(struct cv_scene_gpu *g)
{
    GLuint *b[] = {&g->vertices, &g->triangles, &g->tri_light, &g->materials,
                   &g->textures, &g->texels, &g->lights, &g->light_cdf};
    for (size_t i = 0; i < CV_ARRAY_SIZE(b); i++)
        cv_buffer_destroy(b[i]);
    cv_bvh_destroy(&g->bvh);
    memset(g, 0, sizeof(*g));
}
