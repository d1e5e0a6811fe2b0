/* filter_table_test.c: the Gaussian filter's inverse-CDF table: ends at 0
 * and 1, increasing, symmetric, and its quartiles where the truncated
 * Gaussian's are (found by integrating the filter here). */
#include "config.h"

#include <math.h>

#include "tests/tap.h"
#include "trace/filter_table.h"

#define N 64

int main(void)
{
    float t[N + 1];
    const float radius = 1.5f, sigma = 0.5f;
    cv_gaussian_filter_table(radius, sigma, t, N);
    tap_ok(t[0] == 0 && t[N] == 1, "ends at 0 and 1");
    bool inc = true, sym = true;
    for (int i = 0; i < N; i++)
        inc = inc && t[i + 1] > t[i];
    for (int i = 0; i <= N; i++)
        sym = sym && fabsf(t[i] + t[N - i] - 1) < 1e-4f;
    tap_ok(inc, "strictly increasing");
    tap_ok(sym, "symmetric about the centre");
    tap_ok(fabsf(t[N / 2] - 0.5f) < 1e-4f, "median at the centre (%.5f)", t[N / 2]);
    /* first quartile by direct integration of exp(-x^2/2s^2) - exp(-r^2/2s^2) */
    double edge = exp(-radius * radius / (2 * sigma * sigma)), total = 0, acc = 0, q1 = 0;
    const int steps = 200000;
    for (int i = 0; i < steps; i++) {
        double x = -radius + 2 * radius * (i + 0.5) / steps;
        total += exp(-x * x / (2 * sigma * sigma)) - edge;
    }
    for (int i = 0; i < steps; i++) {
        double x = -radius + 2 * radius * (i + 0.5) / steps;
        acc += exp(-x * x / (2 * sigma * sigma)) - edge;
        if (acc >= total / 4) {
            q1 = (x + radius) / (2 * radius);
            break;
        }
    }
    tap_ok(fabs(t[N / 4] - q1) < 1e-3, "first quartile %.5f matches %.5f", t[N / 4], q1);
    return tap_done();
}
