/* animated.c: see animated.h. In double; the GPU's float version of the
 * interpolation is glsl/bvh/motion.glsl's. */
#include "scene/animated.h"

#include <math.h>
#include <string.h>

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

static double sin_x_over_x(double x) { return 1 - x * x / 6 == 1 ? 1 : sin(x) / x; }

void cv_quat_slerp(double t, const double q0[4], const double q1[4], double out[4])
{
    double sum = 0, diff = 0, dot = 0;
    for (int i = 0; i < 4; i++) {
        sum += (q0[i] + q1[i]) * (q0[i] + q1[i]);
        diff += (q1[i] - q0[i]) * (q1[i] - q0[i]);
        dot += q0[i] * q1[i];
    }
    double theta = dot < 0 ? M_PI - 2 * asin(fmin(sqrt(sum) / 2, 1)) : 2 * asin(fmin(sqrt(diff) / 2, 1));
    double s = sin_x_over_x(theta), a = (1 - t) * sin_x_over_x((1 - t) * theta) / s,
           b = t * sin_x_over_x(t * theta) / s, n = 0;
    for (int i = 0; i < 4; i++) {
        out[i] = a * q0[i] + b * q1[i];
        n += out[i] * out[i];
    }
    n = sqrt(n);
    for (int i = 0; i < 4; i++)
        out[i] /= n;
}

bool cv_animated_init(struct cv_animated *a, const double start[3][4], double t0,
                      const double end[3][4], double t1)
{
    struct cv_animated r = {.t0 = t0, .t1 = t1};
    memcpy(r.start, start, sizeof(r.start));
    memcpy(r.end, end, sizeof(r.end));
    if (!cv_motion_decompose(start, r.T[0], r.q[0], r.S[0]) ||
        !cv_motion_decompose(end, r.T[1], r.q[1], r.S[1]))
        return false;
    double dot = 0;
    for (int i = 0; i < 4; i++)
        dot += r.q[0][i] * r.q[1][i];
    if (dot < 0) /* the shorter way round, as pbrt-v4 */
        for (int i = 0; i < 4; i++)
            r.q[1][i] = -r.q[1][i];
    r.moving = t1 > t0 && memcmp(start, end, sizeof(r.start)) != 0;
    *a = r;
    return true;
}

/* at the fraction dt of the way from t0 to t1, composed */
static void at_fraction(const struct cv_animated *a, double dt, double m[3][4])
{
    double T[3], q[4], S[3][3];
    for (int i = 0; i < 3; i++) {
        T[i] = (1 - dt) * a->T[0][i] + dt * a->T[1][i];
        for (int j = 0; j < 3; j++)
            S[i][j] = (1 - dt) * a->S[0][i][j] + dt * a->S[1][i][j];
    }
    cv_quat_slerp(dt, a->q[0], a->q[1], q);
    cv_motion_compose(T, q, S, m);
}

void cv_animated_at(const struct cv_animated *a, double time, double m[3][4])
{
    if (!a->moving || time <= a->t0) {
        memcpy(m, a->start, sizeof(a->start));
        return;
    }
    if (time >= a->t1) {
        memcpy(m, a->end, sizeof(a->end));
        return;
    }
    at_fraction(a, (time - a->t0) / (a->t1 - a->t0), m);
}

static double frobenius(const double S[3][3])
{
    double n = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            n += S[i][j] * S[i][j];
    return sqrt(n);
}

/* Time samples of cv_animated_bounds: the growth per sample is the
 * largest distance moved in 1 / (2 * this) of the motion. */
#define BOUND_STEPS 256

void cv_animated_bounds(const struct cv_animated *a, const float lo[3], const float hi[3],
                        float out_lo[3], float out_hi[3])
{
    double blo[3] = {INFINITY, INFINITY, INFINITY}, bhi[3] = {-INFINITY, -INFINITY, -INFINITY};
    /* largest |x| over the box (|x| is convex: at a corner) */
    double r = 0;
    for (int c = 0; c < 8; c++) {
        double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
        r = fmax(r, sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]));
    }
    double grow = 0;
    int steps = a->moving ? BOUND_STEPS : 0;
    if (a->moving) {
        /* |dp/ddt| <= |T1 - T0| + |R'| |S(dt) x| + |(S1 - S0) x|; slerp
         * turns at 2 theta per unit dt, theta the angle between the
         * quaternions; |S(dt)| <= max(|S0|, |S1|) (Frobenius norms, convex) */
        double dT = 0, dS[3][3], dot = 0;
        for (int i = 0; i < 3; i++) {
            dT += (a->T[1][i] - a->T[0][i]) * (a->T[1][i] - a->T[0][i]);
            for (int j = 0; j < 3; j++)
                dS[i][j] = a->S[1][i][j] - a->S[0][i][j];
        }
        for (int i = 0; i < 4; i++)
            dot += a->q[0][i] * a->q[1][i];
        double theta = acos(fmin(fmax(dot, -1), 1)) * 1.001 + 1e-9;
        double v = sqrt(dT) + 2 * theta * fmax(frobenius(a->S[0]), frobenius(a->S[1])) * r +
                   frobenius(dS) * r;
        grow = v / (2.0 * steps);
    }
    for (int k = 0; k <= steps; k++) {
        double m[3][4];
        if (a->moving)
            at_fraction(a, (double)k / steps, m);
        else
            memcpy(m, a->start, sizeof(m));
        for (int c = 0; c < 8; c++) {
            double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
            for (int i = 0; i < 3; i++) {
                double w = m[i][0] * x[0] + m[i][1] * x[1] + m[i][2] * x[2] + m[i][3];
                blo[i] = fmin(blo[i], w);
                bhi[i] = fmax(bhi[i], w);
            }
        }
    }
    /* the ends exactly too (at_fraction's composition rounds) */
    const double(*ends[2])[4] = {a->start, a->end};
    for (int e = 0; e < 2; e++)
        for (int c = 0; c < 8; c++) {
            double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]};
            for (int i = 0; i < 3; i++) {
                double w = ends[e][i][0] * x[0] + ends[e][i][1] * x[1] + ends[e][i][2] * x[2] + ends[e][i][3];
                blo[i] = fmin(blo[i], w);
                bhi[i] = fmax(bhi[i], w);
            }
        }
    /* beside the growth, a margin for the GPU's float transform of rays
     * and vertices */
    double mag = 0;
    for (int i = 0; i < 3; i++)
        mag = fmax(mag, fmax(fabs(blo[i]), fabs(bhi[i])));
    for (int i = 0; i < 3; i++) {
        out_lo[i] = nextafterf((float)(blo[i] - grow - 1e-5 * mag), -INFINITY);
        out_hi[i] = nextafterf((float)(bhi[i] + grow + 1e-5 * mag), INFINITY);
    }
}
