/* camera.c: Camera and Film into CvCamera and the render settings, with
 * pbrt's conventions (the CTM at Camera is world-to-camera; the screen
 * window spans [-aspect, aspect] x [-1, 1] on the longer axis; fov is
 * measured on the shorter axis). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/limits.h"
#include "base/mem.h"
#include "scene/builder.h"
#include "scene/film.h"

/* The shutter's open and close times, which every kind of camera reads. */
static bool shutter(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                    struct cv_error *err)
{
    double open = cv_params_float(ps, "shutteropen", 0), close = cv_params_float(ps, "shutterclose", 1);
    if (close < open) { /* pbrt-v4 swaps them too */
        double t = open;
        open = close;
        close = t;
        if (!cv_b_warn(b, err, loc, "shutterclose is before shutteropen; swapped"))
            return false;
    }
    b->shutter[0] = open;
    b->shutter[1] = close;
    b->exposure_time = close - open;
    return true;
}

/* pbrt-v4's "spherical" (mapping "equalarea", its default, or
 * "equirectangular") and pbrt-v3's "environment" (equirectangular): rays
 * from the camera's origin over the whole sphere. Its lens and screen
 * window are read, as pbrt-v4 reads them, and have no effect; fov is not
 * read (pbrt-v4's unused-parameter warning). */
static bool spherical(struct cv_builder *b, const char *type, struct cv_params *ps,
                      const struct cv_loc *loc, struct cv_error *err)
{
    b->cam_type = CV_CAMERA_EQUIRECT;
    b->lensradius = 0;  /* a Camera before it may have set one */
    if (strcmp(type, "spherical") == 0) {
        const char *m = cv_params_string(ps, "mapping", "equalarea");
        if (strcmp(m, "equalarea") == 0) {
            b->cam_type = CV_CAMERA_EQUAL_AREA;
        } else if (strcmp(m, "equirectangular") != 0) {
            const struct cv_param *p = cv_params_find(ps, "mapping");
            return cv_fail(err, "%s:%d:%d: unknown mapping \"%s\" of the spherical camera "
                           "(\"equalarea\" or \"equirectangular\")",
                           p->file, p->line, p->col, m);
        }
    }
    static const char *const read[] = {"lensradius", "focaldistance", "frameaspectratio",
                                       "screenwindow"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(read); i++)
        cv_params_find(ps, read[i]);
    return shutter(b, ps, loc, err);
}

bool cv_b_camera(struct cv_builder *b, const char *type, struct cv_params *ps,
                 const struct cv_loc *loc, struct cv_error *err)
{
    if (b->camera_set && !cv_b_warn(b, err, loc, "second Camera replaces the first"))
        return false;
    struct cv_mat4 inv, inv_end;
    if (!cv_mat4_inverse(&b->gs.ctm, &inv) || !cv_mat4_inverse(&b->gs.ctm_end, &inv_end))
        return cv_fail(err, "%s:%d:%d: the camera transform is singular", loc->file, loc->line, loc->col);
    b->camera_to_world = inv;
    b->camera_to_world_end = inv_end;
    b->camera_set = true;
    /* pbrt-v4: the camera sits in the outside medium current here */
    b->s->camera_medium = (uint32_t)b->gs.medium_outside;
    size_t i;
    for (i = 0; i < b->n_coordsys; i++)
        if (strcmp(b->coordsys[i].name, "camera") == 0)
            break;
    if (i == b->n_coordsys) {
        struct cv_coordsys c = {cv_xstrdup("camera"), inv, inv_end};
        CV_PUSH(b->coordsys, b->n_coordsys, b->cap_coordsys, c);
    } else {
        b->coordsys[i].m = inv;
        b->coordsys[i].m_end = inv_end;
    }
    if (strcmp(type, "perspective") == 0) {
        b->cam_type = CV_CAMERA_PERSPECTIVE;
    } else if (strcmp(type, "orthographic") == 0) {
        b->cam_type = CV_CAMERA_ORTHOGRAPHIC;
    } else if (strcmp(type, "spherical") == 0 || strcmp(type, "environment") == 0) {
        return spherical(b, type, ps, loc, err);
    } else {
        if (!cv_b_warn(b, err, loc, "camera \"%s\" is not supported; perspective used", type))
            return false;
        b->cam_type = CV_CAMERA_PERSPECTIVE;
        for (size_t k = 0; k < ps->n; k++)
            ps->v[k].used = true;
    }
    b->fov = cv_params_float(ps, "fov", 90);
    double half = cv_params_float(ps, "halffov", -1);
    if (half > 0)
        b->fov = 2 * half;
    if (!(b->fov > 0 && b->fov < 180))
        return cv_fail(err, "%s:%d:%d: fov must be in (0, 180) degrees", loc->file, loc->line, loc->col);
    b->lensradius = cv_params_float(ps, "lensradius", 0);
    b->focaldistance = cv_params_float(ps, "focaldistance", 1e6);
    b->frameaspect = cv_params_float(ps, "frameaspectratio", -1);
    b->has_screen = cv_params_floats(ps, "screenwindow", b->screen, 4);
    return shutter(b, ps, loc, err);
}

