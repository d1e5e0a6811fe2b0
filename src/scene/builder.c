/* builder.c: graphics state bookkeeping and the growth of the flat scene:
 * meshes go in transformed to world space with their material word and
 * flags, emitting triangles become one area light each, object instances are
 * flattened (copied per instance: the scenes we target instance little, and
 * a flat list keeps the BVH and shaders simple). */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "scene/builder.h"
#include "scene/filter.h"

bool cv_b_warn(struct cv_builder *b, struct cv_error *err, const struct cv_loc *loc,
               const char *fmt, ...)
{
    char msg[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    b->s->warnings++;
    if (b->strict) {
        if (loc)
            return cv_fail(err, "%s:%d:%d: %s (--strict)", loc->file, loc->line, loc->col, msg);
        return cv_fail(err, "%s (--strict)", msg);
    }
    if (loc)
        cv_warn("%s:%d:%d: %s", loc->file, loc->line, loc->col, msg);
    else
        cv_warn("%s", msg);
    return true;
}

bool cv_b_check_unused(struct cv_builder *b, struct cv_params *ps, const char *directive,
                       struct cv_error *err)
{
    for (size_t i = 0; i < ps->n; i++) {
        struct cv_param *p = &ps->v[i];
        if (p->used)
            continue;
        struct cv_loc loc = {p->file, p->line, p->col};
        if (!cv_b_warn(b, err, &loc, "%s: parameter \"%s %s\" unused", directive,
                       cv_param_type_name(p->type), p->name))
            return false;
    }
    return true;
}

void cv_b_init(struct cv_builder *b, struct cv_scene *s, bool strict)
{
    memset(b, 0, sizeof(*b));
    b->s = s;
    b->strict = strict;
    b->gs.ctm = b->gs.ctm_end = cv_mat4_identity();
    b->gs.active = CV_XFORM_START | CV_XFORM_END;
    b->transform_times[1] = 1;
    b->shutter[1] = 1;
    b->gs.material = -1;
    b->gs.area.tex = -1;
    b->cur_object = -1;
    b->default_material = -1;
    b->camera_to_world = b->camera_to_world_end = cv_mat4_identity();
    b->fov = 90;
    b->focaldistance = 1e6;
    b->xres = 1280;
    b->yres = 720;
    b->crop[1] = b->crop[3] = 1;
    b->iso = 100;
    b->exposure_time = 1;
    b->film_exposure_time = 1;
    s->settings.spp = CV_DEFAULT_SPP;
    s->settings.max_depth = CV_DEFAULT_MAX_DEPTH;
    s->settings.filter = CV_FILTER_DEFAULT;
    s->settings.filter_radius[0] = s->settings.filter_radius[1] =
        cv_filter_info(CV_FILTER_DEFAULT)->radius;
    s->settings.filter_sigma = CV_FILTER_GAUSSIAN_SIGMA;
    s->settings.filter_b = CV_FILTER_MITCHELL_B;
    s->settings.filter_c = CV_FILTER_MITCHELL_C;
    s->settings.filter_tau = CV_FILTER_SINC_TAU;
    s->settings.exposure = 1;
    s->settings.crop[1] = s->settings.crop[3] = 1;
}

static void free_named(struct cv_named *v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i].name);
    free(v);
}

void cv_b_free(struct cv_builder *b)
{
    free(b->stack);
    free(b->stack_loc);
    free_named(b->materials_named, b->n_materials_named);
    free_named(b->float_tex, b->n_float_tex);
    free_named(b->spec_tex, b->n_spec_tex);
    free_named(b->images, b->n_images);
    free_named(b->media_named, b->n_media_named);
    free_named(b->measured_files, b->n_measured_files);
    free(b->media_copies);
    for (size_t i = 0; i < b->n_coordsys; i++)
        free(b->coordsys[i].name);
    free(b->coordsys);
    for (size_t i = 0; i < b->n_objects; i++) {
        free(b->objects[i].name);
        free(b->objects[i].v);
        free(b->objects[i].t);
        free(b->objects[i].c);
    }
    free(b->objects);
    free(b->color_space);
    free(b->main_dir);
    free(b->root);
    for (size_t i = 0; i < b->n_paths; i++)
        free(b->paths[i]);
    free(b->paths);
    memset(b, 0, sizeof(*b));
}

