/* animated_test.c: pbrt-v4's AnimatedTransform on the host
 * (src/scene/animated.c):
 * - the interpolation against values worked by hand: translation and
 *   scale linear, rotation by slerp (the arc, not the chord), the shorter
 *   way round, a non-uniform scale kept apart from the rotation, the ends
 *   held before the start time and after the end time;
 * - motion bounds hold the box's corners and random points inside it at
 *   many times over the motion, for random transforms with large turns;
 *   the boxes of the two ends alone (the bound without the sweep) are
 *   shown to miss points of a turning box, so the check has teeth; and the
 *   bounds are at most two hundredths of the sweep's size above the
 *   sampled sweep.
 * Fixed seeds. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "scene/animated.h"
#include "scene/transform.h"
#include "tests/rng.h"
#include "tests/tap.h"

static uint64_t rng = 0x2545f4914f6cdd1dull;
static double rnd(void)
{
    return cv_test_xorshift64(&rng);
}

static void rows(const struct cv_mat4 *a, double m[3][4])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m[r][c] = a->m[r][c];
}

static void apply(const double m[3][4], const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
}

static bool point_is(const double m[3][4], double x, double y, double z, double ex, double ey, double ez)
{
    double p[3] = {x, y, z}, w[3];
    apply(m, p, w);
    return fabs(w[0] - ex) < 1e-9 && fabs(w[1] - ey) < 1e-9 && fabs(w[2] - ez) < 1e-9;
}

static struct cv_mat4 mul3(struct cv_mat4 a, struct cv_mat4 b, struct cv_mat4 c)
{
    struct cv_mat4 ab = cv_mat4_mul(&a, &b);
    return cv_mat4_mul(&ab, &c);
}

static void test_interpolation(void)
{
    struct cv_animated a;
    double m0[3][4], m1[3][4], m[3][4];
    /* identity at time 2 to Translate 2 0 0, Rotate 90 about z, Scale 3
     * at time 4 */
    struct cv_mat4 id = cv_mat4_identity();
    struct cv_mat4 end = mul3(cv_mat4_translate(2, 0, 0), cv_mat4_rotate(90, 0, 0, 1), cv_mat4_scale(3, 3, 3));
    rows(&id, m0);
    rows(&end, m1);
    tap_ok(cv_animated_init(&a, m0, 2, m1, 4) && a.moving, "translate, rotate and scale: moving");
    cv_animated_at(&a, 3, m);
    /* halfway: Translate 1 0 0, Rotate 45, Scale 2: (1,0,0) -> (1 + sqrt 2, sqrt 2, 0) */
    tap_ok(point_is(m, 1, 0, 0, 1 + sqrt(2), sqrt(2), 0) && point_is(m, 0, 0, 1, 1, 0, 2),
           "halfway: translation and scale halfway, rotation by 45 degrees (%g %g %g)",
           m[0][0] + m[0][3], m[1][0] + m[1][3], m[2][0] + m[2][3]);
    cv_animated_at(&a, 2.5, m);
    /* a quarter: Translate 0.5, Rotate 22.5, Scale 1.5 */
    tap_ok(point_is(m, 1, 0, 0, 0.5 + 1.5 * cos(M_PI / 8), 1.5 * sin(M_PI / 8), 0),
           "a quarter of the way: the arc at 22.5 degrees, not the chord");
    cv_animated_at(&a, 1, m);
    tap_ok(memcmp(m, m0, sizeof(m)) == 0, "before the start time: the start transform, exactly");
    cv_animated_at(&a, 9, m);
    tap_ok(memcmp(m, m1, sizeof(m)) == 0, "after the end time: the end transform, exactly");
    /* 270 degrees about z is -90 the short way: halfway is -45 */
    struct cv_mat4 r270 = cv_mat4_rotate(270, 0, 0, 1);
    rows(&r270, m1);
    cv_animated_init(&a, m0, 0, m1, 1);
    cv_animated_at(&a, 0.5, m);
    tap_ok(point_is(m, 1, 0, 0, sqrt(0.5), -sqrt(0.5), 0), "270 degrees turns -90, the shorter way");
    /* a non-uniform scale under a turning rotation stays in the object's frame */
    struct cv_mat4 s = cv_mat4_scale(1, 2, 1);
    struct cv_mat4 r90 = cv_mat4_rotate(90, 0, 0, 1), rs = cv_mat4_mul(&r90, &s);
    rows(&s, m0);
    rows(&rs, m1);
    cv_animated_init(&a, m0, 0, m1, 1);
    cv_animated_at(&a, 0.5, m);
    tap_ok(point_is(m, 0, 1, 0, -sqrt(2), sqrt(2), 0), "Scale 1 2 1 turning: (0,1,0) -> 2 at 135 degrees");
    /* a handedness swap at both ends moves as its matrices say */
    struct cv_mat4 f0 = cv_mat4_scale(-1, 1, 1), up = cv_mat4_translate(0, 4, 0), f1 = cv_mat4_mul(&up, &f0);
    rows(&f0, m0);
    rows(&f1, m1);
    cv_animated_init(&a, m0, 0, m1, 1);
    cv_animated_at(&a, 0.25, m);
    tap_ok(point_is(m, 1, 0, 0, -1, 1, 0), "a mirrored shape slides mirrored");
    /* equal ends, or times that do not increase: no motion */
    rows(&id, m0);
    tap_ok(cv_animated_init(&a, m0, 0, m0, 1) && !a.moving, "equal ends do not move");
    struct cv_mat4 zero = cv_mat4_scale(0, 1, 1);
    rows(&zero, m1);
    tap_ok(!cv_animated_init(&a, m0, 0, m1, 1), "a singular end is refused");
}

