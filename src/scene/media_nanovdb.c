/* media_nanovdb.c: pbrt-v4's "nanovdb" medium (NanoVDBMedium): the float
 * grids of a NanoVDB file (read by nanovdb.c) copied into dense lattices
 * of the scene's grid buffer, which glsl/trace/medium/grid.glsl looks up
 * as NanoVDB samples its voxels (CV_MEDIUM_NANOVDB in
 * glsl/shared/medium.h). media_grid.c adds the majorant grid. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"
#include "scene/nanovdb.h"

/* The grids are resampled densely (below), a float a sample, so memory
 * grows with the volume of the active voxels' bounds, not with the number
 * of active voxels as in the file. How many floats the GPU holds is
 * checked at upload against the driver's limits (trace/scene_upload.c);
 * here only the grid buffer's 32-bit offsets bound them. */

/* Grid `grid` of a nanovdb medium's file, or absent (*found false) when
 * optional; errors at the statement. */
static bool nanovdb_grid(const char *path, const char *file, const char *medium,
                         const char *grid, bool required, const struct cv_loc *loc,
                         struct cv_nvdb_grid *out, bool *found, struct cv_error *err)
{
    if (!cv_nvdb_read(path, grid, out, found, err)) {
        cv_error_prefix(err, "%s:%d:%d: medium \"%s\"", loc->file, loc->line, loc->col, medium);
        return false;
    }
    if (!*found && required)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": %s has no grid \"%s\"", loc->file,
                       loc->line, loc->col, medium, file, grid);
    return true;
}

/* The lattice of grid g's voxels lo .. lo + n - 1 appended to the grid
 * buffer; its values must be finite and not negative (`what` names the
 * grid), *top gets (value - off) x scale at its hottest. */
static bool nanovdb_lattice(struct cv_builder *b, const struct cv_nvdb_grid *g, const int32_t lo[3],
                            const uint32_t n[3], const char *medium, const char *what,
                            const struct cv_loc *loc, double off, double scale, double *top,
                            uint32_t *at, struct cv_error *err)
{
    size_t count = (size_t)n[0] * n[1] * n[2];
    struct cv_scene *s = b->s;
    size_t base = s->n_medium_grids;
    /* filled in place: a large lattice is not held twice */
    s->medium_grids = cv_xgrow(s->medium_grids, &b->cap_medium_grids, base + count, sizeof(float));
    float *v = s->medium_grids + base;
    cv_nvdb_fill(g, lo, n, v);
    *top = -off * scale;
    for (size_t i = 0; i < count; i++) {
        if (!(v[i] >= 0) || !isfinite(v[i])) {
            size_t x = i % n[0], y = i / n[0] % n[1], z = i / n[0] / n[1];
            bool ok = cv_fail(err, "%s:%d:%d: medium \"%s\": grid \"%s\" holds %g at voxel "
                                   "(%d, %d, %d); values must be finite and not negative",
                              loc->file, loc->line, loc->col, medium, what, v[i],
                              lo[0] + (int)x, lo[1] + (int)y, lo[2] + (int)z);
            return ok;
        }
        *top = fmax(*top, (v[i] - off) * scale);
    }
    s->n_medium_grids = base + count;
    *at = (uint32_t)base;
    return true;
}

/* to_grid: render space to medium space (the CTM's inverse), to the
 * density grid's index space (its map's inverse), to the unit cube of the
 * lattice (index lo at 0, hi + 1 at 1). */
static bool nanovdb_transform(struct cv_builder *b, const struct cv_nvdb_grid *g,
                              const int32_t lo[3], const int32_t hi[3], const char *name,
                              const struct cv_loc *loc, CvMedium *m, struct cv_error *err)
{
    struct cv_mat4 inv;
    if (!cv_mat4_inverse(&b->gs.ctm, &inv))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": its transform is singular", loc->file,
                       loc->line, loc->col, name);
    cv_vec4 *rows[3] = {&m->to_grid[0], &m->to_grid[1], &m->to_grid[2]};
    for (int a = 0; a < 3; a++) {
        double k = 1.0 / ((double)hi[a] + 1 - lo[a]);
        double row[4] = {0, 0, 0, 0};
        for (int c = 0; c < 3; c++)
            for (int j = 0; j < 4; j++)
                row[j] += g->inv[a][c] * (inv.m[c][j] - (j == 3 ? g->inv[c][3] : 0));
        *rows[a] = (cv_vec4){(float)(row[0] * k), (float)(row[1] * k), (float)(row[2] * k),
                             (float)((row[3] - lo[a]) * k)};
    }
    return true;
}