bool cv_b_set_root(struct cv_builder *b, const char *root, struct cv_error *err)
{
    char *real = realpath(root, NULL);
    struct stat st;
    if (!real || stat(real, &st) != 0 || !S_ISDIR(st.st_mode)) {
        bool exists = real != NULL;
        free(real);
        return cv_fail(err, "scene root \"%s\": %s", root,
                       exists ? "not a folder" : strerror(errno));
    }
    free(b->root);
    b->root = real;
    return true;
}

/* The test is on real paths, so neither "../" nor a symbolic link (to a
 * file or to a folder above) leads out. A file that does not exist is
 * judged by its folder, so that whether a file outside exists cannot be
 * learnt from the message; with no folder either, its reader reports it. */
bool cv_b_check_root(struct cv_builder *b, const char *path, struct cv_error *err)
{
    if (!b->root)
        return true;
    char *real = realpath(path, NULL);
    if (!real) {
        char *dir = cv_path_dirname(path);
        real = realpath(dir, NULL);
        free(dir);
        if (!real)
            return true;
    }
    size_t n = strlen(b->root);
    bool inside = strncmp(real, b->root, n) == 0 &&
                  (real[n] == '/' || real[n] == '\0' || b->root[n - 1] == '/');
    free(real);
    if (!inside)
        return cv_fail(err, "%s: outside the scene root %s (--scene-root)", path, b->root);
    return true;
}

char *cv_b_resolve(struct cv_builder *b, const char *dir, const char *name, struct cv_error *err)
{
    char *path = cv_path_join(dir, name);
    if (b->main_dir && !cv_path_exists(path)) {
        char *alt = cv_path_join(b->main_dir, name);
        if (cv_path_exists(alt)) {
            free(path);
            path = alt;
        } else {
            free(alt);
        }
    }
    if (!cv_b_check_root(b, path, err) || !cv_input_check(path, err)) {
        free(path);
        return NULL;
    }
    struct cv_scene *sc = b->s;
    size_t i = 0;
    while (i < sc->n_inputs && strcmp(sc->inputs[i], path) != 0)
        i++;
    if (i == sc->n_inputs)
        CV_PUSH(sc->inputs, sc->n_inputs, sc->cap_inputs, cv_xstrdup(path));
    return path;
}

int cv_b_lookup(const struct cv_named *v, size_t n, const char *name)
{
    for (size_t i = n; i-- > 0;)
        if (strcmp(v[i].name, name) == 0)
            return v[i].index;
    return -1;
}

void cv_b_set_named(struct cv_named **v, size_t *n, size_t *cap, const char *name, int index)
{
    for (size_t i = 0; i < *n; i++)
        if (strcmp((*v)[i].name, name) == 0) {
            (*v)[i].index = index;
            return;
        }
    struct cv_named e = {cv_xstrdup(name), index};
    CV_PUSH(*v, *n, *cap, e);
}

uint32_t cv_b_add_material(struct cv_builder *b, const CvMaterial *m, const char *name)
{
    struct cv_scene *s = b->s;
    size_t cap = b->cap_m, n = s->n_materials;
    CV_PUSH(s->materials, n, b->cap_m, *m);
    if (cap != b->cap_m) {
        s->material_names = cv_xrealloc(s->material_names, b->cap_m * sizeof(char *));
        s->material_at = cv_xrealloc(s->material_at, b->cap_m * sizeof(char *));
    }
    s->material_names[s->n_materials] = name ? cv_xstrdup(name) : NULL;
    s->material_at[s->n_materials] = NULL;
    s->n_materials = (uint32_t)n;
    return (uint32_t)(n - 1);
}

int cv_b_add_texture(struct cv_builder *b, const CvTexture *t)
{
    size_t n = b->s->n_textures;
    CV_PUSH(b->s->textures, n, b->cap_tex, *t);
    b->s->n_textures = (uint32_t)n;
    return (int)(n - 1);
}

uint32_t cv_b_add_light(struct cv_builder *b, const CvLight *l, float power)
{
    struct cv_scene *s = b->s;
    size_t cap = b->cap_l, n = s->n_lights;
    CV_PUSH(s->lights, n, b->cap_l, *l);
    s->lights[n - 1].flags |= (uint32_t)b->gs.medium_outside << CV_LIGHTF_MEDIUM_SHIFT;
    if (cap != b->cap_l) {
        s->light_power = cv_xrealloc(s->light_power, b->cap_l * sizeof(float));
        s->light_source = cv_xrealloc(s->light_source, b->cap_l * sizeof(uint32_t));
    }
    s->light_power[s->n_lights] = power;
    s->light_source[s->n_lights] = b->light_source;
    s->n_lights = (uint32_t)n;
    return (uint32_t)(n - 1);
}

