/* camera_matrix.c: see camera_matrix.h. Computed in double from the
 * camera's float rows, rounded to float once at the end. */
#include <string.h>

#include "scene/camera_matrix.h"
#include "scene/transform.h"

/* world-to-camera in column-vector form (p' = M p) */
static bool world_to_camera(const CvCamera *cam, struct cv_mat4 *out)
{
    struct cv_mat4 c2w = cv_mat4_identity();
    for (int r = 0; r < 3; r++) {
        const float *row = &cam->to_world[r].x;
        for (int c = 0; c < 4; c++)
            c2w.m[r][c] = row[c];
    }
    return cv_mat4_inverse(&c2w, out);
}

/* column-vector form to Imath's row-vector form: the transpose */
static void to_imath(const struct cv_mat4 *m, float out[16])
{
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            out[4 * r + c] = (float)m->m[c][r];
}

bool cv_camera_world_to_camera(const CvCamera *cam, float out[16])
{
    struct cv_mat4 w2c;
    if (!world_to_camera(cam, &w2c))
        return false;
    to_imath(&w2c, out);
    return true;
}

bool cv_camera_world_to_ndc(const CvCamera *cam, float out[16])
{
    struct cv_mat4 w2c;
    if (cam->type >= CV_CAMERA_EQUAL_AREA || !world_to_camera(cam, &w2c))
        return false;
    /* glsl/shared/scene.h: screen x = camera x / (z tan_half) (perspective)
     * or camera x (orthographic); ndc x = (sx - xmin) / (xmax - xmin),
     * ndc y = (ymax - sy) / (ymax - ymin). Written with w the divisor. */
    double xmin = cam->screen.x, xmax = cam->screen.y;
    double ymin = cam->screen.z, ymax = cam->screen.w;
    double t = cam->lens.z, dx = xmax - xmin, dy = ymax - ymin;
    struct cv_mat4 proj;
    memset(&proj, 0, sizeof(proj));
    if (cam->type == CV_CAMERA_ORTHOGRAPHIC) {
        proj.m[0][0] = 1 / dx;
        proj.m[0][3] = -xmin / dx;
        proj.m[1][1] = -1 / dy;
        proj.m[1][3] = ymax / dy;
        proj.m[2][3] = 1;
        proj.m[3][3] = 1;
    } else {
        proj.m[0][0] = 1 / (t * dx);
        proj.m[0][2] = -xmin / dx;
        proj.m[1][1] = -1 / (t * dy);
        proj.m[1][2] = ymax / dy;
        proj.m[2][2] = 1;
        proj.m[3][2] = 1;
    }
    struct cv_mat4 ndc = cv_mat4_mul(&proj, &w2c);
    to_imath(&ndc, out);
    return true;
}
