/* bssrdf_sample_test.c: the shipped BSSRDF profile code
 * (glsl/trace/bsdf/bssrdf.glsl, through trace/test/bssrdf_probe.comp) on
 * tables made by src/scene/bssrdf_table.c, for several albedos,
 * extinctions and (g, eta):
 * - chi-square of 200000 radii drawn by cv_bssrdf_sample_sr against the
 *   density it returns (2 pi r pdf_Sr, integrated over 512 radial cells,
 *   tests/trace/bsdf_stats.h), alpha 0.01 with the Šidák correction over
 *   the runs: the sampling inverts the profile it evaluates;
 * - that density integrates to 1 over the plane (the profile's
 *   normalisation by the effective albedo);
 * - Sr at a table node is the node's value over 2 pi r, times sigma_t^2
 *   (pbrt-v4's units), computed here from the table;
 * - the GPU's inversion of effective albedos (textured reflectance) finds
 *   the albedos src/scene/bssrdf_table.c finds. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/bssrdf_table.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/gpu/probe.h"
#include "tests/trace/bsdf_stats.h"
#include "trace/rlpath.h"

#define N 200000
#define CELL_A 0.01 /* optical radius where the cells turn from even to logarithmic */

struct sr_case {
    unsigned table;
    float rho, sigma_t;
};

/* tables: 0 (g 0, eta 1.33), 1 (g 0.3, eta 1.5) */
static const struct sr_case cases[] = {
    {0, 0.9f, 1.0f}, {0, 0.3f, 2.5f}, {1, 0.99f, 0.5f}, {1, 0.6f, 10.0f}, {0, 0.999f, 4.0f},
};
#define N_CASES (sizeof(cases) / sizeof(cases[0]))

static double cell_edge(int k, double r_max)
{
    return CELL_A * (exp((double)k / CHI_CELLS * log(1 + r_max / CELL_A)) - 1);
}

static bool run(struct cv_program *prog, unsigned mode, const struct sr_case *c, const float *in,
                size_t n, float *out, struct cv_error *err)
{
    GLuint id = probe_use(prog);
    glUniform1ui(glGetUniformLocation(id, "u_seed"), 91);
    glUniform1ui(glGetUniformLocation(id, "u_table"), c->table);
    glUniform1f(glGetUniformLocation(id, "u_rho"), c->rho);
    glUniform1f(glGetUniformLocation(id, "u_sigma_t"), c->sigma_t);
    return probe_dispatch(prog, mode, in, n * 16, n, out, n * 16, err);
}

static void check_case(struct cv_program *prog, const float *tables, const struct sr_case *c, double alpha)
{
    struct cv_error err = {{0}};
    const float *t = tables + (size_t)c->table * CV_BSSRDF_FLOATS;
    double r_max = t[CV_BSSRDF_RADIUS + CV_BSSRDF_N_RADIUS - 1] / c->sigma_t;
    size_t ng = (size_t)CHI_CELLS * CHI_SUB;
    float *s = cv_xmalloc((size_t)N * 16), *grid = cv_xcalloc(ng, 16), *gp = cv_xmalloc(ng * 16);
    double *width = cv_xmalloc(ng * sizeof(double));
    for (int k = 0; k < CHI_CELLS; k++) {
        double a = cell_edge(k, r_max), b = cell_edge(k + 1, r_max);
        for (int j = 0; j < CHI_SUB; j++) {
            grid[4 * (k * CHI_SUB + j)] = (float)(a + (j + 0.5) * (b - a) / CHI_SUB);
            width[k * CHI_SUB + j] = (b - a) / CHI_SUB;
        }
    }
    if (!tap_ok(run(prog, 0, c, NULL, N, s, &err) && run(prog, 1, c, grid, ng, gp, &err),
                "rho %.3f sigma_t %.1f: probe runs %s", c->rho, c->sigma_t, err.msg))
        goto done;
    double *obs = cv_xcalloc(CHI_CELLS, sizeof(double)), *cell = cv_xcalloc(CHI_CELLS, sizeof(double));
    int missed = 0;
    for (size_t i = 0; i < N; i++) {
        double r = s[4 * i];
        if (!(r >= 0 && r <= r_max)) {
            missed++;
            continue;
        }
        int lo = 0, hi = CHI_CELLS;
        while (hi - lo > 1) {
            int mid = (lo + hi) / 2;
            if (cell_edge(mid, r_max) <= r)
                lo = mid;
            else
                hi = mid;
        }
        obs[lo] += 1;
    }
    for (size_t i = 0; i < ng; i++)
        cell[i / CHI_SUB] += 2 * M_PI * grid[4 * i] * gp[4 * i + 1] * width[i];
    struct stats_chi2 r = stats_chi2_test(obs, cell, N);
    tap_ok(missed == 0 && r.p_value > alpha && !r.zero_cell_hit,
           "rho %.3f sigma_t %.1f: chi-square p = %.4f (chi2 %.1f, %d dof), %d radii outside the table",
           c->rho, c->sigma_t, r.p_value, r.chi2, r.dof, missed);
    tap_ok(fabs(r.total_expected - 1) < 2e-3, "rho %.3f sigma_t %.1f: the density integrates to %.5f",
           c->rho, c->sigma_t, r.total_expected);
    free(obs);
    free(cell);
done:
    free(s);
    free(grid);
    free(gp);
    free(width);
}