uint32_t cv_b_light_source(struct cv_builder *b, const char *type, bool area,
                           const struct cv_loc *loc)
{
    struct cv_scene *s = b->s;
    size_t n = s->n_light_sources;
    struct cv_light_source ls = {
        .type = cv_xstrdup(type),
        .at = cv_xasprintf("%s:%d:%d", loc->file, loc->line, loc->col),
        .area = area,
    };
    CV_PUSH(s->light_sources, n, b->cap_light_sources, ls);
    s->n_light_sources = (uint32_t)n;
    return (uint32_t)(n - 1);
}

static uint32_t current_material(struct cv_builder *b)
{
    if (b->gs.material >= 0)
        return (uint32_t)b->gs.material;
    if (b->default_material < 0) {
        /* pbrt's default: diffuse, reflectance 0.5 */
        CvMaterial m;
        memset(&m, 0, sizeof(m));
        m.type = CV_MAT_DIFFUSE;
        m.reflectance = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
        m.displacement_tex = m.normal_tex = m.reflectance_tex = m.specular_tex = -1;
        m.roughness_u_tex = m.roughness_v_tex = m.alpha_tex = m.amount_tex = m.eta_tex = -1;
        m.mix_a = m.mix_b = -1;
        m.alpha = 1;
        b->default_material = (int)cv_b_add_material(b, &m, "(default)");
    }
    return (uint32_t)b->default_material;
}

uint32_t cv_b_current_material(struct cv_builder *b) { return current_material(b); }

static double tri_area(const CvVertex *v, const CvTriangle *t)
{
    const cv_vec4 *a = &v[t->idx.x].pos_u, *bb = &v[t->idx.y].pos_u, *c = &v[t->idx.z].pos_u;
    double e1[3] = {bb->x - a->x, bb->y - a->y, bb->z - a->z};
    double e2[3] = {c->x - a->x, c->y - a->y, c->z - a->z};
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2],
           z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static double luminance(const double rgb[3])
{
    return CV_LUMA(rgb[0], rgb[1], rgb[2]);
}

/* "file:line" with the file's base name: a name for what a directive made */
static char *loc_name(const struct cv_loc *loc)
{
    const char *slash = strrchr(loc->file, '/');
    return cv_xasprintf("%s:%d", slash ? slash + 1 : loc->file, loc->line);
}

void cv_b_material_at(struct cv_builder *b, int index, const struct cv_loc *loc)
{
    struct cv_scene *s = b->s;
    if (index < 0 || (uint32_t)index >= s->n_materials || s->material_at[index])
        return;
    s->material_at[index] = loc_name(loc);
}

uint32_t cv_b_add_object_at(struct cv_builder *b, const struct cv_loc *loc)
{
    char *at = loc_name(loc);
    uint32_t id = cv_b_add_object(b, at);
    free(at);
    return id;
}

uint32_t cv_b_add_object(struct cv_builder *b, const char *name)
{
    struct cv_scene *s = b->s;
    size_t n = s->n_objects;
    CV_PUSH(s->object_names, n, b->cap_object_names, cv_xstrdup(name));
    return s->n_objects++;
}

bool cv_b_emit_mesh(struct cv_builder *b, const struct cv_mesh *m, const struct cv_loc *loc,
                    struct cv_error *err)
{
    struct cv_scene *s = b->s;
    if (m->n_tris == 0)
        return true;
    struct cv_object *obj = b->cur_object >= 0 ? &b->objects[b->cur_object] : NULL;
    size_t nv0 = obj ? obj->nv : s->n_vertices;
    size_t nt0 = obj ? obj->nt : s->n_triangles;
    if (nv0 + m->n_verts > 0xffffffffu || nt0 + m->n_tris > 0xffffffffu)
        return cv_fail(err, "%s:%d:%d: scene exceeds 2^32 vertices or triangles", loc->file,
                       loc->line, loc->col);
    uint32_t mat = cv_b_material_in_media(b, current_material(b));
    if (mat > CV_TRI_MATERIAL_MASK)
        return cv_fail(err, "%s:%d:%d: more than 2^24 materials", loc->file, loc->line, loc->col);

    const struct cv_mat4 *M = &b->gs.ctm;
    struct cv_mat4 inv;
    cv_mat4_inverse(M, &inv);
    bool swaps = cv_mat4_det3(M) < 0;
    bool flip_n = m->analytic ? (b->gs.reverse != swaps) : b->gs.reverse;
    uint32_t flags = mat;
    if (m->uv)
        flags |= CV_TRI_HAS_UV;
    if (m->N)
        flags |= CV_TRI_HAS_NORMAL;
    if (b->gs.reverse != swaps)
        flags |= CV_TRI_REVERSE;

