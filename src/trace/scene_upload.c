/* scene_upload.c: see scene_upload.h. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "bvh/curve_bvh.h"
#include "bvh/motion_bvh.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/bssrdf.h"
#include "glsl/shared/conductor_fresnel.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/gl_check.h"
#include "gpu/memory.h"
#include "gpu/storage.h"
#include "glsl/shared/envmap.h"
#include "trace/envmap_dist.h"
#include "trace/scene_upload.h"
#include "trace/shade_bins.h"

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

/* Each image infinite light's prim: the offset of its distribution in the
 * environment buffer, in light order (build_env_dists fills the buffer in
 * the same order). */
static void env_offsets(const struct cv_scene *s, CvLight *lights)
{
    size_t at = 0;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        CvLight *l = &lights[i];
        if (l->type != CV_LIGHT_INFINITE_MAP || l->tex < 0 || (uint32_t)l->tex >= s->n_textures)
            continue;
        const CvTexture *t = &s->textures[l->tex];
        l->prim = (uint32_t)at;
        at += cv_envmap_dist_floats(t->width, t->height);
    }
}

/* Environment-map distributions of the image infinite lights, one float
 * buffer (glsl/shared/envmap.h); each such light's prim becomes its offset
 * in `lights` (a copy; env_offsets). *dist is at least one float. */
static bool build_env_dists(const struct cv_scene *s, CvLight *lights, float **dist, size_t *n,
                            struct cv_error *err)
{
    size_t total = 1;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        const CvLight *l = &lights[i];
        if (l->type != CV_LIGHT_INFINITE_MAP)
            continue;
        if (l->tex < 0 || (uint32_t)l->tex >= s->n_textures)
            return cv_fail(err, "image infinite light %u has no texture", i);
        const CvTexture *t = &s->textures[l->tex];
        total += cv_envmap_dist_floats(t->width, t->height);
    }
    float *out = cv_xcalloc(total, sizeof(float));
    size_t at = 0;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        CvLight *l = &lights[i];
        if (l->type != CV_LIGHT_INFINITE_MAP)
            continue;
        const CvTexture *t = &s->textures[l->tex];
        size_t np = (size_t)t->width * t->height;
        if ((uint64_t)t->offset + np * CV_TEX_SLOTS(t->flags) > s->n_texels) {
            free(out);
            return cv_fail(err, "image infinite light %u: texels out of range", i);
        }
        /* the values the GPU looks up, so that sampling follows them */
        float *rgba = cv_xmalloc(np * 4 * sizeof(float));
        for (size_t k = 0; k < np; k++)
            cv_scene_texel(s, t, k, &rgba[4 * k]);
        bool ok = cv_envmap_dist_build(rgba, t->width, t->height, 4,
                                       (l->flags & CV_LIGHTF_EQUAL_AREA) != 0, out + at, err);
        free(rgba);
        if (!ok) {
            free(out);
            return false;
        }
        l->prim = (uint32_t)at;
        at += cv_envmap_dist_floats(t->width, t->height);
    }
    *dist = out;
    *n = total;
    return true;
}

static bool up(struct cv_gpu *gpu, GLuint *b, size_t bytes, const void *data, const char *label,
               struct cv_error *err)
{
    *b = cv_gpu_storage_buffer(gpu, bytes, data, label, err);
    return *b != 0;
}

/* up() for a table the kernels read as a buffer texture of n texels of
 * texel_bytes each (shared/bindings.h says why those are not blocks). */
static bool up_texture(struct cv_gpu *gpu, GLuint *b, GLuint *tex, GLenum format,
                       size_t n, size_t texel_bytes, const void *data, const char *label,
                       struct cv_error *err)
{
    return up(gpu, b, n * texel_bytes, data, label, err) &&
           (*tex = cv_buffer_texture(*b, format, n, err)) != 0;
}

/* Page k of the grid store: texels [k x page, k x page + texels) as a
 * buffer and its rgba32f texture, what lies beyond the floats zero. */
