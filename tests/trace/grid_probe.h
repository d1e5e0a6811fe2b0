/* grid_probe.h: what the grid-medium probe tests share (medium_grid_test.c,
 * medium_cloud_test.c, medium_nanovdb_test.c): a run of
 * glsl/trace/test/grid_probe.comp in one of its modes; the lookups at unit-cube points that cover every majorant
 * cell (random points, then each cell's corners pulled a hair inside, then
 * points beside and outside the bounds); random rays about the bounds; and
 * ratio and delta tracking along them, measured against a transmittance in
 * standard errors. */
#ifndef CV_TESTS_TRACE_GRID_PROBE_H
#define CV_TESTS_TRACE_GRID_PROBE_H

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/medium.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/transform.h"
#include "tests/gpu/probe.h"
#include "tests/tap.h"

/* pbrt-v4's SampledGrid::Lookup at g in the unit cube: trilinear over the
 * n[0] x n[1] x n[2] samples that value(ctx, x, y, z) gives, samples past
 * the bounds 0 (the tests' reference for the GPU's grid lookups). */
static inline double grid_probe_ref_lookup(double (*value)(const void *ctx, int x, int y, int z),
                                           const void *ctx, const int n[3], const double g[3])
{
    double s[3], d[3];
    int i[3];
    for (int a = 0; a < 3; a++) {
        s[a] = g[a] * n[a] - 0.5;
        i[a] = (int)floor(s[a]);
        d[a] = s[a] - i[a];
    }
    double r = 0;
    for (int k = 0; k < 8; k++) {
        int x = i[0] + (k & 1), y = i[1] + ((k >> 1) & 1), z = i[2] + (k >> 2);
        double w = ((k & 1) ? d[0] : 1 - d[0]) * (((k >> 1) & 1) ? d[1] : 1 - d[1]) *
                   ((k >> 2) ? d[2] : 1 - d[2]);
        if (x >= 0 && y >= 0 && z >= 0 && x < n[0] && y < n[1] && z < n[2])
            r += w * value(ctx, x, y, z);
    }
    return r;
}

/* Runs prog (grid_probe.comp) in mode on medium for count invocations,
 * samples estimates each where the mode tracks; n_in4 vec4s in, n_out4
 * read back into out. */
static inline bool grid_probe_run(struct cv_program *prog, unsigned mode, unsigned medium,
                                  unsigned samples, const float *in, size_t n_in4, size_t count,
                                  float *out, size_t n_out4, struct cv_error *err)
{
    GLuint id = probe_use(prog);
    glUniform1ui(glGetUniformLocation(id, "u_medium"), medium);
    glUniform1ui(glGetUniformLocation(id, "u_samples"), samples);
    return probe_dispatch(prog, mode, in, n_in4 * 16, count, out, n_out4 * 16, err);
}

/* Unit-cube points (3 doubles each, *n of them): per_cell random points
 * in every majorant cell, then its 8 corners pulled 0.001 of a cell
 * inside, then 4096 points in [-0.1, 1.1]^3. rnd draws from [0, 1). */
static inline double *grid_probe_cell_points(int per_cell, double (*rnd)(void), size_t *n)
{
    const unsigned R = CV_MAJORANT_RES;
    size_t n_cells = (size_t)R * R * R;
    *n = n_cells * (size_t)(per_cell + 8) + 4096;
    double *g = cv_xmalloc(*n * 3 * sizeof(double));
    size_t i = 0;
    for (size_t c = 0; c < n_cells; c++) {
        int cx = (int)(c % R), cy = (int)(c / R % R), cz = (int)(c / (R * R));
        for (int j = 0; j < per_cell + 8; j++, i++) {
            double t[3] = {rnd(), rnd(), rnd()};
            if (j >= per_cell)
                for (int a = 0; a < 3; a++)
                    t[a] = ((j - per_cell) >> a) & 1 ? 0.999 : 0.001;
            g[3 * i] = (cx + t[0]) / R;
            g[3 * i + 1] = (cy + t[1]) / R;
            g[3 * i + 2] = (cz + t[2]) / R;
        }
    }
    for (; i < *n; i++)
        for (int a = 0; a < 3; a++)
            g[3 * i + a] = -0.1 + 1.2 * rnd();
    return g;
}

/* A medium's bounds [p0, p1] in its own space, and its CTM to render space. */
struct grid_probe_box {
    double p0[3], p1[3];
    struct cv_mat4 ctm;
};

/* The render-space point p of g in the box's unit cube. */
static inline void grid_probe_to_render(const struct grid_probe_box *b, const double g[3],
                                        double p[3])
{
    double q[3];
    for (int a = 0; a < 3; a++)
        q[a] = b->p0[a] + g[a] * (b->p1[a] - b->p0[a]);
    cv_mat4_point(&b->ctm, q, p);
}

/* Mode 0 (the lookups) on medium at grid_probe_cell_points(per_cell) of
 * the box in render space: *n points, 16 floats each (the caller frees
 * them); NULL where the run fails (err says why). */
