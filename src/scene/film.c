/* film.c: see film.h. */
#include <math.h>

#include "scene/film.h"
#include "scene/transform.h"

static void crop_axis(uint32_t res, double lo, double hi, uint32_t *a, uint32_t *b)
{
    uint32_t p0 = (uint32_t)ceil(res * lo), p1 = (uint32_t)ceil(res * hi);
    if (p1 <= p0) {
        /* res*lo and res*hi lie in one pixel (p0 - 1, p0]: p0 >= 1, since
         * lo < hi puts res*hi above 0 */
        p1 = p0;
        p0 = p0 - 1;
    }
    *a = p0;
    *b = p1;
}

void cv_film_crop_pixels(uint32_t w, uint32_t h, const double crop[4], uint32_t px[4])
{
    crop_axis(w, crop[0], crop[1], &px[0], &px[1]);
    crop_axis(h, crop[2], crop[3], &px[2], &px[3]);
}

cv_vec4 cv_film_default_screen(double aspect)
{
    if (aspect > 1)
        return (cv_vec4){(float)-aspect, (float)aspect, -1, 1};
    return (cv_vec4){-1, 1, (float)(-1 / aspect), (float)(1 / aspect)};
}

float cv_camera_fov_scale(double fov_deg)
{
    return (float)tan(fov_deg * M_PI / 360);
}

bool cv_camera_fit_film(CvCamera *cam, const double crop[4], uint32_t w, uint32_t h)
{
    bool reshaped = false;
    if (cam->film.x && cam->film.y) {
        double old_aspect = (double)cam->film.x / cam->film.y, aspect = (double)w / h;
        reshaped = fabs(old_aspect - aspect) > 1e-6 * aspect;
    }
    if (reshaped)
        cam->screen = cv_film_default_screen((double)w / h);
    uint32_t px[4];
    cv_film_crop_pixels(w, h, crop, px);
    cam->film = (cv_uvec4){w, h, px[0], px[2]};
    cam->crop.x = px[1] - px[0];
    cam->crop.y = px[3] - px[2];
    return reshaped;
}

bool cv_camera_look_at(CvCamera *cam, const double eye[3], const double at[3],
                       const double up[3])
{
    /* the same matrices as `LookAt ... Camera` in a scene file */
    struct cv_mat4 w2c, c2w;
    if (!cv_mat4_look_at(eye, at, up, &w2c) || !cv_mat4_inverse(&w2c, &c2w))
        return false;
    for (int r = 0; r < 3; r++)
        cam->to_world[r] = cam->to_world_end[r] = (cv_vec4){
            (float)c2w.m[r][0], (float)c2w.m[r][1], (float)c2w.m[r][2], (float)c2w.m[r][3]};
    return true;
}
