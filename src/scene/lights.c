/* lights.c: LightSource and AreaLightSource. Colours follow pbrt-v4: a
 * spectrum (blackbody, named, file) is normalised to luminance 1 before
 * "scale"; rgb keeps its magnitude; "power" sets the emitted flux as pbrt-v4
 * computes it. */
#include <math.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"
#include "scene/image.h"

static double luminance(const double c[3]) { return CV_LUMA(c[0], c[1], c[2]); }

static bool normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0) || !isfinite(l))
        return false;
    for (int i = 0; i < 3; i++)
        v[i] /= l;
    return true;
}

/* Rows of a rotation taking world directions into the light frame whose
 * +z is dir (light-to-world columns: x, y, dir). */
static void frame_rows(const double dir[3], CvLight *l)
{
    double z[3] = {dir[0], dir[1], dir[2]}, x[3], y[3];
    /* Duff et al. orthonormal basis */
    double sign = copysign(1.0, z[2]);
    double a = -1 / (sign + z[2]), bb = z[0] * z[1] * a;
    x[0] = 1 + sign * z[0] * z[0] * a; x[1] = sign * bb; x[2] = -sign * z[0];
    y[0] = bb; y[1] = sign + z[1] * z[1] * a; y[2] = -z[1];
    l->to_light[0] = (cv_vec4){(float)x[0], (float)x[1], (float)x[2], 0};
    l->to_light[1] = (cv_vec4){(float)y[0], (float)y[1], (float)y[2], 0};
    l->to_light[2] = (cv_vec4){(float)z[0], (float)z[1], (float)z[2], 0};
}

static bool light_color(struct cv_builder *b, struct cv_params *ps, const char *name,
                        const char *dir, double rgb[3], struct cv_error *err)
{
    bool found;
    rgb[0] = rgb[1] = rgb[2] = 1;
    if (!cv_b_color(b, ps, name, CV_SPEC_ILLUMINANT, dir, rgb, &found, err))
        return false;
    double sc = cv_params_float(ps, "scale", 1);
    for (int c = 0; c < 3; c++)
        rgb[c] *= sc;
    return true;
}

