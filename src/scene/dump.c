/* dump.c: see dump.h. The geometry checksum hashes positions rounded to about 5
 * significant digits, triangle by triangle, so two loads of the same scene
 * written in different syntaxes compare equal. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/dump.h"

static const char *mat_type(uint32_t t)
{
    static const char *const n[] = {"diffuse", "conductor", "dielectric", "thindielectric",
                                    "mirror", "coateddiffuse", "coatedconductor",
                                    "diffusetransmission", "mix", "interface", "plastic", "hair",
                                    "subsurface", "measured"};
    return t < sizeof(n) / sizeof(n[0]) ? n[t] : "?";
}

static const char *light_type(uint32_t t)
{
    static const char *const n[] = {"point", "spot", "distant", "area", "infinite", "infinite-map"};
    return t < sizeof(n) / sizeof(n[0]) ? n[t] : "?";
}

static const char *tex_type(uint32_t t)
{
    static const char *const n[] = {"constant", "image", "checkerboard", "scale", "mix"};
    return t < sizeof(n) / sizeof(n[0]) ? n[t] : "?";
}

static void v4(FILE *o, const char *name, cv_vec4 v)
{
    fprintf(o, " %s=(%.6g %.6g %.6g %.6g)", name, v.x, v.y, v.z, v.w);
}

static uint64_t mix64(uint64_t h, uint64_t v)
{
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    return h;
}

/* Hashes f rounded to 17 bits of mantissa (about 5 significant digits). */
static uint64_t qhash(uint64_t h, float f)
{
    if (f == 0 || !isfinite(f)) /* -0 == 0 */
        return mix64(h, f == 0 ? 0 : 1);
    int e;
    double m = frexp((double)f, &e);
    long long q = llround(m * 131072.0);
    return mix64(mix64(h, (uint64_t)q), (uint64_t)(e + 2048));
}