/* Sr at albedo node i and radius node j against the table's value. */
static void check_node(struct cv_program *prog, const float *tables)
{
    struct cv_error err = {{0}};
    const float *t = tables;
    static const int nodes[][2] = {{60, 5}, {80, 20}, {95, 40}};
    bool ok = true;
    for (size_t k = 0; k < sizeof(nodes) / sizeof(nodes[0]); k++) {
        int i = nodes[k][0], j = nodes[k][1];
        struct sr_case c = {0, t[CV_BSSRDF_RHO + i], 2.0f};
        float in[4] = {t[CV_BSSRDF_RADIUS + j] / c.sigma_t, 0, 0, 0}, out[4];
        double ro = t[CV_BSSRDF_RADIUS + j];
        double want = t[CV_BSSRDF_PROFILE + i * CV_BSSRDF_N_RADIUS + j] / (2 * M_PI * ro) * c.sigma_t * c.sigma_t;
        double want_pdf = want / t[CV_BSSRDF_RHO_EFF + i];
        if (!run(prog, 1, &c, in, 1, out, &err) || fabs(out[0] - want) > 1e-4 * want ||
            fabs(out[1] - want_pdf) > 1e-4 * want_pdf) {
            ok = false;
            tap_diag("node %d,%d: Sr %.7g (table %.7g), pdf %.7g (%.7g) %s", i, j, out[0], want, out[1], want_pdf,
                     err.msg);
        }
    }
    tap_ok(ok, "Sr and pdf_Sr at table nodes: the table's values in scene units");
}

/* cv_bssrdf_invert against cv_bssrdf_invert_rho_eff over the table's range. */
static void check_invert(struct cv_program *prog, const float *tables)
{
    struct cv_error err = {{0}};
    enum { M = 64 };
    float in[4 * M] = {0}, out[4 * M];
    for (unsigned t = 0; t < 2; t++) {
        struct sr_case c = {t, 0, 1};
        for (int k = 0; k < M; k++)
            in[4 * k] = (float)k / (M - 1) * 1.05f;  /* beyond both ends too */
        double worst = 0;
        bool ok = run(prog, 2, &c, in, M, out, &err);
        for (int k = 0; ok && k < M; k++) {
            double want = cv_bssrdf_invert_rho_eff(tables + (size_t)t * CV_BSSRDF_FLOATS, in[4 * k]);
            worst = fmax(worst, fabs(out[4 * k] - want) / fmax(1 - want, 1e-3));
        }
        tap_ok(ok && worst < 1e-3, "table %u: GPU inverts effective albedos as the CPU (worst %.2g of 1 - rho) %s",
               t, worst, err.msg);
    }
}

int main(void)
{
    (void)stats_cell;  /* the direction helpers of bsdf_stats.h: not for radii */
    (void)stats_grid_dirs;
    (void)stats_integrate;
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    size_t n = 2 * (size_t)CV_BSSRDF_FLOATS;
    float *tables = cv_xmalloc(n * sizeof(float));
    cv_bssrdf_table_compute(0, 1.33, tables);
    cv_bssrdf_table_compute(0.3, 1.5, tables + CV_BSSRDF_FLOATS);
    GLuint buf = cv_buffer_create(n * sizeof(float), tables, "bssrdf tables", &err);
    GLuint tex = buf ? cv_buffer_texture(buf, GL_R32F, n, &err) : 0;
    struct cv_program *prog = tex ? cv_program_get(gpu, "trace/test/bssrdf_probe.comp", NULL, &err) : NULL;
    if (tap_ok(prog != NULL, "bssrdf_probe.comp compiles, tables bound: %s", prog ? "" : err.msg)) {
        glBindTextureUnit(CV_TEXUNIT_BSSRDF, tex);
        double alpha = stats_sidak(0.01, (int)N_CASES);
        for (size_t i = 0; i < N_CASES; i++)
            check_case(prog, tables, &cases[i], alpha);
        check_node(prog, tables);
        check_invert(prog, tables);
    }
    if (tex)
        glDeleteTextures(1, &tex);
    cv_buffer_destroy(&buf);
    free(tables);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