static bool up_grid_page(const struct cv_scene *s, size_t page, size_t k, size_t texels,
                         GLuint *buf, GLuint *tex, struct cv_error *err)
{
    size_t first = k * page * 4, n = s->n_medium_grids - first;
    n = n < texels * 4 ? n : texels * 4;
    *buf = cv_buffer_create_uninit(texels * 16, "scene medium grids", err);
    if (!*buf)
        return false;
    const float zero[3] = {0, 0, 0};
    glNamedBufferSubData(*buf, 0, (GLsizeiptr)(n * sizeof(float)), s->medium_grids + first);
    if (texels * 4 > n)
        glNamedBufferSubData(*buf, (GLintptr)(n * sizeof(float)),
                             (GLsizeiptr)((texels * 4 - n) * sizeof(float)), zero);
    if (!cv_gl_check(err, "uploading %zu floats of grid media", n))
        return false;
    *tex = cv_buffer_texture(*buf, GL_RGBA32F, texels, err);
    return *tex != 0;
}

/* The grid media's floats as rgba32f buffer textures, four a texel
 * (glsl/trace/medium/grid.glsl), the last texel padded with zeros: one
 * texture holds GL_MAX_TEXTURE_BUFFER_SIZE texels, and where that is too
 * few the store goes on in pages of that many, one texture unit each from
 * CV_TEXUNIT_MEDIUM_GRID_PAGES up to GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS. A
 * scene beyond that fails here, before any rendering, at the first medium
 * whose floats do not fit, with its statement's location. The buffers are
 * never storage blocks, so the storage block size does not bound them. */
static bool up_medium_grids(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_scene_gpu *g,
                            struct cv_error *err)
{
    size_t n = s->n_medium_grids, texels = (n + 3) / 4;
    long long max = gpu->info.max_texture_buffer_texels;
    size_t page = max > 0 ? (size_t)max : texels;
    int units = gpu->info.max_compute_texture_units - CV_TEXUNIT_MEDIUM_GRID_PAGES + 1;
    size_t max_pages = units > 1 ? (size_t)units : 1, pages = (texels + page - 1) / page;
    if (pages > max_pages) {
        /* the first medium that ends beyond the store (a scene made by
         * hand has no sources) */
        size_t limit = max_pages * page * 4, start = 0, end = n;
        const char *at = "grid media";
        for (uint32_t i = 1; s->medium_sources && i < s->n_media; i++) {
            if (s->medium_sources[i].grid_end > limit) {
                at = s->medium_sources[i].at;
                end = s->medium_sources[i].grid_end;
                break;
            }
            start = s->medium_sources[i].grid_end;
        }
        return cv_fail(err, "%s: its grids take %zu floats (%.1f MiB), floats %zu to %zu of the "
                            "scene's grid store; this GPU's holds %zu floats (%.1f MiB: four a "
                            "texel of %zu buffer textures of GL_MAX_TEXTURE_BUFFER_SIZE %zu "
                            "texels, GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS %d)", at, end - start,
                       (end - start) * 4.0 / (1024 * 1024), start, end, limit,
                       limit * 4.0 / (1024 * 1024), max_pages, page,
                       gpu->info.max_compute_texture_units);
    }
    if (!up_grid_page(s, page, 0, texels < page ? texels : page, &g->medium_grids,
                      &g->medium_grids_tex, err))
        return false;
    g->n_grid_pages = (uint32_t)pages;
    if (pages == 1)
        return true;
    g->grid_pages = cv_xcalloc(pages - 1, sizeof(GLuint));
    g->grid_pages_tex = cv_xcalloc(pages - 1, sizeof(GLuint));
    for (size_t k = 1; k < pages; k++) {
        size_t t = texels - k * page < page ? texels - k * page : page;
        if (!up_grid_page(s, page, k, t, &g->grid_pages[k - 1], &g->grid_pages_tex[k - 1], err))
            return false;
    }
    snprintf(g->grid_pages_define, sizeof(g->grid_pages_define), "CV_MEDIUM_GRID_PAGES=%zu",
             pages);
    snprintf(g->grid_page_texels_define, sizeof(g->grid_page_texels_define),
             "CV_MEDIUM_GRID_PAGE_TEXELS=%zuu", page);
    return true;
}