void cv_scene_dump(const struct cv_scene *s, FILE *o)
{
    const struct cv_render_settings *st = &s->settings;
    const CvCamera *c = &s->camera;
    fprintf(o, "cavalry-scene-dump 1\n");
    fprintf(o, "film %ux%u crop %.6g %.6g %.6g %.6g exposure %.6g\n", st->width, st->height,
            st->crop[0], st->crop[1], st->crop[2], st->crop[3], st->exposure);
    fprintf(o, "film.filename %s\n", st->film_filename ? st->film_filename : "-");
    fprintf(o, "sampler %s spp %u\n", st->sampler ? st->sampler : "-", st->spp);
    fprintf(o, "integrator %s maxdepth %u\n", st->integrator ? st->integrator : "-", st->max_depth);
    fprintf(o, "filter %d radius %.6g %.6g sigma %.6g\n", (int)st->filter, st->filter_radius[0],
            st->filter_radius[1], st->filter_sigma);
    static const char *const types[] = {
        [CV_CAMERA_PERSPECTIVE] = "perspective",
        [CV_CAMERA_ORTHOGRAPHIC] = "orthographic",
        [CV_CAMERA_EQUAL_AREA] = "spherical-equalarea",
        [CV_CAMERA_EQUIRECT] = "spherical-equirectangular",
    };
    fprintf(o, "camera %s", c->type < CV_ARRAY_SIZE(types) ? types[c->type] : "?");
    v4(o, "row0", c->to_world[0]);
    v4(o, "row1", c->to_world[1]);
    v4(o, "row2", c->to_world[2]);
    v4(o, "screen", c->screen);
    v4(o, "lens", c->lens);
    fprintf(o, " film=(%u %u %u %u) crop=(%u %u)\n", c->film.x, c->film.y, c->film.z, c->film.w,
            c->crop.x, c->crop.y);
    fprintf(o, "vertices %u\ntriangles %u\n", s->n_vertices, s->n_triangles);
    if (s->n_curves)
        fprintf(o, "curves %u\n", s->n_curves);
    if (s->n_motions)  /* their triangles are counted above, in object space */
        fprintf(o, "moving shapes %u triangles %u\n", s->n_motions, s->n_triangles - cv_scene_static_triangles(s));
    fprintf(o, "bounds %.6g %.6g %.6g  %.6g %.6g %.6g\n", s->bounds_min[0], s->bounds_min[1],
            s->bounds_min[2], s->bounds_max[0], s->bounds_max[1], s->bounds_max[2]);
    uint64_t h = 1469598103934665603ull;
    double area = 0;
    unsigned n_uv = 0, n_n = 0, n_rev = 0;
    for (uint32_t i = 0; i < s->n_triangles; i++) {
        const cv_uvec4 *t = &s->triangles[i].idx;
        uint32_t id[3] = {t->x, t->y, t->z};
        double p[3][3];
        for (int k = 0; k < 3; k++) {
            const CvVertex *v = &s->vertices[id[k]];
            h = qhash(qhash(qhash(h, v->pos_u.x), v->pos_u.y), v->pos_u.z);
            p[k][0] = v->pos_u.x;
            p[k][1] = v->pos_u.y;
            p[k][2] = v->pos_u.z;
        }
        h = mix64(h, t->w);
        double e1[3], e2[3];
        for (int d = 0; d < 3; d++) {
            e1[d] = p[1][d] - p[0][d];
            e2[d] = p[2][d] - p[0][d];
        }
        double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2],
               z = e1[0] * e2[1] - e1[1] * e2[0];
        area += 0.5 * sqrt(x * x + y * y + z * z);
        n_uv += (t->w & CV_TRI_HAS_UV) != 0;
        n_n += (t->w & CV_TRI_HAS_NORMAL) != 0;
        n_rev += (t->w & CV_TRI_REVERSE) != 0;
    }
    fprintf(o, "geometry area %.6g hash %016llx with-uv %u with-normals %u reversed %u\n", area,
            (unsigned long long)h, n_uv, n_n, n_rev);
    fprintf(o, "materials %u\n", s->n_materials);
    unsigned *uses = calloc(s->n_materials + 1, sizeof(unsigned));
    for (uint32_t t = 0; uses && t < s->n_triangles; t++) {
        uint32_t mi = s->triangles[t].idx.w & CV_TRI_MATERIAL_MASK;
        if (mi < s->n_materials)
            uses[mi]++;
    }
    for (uint32_t i = 0; i < s->n_materials; i++) {
        const CvMaterial *m = &s->materials[i];
        unsigned used = uses ? uses[i] : 0;
        fprintf(o, "  material %u \"%s\" %s flags %u tris %u", i,
                s->material_names[i] ? s->material_names[i] : "", mat_type(m->type), m->flags, used);
        v4(o, "refl", m->reflectance);
        v4(o, "spec", m->specular);
        v4(o, "eta", m->eta);
        v4(o, "k", m->k);
        v4(o, "rough", m->roughness);
        v4(o, "rough2", m->roughness2);
        fprintf(o, " tex=(%d %d %d %d %d %d %d %d) alpha %.6g mix=(%d %d %.6g %d)\n",
                m->reflectance_tex, m->specular_tex, m->roughness_u_tex, m->roughness_v_tex,
                m->displacement_tex, m->normal_tex, m->alpha_tex, m->eta_tex, m->alpha, m->mix_a,
                m->mix_b, m->amount, m->amount_tex);
        if (m->media)
            fprintf(o, "    media inside %u outside %u\n", m->media & 255u, (m->media >> 8) & 255u);
    }
    free(uses);
    /* measured BRDF tables likewise */
    if (s->n_measured)
        fprintf(o, "measured tables %zu words\n", s->n_measured);
    /* media only where the scene has them: other scenes' dumps stay as they were */
    if (s->n_media) {
        fprintf(o, "media %u camera %u\n", s->n_media - 1, s->camera_medium);
        for (uint32_t i = 1; i < s->n_media; i++) {
            const CvMedium *m = &s->media[i];
            static const char *const names[] = {"vacuum", "homogeneous", "uniformgrid", "rgbgrid",
                                                "cloud", "nanovdb"};
            fprintf(o, "  medium %u %s", i, m->type < sizeof(names) / sizeof(names[0]) ? names[m->type] : "?");
            if (m->type == CV_MEDIUM_UNIFORMGRID || m->type == CV_MEDIUM_RGBGRID ||
                m->type == CV_MEDIUM_NANOVDB)
                fprintf(o, " grid %ux%ux%u", m->res.x, m->res.y, m->res.z);
            v4(o, "sigma_a", m->sigma_a);
            v4(o, "sigma_s", m->sigma_s);
            v4(o, "Le", m->Le);
            fprintf(o, "\n");
        }
    }
    fprintf(o, "textures %u texels %llu\n", s->n_textures, (unsigned long long)s->n_texels);
    for (uint32_t i = 0; i < s->n_textures; i++) {
        const CvTexture *t = &s->textures[i];
        fprintf(o, "  texture %u %s flags %u %ux%u levels %u offset %u tex=(%d %d %d)", i,
                tex_type(t->type), t->flags, t->width, t->height, t->levels, t->offset, t->tex_a,
                t->tex_b, t->amount_tex);
        v4(o, "a", t->value_a);
        v4(o, "b", t->value_b);
        v4(o, "uv", t->uv_map);
        fprintf(o, " amount %.6g scale %.6g\n", t->amount, t->scale);
    }
    /* Area lights are summarised per type; others listed. */
    unsigned counts[6] = {0};
    double power[6] = {0}, total = 0;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        uint32_t ty = s->lights[i].type < 6 ? s->lights[i].type : 0;
        counts[ty]++;
        power[ty] += s->light_power[i];
        total += s->light_power[i];
    }
    fprintf(o, "lights %u power %.6g\n", s->n_lights, total);
    for (int t = 0; t < 6; t++)
        if (counts[t])
            fprintf(o, "  %s count %u power %.6g\n", light_type((uint32_t)t), counts[t], power[t]);
    unsigned shown = 0;
    for (uint32_t i = 0; i < s->n_lights; i++) {
        const CvLight *l = &s->lights[i];
        if (l->type == CV_LIGHT_AREA && shown >= 8)
            continue;
        if (l->type == CV_LIGHT_AREA)
            shown++;
        fprintf(o, "  light %u %s flags %u tex %d prim %u", i, light_type(l->type), l->flags,
                l->tex, l->prim);
        v4(o, "L", l->L);
        v4(o, "pos", l->position);
        v4(o, "dir", l->direction);
        fprintf(o, " power %.6g\n", s->light_power[i]);
    }
    /* the names a job's lights.scale uses: index, type, lights made */
    for (uint32_t k = 0; k < s->n_light_sources; k++) {
        unsigned made = 0;
        for (uint32_t i = 0; i < s->n_lights; i++)
            made += s->light_source[i] == k;
        fprintf(o, "  light-source %u %s%s lights %u\n", k,
                s->light_sources[k].area ? "area " : "", s->light_sources[k].type, made);
    }
    unsigned lit = 0;
    for (uint32_t t = 0; t < s->n_triangles; t++)
        lit += s->tri_light[t] >= 0;
    fprintf(o, "emissive-triangles %u\n", lit);
    fprintf(o, "warnings %u\n", s->warnings);
}
