/* transform.c: matrix arithmetic behind the pbrt transform directives. */
#include <math.h>
#include <string.h>

#include "scene/transform.h"

struct cv_mat4 cv_mat4_identity(void)
{
    struct cv_mat4 r;
    memset(&r, 0, sizeof(r));
    for (int i = 0; i < 4; i++)
        r.m[i][i] = 1;
    return r;
}

struct cv_mat4 cv_mat4_mul(const struct cv_mat4 *a, const struct cv_mat4 *b)
{
    struct cv_mat4 r;
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] +
                        a->m[i][2] * b->m[2][j] + a->m[i][3] * b->m[3][j];
    return r;
}

bool cv_mat4_inverse(const struct cv_mat4 *a, struct cv_mat4 *out)
{
    /* Gauss-Jordan with partial pivoting. */
    double t[4][8];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            t[i][j] = a->m[i][j];
            t[i][j + 4] = i == j;
        }
    for (int c = 0; c < 4; c++) {
        int p = c;
        for (int r = c + 1; r < 4; r++)
            if (fabs(t[r][c]) > fabs(t[p][c]))
                p = r;
        if (!(fabs(t[p][c]) > 1e-300)) {
            *out = cv_mat4_identity();
            return false;
        }
        if (p != c)
            for (int j = 0; j < 8; j++) {
                double s = t[c][j];
                t[c][j] = t[p][j];
                t[p][j] = s;
            }
        double inv = 1.0 / t[c][c];
        for (int j = 0; j < 8; j++)
            t[c][j] *= inv;
        for (int r = 0; r < 4; r++) {
            if (r == c || t[r][c] == 0)
                continue;
            double f = t[r][c];
            for (int j = 0; j < 8; j++)
                t[r][j] -= f * t[c][j];
        }
    }
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++)
            out->m[i][j] = t[i][j + 4];
    return true;
}

struct cv_mat4 cv_mat4_translate(double x, double y, double z)
{
    struct cv_mat4 r = cv_mat4_identity();
    r.m[0][3] = x;
    r.m[1][3] = y;
    r.m[2][3] = z;
    return r;
}

struct cv_mat4 cv_mat4_scale(double x, double y, double z)
{
    struct cv_mat4 r = cv_mat4_identity();
    r.m[0][0] = x;
    r.m[1][1] = y;
    r.m[2][2] = z;
    return r;
}

struct cv_mat4 cv_mat4_rotate(double angle_deg, double x, double y, double z)
{
    struct cv_mat4 r = cv_mat4_identity();
    double len = sqrt(x * x + y * y + z * z);
    if (!(len > 0))
        return r;
    x /= len;
    y /= len;
    z /= len;
    double th = angle_deg * M_PI / 180.0, s = sin(th), c = cos(th);
    r.m[0][0] = x * x + (1 - x * x) * c;
    r.m[0][1] = x * y * (1 - c) - z * s;
    r.m[0][2] = x * z * (1 - c) + y * s;
    r.m[1][0] = x * y * (1 - c) + z * s;
    r.m[1][1] = y * y + (1 - y * y) * c;
    r.m[1][2] = y * z * (1 - c) - x * s;
    r.m[2][0] = x * z * (1 - c) - y * s;
    r.m[2][1] = y * z * (1 - c) + x * s;
    r.m[2][2] = z * z + (1 - z * z) * c;
    return r;
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

static bool normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(l > 0) || !isfinite(l))
        return false;
    v[0] /= l;
    v[1] /= l;
    v[2] /= l;
    return true;
}

bool cv_mat4_look_at(const double eye[3], const double look[3], const double up[3],
                     struct cv_mat4 *out)
{
    /* Build camera-to-world with columns right, newUp, dir, eye; invert. */
    double dir[3] = {look[0] - eye[0], look[1] - eye[1], look[2] - eye[2]};
    double u[3] = {up[0], up[1], up[2]}, right[3], nup[3];
    *out = cv_mat4_identity();
    if (!normalize(dir) || !normalize(u))
        return false;
    cross(u, dir, right);
    if (!normalize(right))
        return false;
    cross(dir, right, nup);
    struct cv_mat4 c2w = cv_mat4_identity();
    for (int i = 0; i < 3; i++) {
        c2w.m[i][0] = right[i];
        c2w.m[i][1] = nup[i];
        c2w.m[i][2] = dir[i];
        c2w.m[i][3] = eye[i];
    }
    return cv_mat4_inverse(&c2w, out);
}

double cv_mat4_det3(const struct cv_mat4 *a)
{
    const double(*m)[4] = a->m;
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

void cv_mat4_point(const struct cv_mat4 *a, const double p[3], double out[3])
{
    double r[4];
    for (int i = 0; i < 4; i++)
        r[i] = a->m[i][0] * p[0] + a->m[i][1] * p[1] + a->m[i][2] * p[2] + a->m[i][3];
    double w = (r[3] == 1 || r[3] == 0) ? 1 : 1 / r[3];
    out[0] = r[0] * w;
    out[1] = r[1] * w;
    out[2] = r[2] * w;
}

void cv_mat4_vector(const struct cv_mat4 *a, const double v[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = a->m[i][0] * v[0] + a->m[i][1] * v[1] + a->m[i][2] * v[2];
    memcpy(out, r, sizeof(r));
}