/* The light-selection CDF of n lights (one texel at least) as a buffer
 * texture. */
static bool up_light_cdf(struct cv_gpu *gpu, struct cv_scene_gpu *g, uint32_t n, const float *cdf,
                         const char *label, struct cv_error *err)
{
    return up_texture(gpu, &g->light_cdf, &g->light_cdf_tex, GL_R32F, n ? n : 1, sizeof(float),
                      cdf, label, err);
}

/* Each triangle's ID-matte object as a buffer texture, where the driver's
 * buffer textures hold them all (else tri_object_tex stays 0). */
static bool up_tri_object(const struct cv_scene *s, struct cv_scene_gpu *g, struct cv_error *err)
{
    GLint max = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max);
    if (s->n_triangles == 0 || (max > 0 && s->n_triangles > (uint32_t)max))
        return true;
    g->tri_object_tex = cv_buffer_texture(g->tri_object, GL_R32UI, s->n_triangles, err);
    return g->tri_object_tex != 0;
}

/* The build's scratch (about 260 bytes per triangle) stays pooled for the
 * next scene's build, a batch's next job, while it is under a quarter of
 * the GPU's free memory: fresh scratch costs a build GPU time in
 * proportion to its size on its first use (gpu/buffer_pool.h;
 * bench/RESULTS.md, "Fresh and kept scratch"). Beyond that, or
 * where the driver does not say what is free (Mesa), it is freed, so that a
 * large scene's render never runs short for it. The same holds when a
 * scene is released and its BVH's own buffers (their size per triangle:
 * bvh/bvh.c) join the idle scratch. */
static void keep_or_trim(struct cv_gpu *gpu, size_t idle, const char *what)
{
    uint64_t total = 0, avail = 0;
    if (!cv_gpu_memory(gpu, &total, &avail) || idle > avail / 4) {
        cv_buffer_pool_trim(gpu->scratch);
        cv_debug("%s: BVH buffers freed (%zu MB idle)", what, idle >> 20);
    } else {
        cv_debug("%s: BVH buffers kept for the next build (%zu MB, %llu MB free)", what,
                 idle >> 20, (unsigned long long)(avail >> 20));
    }
}

/* The shade bins whose kernels read textures (cv_scene_gpu.textured_bins):
 * every bin where a light reads one, as emission is evaluated in every
 * bin, else those of the materials that do. */
static uint32_t textured_bins(const struct cv_scene *s, const CvLight *lights, uint32_t n_lights)
{
    for (uint32_t i = 0; i < n_lights; i++) {
        if (lights[i].tex >= 0)
            return ~0u;
        /* every bin's light samples read a textured cut-out */
        if ((lights[i].flags & CV_LIGHTF_ALPHA) &&
            s->materials[s->triangles[lights[i].prim].idx.w & CV_TRI_MATERIAL_MASK].alpha_tex >= 0)
            return ~0u;
    }
    return cv_shade_bins_textured(s->materials, s->n_materials);
}

