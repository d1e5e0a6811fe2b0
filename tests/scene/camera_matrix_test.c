/* camera_matrix_test.c: worldToCamera and worldToNDC (scene/camera_matrix.h)
 * against points worked out by hand: a perspective LookAt camera, one with
 * a crop (NDC spans the full film, not the crop) and an orthographic one; a
 * spherical one has no worldToNDC. */
#include <math.h>

#include "scene/camera_matrix.h"
#include "scene/film.h"
#include "tests/tap.h"

/* p * M (row vector), divided by w */
static void apply(const float m[16], const double p[3], double out[3])
{
    double q[4] = {0, 0, 0, 0}, v[4] = {p[0], p[1], p[2], 1};
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            q[c] += v[r] * m[4 * r + c];
    for (int i = 0; i < 3; i++)
        out[i] = q[i] / q[3];
}

static bool near(double a, double b)
{
    return fabs(a - b) < 1e-5;
}

static CvCamera camera(uint32_t type, const double crop[4])
{
    CvCamera c = {0};
    c.screen = cv_film_default_screen(16.0 / 12.0);
    c.lens.z = cv_camera_fov_scale(45);
    c.type = type;
    cv_camera_fit_film(&c, crop, 16, 12);
    static const double eye[3] = {2, 0, 0}, at[3] = {0, 0, 0}, up[3] = {0, 1, 0};
    cv_camera_look_at(&c, eye, at, up);
    return c;
}

int main(void)
{
    static const double whole[4] = {0, 1, 0, 1}, part[4] = {0.5, 1, 0.25, 0.75};
    float m[16];
    double out[3];
    /* eye (2,0,0) looking at the origin, up +y: camera +z is world -x,
     * +x (image right) is world +z */
    static const double p[3] = {0, 0.25, 0.5};
    CvCamera c = camera(CV_CAMERA_PERSPECTIVE, whole);
    tap_ok(cv_camera_world_to_camera(&c, m), "worldToCamera");
    apply(m, p, out);
    tap_ok(near(out[0], 0.5) && near(out[1], 0.25) && near(out[2], 2),
           "world (0, 0.25, 0.5) is camera (0.5, 0.25, 2): got (%g, %g, %g)", out[0], out[1],
           out[2]);
    tap_ok(near(m[12], 0) && near(m[13], 0) && near(m[14], 2),
           "translation in the last row (Imath's convention)");
    tap_ok(cv_camera_world_to_ndc(&c, m), "worldToNDC");
    double t = tan(22.5 * M_PI / 180);
    double want_x = (0.5 / (2 * t) + 4.0 / 3) / (8.0 / 3), want_y = (1 - 0.25 / (2 * t)) / 2;
    apply(m, p, out);
    tap_ok(near(out[0], want_x) && near(out[1], want_y),
           "perspective NDC (%g, %g), want (%g, %g)", out[0], out[1], want_x, want_y);
    static const double origin[3] = {0, 0, 0};
    apply(m, origin, out);
    tap_ok(near(out[0], 0.5) && near(out[1], 0.5), "look-at point at the centre");

    CvCamera cc = camera(CV_CAMERA_PERSPECTIVE, part);
    tap_ok(cc.crop.x == 8 && cc.crop.y == 6, "crop renders 8x6 pixels");
    cv_camera_world_to_ndc(&cc, m);
    apply(m, p, out);
    tap_ok(near(out[0], want_x) && near(out[1], want_y), "a crop keeps the full film's NDC");

    CvCamera co = camera(CV_CAMERA_ORTHOGRAPHIC, whole);
    cv_camera_world_to_ndc(&co, m);
    apply(m, p, out);
    want_x = (0.5 + 4.0 / 3) / (8.0 / 3);
    want_y = (1 - 0.25) / 2;
    tap_ok(near(out[0], want_x) && near(out[1], want_y),
           "orthographic NDC (%g, %g), want (%g, %g)", out[0], out[1], want_x, want_y);

    CvCamera cs = camera(CV_CAMERA_EQUAL_AREA, whole);
    float w2c[16];
    tap_ok(cv_camera_world_to_camera(&cs, w2c) && !cv_camera_world_to_ndc(&cs, m),
           "a spherical camera has worldToCamera and no worldToNDC");
    return tap_done();
}