static void random_transform(double m[3][4])
{
    double axis[3] = {rnd() - 0.5, rnd() - 0.5, rnd() - 0.5};
    struct cv_mat4 r = cv_mat4_rotate(rnd() * 360 - 180, axis[0], axis[1], axis[2]);
    struct cv_mat4 t = cv_mat4_translate(rnd() * 4 - 2, rnd() * 4 - 2, rnd() * 4 - 2);
    struct cv_mat4 s = cv_mat4_scale(0.5 + rnd() * 2, 0.5 + rnd() * 2, 0.5 + rnd() * 2);
    struct cv_mat4 a = mul3(t, r, s);
    rows(&a, m);
}

static bool inside(const float lo[3], const float hi[3], const double w[3])
{
    return w[0] >= lo[0] && w[0] <= hi[0] && w[1] >= lo[1] && w[1] <= hi[1] && w[2] >= lo[2] && w[2] <= hi[2];
}

static void test_bounds(void)
{
    int outside = 0, naive_outside = 0, loose = 0;
    double worst_slack = 0;
    for (int k = 0; k < 200; k++) {
        double m0[3][4], m1[3][4];
        random_transform(m0);
        random_transform(m1);
        struct cv_animated a;
        if (!cv_animated_init(&a, m0, 0, m1, 1))
            continue;
        float lo[3], hi[3], blo[3], bhi[3];
        for (int c = 0; c < 3; c++) {
            lo[c] = (float)(rnd() * 2 - 1);
            hi[c] = lo[c] + (float)(0.1 + rnd());
        }
        cv_animated_bounds(&a, lo, hi, blo, bhi);
        /* the ends' boxes alone */
        float nlo[3] = {INFINITY, INFINITY, INFINITY}, nhi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int e = 0; e < 2; e++)
            for (int c = 0; c < 8; c++) {
                double x[3] = {c & 1 ? hi[0] : lo[0], c & 2 ? hi[1] : lo[1], c & 4 ? hi[2] : lo[2]}, w[3];
                apply(e ? m1 : m0, x, w);
                for (int i = 0; i < 3; i++) {
                    nlo[i] = fminf(nlo[i], (float)w[i]);
                    nhi[i] = fmaxf(nhi[i], (float)w[i]);
                }
            }
        double slo[3] = {INFINITY, INFINITY, INFINITY}, shi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int it = 0; it <= 2000; it++) {
            double m[3][4], x[3], w[3];
            cv_animated_at(&a, it / 2000.0, m);
            for (int c = 0; c < 12; c++) {
                for (int i = 0; i < 3; i++)
                    x[i] = c < 8 ? ((c >> i) & 1 ? hi[i] : lo[i]) : lo[i] + rnd() * (hi[i] - lo[i]);
                apply(m, x, w);
                if (!inside(blo, bhi, w))
                    outside++;
                if (!inside(nlo, nhi, w))
                    naive_outside++;
                for (int i = 0; i < 3; i++) {
                    slo[i] = fmin(slo[i], w[i]);
                    shi[i] = fmax(shi[i], w[i]);
                }
            }
        }
        double size = 0;
        for (int i = 0; i < 3; i++)
            size = fmax(size, shi[i] - slo[i]);
        for (int i = 0; i < 3; i++) {
            double slack = fmax(slo[i] - blo[i], bhi[i] - shi[i]) / size;
            worst_slack = fmax(worst_slack, slack);
            if (slack > 0.02)
                loose++;
        }
    }
    tap_ok(outside == 0, "motion bounds hold every sampled point at every sampled time (%d outside)", outside);
    tap_ok(naive_outside > 0, "the ends' boxes alone would not (%d points outside them)", naive_outside);
    tap_ok(loose == 0, "motion bounds exceed the sampled sweep by at most 2%% of its size (worst %.4f)",
           worst_slack);
    /* a still transform: the box under it */
    double m[3][4];
    random_transform(m);
    struct cv_animated a;
    cv_animated_init(&a, m, 0, m, 1);
    float lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1}, blo[3], bhi[3];
    cv_animated_bounds(&a, lo, hi, blo, bhi);
    double c[3] = {1, 1, 1}, w[3];
    apply(m, c, w);
    tap_ok(!a.moving && inside(blo, bhi, w), "a still transform's bounds hold its box");
}

int main(void)
{
    test_interpolation();
    test_bounds();
    return tap_done();
}