void cv_scene_gpu_features(const struct cv_scene *s, struct cv_scene_gpu *g)
{
    for (uint32_t i = 0; i < s->n_lights; i++) {
        if (s->lights[i].type == CV_LIGHT_INFINITE || s->lights[i].type == CV_LIGHT_INFINITE_MAP)
            g->has_env = true;
        if (s->lights[i].flags & CV_LIGHTF_ALPHA)
            g->alpha_emitters = true;
    }
    g->spherical_camera = s->camera.type >= CV_CAMERA_EQUAL_AREA;
    g->has_textures = s->n_textures > 0;
    g->has_media = s->n_media > 0;
    g->has_medium_grids = s->n_medium_grids > 0;
    for (uint32_t i = 0; i < s->n_media; i++)
        if (s->media[i].type == CV_MEDIUM_CLOUD)
            g->has_medium_cloud = true;
    g->basic_materials = true;
    for (uint32_t i = 0; i < s->n_materials; i++) {
        const CvMaterial *m = &s->materials[i];
        if (m->alpha_tex >= 0 || m->alpha < 1 || m->type == CV_MAT_INTERFACE)
            g->has_alpha = true;
        if (m->type == CV_MAT_HAIR)
            g->has_hair = true;
        if (m->type == CV_MAT_SUBSURFACE)
            g->has_subsurface = true;
        if (m->type == CV_MAT_MEASURED)
            g->has_measured = true;
        if (m->flags & CV_MATF_COAT_CLOSED)
            g->has_coat_closed = true;
        if (m->flags & CV_MATF_CONDUCTOR_FRESNEL)
            g->has_conductor_fresnel = true;
        if ((m->type != CV_MAT_DIFFUSE && m->type != CV_MAT_MIRROR) || m->reflectance_tex >= 0 ||
            m->displacement_tex >= 0 || m->normal_tex >= 0)
            g->basic_materials = false;
    }
    if (g->has_alpha)
        g->basic_materials = false;
    cv_shade_bins_features(s->materials, s->n_materials, &g->shade_bins, &g->walk_coat_closed);
    g->textured_bins = textured_bins(s, s->lights, s->n_lights);
    g->walk_only = cv_shade_bins_walk_only(s->materials, s->n_materials);
    g->guided_bins = cv_shade_bins_guided(s->materials, s->n_materials);
    g->empty = s->n_triangles == 0 && s->n_curves == 0;
    g->has_curves = s->n_curves > 0;
    g->has_motion = s->n_motions > 0;
    g->no_triangles = cv_scene_static_triangles(s) == 0;
}