    CvVertex *V;
    CvTriangle *T;
    size_t need_v = nv0 + m->n_verts, need_t = nt0 + m->n_tris;
    if (obj) {
        obj->v = cv_xgrow(obj->v, &obj->cap_v, need_v, sizeof(CvVertex));
        obj->t = cv_xgrow(obj->t, &obj->cap_t, need_t, sizeof(CvTriangle));
        V = obj->v;
        T = obj->t;
    } else {
        size_t cap_t = b->cap_t;
        s->vertices = cv_xgrow(s->vertices, &b->cap_v, need_v, sizeof(CvVertex));
        s->triangles = cv_xgrow(s->triangles, &b->cap_t, need_t, sizeof(CvTriangle));
        if (cap_t != b->cap_t) {
            s->tri_light = cv_xrealloc(s->tri_light, b->cap_t * sizeof(int32_t));
            s->tri_object = cv_xrealloc(s->tri_object, b->cap_t * sizeof(uint32_t));
        }
        V = s->vertices;
        T = s->triangles;
    }
    /* The hot loop of big meshes: affine transforms (all pbrt gives but a
     * perspective Transform) go inline, in double like pbrt. */
    const double(*mm)[4] = M->m;
    bool affine = mm[3][0] == 0 && mm[3][1] == 0 && mm[3][2] == 0 && mm[3][3] == 1;
    double sgn = flip_n ? -1 : 1;
    int finite = 1;
    for (size_t i = 0; i < m->n_verts; i++) {
        double p[3] = {m->P[3 * i], m->P[3 * i + 1], m->P[3 * i + 2]}, w[3];
        if (affine) {
            for (int r = 0; r < 3; r++)
                w[r] = mm[r][0] * p[0] + mm[r][1] * p[1] + mm[r][2] * p[2] + mm[r][3];
        } else {
            cv_mat4_point(M, p, w);
        }
        CvVertex *v = &V[nv0 + i];
        v->pos_u = (cv_vec4){(float)w[0], (float)w[1], (float)w[2], m->uv ? m->uv[2 * i] : 0};
        finite &= isfinite(v->pos_u.x) & isfinite(v->pos_u.y) & isfinite(v->pos_u.z);
        v->nrm_v = (cv_vec4){0, 0, 0, m->uv ? m->uv[2 * i + 1] : 0};
        if (m->N) {
            double n[3] = {m->N[3 * i], m->N[3 * i + 1], m->N[3 * i + 2]}, o[3];
            cv_mat4_normal(&inv, n, o);
            double l = sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]);
            if (l > 0)
                l = sgn / l;
            v->nrm_v.x = (float)(o[0] * l);
            v->nrm_v.y = (float)(o[1] * l);
            v->nrm_v.z = (float)(o[2] * l);
        }
    }
    if (!finite) /* the arrays grew, but their lengths below are not committed */
        return cv_fail(err, "%s:%d:%d: vertex positions are not finite after the transform",
                       loc->file, loc->line, loc->col);
    for (size_t i = 0; i < m->n_tris; i++)
        T[nt0 + i].idx = (cv_uvec4){(uint32_t)nv0 + m->idx[3 * i], (uint32_t)nv0 + m->idx[3 * i + 1],
                                    (uint32_t)nv0 + m->idx[3 * i + 2], flags};
    if (obj) {
        obj->nv = need_v;
        obj->nt = need_t;
        if (b->gs.area.on && !cv_b_warn(b, err, loc, "area lights inside object definitions are ignored (as in pbrt)"))
            return false;
        return true;
    }
    s->n_vertices = (uint32_t)need_v;
    s->n_triangles = (uint32_t)need_t;
    for (size_t i = nt0; i < need_t; i++)
        s->tri_light[i] = -1;
    uint32_t object = m->object;
    if (!object) {
        object = (m->name ? cv_b_add_object(b, m->name) : cv_b_add_object_at(b, loc)) + 1;
    }
    for (size_t i = nt0; i < need_t; i++)
        s->tri_object[i] = object - 1;
    /* pbrt-v4 drops the area light of a shape whose material is
     * "interface" (or "none" or ""), with a warning (its scene.cpp) */
    bool emits = b->gs.area.on;
    const CvMaterial *em = &s->materials[mat & CV_TRI_MATERIAL_MASK];
    if (emits && em->type == CV_MAT_INTERFACE) {
        if (!cv_b_warn(b, err, loc, "the area light of a shape with the \"interface\" material is "
                       "ignored, as pbrt-v4 ignores it"))
            return false;
        emits = false;
    }
    /* pbrt-v4 hands an emitting shape's alpha to its area light
     * (DiffuseAreaLight::AlphaMasked) */
    bool cut_out = em->alpha < 1 || em->alpha_tex >= 0;
    if (emits) {
        const struct cv_area_state *a = &b->gs.area;
        double L[3] = {a->L[0], a->L[1], a->L[2]};
        double sides = a->twosided ? 2 : 1;
        if (a->power > 0) {
            double total = 0;
            for (size_t i = nt0; i < need_t; i++)
                total += tri_area(V, &T[i]);
            /* pbrt-v4's k_e: an image's mean luminance, the area, pi, the
             * sides (lights.cpp: DiffuseAreaLight::Create) */
            double mean = a->tex >= 0 ? cv_scene_texture_luminance(s, &s->textures[a->tex]) : 1;
            double k = M_PI * sides * total * mean;
            if (k > 0)
                for (int c = 0; c < 3; c++)
                    L[c] *= a->power / k;
        }
        double y = luminance(L);
        b->light_source = a->source;
        for (size_t i = nt0; i < need_t; i++) {
            double area = tri_area(V, &T[i]);
            CvLight l;
            memset(&l, 0, sizeof(l));
            l.type = CV_LIGHT_AREA;
            l.flags = (a->twosided ? CV_LIGHTF_TWO_SIDED : 0) | (cut_out ? CV_LIGHTF_ALPHA : 0);
            l.tex = a->tex;
            l.prim = (uint32_t)i;
            l.L = (cv_vec4){(float)L[0], (float)L[1], (float)L[2], (float)area};
            double power = y * area * M_PI * sides;
            if (a->tex >= 0 && !(power > 0))
                power = area * M_PI * sides; /* textured: texture scale unknown here */
            s->tri_light[i] = (int32_t)cv_b_add_light(b, &l, (float)power);
        }
    }
    return true;
}

