/* camera_motion.c: see camera_motion.h. In double; rounded to float for
 * the GPU at the end. */
#include <math.h>
#include <string.h>

#include "trace/camera_motion.h"

static double det3(const double a[3][3])
{
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

/* inverse of a 3x3 (false when singular) */
static bool inverse3(const double a[3][3], double out[3][3])
{
    double d = det3(a);
    if (!(fabs(d) > 1e-300))
        return false;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (c + 1) % 3, r2 = (c + 2) % 3, c1 = (r + 1) % 3, c2 = (r + 2) % 3;
            out[r][c] = (a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]) / d;
        }
    return true;
}

/* rotation matrix (column vectors: v' = R v) to a unit quaternion */
static void quat_from(const double R[3][3], double q[4])
{
    double tr = R[0][0] + R[1][1] + R[2][2];
    if (tr > 0) {
        double s = sqrt(tr + 1) * 2; /* 4 w */
        q[3] = s / 4;
        q[0] = (R[2][1] - R[1][2]) / s;
        q[1] = (R[0][2] - R[2][0]) / s;
        q[2] = (R[1][0] - R[0][1]) / s;
    } else {
        int i = R[1][1] > R[0][0] ? 1 : 0;
        if (R[2][2] > R[i][i])
            i = 2;
        int j = (i + 1) % 3, k = (i + 2) % 3;
        double s = sqrt(R[i][i] - R[j][j] - R[k][k] + 1) * 2; /* 4 q_i */
        q[i] = s / 4;
        q[j] = (R[j][i] + R[i][j]) / s;
        q[k] = (R[k][i] + R[i][k]) / s;
        q[3] = (R[k][j] - R[j][k]) / s;
    }
}

static void quat_to(const double q_in[4], double R[3][3])
{
    double n = sqrt(q_in[0] * q_in[0] + q_in[1] * q_in[1] + q_in[2] * q_in[2] + q_in[3] * q_in[3]);
    double x = q_in[0] / n, y = q_in[1] / n, z = q_in[2] / n, w = q_in[3] / n;
    R[0][0] = 1 - 2 * (y * y + z * z);
    R[0][1] = 2 * (x * y - z * w);
    R[0][2] = 2 * (x * z + y * w);
    R[1][0] = 2 * (x * y + z * w);
    R[1][1] = 1 - 2 * (x * x + z * z);
    R[1][2] = 2 * (y * z - x * w);
    R[2][0] = 2 * (x * z - y * w);
    R[2][1] = 2 * (y * z + x * w);
    R[2][2] = 1 - 2 * (x * x + y * y);
}

bool cv_motion_decompose(const double m[3][4], double T[3], double q[4], double S[3][3])
{
    double M[3][3], R[3][3];
    for (int r = 0; r < 3; r++) {
        T[r] = m[r][3];
        for (int c = 0; c < 3; c++)
            M[r][c] = R[r][c] = m[r][c];
    }
    /* polar decomposition M = R S by pbrt-v4's iteration R <- (R + R^-T) / 2 */
    for (int it = 0; it < 100; it++) {
        double inv[3][3], next[3][3], norm = 0;
        if (!inverse3(R, inv))
            return false;
        for (int r = 0; r < 3; r++) {
            double n = 0;
            for (int c = 0; c < 3; c++) {
                next[r][c] = (R[r][c] + inv[c][r]) / 2;
                n += fabs(R[r][c] - next[r][c]);
            }
            norm = fmax(norm, n);
        }
        memcpy(R, next, sizeof(R));
        if (norm < 1e-12)
            break;
    }
    if (det3(R) < 0) /* a reflection: keep it in S (camera_motion.h) */
        for (int r = 0; r < 3; r++)
            for (int c = 0; c < 3; c++)
                R[r][c] = -R[r][c];
    double Rinv[3][3];
    if (!inverse3(R, Rinv))
        return false;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            S[r][c] = Rinv[r][0] * M[0][c] + Rinv[r][1] * M[1][c] + Rinv[r][2] * M[2][c];
    quat_from(R, q);
    return true;
}

void cv_motion_compose(const double T[3], const double q[4], const double S[3][3], double m[3][4])
{
    double R[3][3];
    quat_to(q, R);
    for (int r = 0; r < 3; r++) {
        for (int c = 0; c < 3; c++)
            m[r][c] = R[r][0] * S[0][c] + R[r][1] * S[1][c] + R[r][2] * S[2][c];
        m[r][3] = T[r];
    }
}

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