/* pbrt-v4's "nanovdb" medium: the float grids "density" (gridname) and,
 * optionally, "temperature" (temperaturename) of the NanoVDB file
 * "filename", sampled at the voxels as NanoVDB's trilinear sampler does
 * (voxel (i, j, k) at index point (i, j, k)), vacuum outside the bounds of
 * the active voxels (in index space [lo, hi + 1], whose image under the
 * grids' map is the world box pbrt-v4 bounds the medium with). The voxels
 * lo .. hi + 1 of the grids' union of bounds go into lattices of the grid
 * buffer whose samples run from corner to corner of the unit cube
 * (CV_MEDIUM_NANOVDB), so that the shader's trilinear lookup is
 * NanoVDB's. */
bool cv_b_medium_nanovdb(struct cv_builder *b, const char *name, struct cv_params *ps,
                         const struct cv_loc *loc, const char *dir, CvMedium *m,
                         struct cv_error *err)
{
    const char *file = cv_params_string(ps, "filename", NULL);
    if (!file || !file[0])
        return cv_fail(err, "%s:%d:%d: medium \"%s\": a nanovdb medium needs \"string "
                            "filename\"", loc->file, loc->line, loc->col, name);
    double sa[3] = {1, 1, 1}, ss[3] = {1, 1, 1};
    bool found;
    if (!cv_b_color(b, ps, "sigma_a", CV_SPEC_UNBOUNDED, dir, sa, &found, err) ||
        !cv_b_color(b, ps, "sigma_s", CV_SPEC_UNBOUNDED, dir, ss, &found, err))
        return false;
    double scale = cv_params_float(ps, "scale", 1), le_scale = cv_params_float(ps, "Lescale", 1);
    double off = cv_params_float(ps, "temperatureoffset",
                                 cv_params_float(ps, "temperaturecutoff", 0));
    double tscale = cv_params_float(ps, "temperaturescale", 1);
    for (int c = 0; c < 3; c++)
        if (!(sa[c] * scale >= 0) || !(ss[c] * scale >= 0) || !isfinite(sa[c] * scale) ||
            !isfinite(ss[c] * scale))
            return cv_fail(err, "%s:%d:%d: medium \"%s\": sigma_a and sigma_s must be finite "
                                "and not negative", loc->file, loc->line, loc->col, name);
    if (!isfinite(le_scale) || !isfinite(off) || !isfinite(tscale))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": Lescale, temperatureoffset and "
                            "temperaturescale must be finite", loc->file, loc->line, loc->col,
                       name);
    const char *gname = cv_params_string(ps, "gridname", "density");
    const char *tname = cv_params_string(ps, "temperaturename", "temperature");
    char *path = cv_b_resolve(b, dir, file, err);
    if (!path) {
        cv_error_prefix(err, "%s:%d:%d: medium \"%s\"", loc->file, loc->line, loc->col, name);
        return false;
    }
    struct cv_nvdb_grid dg, tg;
    bool has_t = false;
    memset(&tg, 0, sizeof(tg));
    bool ok = nanovdb_grid(path, file, name, gname, true, loc, &dg, &found, err) &&
              nanovdb_grid(path, file, name, tname, false, loc, &tg, &has_t, err);
    free(path);
    if (!ok) {
        cv_nvdb_free(&dg);
        return false;
    }
    /* one lattice for both grids: the union of their bounds, in the index
     * space that they must then share */
    int32_t lo[3], hi[3];
    uint32_t n[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = dg.index_lo[a];
        hi[a] = dg.index_hi[a];
        if (has_t) {
            lo[a] = tg.index_lo[a] < lo[a] ? tg.index_lo[a] : lo[a];
            hi[a] = tg.index_hi[a] > hi[a] ? tg.index_hi[a] : hi[a];
            for (int c = 0; c < 4; c++)
                if (fabs(tg.map[a][c] - dg.map[a][c]) > 1e-9 * fabs(dg.map[a][c]))
                    ok = cv_fail(err, "%s:%d:%d: medium \"%s\": grids \"%s\" and \"%s\" have "
                                      "different transforms; Cavalry reads them only on one "
                                      "voxel lattice", loc->file, loc->line, loc->col, name,
                                 gname, tname);
        }
    }
    /* in double: damaged bounds may span more than 2^32 voxels; the
     * lattices, the majorant grid and the blackbody table must end below
     * CV_NO_GRID, the last offset a float index reaches */
    double span[3], samples = 1;
    for (int a = 0; a < 3; a++) {
        span[a] = (double)hi[a] - lo[a] + 1;
        samples *= span[a] + 1;
    }
    double floats = (double)b->s->n_medium_grids + samples * (has_t ? 2 : 1) +
                    (double)CV_MAJORANT_RES * CV_MAJORANT_RES * CV_MAJORANT_RES +
                    3.0 * CV_BLACKBODY_STEPS;
    if (ok && floats > CV_NO_GRID)
        ok = cv_fail(err, "%s:%d:%d: medium \"%s\": the grids' bounds span %.0f x %.0f x %.0f "
                          "voxels; Cavalry copies nanovdb grids densely, %.0f samples with the "
                          "plane beyond the bounds on each axis, and a scene's grid media "
                          "address at most %u floats", loc->file, loc->line, loc->col, name,
                     span[0], span[1], span[2], samples, CV_NO_GRID);
    for (int a = 0; a < 3; a++)
        n[a] = ok ? (uint32_t)span[a] + 1 : 0;
    /* pbrt-v4 bounds the medium by the grids' stored world boxes; with a
     * map that only scales and moves (what VDB volumes use), that box is
     * the map's image of [lo, hi + 1] */
    bool axis_map = true;
    for (int a = 0; a < 3; a++)
        for (int c = 0; c < 3; c++)
            axis_map &= a == c || dg.map[a][c] == 0;
    if (ok && !axis_map &&
        !cv_b_warn(b, err, loc, "medium \"%s\": the grids' map rotates or shears; the medium "
                                "is bounded by the voxels' index box, not by its world box as "
                                "pbrt-v4 does", name))
        ok = false;
    double top = 0;
    uint32_t dens = CV_NO_GRID, temp = CV_NO_GRID;
    ok = ok && nanovdb_lattice(b, &dg, lo, n, name, gname, loc, 0, 1, &top, &dens, err) &&
         (!has_t || nanovdb_lattice(b, &tg, lo, n, name, tname, loc, off, tscale, &top, &temp, err)) &&
         nanovdb_transform(b, &dg, lo, hi, name, loc, m, err);
    cv_nvdb_free(&dg);
    cv_nvdb_free(&tg);
    if (!ok)
        return false;
    m->type = CV_MEDIUM_NANOVDB;
    m->sigma_a = (cv_vec4){(float)(sa[0] * scale), (float)(sa[1] * scale),
                           (float)(sa[2] * scale), m->sigma_a.w};
    m->sigma_s = (cv_vec4){(float)(ss[0] * scale), (float)(ss[1] * scale),
                           (float)(ss[2] * scale), 0};
    m->res = (cv_uvec4){n[0], n[1], n[2], 0};
    m->grids = (cv_uvec4){dens, dens, CV_NO_GRID, 0};
    m->le_res = (cv_uvec4){1, 1, 1, 0};
    /* pbrt-v4 emits Lescale times the blackbody (peak 1) where there is a
     * temperature grid, nothing otherwise */
    if (has_t && le_scale > 0) {
        float ls = (float)le_scale;
        m->Le = (cv_vec4){ls, ls, ls, 0};
        m->emissive = 1;
        cv_b_medium_blackbody(b, m, temp, off, tscale, top);
    }
    return true;
}
