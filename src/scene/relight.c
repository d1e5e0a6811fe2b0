/* relight.c: see relight.h. */
#include <math.h>
#include <string.h>

#include "scene/relight.h"

static bool is_infinite(const CvLight *l)
{
    return l->type == CV_LIGHT_INFINITE || l->type == CV_LIGHT_INFINITE_MAP;
}

bool cv_scene_has_env(const struct cv_scene *s)
{
    for (uint32_t i = 0; i < s->n_lights; i++)
        if (is_infinite(&s->lights[i]))
            return true;
    return false;
}

/* Rotation matrix of deg degrees about axis (normalised here), as pbrt's
 * Rotate: R[r][c], applied as R * v. */
static void rotation(const float *deg_axis, double R[3][3])
{
    double a[3] = {deg_axis[1], deg_axis[2], deg_axis[3]};
    double len = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (int i = 0; i < 3; i++)
        a[i] /= len;
    double t = deg_axis[0] * M_PI / 180, s = sin(t), c = cos(t);
    R[0][0] = a[0] * a[0] + (1 - a[0] * a[0]) * c;
    R[0][1] = a[0] * a[1] * (1 - c) - a[2] * s;
    R[0][2] = a[0] * a[2] * (1 - c) + a[1] * s;
    R[1][0] = a[0] * a[1] * (1 - c) + a[2] * s;
    R[1][1] = a[1] * a[1] + (1 - a[1] * a[1]) * c;
    R[1][2] = a[1] * a[2] * (1 - c) - a[0] * s;
    R[2][0] = a[0] * a[2] * (1 - c) - a[1] * s;
    R[2][1] = a[1] * a[2] * (1 - c) + a[0] * s;
    R[2][2] = a[2] * a[2] + (1 - a[2] * a[2]) * c;
}

bool cv_scene_env_equal_area(const struct cv_scene *s, const struct cv_scene *env)
{
    for (uint32_t i = 0; i < s->n_lights; i++)
        if (s->lights[i].type == CV_LIGHT_INFINITE_MAP)
            return (s->lights[i].flags & CV_LIGHTF_EQUAL_AREA) != 0;
    const CvTexture *t = &env->textures[env->lights[0].tex];
    return t->width == t->height;
}

/* Luminance of a map's average. */
static double map_average(const struct cv_scene *s, const CvTexture *t)
{
    float c[4];
    cv_scene_texture_average(s, t, c);
    return CV_LUMA(c[0], c[1], c[2]);
}

/* Every infinite light shows r->env's image: its type, texture and flags
 * change; its colour and transform stay, and its power follows the new
 * map's average. */
static void swap_env(const struct cv_scene *s, const struct cv_relight *r, CvLight *l,
                     float *power)
{
    const CvLight *el = &r->env->lights[0];
    double avg_new = map_average(r->env, &r->env->textures[el->tex]);
    double avg_old = l->type == CV_LIGHT_INFINITE_MAP ? map_average(s, &s->textures[l->tex]) : 1;
    if (avg_old > 0)
        *power = (float)(*power * avg_new / avg_old);
    l->type = CV_LIGHT_INFINITE_MAP;
    l->tex = (int32_t)(s->n_textures + (uint32_t)el->tex);
    l->flags = (l->flags & ~CV_LIGHTF_EQUAL_AREA) | (r->env_equal_area ? CV_LIGHTF_EQUAL_AREA : 0);
}

static void scale_light(CvLight *l, float *power, float k)
{
    l->L.x *= k;
    l->L.y *= k;
    l->L.z *= k;  /* L.w is an area light's triangle area: not a colour */
    *power *= k;
}

void cv_scene_relight(const struct cv_scene *s, const struct cv_relight *r, CvLight *lights,
                      float *power, CvTexture *env_textures)
{
    memcpy(lights, s->lights, s->n_lights * sizeof(CvLight));
    memcpy(power, s->light_power, s->n_lights * sizeof(float));
    if (r->env) {
        const CvLight *el = &r->env->lights[0];
        for (uint32_t i = 0; i < r->env->n_textures; i++) {
            CvTexture *t = &env_textures[i];
            *t = r->env->textures[i];
            t->offset += (uint32_t)s->n_texels;
            if (t->tex_a >= 0)
                t->tex_a += (int32_t)s->n_textures;
            if (t->tex_b >= 0)
                t->tex_b += (int32_t)s->n_textures;
            if (t->amount_tex >= 0)
                t->amount_tex += (int32_t)s->n_textures;
            if ((int32_t)i == el->tex && r->env_equal_area)
                t->flags = (t->flags & ~CV_TEXF_WRAP_LATLONG) | CV_TEXF_WRAP_OCTAHEDRAL;
        }
    }
    double R[3][3];
    if (r->env_rotate)
        rotation(r->rotate, R);
    for (uint32_t i = 0; i < s->n_lights; i++) {
        CvLight *l = &lights[i];
        for (uint32_t k = 0; k < r->n_scales; k++)
            if (r->scales[k].source == s->light_source[i])
                scale_light(l, &power[i], r->scales[k].scale);
        if (!is_infinite(l))
            continue;
        if (r->env)
            swap_env(s, r, l, &power[i]);
        if (r->env_scale != 1)
            scale_light(l, &power[i], r->env_scale);
        if (r->env_rotate) {
            /* light-to-world becomes R * M, so world-to-light (the rows) T * R^T */
            double T[3][3], out[3][3];
            for (int a = 0; a < 3; a++) {
                T[a][0] = l->to_light[a].x;
                T[a][1] = l->to_light[a].y;
                T[a][2] = l->to_light[a].z;
            }
            for (int a = 0; a < 3; a++)
                for (int c = 0; c < 3; c++)
                    out[a][c] = T[a][0] * R[c][0] + T[a][1] * R[c][1] + T[a][2] * R[c][2];
            for (int a = 0; a < 3; a++)
                l->to_light[a] = (cv_vec4){(float)out[a][0], (float)out[a][1],
                                           (float)out[a][2], l->to_light[a].w};
        }
    }
}