bool cv_b_instance(struct cv_builder *b, int index, const struct cv_loc *loc, struct cv_error *err)
{
    struct cv_object *o = &b->objects[index];
    if (!o->matte_object && b->cur_object < 0 && (o->nt || o->nc))
        o->matte_object = cv_b_add_object(b, o->name) + 1;
    /* the definition's curves, placed as its triangles are */
    if (o->nc && !cv_b_place_curves(b, o->c, o->nc, &b->gs.ctm, b->cur_object < 0 ? o->matte_object - 1 : UINT32_MAX,
                                    loc, err))
        return false;
    if (o->nt == 0)
        return true;
    /* Object vertices are already in the space of their definition; the
     * instance transform goes on top (pbrt: render-from-instance). */
    float *P = cv_xmalloc(o->nv * 3 * sizeof(float));
    float *N = cv_xmalloc(o->nv * 3 * sizeof(float));
    float *uv = cv_xmalloc(o->nv * 2 * sizeof(float));
    uint32_t *idx = cv_xmalloc(o->nt * 3 * sizeof(uint32_t));
    for (size_t i = 0; i < o->nv; i++) {
        P[3 * i] = o->v[i].pos_u.x;
        P[3 * i + 1] = o->v[i].pos_u.y;
        P[3 * i + 2] = o->v[i].pos_u.z;
        N[3 * i] = o->v[i].nrm_v.x;
        N[3 * i + 1] = o->v[i].nrm_v.y;
        N[3 * i + 2] = o->v[i].nrm_v.z;
        uv[2 * i] = o->v[i].pos_u.w;
        uv[2 * i + 1] = o->v[i].nrm_v.w;
    }
    for (size_t i = 0; i < o->nt; i++) {
        idx[3 * i] = o->v ? o->t[i].idx.x : 0;
        idx[3 * i + 1] = o->t[i].idx.y;
        idx[3 * i + 2] = o->t[i].idx.z;
    }
    /* Emit with a neutral graphics state except the transform; then restore
     * the per-triangle words of the definition (material, flags). */
    struct cv_gstate saved = b->gs;
    b->gs.reverse = false;
    b->gs.area.on = false;
    struct cv_mesh m = {o->nv, o->nt, P, N, uv, idx, false, o->name, o->matte_object};
    size_t nt0 = b->s->n_triangles;
    bool ok = cv_b_emit_mesh(b, &m, loc, err);
    b->gs = saved;
    if (ok) {
        CvTriangle *T = b->cur_object >= 0 ? b->objects[b->cur_object].t + b->objects[b->cur_object].nt - o->nt
                                           : b->s->triangles + nt0;
        bool swaps = cv_mat4_det3(&b->gs.ctm) < 0;
        for (size_t i = 0; i < o->nt; i++) {
            uint32_t w = o->t[i].idx.w;
            if (swaps)
                w ^= CV_TRI_REVERSE;
            T[i].idx.w = w;
        }
    }
    free(P);
    free(N);
    free(uv);
    free(idx);
    return ok;
}

