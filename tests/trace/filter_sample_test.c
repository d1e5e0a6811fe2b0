/* filter_sample_test.c: the pixel filter sampling that ships
 * (glsl/trace/filter.glsl, with the tables of src/trace/filter_table.c)
 * run through a probe shader. For each filter, the offsets' 2D histogram
 * (32 x 16 cells over the filter's extent) must follow |f| by a chi-square
 * test: expected counts from the density pbrt-v4's FilterSampler samples,
 * |f| constant over cells of 1/32 pixel at its value at their centres
 * (box and triangle: |f| itself), integrated here over each histogram
 * cell; the histogram cells do not line up with the table's for the
 * Gaussian's 48, where the continuous |f| gives p 1e-4 at a million
 * samples. Each sample's weight must be the sign of f where it lands (away
 * from f's zeros, where a table cell may straddle one), and their mean
 * the integral of f over that of |f|. Fixed seeds. */
#include "config.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/filter.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/trace/bsdf_stats.h"
#include "trace/filter_table.h"

#define NX 32
#define NY 16
#define N_SAMPLES (1u << 20)
#define SUB 64

_Static_assert(NX * NY == CHI_CELLS, "one chi-square cell per histogram cell");

struct filter_case {
    const char *what;
    enum cv_filter_type type;
    float rx, ry;
    float b, c, tau, sigma;
};

static const struct filter_case cases[] = {
    {"mitchell (defaults)", CV_FILTER_MITCHELL, 2, 2, 1.0f / 3, 1.0f / 3, 3, 0.5f},
    {"mitchell B 0 C 0.75, radius 2.5 x 1.5", CV_FILTER_MITCHELL, 2.5f, 1.5f, 0, 0.75f, 3, 0.5f},
    {"sinc (defaults)", CV_FILTER_SINC, 4, 4, 1.0f / 3, 1.0f / 3, 3, 0.5f},
    {"sinc tau 2, radius 3 x 2", CV_FILTER_SINC, 3, 2, 1.0f / 3, 1.0f / 3, 2, 0.5f},
    {"gaussian (defaults)", CV_FILTER_GAUSSIAN, 1.5f, 1.5f, 1.0f / 3, 1.0f / 3, 3, 0.5f},
    {"triangle (defaults)", CV_FILTER_TRIANGLE, 2, 2, 1.0f / 3, 1.0f / 3, 3, 0.5f},
    {"box 0.5 x 1", CV_FILTER_BOX, 0.5f, 1, 1.0f / 3, 1.0f / 3, 3, 0.5f},
};

/* The density pbrt-v4 samples along one axis: |f| at the centre of the
 * cell of 1/32 pixel (32 r cells, at most CV_FILTER_CELLS) that holds x,
 * or |f| itself for a filter sampled in closed form. */
static double density(const struct cv_render_settings *st, int axis, double x)
{
    double r = cv_filter_radius(st, axis);
    if (st->filter == CV_FILTER_BOX || st->filter == CV_FILTER_TRIANGLE)
        return fabs(cv_filter_1d(st, axis, x));
    double n = fmin(floor(32 * r), CV_FILTER_CELLS), k = floor((x + r) / (2 * r) * n);
    k = fmin(fmax(k, 0), n - 1);
    return fabs(cv_filter_1d(st, axis, -r + 2 * r * (k + 0.5) / n));
}

/* The density integrated over the n equal bins of [-r, r] of one axis,
 * normalised to sum 1 */
static void bins(const struct cv_render_settings *st, int axis, int n, double *out)
{
    double r = cv_filter_radius(st, axis), total = 0;
    for (int i = 0; i < n; i++) {
        double s = 0;
        for (int j = 0; j < SUB; j++)
            s += density(st, axis, -r + 2 * r * (i + (j + 0.5) / SUB) / n);
        out[i] = s;
        total += s;
    }
    for (int i = 0; i < n; i++)
        out[i] /= total;
}

