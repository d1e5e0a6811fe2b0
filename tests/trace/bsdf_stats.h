/* bsdf_stats.h: statistics for the BSDF and light sampling tests: the
 * chi-square goodness-of-fit test of a sampling routine against its pdf
 * (pbrt's approach: a theta x phi histogram over the sphere, expected
 * counts from the pdf integrated numerically per cell, cells with expected
 * < 5 pooled, p-value from the regularized incomplete gamma function). */
#ifndef CV_TESTS_TRACE_BSDF_STATS_H
#define CV_TESTS_TRACE_BSDF_STATS_H

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

/* Histogram resolution: theta over [0, pi], phi over [0, 2 pi). */
#define CHI_THETA 16
#define CHI_PHI 32
#define CHI_CELLS (CHI_THETA * CHI_PHI)
/* Sub-cell midpoint grid used to integrate the pdf over each cell: 10 was
 * too coarse for the narrow lobes of alpha 0.05 (p ~ 1e-8 from the
 * integration error alone; 20 and 30 agree). */
#ifndef CHI_SUB
#define CHI_SUB 20
#endif

/* Regularized upper incomplete gamma Q(a, x), series for x < a + 1, else
 * Lentz's continued fraction. */
static inline double stats_gamma_q(double a, double x)
{
    if (x <= 0)
        return 1;
    double gln = lgamma(a);
    if (x < a + 1) {
        double ap = a, sum = 1 / a, del = sum;
        for (int n = 0; n < 1000; n++) {
            ap += 1;
            del *= x / ap;
            sum += del;
            if (fabs(del) < fabs(sum) * 1e-15)
                break;
        }
        return 1 - sum * exp(-x + a * log(x) - gln);
    }
    double b = x + 1 - a, c = 1 / 1e-300, d = 1 / b, h = d;
    for (int i = 1; i < 1000; i++) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (fabs(d) < 1e-300)
            d = 1e-300;
        c = b + an / c;
        if (fabs(c) < 1e-300)
            c = 1e-300;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1) < 1e-15)
            break;
    }
    return exp(-x + a * log(x) - gln) * h;
}

static inline int stats_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The cell of a unit direction. */
static inline int stats_cell(const float w[3])
{
    double z = w[2] < -1 ? -1 : (w[2] > 1 ? 1 : w[2]);
    double theta = acos(z), phi = atan2(w[1], w[0]);
    if (phi < 0)
        phi += 2 * M_PI;
    int t = (int)(theta / M_PI * CHI_THETA), p = (int)(phi / (2 * M_PI) * CHI_PHI);
    t = t < 0 ? 0 : (t >= CHI_THETA ? CHI_THETA - 1 : t);
    p = p < 0 ? 0 : (p >= CHI_PHI ? CHI_PHI - 1 : p);
    return t * CHI_PHI + p;
}

/* Directions at which to evaluate the pdf: CHI_SUB^2 midpoints per cell,
 * cell-major; 4 floats each. */
static inline float *stats_grid_dirs(size_t *n)
{
    *n = (size_t)CHI_CELLS * CHI_SUB * CHI_SUB;
    float *d = calloc(*n * 4, sizeof(float));
    size_t k = 0;
    for (int t = 0; t < CHI_THETA; t++)
        for (int p = 0; p < CHI_PHI; p++)
            for (int i = 0; i < CHI_SUB; i++)
                for (int j = 0; j < CHI_SUB; j++, k++) {
                    double theta = (t + (i + 0.5) / CHI_SUB) * M_PI / CHI_THETA;
                    double phi = (p + (j + 0.5) / CHI_SUB) * 2 * M_PI / CHI_PHI;
                    d[4 * k] = (float)(sin(theta) * cos(phi));
                    d[4 * k + 1] = (float)(sin(theta) * sin(phi));
                    d[4 * k + 2] = (float)cos(theta);
                }
    return d;
}

/* Per-cell integral of the pdf from values at stats_grid_dirs' points
 * (value i at pdf[stride * i]). */
static inline void stats_integrate(const float *pdf, size_t stride, double *cell)
{
    size_t k = 0;
    double dt = M_PI / CHI_THETA / CHI_SUB, dp = 2 * M_PI / CHI_PHI / CHI_SUB;
    for (int t = 0; t < CHI_THETA; t++)
        for (int p = 0; p < CHI_PHI; p++) {
            double s = 0;
            for (int i = 0; i < CHI_SUB; i++) {
                double theta = (t + (i + 0.5) / CHI_SUB) * M_PI / CHI_THETA;
                for (int j = 0; j < CHI_SUB; j++, k++)
                    s += pdf[stride * k] * sin(theta) * dt * dp;
            }
            cell[t * CHI_PHI + p] = s;
        }
}

struct stats_chi2 {
    double p_value;
    double chi2;
    int dof;
    bool zero_cell_hit;  /* samples where the pdf integrates to 0 */
    double total_expected; /* integral of the pdf over the sphere */
};

/* observed: counts per cell out of n samples; expected_pdf: pdf integral
 * per cell (scaled by n here). */
static inline struct stats_chi2 stats_chi2_test(const double *observed, const double *cell_pdf, double n)
{
    struct stats_chi2 r = {0};
    double pairs[CHI_CELLS][2];
    for (int i = 0; i < CHI_CELLS; i++) {
        pairs[i][0] = cell_pdf[i] * n;
        pairs[i][1] = observed[i];
        r.total_expected += cell_pdf[i];
        if (cell_pdf[i] == 0 && observed[i] > n * 1e-5)
            r.zero_cell_hit = true;
    }
    qsort(pairs, CHI_CELLS, sizeof(pairs[0]), stats_cmp_double);
    double pooled_e = 0, pooled_o = 0, chi = 0;
    int cells = 0;
    for (int i = 0; i < CHI_CELLS; i++) {
        double e = pairs[i][0], o = pairs[i][1];
        if (e == 0)
            continue;
        if (e < 5) {
            pooled_e += e;
            pooled_o += o;
            continue;
        }
        if (pooled_e > 0 && pooled_e < 5) {
            /* fold a still-small pool into this cell */
            e += pooled_e;
            o += pooled_o;
            pooled_e = pooled_o = 0;
        }
        chi += (o - e) * (o - e) / e;
        cells++;
    }
    if (pooled_e >= 5) {
        chi += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
        cells++;
    }
    r.dof = cells - 1;
    r.chi2 = chi;
    r.p_value = r.dof > 0 ? stats_gamma_q(r.dof / 2.0, chi / 2.0) : 1;
    return r;
}

/* Šidák: per-test significance so that `tests` tests together keep alpha. */
static inline double stats_sidak(double alpha, int tests)
{
    return 1 - pow(1 - alpha, 1.0 / tests);
}

#endif
