/* transform.h: 4x4 row-major affine/projective matrices for the pbrt
 * transform directives. m[r][c]; points are column vectors (p' = M p), as in
 * pbrt, so `Transform [...]` (column-major in the file) is transposed on read. */
#ifndef CV_SCENE_TRANSFORM_H
#define CV_SCENE_TRANSFORM_H

#include <stdbool.h>

struct cv_mat4 {
    double m[4][4];
};

struct cv_mat4 cv_mat4_identity(void);
struct cv_mat4 cv_mat4_mul(const struct cv_mat4 *a, const struct cv_mat4 *b);
/* false when singular; *out is then the identity. */
bool cv_mat4_inverse(const struct cv_mat4 *a, struct cv_mat4 *out);
struct cv_mat4 cv_mat4_translate(double x, double y, double z);
struct cv_mat4 cv_mat4_scale(double x, double y, double z);
/* angle in degrees about axis (need not be normalized; zero axis: identity). */
struct cv_mat4 cv_mat4_rotate(double angle_deg, double x, double y, double z);
/* pbrt's LookAt: the world-to-camera matrix; false if up is parallel to the
 * view direction or eye == look. */
bool cv_mat4_look_at(const double eye[3], const double look[3], const double up[3],
                     struct cv_mat4 *out);
/* Determinant of the upper 3x3: negative means the transform swaps handedness. */
double cv_mat4_det3(const struct cv_mat4 *a);
void cv_mat4_point(const struct cv_mat4 *a, const double p[3], double out[3]);
void cv_mat4_vector(const struct cv_mat4 *a, const double v[3], double out[3]);
/* Transforms a normal by the inverse transpose `inv` of the point transform
 * (not normalized). Inline: the scene builder's per-vertex loop calls it. */
static inline void cv_mat4_normal(const struct cv_mat4 *inv, const double n[3], double out[3])
{
    double r[3];
    for (int i = 0; i < 3; i++)
        r[i] = inv->m[0][i] * n[0] + inv->m[1][i] * n[1] + inv->m[2][i] * n[2];
    out[0] = r[0];
    out[1] = r[1];
    out[2] = r[2];
}

#endif
