/* rlpath_stats.h: statistics for the rlpath tests: the chi-square upper
 * tail probability (regularised upper incomplete gamma function, by its
 * series below a + 1 and Lentz's continued fraction above, as in the
 * standard numerical treatments) and a pooled chi-square test of observed
 * against expected counts, and its TAP report. */
#ifndef CV_TESTS_TRACE_RLPATH_STATS_H
#define CV_TESTS_TRACE_RLPATH_STATS_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdlib.h>

#include "tests/tap.h"

/* Q(a, x) = Gamma(a, x) / Gamma(a). */
static inline double rl_gamma_q(double a, double x)
{
    if (x <= 0)
        return 1;
    double lg = lgamma(a);
    if (x < a + 1) {
        double term = 1 / a, sum = term;
        for (int n = 1; n < 10000; n++) {
            term *= x / (a + n);
            sum += term;
            if (fabs(term) < fabs(sum) * 1e-15)
                break;
        }
        return 1 - sum * exp(-x + a * log(x) - lg);
    }
    const double tiny = 1e-300;
    double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
    for (int i = 1; i < 10000; i++) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (fabs(d) < tiny)
            d = tiny;
        c = b + an / c;
        if (fabs(c) < tiny)
            c = tiny;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (fabs(del - 1) < 1e-15)
            break;
    }
    return exp(-x + a * log(x) - lg) * h;
}

/* Pools cells in order until each pool expects at least 5 (a short tail
 * joins the last pool), then returns the p-value of the chi-square
 * statistic with pools - 1 degrees of freedom (*dof_out); 0 when samples
 * fall where nothing is expected. */
static inline double rl_chi2_pvalue(const double *observed, const double *expected, size_t n,
                                    int *dof_out)
{
    double *po = calloc(n + 1, sizeof(double)), *pe = calloc(n + 1, sizeof(double));
    size_t pools = 0;
    double o = 0, e = 0;
    for (size_t i = 0; i < n; i++) {
        o += observed[i];
        e += expected[i];
        if (e >= 5) {
            po[pools] = o;
            pe[pools++] = e;
            o = e = 0;
        }
    }
    if (o > 0 || e > 0) {
        if (pools > 0) {
            po[pools - 1] += o;
            pe[pools - 1] += e;
        } else {
            po[pools] = o;
            pe[pools++] = e;
        }
    }
    double chi2 = 0;
    bool impossible = false;
    for (size_t k = 0; k < pools; k++) {
        if (pe[k] > 0)
            chi2 += (po[k] - pe[k]) * (po[k] - pe[k]) / pe[k];
        else if (po[k] > 0)
            impossible = true;
    }
    free(po);
    free(pe);
    int dof = (int)pools - 1;
    if (dof_out)
        *dof_out = dof;
    if (impossible)
        return 0;
    return dof > 0 ? rl_gamma_q(dof / 2.0, chi2 / 2.0) : 1;
}

/* The pooled chi-square test of a w x h histogram (observed) against its
 * expected counts, reported as one TAP line labelled what: passes at
 * p >= 0.01. */
static inline bool rl_chi2_check(const double *observed, const double *expected, unsigned w,
                                 unsigned h, const char *what)
{
    int dof = 0;
    double pv = rl_chi2_pvalue(observed, expected, (size_t)w * h, &dof);
    return tap_ok(pv >= 0.01, "%s: chi-square over %ux%u cells: p = %.4f (dof %d) >= 0.01", what,
                  w, h, pv, dof);
}

#endif