static void rows3x4(const struct cv_mat4 *a, double m[3][4])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m[r][c] = a->m[r][c];
}

bool cv_b_can_move(struct cv_builder *b, const char *type, const char **why)
{
    *why = NULL;
    if (memcmp(&b->gs.ctm, &b->gs.ctm_end, sizeof(b->gs.ctm)) == 0)
        return false;
    struct cv_animated a;
    double m0[3][4], m1[3][4];
    rows3x4(&b->gs.ctm, m0);
    rows3x4(&b->gs.ctm_end, m1);
    if (b->cur_object >= 0)
        *why = "shapes moving inside an object definition are not rendered moving";
    else if (b->gs.area.on && type)
        *why = "moving area lights are not rendered moving (nor by pbrt-v4)";
    else if (b->gs.ctm.m[3][0] != 0 || b->gs.ctm.m[3][1] != 0 || b->gs.ctm.m[3][2] != 0 ||
             b->gs.ctm_end.m[3][0] != 0 || b->gs.ctm_end.m[3][1] != 0 || b->gs.ctm_end.m[3][2] != 0 ||
             !cv_animated_init(&a, m0, b->transform_times[0], m1, b->transform_times[1]))
        *why = "a projective or singular transform cannot be interpolated";
    else if (!a.moving)
        *why = "TransformTimes do not increase";
    return *why == NULL;
}

/* Grows [lo, hi] by curve c: its control points bound the piece, half
 * the wider end's width around them (float rounding: within
 * cv_animated_bounds's margin). */
static void curve_box_grow(const struct cv_scene *s, const CvCurve *c, float lo[3], float hi[3])
{
    double r = 0.5 * fmax(c->cp[0].w, c->cp[1].w), l[3] = {INFINITY, INFINITY, INFINITY},
           h[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 4; k++)
        for (int a = 0; a < 3; a++) {
            l[a] = fmin(l[a], (&c->cp[k].x)[a] - r);
            h[a] = fmax(h[a], (&c->cp[k].x)[a] + r);
        }
    uint32_t xf = c->info.y >> CV_CURVE_XF_SHIFT;
    if (xf) /* in the curve's own object space (scene.h, CvCurveXform) */
        cv_curve_xform_box(&s->curve_xforms[xf - 1], l, h, l, h);
    for (int a = 0; a < 3; a++) {
        lo[a] = fminf(lo[a], (float)l[a]);
        hi[a] = fmaxf(hi[a], (float)h[a]);
    }
}

/* pbrt-v4's render space origin (its default "cameraworld"): the camera's
 * position at the middle of its transform times. pbrt-v4 interpolates a
 * moving shape's render-from-object transform, which differs from
 * world-from-object by a fixed translation, so the interpolation is the
 * same; but a moving instance's render-from-instance is
 * render-from-world * world-from-instance * world-from-render, whose
 * interpolated translation moves the instance's point at the camera's
 * position (not its origin) along a line. Emitting the instance about
 * that point and interpolating world-from-instance * translate(c)
 * reproduces it: a turning instance sweeps about the camera as there. */
static void render_origin(const struct cv_builder *b, double c[3])
{
    double m0[3][4], m1[3][4], m[3][4];
    rows3x4(&b->camera_to_world, m0);
    rows3x4(&b->camera_to_world_end, m1);
    struct cv_animated a;
    if (cv_animated_init(&a, m0, b->transform_times[0], m1, b->transform_times[1]))
        cv_animated_at(&a, 0.5 * (b->transform_times[0] + b->transform_times[1]), m);
    else
        memcpy(m, m0, sizeof(m));
    for (int i = 0; i < 3; i++)
        c[i] = m[i][3];
}

void cv_b_motion_begin(struct cv_builder *b, bool instance)
{
    b->motion_ctm = b->gs.ctm;
    double c[3] = {0, 0, 0};
    if (instance)
        render_origin(b, c);
    b->motion_pivot = cv_mat4_translate(c[0], c[1], c[2]);
    b->gs.ctm = cv_mat4_translate(-c[0], -c[1], -c[2]);
    b->motion_nt0 = b->s->n_triangles;
    b->motion_nv0 = b->s->n_vertices;
    b->motion_nc0 = b->s->n_curves;
}