static inline float *grid_probe_lookups(struct cv_program *prog, unsigned medium,
                                        const struct grid_probe_box *b, int per_cell,
                                        double (*rnd)(void), size_t *n, struct cv_error *err)
{
    double *g = grid_probe_cell_points(per_cell, rnd, n);
    float *in = cv_xmalloc(*n * 16), *out = cv_xmalloc(*n * 64);
    for (size_t i = 0; i < *n; i++) {
        double p[3];
        grid_probe_to_render(b, g + 3 * i, p);
        memcpy(in + 4 * i, (float[4]){(float)p[0], (float)p[1], (float)p[2], 0}, 16);
    }
    if (!grid_probe_run(prog, 0, medium, 1, in, *n, *n, out, 4 * *n, err)) {
        free(out);
        out = NULL;
    }
    free(g);
    free(in);
    return out;
}

/* n rays from points near the box towards others (some start inside,
 * some end inside, some miss): origins o, unit directions d, lengths t1,
 * and the probe's input, 8 floats a ray (o, t1, d, 0). */
static inline void grid_probe_rays(const struct grid_probe_box *b, double (*rnd)(void), int n,
                                   double (*o)[3], double (*d)[3], double *t1, float *in)
{
    for (int i = 0; i < n; i++) {
        double ga[3], gb[3], pa[3], pb[3], len = 0;
        for (int a = 0; a < 3; a++) {
            ga[a] = -0.3 + 1.6 * rnd();
            gb[a] = -0.3 + 1.6 * rnd();
        }
        grid_probe_to_render(b, ga, pa);
        grid_probe_to_render(b, gb, pb);
        for (int a = 0; a < 3; a++)
            len += (pb[a] - pa[a]) * (pb[a] - pa[a]);
        t1[i] = len = sqrt(len);
        for (int a = 0; a < 3; a++) {
            o[i][a] = pa[a];
            d[i][a] = (pb[a] - pa[a]) / len;
        }
        memcpy(in + 8 * i, (float[8]){(float)o[i][0], (float)o[i][1], (float)o[i][2], (float)t1[i],
                                       (float)d[i][0], (float)d[i][1], (float)d[i][2], 0}, 32);
    }
}

/* Modes 2 and 3 on medium along the n_rays rays of `in` (grid_probe_rays),
 * samples estimates a ray: ratio tracking into ratio, delta tracking into
 * delta, 8 floats an estimate (n_rays * samples * 32 bytes each). */
static inline bool grid_probe_track(struct cv_program *prog, unsigned medium, unsigned samples,
                                    const float *in, int n_rays, float *ratio, float *delta,
                                    struct cv_error *err)
{
    size_t n_est = (size_t)n_rays * samples, n_in4 = 2 * (size_t)n_rays;
    return grid_probe_run(prog, 2, medium, samples, in, n_in4, n_est, ratio, 2 * n_est, err) &&
           grid_probe_run(prog, 3, medium, samples, in, n_in4, n_est, delta, 2 * n_est, err);
}

/* The tap checks of grid_probe_track's estimates along n_rays rays of
 * optical depths tau (per channel, integrated by the caller): per ray and
 * channel, ratio tracking's transmittance must average to T = exp(-tau),
 * delta tracking's pass and collision weights to T and 1 - T, within 4.5
 * standard errors (each from its own samples, plus 1e-4); and some ray
 * must go deeper than min_depth, so that the check says something. */
static inline void grid_probe_check_tracking(const char *name, const float *ratio,
                                             const float *delta, int n_rays, unsigned samples,
                                             const double (*tau)[3], double min_depth)
{
    double worst[3] = {0, 0, 0}, deepest = 0;
    for (int i = 0; i < n_rays; i++)
        for (int c = 0; c < 3; c++) {
            double T = exp(-tau[i][c]), want[3] = {T, T, 1 - T};
            double m[3] = {0, 0, 0}, q[3] = {0, 0, 0};
            deepest = fmax(deepest, tau[i][c]);
            for (unsigned j = 0; j < samples; j++) {
                const float *e = ratio + 8 * ((size_t)i * samples + j);
                const float *f = delta + 8 * ((size_t)i * samples + j);
                double v[3] = {e[c], f[c], f[4 + c]};
                for (int x = 0; x < 3; x++) {
                    m[x] += v[x] / samples;
                    q[x] += v[x] * v[x] / samples;
                }
            }
            for (int x = 0; x < 3; x++) {
                double se = sqrt(fmax(q[x] - m[x] * m[x], 0) / samples) + 1e-4;
                worst[x] = fmax(worst[x], fabs(m[x] - want[x]) / se);
            }
        }
    tap_ok(worst[0] < 4.5 && deepest > min_depth,
           "%s: ratio tracking averages to exp(-optical depth) per channel (worst %.2f standard "
           "errors; optical depths up to %.2f)", name, worst[0], deepest);
    tap_ok(worst[1] < 4.5 && worst[2] < 4.5,
           "%s: delta tracking's pass and collision weights average to T and 1 - T per channel "
           "(worst %.2f and %.2f standard errors)", name, worst[1], worst[2]);
}

#endif