bool cv_b_light(struct cv_builder *b, const char *type, struct cv_params *ps,
                const struct cv_loc *loc, const char *dir, struct cv_error *err)
{
    const struct cv_mat4 *M = &b->gs.ctm;
    b->light_source = cv_b_light_source(b, type, false, loc);
    CvLight l;
    memset(&l, 0, sizeof(l));
    l.tex = -1;
    /* "power" is read by the lights pbrt-v4 reads it for alone: on the
     * others it stays unused, and the unused-parameter warning says so */
    bool powered = strcmp(type, "point") == 0 || strcmp(type, "spot") == 0;
    double rgb[3], power = powered ? cv_params_float(ps, "power", -1) : -1;
    if (strcmp(type, "point") == 0) {
        if (!light_color(b, ps, "I", dir, rgb, err))
            return false;
        double from[3] = {0, 0, 0}, w[3];
        cv_params_floats(ps, "from", from, 3);
        cv_mat4_point(M, from, w);
        if (power > 0)
            for (int c = 0; c < 3; c++)
                rgb[c] *= power / (4 * M_PI);
        l.type = CV_LIGHT_POINT;
        l.L = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 0};
        l.position = (cv_vec4){(float)w[0], (float)w[1], (float)w[2], 0};
        cv_b_add_light(b, &l, (float)(4 * M_PI * luminance(rgb)));
    } else if (strcmp(type, "spot") == 0) {
        if (!light_color(b, ps, "I", dir, rgb, err))
            return false;
        double from[3] = {0, 0, 0}, to[3] = {0, 0, 1}, wf[3], wt[3];
        cv_params_floats(ps, "from", from, 3);
        cv_params_floats(ps, "to", to, 3);
        cv_mat4_point(M, from, wf);
        cv_mat4_point(M, to, wt);
        double d[3] = {wt[0] - wf[0], wt[1] - wf[1], wt[2] - wf[2]};
        if (!normalize3(d))
            return cv_fail(err, "%s:%d:%d: spot light with from == to", loc->file, loc->line, loc->col);
        double cone = cv_params_float(ps, "coneangle", 30), delta = cv_params_float(ps, "conedeltaangle", 5);
        double cos_end = cos(cone * M_PI / 180), cos_start = cos((cone - delta) * M_PI / 180);
        double k = 2 * M_PI * ((1 - cos_start) + (cos_start - cos_end) / 2);
        if (power > 0 && k > 0)
            for (int c = 0; c < 3; c++)
                rgb[c] *= power / k;
        l.type = CV_LIGHT_SPOT;
        l.L = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 0};
        l.position = (cv_vec4){(float)wf[0], (float)wf[1], (float)wf[2], (float)cos_start};
        l.direction = (cv_vec4){(float)d[0], (float)d[1], (float)d[2], (float)cos_end};
        frame_rows(d, &l);
        cv_b_add_light(b, &l, (float)(k * luminance(rgb)));
    } else if (strcmp(type, "distant") == 0) {
        if (!light_color(b, ps, "L", dir, rgb, err))
            return false;
        double from[3] = {0, 0, 0}, to[3] = {0, 0, 1}, d0[3], d[3];
        cv_params_floats(ps, "from", from, 3);
        cv_params_floats(ps, "to", to, 3);
        for (int c = 0; c < 3; c++)
            d0[c] = to[c] - from[c];
        cv_mat4_vector(M, d0, d);
        if (!normalize3(d))
            return cv_fail(err, "%s:%d:%d: distant light with from == to", loc->file, loc->line, loc->col);
        double E = cv_params_float(ps, "illuminance", -1);
        if (E > 0)
            for (int c = 0; c < 3; c++)
                rgb[c] *= E;
        l.type = CV_LIGHT_DISTANT;
        l.L = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 0};
        l.direction = (cv_vec4){(float)d[0], (float)d[1], (float)d[2], 0};
        frame_rows(d, &l);
        cv_b_add_light(b, &l, 0); /* set in cv_b_finish from the scene radius */
    } else if (strcmp(type, "infinite") == 0) {
        const char *file = cv_params_string(ps, "filename", NULL);
        bool v4map = file != NULL;
        if (!file)
            file = cv_params_string(ps, "mapname", NULL);
        if (file) {
            /* pbrt: the map's own values, times L (v3) and scale */
            if (v4map && cv_params_find(ps, "L") &&
                !cv_b_warn(b, err, loc, "infinite light with both \"L\" and \"filename\", "
                           "which pbrt-v4 refuses: the map times L is rendered"))
                return false;
            if (!light_color(b, ps, "L", dir, rgb, err))
                return false;
        } else if (!light_color(b, ps, "L", dir, rgb, err)) {
            return false;
        }
        cv_params_int(ps, "samples", 1);
        cv_params_int(ps, "nsamples", 1);
        struct cv_mat4 inv;
        cv_mat4_inverse(M, &inv);
        for (int r = 0; r < 3; r++) {
            double row[3] = {inv.m[r][0], inv.m[r][1], inv.m[r][2]};
            normalize3(row);
            l.to_light[r] = (cv_vec4){(float)row[0], (float)row[1], (float)row[2], 0};
        }
        l.L = (cv_vec4){(float)rgb[0], (float)rgb[1], (float)rgb[2], 0};
        float avg = 1;
        if (file) {
            int t = cv_b_image_texture(b, file, dir, true, loc, err);
            if (t < 0)
                return false;
            /* the light's own record of the (shared) image, wrapped as the
             * sphere it maps: pbrt-v4 mirrors the equal-area square's
             * edges and clamps a lat-long map at the poles */
            CvTexture own = b->s->textures[t];
            own.flags |= v4map ? CV_TEXF_WRAP_OCTAHEDRAL : CV_TEXF_WRAP_LATLONG;
            t = cv_b_add_texture(b, &own);
            const CvTexture *tx = &b->s->textures[t];
            if (v4map && tx->width != tx->height)
                return cv_fail(err, "%s:%d:%d: pbrt-v4 environment map \"%s\" must be square (equal-area octahedral), is %ux%u",
                               loc->file, loc->line, loc->col, file, tx->width, tx->height);
            l.type = CV_LIGHT_INFINITE_MAP;
            l.flags = v4map ? CV_LIGHTF_EQUAL_AREA : 0;
            l.tex = t;
            avg = (float)cv_scene_texture_luminance(b->s, tx);
        } else {
            l.type = CV_LIGHT_INFINITE;
        }
        if (cv_params_find(ps, "illuminance") &&
            !cv_b_warn(b, err, loc, "infinite light \"illuminance\" is not supported; ignored"))
            return false;
        cv_b_add_light(b, &l, avg);
    } else {
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        return cv_b_warn(b, err, loc, "light \"%s\" is not supported; skipped", type);
    }
    if (b->cur_object >= 0 && !cv_b_warn(b, err, loc, "light inside ObjectBegin is added once, not per instance"))
        return false;
    return true;
}

bool cv_b_area_light(struct cv_builder *b, const char *type, struct cv_params *ps,
                     const struct cv_loc *loc, const char *dir, struct cv_error *err)
{
    /* every directive is counted, supported or not: the indices are the file's */
    uint32_t source = cv_b_light_source(b, type, true, loc);
    if (strcmp(type, "diffuse") != 0) {
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        return cv_b_warn(b, err, loc, "area light \"%s\" is not supported; ignored", type);
    }
    struct cv_area_state *a = &b->gs.area;
    memset(a, 0, sizeof(*a));
    a->tex = -1;
    a->source = source;
    if (!light_color(b, ps, "L", dir, a->L, err))
        return false;
    a->twosided = cv_params_bool(ps, "twosided", false);
    a->power = cv_params_float(ps, "power", -1);
    const char *file = cv_params_string(ps, "filename", NULL);
    if (file) {
        if (cv_params_find(ps, "L") &&
            !cv_b_warn(b, err, loc, "area light with both \"L\" and \"filename\", which "
                       "pbrt-v4 refuses: the image times L is rendered"))
            return false;
        a->tex = cv_b_image_texture(b, file, dir, true, loc, err);
        if (a->tex < 0)
            return false;
    }
    a->on = true;
    return true;
}
