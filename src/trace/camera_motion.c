/* camera_motion.c: see camera_motion.h. In double (scene/animated.c);
 * rounded to float for the GPU at the end. */
#include <math.h>
#include <string.h>

#include "trace/camera_motion.h"

void cv_camera_motion_setup(const CvCamera *cam, CvPassParams *u)
{
    memset(&u->cam_moves, 0, sizeof(u->cam_moves));
    u->cam_time = cam->time;
    if (memcmp(cam->to_world, cam->to_world_end, sizeof(cam->to_world)) == 0)
        return;
    double m[2][3][4], T[2][3], q[2][4], S[2][3][3];
    for (int r = 0; r < 3; r++) {
        const float *a = &cam->to_world[r].x, *b = &cam->to_world_end[r].x;
        for (int c = 0; c < 4; c++) {
            m[0][r][c] = a[c];
            m[1][r][c] = b[c];
        }
    }
    if (!cv_motion_decompose(m[0], T[0], q[0], S[0]) || !cv_motion_decompose(m[1], T[1], q[1], S[1]))
        return; /* singular: the loader has refused it already */
    double dot = q[0][0] * q[1][0] + q[0][1] * q[1][1] + q[0][2] * q[1][2] + q[0][3] * q[1][3];
    if (dot < 0) /* the shorter way round, as pbrt-v4 */
        for (int i = 0; i < 4; i++)
            q[1][i] = -q[1][i];
    u->cam_moves.x = 1;
    for (int e = 0; e < 2; e++) {
        u->cam_T[e] = (cv_vec4){(float)T[e][0], (float)T[e][1], (float)T[e][2], 0};
        u->cam_R[e] = (cv_vec4){(float)q[e][0], (float)q[e][1], (float)q[e][2], (float)q[e][3]};
        for (int r = 0; r < 3; r++)
            u->cam_S[3 * e + r] = (cv_vec4){(float)S[e][r][0], (float)S[e][r][1], (float)S[e][r][2], 0};
    }
}