void cv_b_motion_end(struct cv_builder *b)
{
    struct cv_scene *s = b->s;
    b->gs.ctm = b->motion_ctm;
    if (s->n_triangles == b->motion_nt0 && s->n_curves == b->motion_nc0)
        return;
    s->motions = cv_xgrow(s->motions, &b->cap_motions, s->n_motions + 1, sizeof(*s->motions));
    struct cv_motion *m = &s->motions[s->n_motions++];
    *m = (struct cv_motion){.first = b->motion_nt0, .count = s->n_triangles - b->motion_nt0,
                            .first_vertex = b->motion_nv0, .n_vertices = s->n_vertices - b->motion_nv0,
                            .first_curve = b->motion_nc0, .n_curves = s->n_curves - b->motion_nc0};
    double m0[3][4], m1[3][4];
    struct cv_mat4 w0 = cv_mat4_mul(&b->gs.ctm, &b->motion_pivot),
                   w1 = cv_mat4_mul(&b->gs.ctm_end, &b->motion_pivot);
    rows3x4(&w0, m0);
    rows3x4(&w1, m1);
    cv_animated_init(&m->xf, m0, b->transform_times[0], m1, b->transform_times[1]); /* cv_b_can_move checked it */
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t v = m->first_vertex; v < m->first_vertex + m->n_vertices; v++)
        for (int c = 0; c < 3; c++) {
            lo[c] = fminf(lo[c], (&s->vertices[v].pos_u.x)[c]);
            hi[c] = fmaxf(hi[c], (&s->vertices[v].pos_u.x)[c]);
        }
    for (uint32_t i = m->first_curve; i < m->first_curve + m->n_curves; i++) {
        CvCurve *cu = &s->curves[i];
        cu->info.w = s->n_motions; /* 1 + the shape's index */
        curve_box_grow(s, cu, lo, hi);
    }
    cv_animated_bounds(&m->xf, lo, hi, m->lo, m->hi);
}

/* Moves the moving shapes' triangles after all static ones (scene.h), the
 * per-triangle arrays and area lights' triangle indices with them. */
static void order_motions(struct cv_scene *s)
{
    if (s->n_motions == 0)
        return;
    uint32_t n = s->n_triangles, k = 0;
    uint32_t *to = cv_xmalloc(n * sizeof(uint32_t));
    bool *moving = cv_xcalloc(n, sizeof(bool));
    for (uint32_t m = 0; m < s->n_motions; m++)
        for (uint32_t t = 0; t < s->motions[m].count; t++)
            moving[s->motions[m].first + t] = true;
    for (uint32_t t = 0; t < n; t++)
        if (!moving[t])
            to[t] = k++;
    for (uint32_t m = 0; m < s->n_motions; m++) {
        uint32_t first = s->motions[m].first;
        s->motions[m].first = k;
        for (uint32_t t = 0; t < s->motions[m].count; t++)
            to[first + t] = k++;
    }
    CvTriangle *tri = cv_xmalloc(n * sizeof(CvTriangle));
    int32_t *tl = cv_xmalloc(n * sizeof(int32_t));
    uint32_t *to_obj = cv_xmalloc(n * sizeof(uint32_t));
    for (uint32_t t = 0; t < n; t++) {
        tri[to[t]] = s->triangles[t];
        tl[to[t]] = s->tri_light[t];
        to_obj[to[t]] = s->tri_object[t];
    }
    memcpy(s->triangles, tri, n * sizeof(CvTriangle));
    memcpy(s->tri_light, tl, n * sizeof(int32_t));
    memcpy(s->tri_object, to_obj, n * sizeof(uint32_t));
    for (uint32_t i = 0; i < s->n_lights; i++)
        if (s->lights[i].type == CV_LIGHT_AREA)
            s->lights[i].prim = to[s->lights[i].prim];
    free(tri);
    free(tl);
    free(to_obj);
    free(moving);
    free(to);
}

static bool is_infinite(const CvLight *l)
{
    return l->type == CV_LIGHT_INFINITE || l->type == CV_LIGHT_INFINITE_MAP;
}

/* Puts the infinite lights first (each group in file order), as the scene
 * promises (scene.h): the GPU finds the environment by walking the lights
 * up to the first other one. Light indices elsewhere (tri_light) follow;
 * light_power moves with its light. */