bool cv_scene_upload(struct cv_gpu *gpu, const struct cv_scene *s,
                     const struct cv_bvh_params *bvh, struct cv_scene_gpu *out,
                     struct cv_error *err)
{
    struct cv_scene_gpu g = {.gpu = gpu};
    cv_scene_gpu_features(s, &g);
    float *cdf = cv_xcalloc(s->n_lights ? s->n_lights : 1, sizeof(float));
    cv_light_cdf(s->light_power, s->n_lights, cdf);
    CvLight *lights = cv_xcalloc(s->n_lights ? s->n_lights : 1, sizeof(CvLight));
    if (s->n_lights)
        memcpy(lights, s->lights, s->n_lights * sizeof(CvLight));
    float *env = NULL;
    size_t n_env = 0;
    if (!build_env_dists(s, lights, &env, &n_env, err)) {
        free(cdf);
        free(lights);
        return false;
    }
    /* each material with its shade bin, for the intersect stage */
    CvMaterial *materials = cv_xcalloc(s->n_materials ? s->n_materials : 1, sizeof(CvMaterial));
    if (s->n_materials)
        memcpy(materials, s->materials, s->n_materials * sizeof(CvMaterial));
    cv_shade_bins_mark(materials, s->n_materials);
    bool ok =
        up(gpu, &g.vertices, s->n_vertices * sizeof(CvVertex), s->vertices, "scene vertices",
           err) &&
        up(gpu, &g.triangles, s->n_triangles * sizeof(CvTriangle), s->triangles,
           "scene triangles", err) &&
        up(gpu, &g.tri_light, s->n_triangles * sizeof(int32_t), s->tri_light,
           "scene triangle lights", err) &&
        /* NULL (a scene made by hand): object 0 everywhere */
        up(gpu, &g.tri_object, s->n_triangles * sizeof(uint32_t), s->tri_object,
           "scene triangle objects", err) &&
        up(gpu, &g.materials, s->n_materials * sizeof(CvMaterial), materials,
           "scene materials", err) &&
        up(gpu, &g.textures, s->n_textures * sizeof(CvTexture), s->textures, "scene textures",
           err) &&
        up(gpu, &g.texels, (size_t)s->n_texels * 8, s->texels, "scene texels", err) &&
        up(gpu, &g.lights, s->n_lights * sizeof(CvLight), lights, "scene lights", err) &&
        up_light_cdf(gpu, &g, s->n_lights, cdf, "scene light cdf", err) &&
        up_tri_object(s, &g, err) &&
        up(gpu, &g.env_dist, n_env * sizeof(float), env, "environment distributions", err) &&
        (s->n_media == 0 ||
         up_texture(gpu, &g.media, &g.media_tex, GL_RGBA32F,
                    (size_t)s->n_media * CV_MEDIUM_TEXELS, 16, s->media, "scene media", err)) &&
        (s->n_medium_grids == 0 || up_medium_grids(gpu, s, &g, err));
    free(cdf);
    free(lights);
    free(env);
    free(materials);
    if (!ok) {
        cv_scene_gpu_release(&g);
        return false;
    }
    if (g.has_measured && !up_texture(gpu, &g.measured, &g.measured_tex, GL_R32UI, s->n_measured,
                                      sizeof(uint32_t), s->measured, "measured BRDF tables",
                                      err)) {
        cv_scene_gpu_release(&g);
        return false;
    }
    if (s->n_bssrdf) {
        size_t n = (size_t)s->n_bssrdf * CV_BSSRDF_FLOATS;
        ok = up_texture(gpu, &g.bssrdf, &g.bssrdf_tex, GL_R32F, n, sizeof(float), s->bssrdf,
                        "BSSRDF tables", err);
        if (!ok) {
            cv_scene_gpu_release(&g);
            return false;
        }
    }
    if (g.has_conductor_fresnel) {
        size_t n = (size_t)s->n_conductor_fresnel * CV_CONDUCTOR_FRESNEL_N;
        ok = up_texture(gpu, &g.conductor_fresnel, &g.conductor_fresnel_tex, GL_RGBA32F, n,
                        4 * sizeof(float), s->conductor_fresnel, "conductor Fresnel tables", err);
        if (!ok) {
            cv_scene_gpu_release(&g);
            return false;
        }
    }
    size_t n_curve4 = 0, n_motion4 = 0;
    float *curve4 = g.has_curves ? cv_curve_bvh_pack(s->curves, s->n_curves, s->curve_xforms, s->n_curve_xforms,
                                                     s->n_motions, &n_curve4)
                                 : NULL;
    float *motion4 = g.has_motion ? cv_motion_bvh_pack(s, &n_motion4) : NULL;
    if (curve4)
        ok = up_texture(gpu, &g.curves, &g.curves_tex, GL_RGBA32F, n_curve4, 16, curve4,
                        "scene curves", err);
    if (ok && motion4)
        ok = up_texture(gpu, &g.motion, &g.motion_tex, GL_RGBA32F, n_motion4, 16, motion4,
                        "scene moving shapes", err);
    free(curve4);
    free(motion4);
    if (!ok) {
        cv_scene_gpu_release(&g);
        return false;
    }
    /* the static triangles' tree; moving shapes' triangles (after them)
     * have their own */
    uint32_t n_static = cv_scene_static_triangles(s);
    struct cv_bvh_params bp = bvh ? *bvh : cv_bvh_default_params();
    /* tests count this line to check that a batch builds each scene's BVH
     * once, and read the knobs that reached the build */
    if (n_static)
        cv_debug("building BVH for %s (%u triangles, %d treelet rounds, split budget %g)",
                 s->path ? s->path : "scene", n_static, bp.treelet_rounds,
                 bp.split_budget);
    if (n_static && !cv_bvh_build(gpu, g.vertices, g.triangles, n_static, &bp, &g.bvh, err)) {
        cv_error_prefix(err, "building the BVH: ");
        cv_scene_gpu_release(&g);
        return false;
    }
    keep_or_trim(gpu, cv_buffer_pool_settle(gpu->scratch), "after the build");
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
    glBindTextureUnit(CV_TEXUNIT_LIGHT_CDF, g->light_cdf_tex);
    cv_buffer_bind(g->env_dist, CV_BIND_ENV_DIST);
    if (g->tri_object_tex)
        glBindTextureUnit(CV_TEXUNIT_TRI_OBJECT, g->tri_object_tex);
    if (g->curves_tex)
        glBindTextureUnit(CV_TEXUNIT_CURVES, g->curves_tex);
    if (g->media_tex)
        glBindTextureUnit(CV_TEXUNIT_MEDIA, g->media_tex);
    if (g->medium_grids_tex)
        glBindTextureUnit(CV_TEXUNIT_MEDIUM_GRIDS, g->medium_grids_tex);
    for (uint32_t k = 1; k < g->n_grid_pages; k++)
        glBindTextureUnit(CV_TEXUNIT_MEDIUM_GRID_PAGES + k - 1, g->grid_pages_tex[k - 1]);
    if (g->motion_tex)
        glBindTextureUnit(CV_TEXUNIT_MOTION, g->motion_tex);
    if (g->bssrdf_tex)
        glBindTextureUnit(CV_TEXUNIT_BSSRDF, g->bssrdf_tex);
    if (g->measured_tex)
        glBindTextureUnit(CV_TEXUNIT_MEASURED, g->measured_tex);
    if (g->conductor_fresnel_tex)
        glBindTextureUnit(CV_TEXUNIT_CONDUCTOR_FRESNEL, g->conductor_fresnel_tex);
    if (g->bvh)
        cv_bvh_bind(g->bvh);
}

