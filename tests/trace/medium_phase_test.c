/* medium_phase_test.c: the shipped Henyey-Greenstein phase function
 * (glsl/trace/medium/medium.glsl) against its density and against the
 * formula, for forward, backward and isotropic g and oblique wo:
 * - chi-square of 200000 sampled directions against cv_hg_pdf integrated
 *   over a theta x phi histogram (tests/trace/bsdf_stats.h: pbrt's test),
 *   alpha 0.01 with the Šidák correction over the runs;
 * - the density integrates to 1 over the sphere;
 * - the density returned with each sample equals cv_hg_pdf at it, and
 *   cv_hg_pdf equals pbrt-v4's formula computed here in double;
 * - the mean cosine between the incoming direction (-wo) and wi is g:
 *   g > 0 scatters forward, as in pbrt-v4. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/gpu/probe.h"
#include "tests/trace/bsdf_stats.h"

#define N 200000

struct phase_case {
    float g;
    float wo[3];
};

static const struct phase_case cases[] = {
    {0.0f, {0, 0, 1}},
    {0.3f, {0, 0, 1}},
    {0.8f, {0.6f, 0, 0.8f}},
    {-0.6f, {0, 0.6f, -0.8f}},
    {0.95f, {-0.48f, 0.6f, 0.64f}},
};
#define N_CASES (sizeof(cases) / sizeof(cases[0]))

/* pbrt-v4's HenyeyGreenstein(cos_theta, g), cos_theta = dot(wo, wi). */
static double hg(double cos_theta, double g)
{
    double d = 1 + g * g + 2 * g * cos_theta;
    return (1 - g * g) / (4 * M_PI * d * sqrt(d));
}

static bool run(struct cv_program *prog, unsigned mode, const struct phase_case *c,
                const float *in, size_t n, float *out, struct cv_error *err)
{
    GLuint id = probe_use(prog);
    glUniform1ui(glGetUniformLocation(id, "u_seed"), 77);
    glUniform3f(glGetUniformLocation(id, "u_wo"), c->wo[0], c->wo[1], c->wo[2]);
    glUniform1f(glGetUniformLocation(id, "u_g"), c->g);
    return probe_dispatch(prog, mode, in, n * 16, n, out, n * 16, err);
}

static void check_case(struct cv_program *prog, const struct phase_case *c, double alpha)
{
    struct cv_error err = {{0}};
    float *s = cv_xmalloc((size_t)N * 16);
    size_t ng;
    float *grid = stats_grid_dirs(&ng);
    float *gp = cv_xmalloc(ng * 16);
    float *sp = cv_xmalloc((size_t)N * 16);
    if (!tap_ok(run(prog, 0, c, NULL, N, s, &err) && run(prog, 1, c, grid, ng, gp, &err) &&
                    run(prog, 1, c, s, N, sp, &err),
                "g %.2f: probe runs %s", c->g, err.msg))
        goto done;
    double *obs = calloc(CHI_CELLS, sizeof(double)), *cell = calloc(CHI_CELLS, sizeof(double));
    double mean_cos = 0, worst_pdf = 0, worst_formula = 0;
    for (size_t i = 0; i < N; i++) {
        const float *w = s + 4 * i;
        obs[stats_cell(w)] += 1;
        mean_cos -= (c->wo[0] * w[0] + c->wo[1] * w[1] + c->wo[2] * w[2]) / N;
        worst_pdf = fmax(worst_pdf, fabs(w[3] - sp[4 * i]) / sp[4 * i]);
    }
    for (size_t i = 0; i < ng; i += 997) {
        const float *w = grid + 4 * i;
        double f = hg(c->wo[0] * w[0] + c->wo[1] * w[1] + c->wo[2] * w[2], c->g);
        worst_formula = fmax(worst_formula, fabs(gp[4 * i] - f) / f);
    }
    stats_integrate(gp, 4, cell);
    struct stats_chi2 r = stats_chi2_test(obs, cell, N);
    tap_ok(r.p_value > alpha && !r.zero_cell_hit, "g %.2f: chi-square p = %.4f (chi2 %.1f, %d dof)",
           c->g, r.p_value, r.chi2, r.dof);
    tap_ok(fabs(r.total_expected - 1) < 2e-3, "g %.2f: the density integrates to %.5f", c->g,
           r.total_expected);
    tap_ok(worst_pdf < 1e-4 && worst_formula < 1e-4,
           "g %.2f: sampled pdf = cv_hg_pdf (worst %.2g), cv_hg_pdf = pbrt-v4's formula (worst %.2g)",
           c->g, worst_pdf, worst_formula);
    tap_ok(fabs(mean_cos - c->g) < 0.01, "g %.2f: mean cosine to the incoming direction %.4f",
           c->g, mean_cos);
    free(obs);
    free(cell);
done:
    free(s);
    free(grid);
    free(gp);
    free(sp);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_program *prog = cv_program_get(gpu, "trace/test/phase_probe.comp", NULL, &err);
    if (tap_ok(prog != NULL, "phase_probe.comp compiles: %s", prog ? "" : err.msg)) {
        double alpha = stats_sidak(0.01, (int)N_CASES);
        for (size_t i = 0; i < N_CASES; i++)
            check_case(prog, &cases[i], alpha);
    }
    cv_gpu_destroy(&gpu);
    return tap_done();
}
