/* camera_motion_test.c: the split of a camera transform into translation,
 * rotation quaternion and scale-shear (src/trace/camera_motion.c): it
 * composes back to the matrix (rotations, non-uniform scale, shear, a
 * handedness flip), the quaternion is unit length with the rotation's
 * angle, and the pass constants mark a still camera as still and keep a
 * moving one's ends on one side (q0 . q1 >= 0). The interpolation itself
 * runs in the shader, checked against pbrt-v4 by oracle_test's
 * camera_motion. */
#include "config.h"

#include <math.h>
#include <string.h>

#include "scene/transform.h"
#include "tests/tap.h"
#include "trace/camera_motion.h"

static void rows(const struct cv_mat4 *a, double m[3][4])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m[r][c] = a->m[r][c];
}

static double roundtrip(const struct cv_mat4 *a, double q[4])
{
    double m[3][4], T[3], S[3][3], back[3][4], err = 0;
    rows(a, m);
    if (!cv_motion_decompose(m, T, q, S))
        return INFINITY;
    cv_motion_compose(T, q, S, back);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            err = fmax(err, fabs(back[r][c] - m[r][c]));
    return err;
}

int main(void)
{
    struct cv_mat4 t = cv_mat4_translate(1, -2, 3), r = cv_mat4_rotate(30, 1, 2, 3);
    struct cv_mat4 sc = cv_mat4_scale(2, 0.5, 1.5), flip = cv_mat4_scale(-1, 1, 1);
    struct cv_mat4 tr = cv_mat4_mul(&t, &r), trs = cv_mat4_mul(&tr, &sc), trsf = cv_mat4_mul(&trs, &flip);
    struct cv_mat4 shear = cv_mat4_identity();
    shear.m[0][1] = 0.4;
    struct cv_mat4 trsh = cv_mat4_mul(&tr, &shear);
    double q[4];
    double e = roundtrip(&tr, q);
    double len = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    tap_ok(e < 1e-9 && fabs(len - 1) < 1e-12, "translate and rotate: composes back (%.2g), |q| 1", e);
    tap_ok(fabs(2 * acos(fabs(q[3])) - 30 * M_PI / 180) < 1e-9 &&
               fabs(q[1] / q[0] - 2) < 1e-9 && fabs(q[2] / q[0] - 3) < 1e-9,
           "q is 30 degrees about (1, 2, 3)");
    e = roundtrip(&trs, q);
    tap_ok(e < 1e-9 && fabs(2 * acos(fabs(q[3])) - 30 * M_PI / 180) < 1e-9,
           "with non-uniform scale: composes back (%.2g), same rotation", e);
    tap_ok(roundtrip(&trsh, q) < 1e-9, "with shear: composes back");
    e = roundtrip(&trsf, q);
    tap_ok(e < 1e-9, "with a handedness flip (Scale -1 1 1): composes back (%.2g)", e);
    struct cv_mat4 big = cv_mat4_rotate(179, 0, 1, 0);
    tap_ok(roundtrip(&big, q) < 1e-9 && fabs(q[3]) < 0.01, "179 degrees: composes back, w near 0");

    CvCamera cam;
    memset(&cam, 0, sizeof(cam));
    for (int i = 0; i < 3; i++) {
        const double *a = tr.m[i];
        cam.to_world[i] = cam.to_world_end[i] = (cv_vec4){(float)a[0], (float)a[1], (float)a[2], (float)a[3]};
    }
    cam.time = (cv_vec4){0, 1, 0, 1};
    CvPassParams u;
    memset(&u, 0xff, sizeof(u));
    cv_camera_motion_setup(&cam, &u);
    tap_ok(u.cam_moves.x == 0, "a still camera is still");
    struct cv_mat4 r2 = cv_mat4_rotate(-170, 1, 2, 3), tr2 = cv_mat4_mul(&t, &r2);
    for (int i = 0; i < 3; i++) {
        const double *a = tr2.m[i];
        cam.to_world_end[i] = (cv_vec4){(float)a[0], (float)a[1], (float)a[2], (float)a[3]};
    }
    cv_camera_motion_setup(&cam, &u);
    const cv_vec4 *q0 = &u.cam_R[0], *q1 = &u.cam_R[1];
    double dot = q0->x * q1->x + q0->y * q1->y + q0->z * q1->z + q0->w * q1->w;
    tap_ok(u.cam_moves.x == 1 && dot >= 0 && fabs(dot - cos(160 * M_PI / 360)) < 1e-5,
           "30 to -170 degrees: moving, the shorter way (160 degrees, q0.q1 %.5f)", dot);
    return tap_done();
}