static void order_lights(struct cv_scene *s)
{
    uint32_t n = s->n_lights, k = 0;
    if (n == 0)
        return;
    uint32_t *to = cv_xmalloc(n * sizeof(uint32_t));
    for (int pass = 0; pass < 2; pass++)
        for (uint32_t i = 0; i < n; i++)
            if (is_infinite(&s->lights[i]) == (pass == 0))
                to[i] = k++;
    CvLight *l = cv_xmalloc(n * sizeof(CvLight));
    float *pw = cv_xmalloc(n * sizeof(float));
    uint32_t *src = cv_xmalloc(n * sizeof(uint32_t));
    for (uint32_t i = 0; i < n; i++) {
        l[to[i]] = s->lights[i];
        pw[to[i]] = s->light_power[i];
        src[to[i]] = s->light_source[i];
    }
    memcpy(s->lights, l, n * sizeof(CvLight));
    memcpy(s->light_power, pw, n * sizeof(float));
    memcpy(s->light_source, src, n * sizeof(uint32_t));
    free(src);
    for (uint32_t t = 0; t < s->n_triangles; t++)
        if (s->tri_light[t] >= 0)
            s->tri_light[t] = (int32_t)to[s->tri_light[t]];
    free(to);
    free(l);
    free(pw);
}

bool cv_b_finish(struct cv_builder *b, struct cv_error *err)
{
    struct cv_scene *s = b->s;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    /* moving shapes' vertices are in object space: their motion boxes count */
    bool *moving = cv_xcalloc(s->n_vertices ? s->n_vertices : 1, sizeof(bool));
    for (uint32_t m = 0; m < s->n_motions; m++) {
        for (uint32_t v = 0; v < s->motions[m].n_vertices; v++)
            moving[s->motions[m].first_vertex + v] = true;
        for (int c = 0; c < 3; c++) {
            lo[c] = fmin(lo[c], s->motions[m].lo[c]);
            hi[c] = fmax(hi[c], s->motions[m].hi[c]);
        }
    }
    for (size_t i = 0; i < s->n_vertices; i++) {
        if (moving[i])
            continue;
        const float *p = &s->vertices[i].pos_u.x;
        for (int c = 0; c < 3; c++) {
            if (p[c] < lo[c])
                lo[c] = p[c];
            if (p[c] > hi[c])
                hi[c] = p[c];
        }
    }
    free(moving);
    for (size_t i = 0; i < s->n_curves; i++) {
        /* control points bound the piece; half the widest width around them */
        const CvCurve *cu = &s->curves[i];
        if (cu->info.w) /* moving: in its shape's motion box */
            continue;
        double r = 0.5 * fmax(cu->cp[0].w, cu->cp[1].w);
        for (int k = 0; k < 4; k++) {
            const float *p = &cu->cp[k].x;
            for (int c = 0; c < 3; c++) {
                lo[c] = fmin(lo[c], p[c] - r);
                hi[c] = fmax(hi[c], p[c] + r);
            }
        }
    }
    for (int c = 0; c < 3; c++) {
        s->bounds_min[c] = s->n_vertices || s->n_curves ? (float)lo[c] : 0;
        s->bounds_max[c] = s->n_vertices || s->n_curves ? (float)hi[c] : 0;
    }
    /* Distant and infinite lights scale with the scene's bounding sphere. */
    double r = 0;
    for (int c = 0; c < 3; c++)
        r += (double)(s->bounds_max[c] - s->bounds_min[c]) * (s->bounds_max[c] - s->bounds_min[c]);
    r = 0.5 * sqrt(r);
    for (size_t i = 0; i < s->n_lights; i++) {
        CvLight *l = &s->lights[i];
        double rgb[3] = {l->L.x, l->L.y, l->L.z};
        if (l->type == CV_LIGHT_DISTANT)
            s->light_power[i] = (float)(M_PI * r * r * luminance(rgb));
        else if (l->type == CV_LIGHT_INFINITE || l->type == CV_LIGHT_INFINITE_MAP)
            s->light_power[i] = (float)(4 * M_PI * M_PI * r * r * luminance(rgb) *
                                        (l->type == CV_LIGHT_INFINITE_MAP ? s->light_power[i] : 1));
    }
    if (b->cur_object >= 0)
        return cv_fail(err, "ObjectBegin \"%s\" not closed at end of input", b->objects[b->cur_object].name);
    order_lights(s);
    order_motions(s);
    cv_b_finish_camera(b);
    return true;
}