bool cv_b_film(struct cv_builder *b, const char *type, struct cv_params *ps,
               const struct cv_loc *loc, struct cv_error *err)
{
    if (strcmp(type, "rgb") != 0 && strcmp(type, "image") != 0 && strcmp(type, "gbuffer") != 0 &&
        !cv_b_warn(b, err, loc, "film \"%s\" read as \"rgb\"", type))
        return false;
    b->xres = cv_params_int(ps, "xresolution", 1280);
    b->yres = cv_params_int(ps, "yresolution", 720);
    if (b->xres <= 0 || b->yres <= 0 || b->xres > CV_MAX_FILM_SIDE || b->yres > CV_MAX_FILM_SIDE)
        return cv_fail(err, "%s:%d:%d: film resolution must be in 1..65536", loc->file, loc->line, loc->col);
    double crop[4] = {0, 1, 0, 1};
    if (cv_params_floats(ps, "cropwindow", crop, 4)) {
        for (int i = 0; i < 4; i++)
            crop[i] = crop[i] < 0 ? 0 : crop[i] > 1 ? 1 : crop[i];
        if (!(crop[0] < crop[1] && crop[2] < crop[3]))
            return cv_fail(err, "%s:%d:%d: empty crop window", loc->file, loc->line, loc->col);
    }
    memcpy(b->crop, crop, sizeof(crop));
    const char *fn = cv_params_string(ps, "filename", NULL);
    free(b->s->settings.film_filename);
    b->s->settings.film_filename = fn ? cv_xstrdup(fn) : NULL;
    b->iso = cv_params_float(ps, "iso", 100);
    b->film_exposure_time = cv_params_float(ps, "exposuretime", 1);
    double scale = cv_params_float(ps, "scale", 1); /* v3 */
    b->s->settings.exposure = (float)scale;
    /* pbrt-v4's sensor model, white balance and sample clamp change the
     * image where they are not the defaults: not rendered, so said */
    const char *sensor = cv_params_string(ps, "sensor", "cie1931");
    if (strcmp(sensor, "cie1931") != 0 &&
        !cv_b_warn(b, err, loc, "film sensor \"%s\" is not supported; colours as the cie1931 "
                   "sensor's", sensor))
        return false;
    if (cv_params_float(ps, "whitebalance", 0) != 0 &&
        !cv_b_warn(b, err, loc, "film whitebalance is not supported; not applied"))
        return false;
    if (isfinite(cv_params_float(ps, "maxcomponentvalue", INFINITY)) &&
        !cv_b_warn(b, err, loc, "film maxcomponentvalue is not supported; samples not clamped"))
        return false;
    if (cv_params_find(ps, "pixelbounds") &&
        !cv_b_warn(b, err, loc, "film pixelbounds is not supported; the whole film rendered"))
        return false;
    /* accepted, with no effect on the image */
    static const char *const known[] = {"diagonal", "savefp16", "writefp16"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(known); i++)
        cv_params_find(ps, known[i]);
    return true;
}

void cv_b_finish_camera(struct cv_builder *b)
{
    struct cv_scene *s = b->s;
    CvCamera *c = &s->camera;
    memset(c, 0, sizeof(*c));
    const struct cv_mat4 *m0 = &b->camera_to_world, *m1 = &b->camera_to_world_end;
    for (int r = 0; r < 3; r++) {
        c->to_world[r] = (cv_vec4){(float)m0->m[r][0], (float)m0->m[r][1], (float)m0->m[r][2],
                                   (float)m0->m[r][3]};
        c->to_world_end[r] = (cv_vec4){(float)m1->m[r][0], (float)m1->m[r][1], (float)m1->m[r][2],
                                       (float)m1->m[r][3]};
    }
    c->time = (cv_vec4){(float)b->shutter[0], (float)b->shutter[1], (float)b->transform_times[0],
                        (float)b->transform_times[1]};
    double aspect = b->frameaspect > 0 ? b->frameaspect : (double)b->xres / b->yres;
    if (b->has_screen)
        c->screen = (cv_vec4){(float)b->screen[0], (float)b->screen[1], (float)b->screen[2],
                              (float)b->screen[3]};
    else
        c->screen = cv_film_default_screen(aspect);
    c->lens = (cv_vec4){(float)b->lensradius, (float)b->focaldistance,
                        cv_camera_fov_scale(b->fov), 0};
    uint32_t px[4];
    cv_film_crop_pixels((uint32_t)b->xres, (uint32_t)b->yres, b->crop, px);
    c->film = (cv_uvec4){(uint32_t)b->xres, (uint32_t)b->yres, px[0], px[2]};
    c->crop = (cv_uvec4){px[1] - px[0], px[3] - px[2], 0, 0};
    c->type = b->cam_type;
    s->settings.width = (uint32_t)b->xres;
    s->settings.height = (uint32_t)b->yres;
    for (int i = 0; i < 4; i++)
        s->settings.crop[i] = b->crop[i];
    /* pbrt-v4's imaging ratio: exposure time * ISO / 100 */
    s->settings.exposure *= (float)(b->iso / 100 * b->exposure_time * b->film_exposure_time);
}