static void check(struct cv_gpu *gpu, struct cv_program *prog, const struct filter_case *fc,
                  double alpha)
{
    struct cv_render_settings st;
    memset(&st, 0, sizeof(st));
    st.filter = fc->type;
    st.filter_radius[0] = fc->rx;
    st.filter_radius[1] = fc->ry;
    st.filter_b = fc->b;
    st.filter_c = fc->c;
    st.filter_tau = fc->tau;
    st.filter_sigma = fc->sigma;
    CvPassParams u;
    memset(&u, 0, sizeof(u));
    cv_filter_setup(&st, &u);
    struct cv_error err = {{0}};
    GLuint ubo = cv_buffer_create(sizeof(u), &u, "filter probe params", &err);
    GLuint out = cv_buffer_create((size_t)N_SAMPLES * 16, NULL, "filter probe out", &err);
    float *s = malloc((size_t)N_SAMPLES * 16);
    bool ran = ubo && out;
    if (ran) {
        glBindBufferBase(GL_UNIFORM_BUFFER, CV_UBO_PASS, ubo);
        cv_buffer_bind(out, CV_BIND_PROBE_OUT);
        glUseProgram(prog->id);
        glUniform1ui(glGetUniformLocation(prog->id, "u_n"), N_SAMPLES);
        glUniform2ui(glGetUniformLocation(prog->id, "u_seed"), 0x2545f491u, (uint32_t)fc->type);
        cv_program_dispatch_1d(prog, N_SAMPLES);
        ran = cv_buffer_read(out, 0, (size_t)N_SAMPLES * 16, s, &err);
    }
    cv_buffer_destroy(&ubo);
    cv_buffer_destroy(&out);
    if (!tap_ok(ran, "%s: probe runs %s", fc->what, err.msg)) {
        free(s);
        return;
    }
    double bx[NX], by[NY], cell[CHI_CELLS], obs[CHI_CELLS] = {0};
    bins(&st, 0, NX, bx);
    bins(&st, 1, NY, by);
    for (int y = 0; y < NY; y++)
        for (int x = 0; x < NX; x++)
            cell[y * NX + x] = bx[x] * by[y];
    double rx = cv_filter_radius(&st, 0), ry = cv_filter_radius(&st, 1);
    double fmax_x = 0, fmax_y = 0;
    for (int i = 0; i <= 1000; i++) {
        fmax_x = fmax(fmax_x, fabs(cv_filter_1d(&st, 0, -rx + 2 * rx * i / 1000)));
        fmax_y = fmax(fmax_y, fabs(cv_filter_1d(&st, 1, -ry + 2 * ry * i / 1000)));
    }
    unsigned outside = 0, wrong_sign = 0;
    double wsum = 0;
    for (unsigned i = 0; i < N_SAMPLES; i++) {
        double px = s[4 * i], py = s[4 * i + 1], w = s[4 * i + 2];
        wsum += w;
        int cx = (int)floor((px + rx) / (2 * rx) * NX), cy = (int)floor((py + ry) / (2 * ry) * NY);
        if (cx < 0 || cx >= NX || cy < 0 || cy >= NY || fabs(w) != 1) {
            outside++;
            continue;
        }
        obs[cy * NX + cx] += 1;
        /* the sign of f, where neither factor is near a zero (one table
         * cell: 1/32 pixel; 1 % of the peak is far more than that) */
        double fx = cv_filter_1d(&st, 0, px), fy = cv_filter_1d(&st, 1, py);
        if (fabs(fx) > 0.01 * fmax_x && fabs(fy) > 0.01 * fmax_y && (fx * fy < 0) != (w < 0))
            wrong_sign++;
    }
    struct stats_chi2 r = stats_chi2_test(obs, cell, N_SAMPLES);
    tap_ok(outside == 0, "%s: every offset inside the radius, weight +-1 (%u outside)", fc->what,
           outside);
    tap_ok(r.p_value > alpha && !r.zero_cell_hit, "%s: chi-square against |f|: p %.4f (chi2 %.1f, %d dof)",
           fc->what, r.p_value, r.chi2, r.dof);
    /* E[w] = integral of f / integral of |f|, axis by axis */
    double ix = 0, ax = 0, iy = 0, ay = 0;
    for (int i = 0; i < 100000; i++) {
        double fx = cv_filter_1d(&st, 0, -rx + 2 * rx * (i + 0.5) / 100000);
        double fy = cv_filter_1d(&st, 1, -ry + 2 * ry * (i + 0.5) / 100000);
        ix += fx, ax += fabs(fx), iy += fy, ay += fabs(fy);
    }
    double expect = ix / ax * (iy / ay), mean = wsum / N_SAMPLES;
    double se = sqrt(fmax(1 - expect * expect, 1e-12) / N_SAMPLES);
    tap_ok(wrong_sign == 0 && fabs(mean - expect) < 5 * se + 1e-6,
           "%s: weights are the sign of f (%u wrong); mean %.5f, integral f / |f| %.5f", fc->what,
           wrong_sign, mean, expect);
    free(s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_program *prog = cv_program_get(gpu, "trace/test/filter_probe.comp", NULL, &err);
    if (!tap_ok(prog != NULL, "probe compiles: %s", prog ? "" : err.msg))
        return tap_done();
    size_t n = sizeof(cases) / sizeof(cases[0]);
    double alpha = stats_sidak(0.01, (int)n);
    for (size_t i = 0; i < n; i++)
        check(gpu, prog, &cases[i], alpha);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