void cv_scene_gpu_release(struct cv_scene_gpu *g)
{
    if (g->base) {  /* a relit copy owns only what differs from its base */
        GLuint *own[] = {&g->lights, &g->light_cdf, &g->textures, &g->texels, &g->env_dist};
        const GLuint theirs[] = {0, 0, g->base->textures, g->base->texels, g->base->env_dist};
        for (size_t i = 0; i < CV_ARRAY_SIZE(own); i++)
            if (*own[i] != theirs[i])
                cv_buffer_destroy(own[i]);
        if (g->light_cdf_tex && g->light_cdf_tex != g->base->light_cdf_tex)
            glDeleteTextures(1, &g->light_cdf_tex);
        memset(g, 0, sizeof(*g));
        return;
    }
    GLuint *b[] = {&g->vertices, &g->triangles, &g->tri_light, &g->materials,
                   &g->textures, &g->texels, &g->lights, &g->light_cdf, &g->env_dist,
                   &g->tri_object, &g->curves, &g->media, &g->medium_grids,
                   &g->motion, &g->bssrdf,
                   &g->measured, &g->conductor_fresnel};
    for (size_t i = 0; i < CV_ARRAY_SIZE(b); i++)
        cv_buffer_destroy(b[i]);
    GLuint tex[] = {g->bssrdf_tex, g->curves_tex, g->motion_tex, g->measured_tex,
                    g->conductor_fresnel_tex, g->tri_object_tex, g->light_cdf_tex,
                    g->media_tex, g->medium_grids_tex};
    for (size_t i = 0; i < CV_ARRAY_SIZE(tex); i++)
        if (tex[i])
            glDeleteTextures(1, &tex[i]);
    for (uint32_t k = 1; k < g->n_grid_pages; k++) {
        if (g->grid_pages_tex && g->grid_pages_tex[k - 1])
            glDeleteTextures(1, &g->grid_pages_tex[k - 1]);
        if (g->grid_pages)
            cv_buffer_destroy(&g->grid_pages[k - 1]);
    }
    free(g->grid_pages);
    free(g->grid_pages_tex);
    bool had_bvh = g->bvh != NULL;
    cv_bvh_destroy(&g->bvh);
    if (had_bvh && g->gpu)
        keep_or_trim(g->gpu, cv_buffer_pool_idle(g->gpu->scratch), "scene released");
    memset(g, 0, sizeof(*g));
}

bool cv_scene_gpu_create(struct cv_gpu *gpu, const struct cv_scene *s,
                         const struct cv_bvh_params *bvh, struct cv_scene_gpu **out,
                         struct cv_error *err)
{
    struct cv_scene_gpu *g = cv_xcalloc(1, sizeof(*g));
    if (!cv_scene_upload(gpu, s, bvh, g, err)) {
        free(g);
        return false;
    }
    *out = g;
    return true;
}

