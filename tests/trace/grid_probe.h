/* grid_probe.h: what the grid-medium probe tests share (medium_grid_test.c,
 * medium_cloud_test.c): a run of glsl/trace/test/grid_probe.comp in one
 * of its modes, and the unit-cube points that cover every majorant cell
 * (random points, then each cell's corners pulled a hair inside, then
 * points beside and outside the bounds). */
#ifndef CV_TESTS_TRACE_GRID_PROBE_H
#define CV_TESTS_TRACE_GRID_PROBE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/medium.h"
#include "gpu/buffer.h"
#include "gpu/program.h"

/* Runs prog (grid_probe.comp) in mode on medium for count invocations,
 * samples estimates each where the mode tracks; n_in4 vec4s in, n_out4
 * read back into out. */
static inline bool grid_probe_run(struct cv_program *prog, unsigned mode, unsigned medium,
                                  unsigned samples, const float *in, size_t n_in4, size_t count,
                                  float *out, size_t n_out4, struct cv_error *err)
{
    GLuint bin = cv_buffer_create(n_in4 * 16, in, "grid probe in", err);
    GLuint bout = cv_buffer_create(n_out4 * 16, NULL, "grid probe out", err);
    bool ok = bin && bout;
    if (ok) {
        cv_buffer_bind(bin, CV_BIND_PROBE_IN);
        cv_buffer_bind(bout, CV_BIND_PROBE_OUT);
        glUseProgram(prog->id);
        glUniform1ui(glGetUniformLocation(prog->id, "u_mode"), mode);
        glUniform1ui(glGetUniformLocation(prog->id, "u_count"), (GLuint)count);
        glUniform1ui(glGetUniformLocation(prog->id, "u_medium"), medium);
        glUniform1ui(glGetUniformLocation(prog->id, "u_samples"), samples);
        cv_program_dispatch_1d(prog, count);
        ok = cv_buffer_read(bout, 0, n_out4 * 16, out, err);
    }
    cv_buffer_destroy(&bin);
    cv_buffer_destroy(&bout);
    return ok;
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

#endif