void cv_scene_gpu_destroy(struct cv_scene_gpu **g)
{
    if (!g || !*g)
        return;
    cv_scene_gpu_release(*g);
    free(*g);
    *g = NULL;
}

/* The relit copy's new environment: the scene's textures then env's, the
 * scene's texels then env's, and the distributions of env's image. */
static bool upload_env(struct cv_gpu *gpu, const struct cv_scene *s, CvLight *lights,
                       const struct cv_scene *env, const CvTexture *env_textures,
                       struct cv_scene_gpu *g, struct cv_error *err)
{
    uint32_t nt = s->n_textures + env->n_textures;
    CvTexture *tex = cv_xcalloc(nt, sizeof(CvTexture));
    if (s->n_textures)
        memcpy(tex, s->textures, s->n_textures * sizeof(CvTexture));
    memcpy(tex + s->n_textures, env_textures, env->n_textures * sizeof(CvTexture));
    /* the distributions read env's texels: a view where the relit lights'
     * textures are env's own records (their own offsets) */
    CvTexture *local = cv_xcalloc(nt, sizeof(CvTexture));
    memcpy(local + s->n_textures, env->textures, env->n_textures * sizeof(CvTexture));
    struct cv_scene view = {.n_lights = s->n_lights, .textures = local, .n_textures = nt,
                            .texels = env->texels, .n_texels = env->n_texels};
    float *dist = NULL;
    size_t n_dist = 0;
    bool ok = build_env_dists(&view, lights, &dist, &n_dist, err);
    free(local);
    size_t base_bytes = (size_t)s->n_texels * 8, env_bytes = (size_t)env->n_texels * 8;
    ok = ok && up(gpu, &g->textures, nt * sizeof(CvTexture), tex, "scene textures (relit)", err) &&
         up(gpu, &g->texels, base_bytes + env_bytes, NULL, "scene texels (relit)", err) &&
         up(gpu, &g->env_dist, n_dist * sizeof(float), dist, "environment distributions (relit)",
            err);
    if (ok) {
        /* the scene's texels stay on the GPU: copied there, not uploaded again */
        if (base_bytes)
            glCopyNamedBufferSubData(g->base->texels, g->texels, 0, 0, (GLsizeiptr)base_bytes);
        glNamedBufferSubData(g->texels, (GLintptr)base_bytes, (GLsizeiptr)env_bytes, env->texels);
        ok = cv_gl_check(err, "cv_scene_gpu_relight: copying the texels");
    }
    free(tex);
    free(dist);
    g->has_textures = true;
    return ok;
}

bool cv_scene_gpu_relight(struct cv_gpu *gpu, const struct cv_scene_gpu *base,
                          const struct cv_scene *s, const CvLight *lights, const float *power,
                          const struct cv_scene *env, const CvTexture *env_textures,
                          struct cv_scene_gpu **out, struct cv_error *err)
{
    struct cv_scene_gpu g = *base;
    g.base = base;
    g.lights = g.light_cdf = g.light_cdf_tex = 0;
    uint32_t n = s->n_lights;
    CvLight *l = cv_xcalloc(n ? n : 1, sizeof(CvLight));
    float *cdf = cv_xcalloc(n ? n : 1, sizeof(float));
    if (n)
        memcpy(l, lights, n * sizeof(CvLight));
    bool ok = true;
    if (env)
        ok = upload_env(gpu, s, l, env, env_textures, &g, err);  /* sets the maps' prim */
    else
        env_offsets(s, l);
    g.textured_bins = textured_bins(s, l, n);  /* the lights as they now read textures */
    cv_light_cdf(power, n, cdf);
    ok = ok && up(gpu, &g.lights, n * sizeof(CvLight), l, "scene lights (relit)", err) &&
         up_light_cdf(gpu, &g, n, cdf, "scene light cdf (relit)", err);
    free(l);
    free(cdf);
    if (!ok) {
        cv_scene_gpu_release(&g);
        return false;
    }
    *out = cv_xmalloc(sizeof(**out));
    **out = g;
    return true;
}
