/* media_grid.c: pbrt-v4's grid media, "uniformgrid" (GridMedium: a density
 * grid scaling sigma_a and sigma_s, an optional Lescale grid scaling Le)
 * and "rgbgrid" (RGBGridMedium: RGB grids of sigma_a, sigma_s and Le), read
 * with pbrt-v4's parameters and defaults, "nanovdb" (NanoVDBMedium: the
 * density and temperature grids of a NanoVDB file, media_nanovdb.c), and
 * their majorant grids (glsl/shared/medium.h says how the GPU sees them). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"

/* pbrt-v4 writes an RGB grid's Le as RGBIlluminantSpectrum values without
 * dividing by their photometric integral (its other emitters do): with the
 * cie1931 sensor, emission of rgb (1, 1, 1) comes out as the integral of
 * CIE Y over its normalised D65, this many times what a light of rgb
 * (1, 1, 1) gives. */
#define CIE_Y_INTEGRAL 106.856895

uint32_t cv_b_medium_floats(struct cv_builder *b, const double *v, size_t n, double scale)
{
    struct cv_scene *s = b->s;
    size_t at = s->n_medium_grids;
    s->medium_grids = cv_xgrow(s->medium_grids, &b->cap_medium_grids, at + n, sizeof(float));
    for (size_t i = 0; i < n; i++)
        s->medium_grids[at + i] = (float)(v[i] * scale);
    s->n_medium_grids = at + n;
    return (uint32_t)at;
}

/* The last parameter `name` of type t, marked used (pbrt-v4's
 * GetFloatArray and GetRGBArray read only their own type). */
static struct cv_param *typed(struct cv_params *ps, const char *name, enum cv_param_type t)
{
    for (size_t i = ps->n; i-- > 0;)
        if (ps->v[i].type == t && strcmp(ps->v[i].name, name) == 0) {
            ps->v[i].used = true;
            return &ps->v[i];
        }
    return NULL;
}

/* Grid `name` of nxyz samples of `comps` numbers each, or absent (*out
 * CV_NO_GRID). Wrong counts, negative or non-finite values are errors at
 * the parameter. */
static bool read_grid(struct cv_builder *b, struct cv_params *ps, const char *medium,
                      const char *name, size_t nxyz, int comps, double scale, uint32_t *out,
                      struct cv_error *err)
{
    *out = CV_NO_GRID;
    struct cv_param *p = typed(ps, name, comps == 3 ? CV_PARAM_RGB : CV_PARAM_FLOAT);
    if (!p)
        return true;
    if (p->n_nums != nxyz * (size_t)comps)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": \"%s\" has %zu values; nx*ny*nz = %zu "
                            "needs %zu", p->file, p->line, p->col, medium, name, p->n_nums, nxyz,
                       nxyz * (size_t)comps);
    for (size_t i = 0; i < p->n_nums; i++)
        if (!(p->nums[i] >= 0) || !isfinite(p->nums[i]))
            return cv_fail(err, "%s:%d:%d: medium \"%s\": \"%s\" value %zu is %g; grid values "
                                "must be finite and not negative", p->file, p->line, p->col,
                           medium, name, i, p->nums[i]);
    *out = cv_b_medium_floats(b, p->nums, p->n_nums, scale);
    return true;
}

/* The largest value of each channel of a grid of comps numbers per sample
 * (a grid of one is the same in every channel) over the samples that a
 * lookup in [lo, hi] of the unit cube reads: pbrt-v4's
 * SampledGrid::MaxValue (samples at cell centres) or, with corners, a
 * nanovdb medium's lattice (samples from corner to corner). 1 for an
 * absent grid (its lookup is 1). One pass over the samples for all three
 * channels: a large lattice's majorants cost a read of each sample (about
 * once: neighbouring cells share one plane). */
static void grid_max(const struct cv_scene *s, uint32_t off, const uint32_t res[3], int comps,
                     const double lo[3], const double hi[3], bool corners, double m[3])
{
    m[0] = m[1] = m[2] = off == CV_NO_GRID ? 1 : 0;
    if (off == CV_NO_GRID)
        return;
    int i0[3], i1[3];
    for (int a = 0; a < 3; a++) {
        int n = (int)res[a];
        double k = corners ? n - 1 : n, h = corners ? 0 : 0.5;
        i0[a] = (int)floor(lo[a] * k - h);
        i1[a] = (int)floor(hi[a] * k - h) + 1;
        i0[a] = i0[a] < 0 ? 0 : i0[a];
        i1[a] = i1[a] > n - 1 ? n - 1 : i1[a];
    }
    /* values are finite and not negative (checked as read) */
    float v[3] = {0, 0, 0};
    for (int z = i0[2]; z <= i1[2]; z++)
        for (int y = i0[1]; y <= i1[1]; y++) {
            const float *row = s->medium_grids + off +
                               (((size_t)z * res[1] + (size_t)y) * res[0]) * (size_t)comps;
            for (int x = i0[0]; x <= i1[0]; x++)
                for (int c = 0; c < comps; c++)
                    v[c] = row[(size_t)x * comps + c] > v[c] ? row[(size_t)x * comps + c] : v[c];
        }
    for (int c = 0; c < 3; c++)
        m[c] = comps == 3 ? v[c] : v[0];
}

/* The majorant grid: per cell, the largest sigma_t of any channel that
 * the cell's lookups can give, a hair above it so that float rounding in
 * the shader's interpolation stays below. */
static void majorants(struct cv_builder *b, CvMedium *m)
{
    const uint32_t R = CV_MAJORANT_RES;
    double *maj = cv_xmalloc((size_t)R * R * R * sizeof(double));
    uint32_t res[3] = {m->res.x, m->res.y, m->res.z};
    int comps = m->grids.w ? 3 : 1;
    bool corners = m->type == CV_MEDIUM_NANOVDB;
    const float sa[3] = {m->sigma_a.x, m->sigma_a.y, m->sigma_a.z};
    const float ss[3] = {m->sigma_s.x, m->sigma_s.y, m->sigma_s.z};
    for (uint32_t z = 0; z < R; z++)
        for (uint32_t y = 0; y < R; y++)
            for (uint32_t x = 0; x < R; x++) {
                double lo[3] = {(double)x / R, (double)y / R, (double)z / R};
                double hi[3] = {(double)(x + 1) / R, (double)(y + 1) / R, (double)(z + 1) / R};
                double ma[3], ms[3], v = 0;
                grid_max(b->s, m->grids.x, res, comps, lo, hi, corners, ma);
                /* uniformgrid and nanovdb: A and S are one grid */
                if (m->grids.y == m->grids.x)
                    memcpy(ms, ma, sizeof(ms));
                else
                    grid_max(b->s, m->grids.y, res, comps, lo, hi, corners, ms);
                for (int c = 0; c < 3; c++)
                    v = fmax(v, sa[c] * ma[c] + ss[c] * ms[c]);
                maj[(z * R + y) * R + x] = v * (1 + 1e-5);
            }
    m->res.w = cv_b_medium_floats(b, maj, (size_t)R * R * R, 1);
    free(maj);
}

bool cv_b_medium_bounds(struct cv_builder *b, struct cv_params *ps, const char *name,
                        const struct cv_loc *loc, CvMedium *m, double lo_out[3],
                        double size_out[3], struct cv_error *err)
{
    double p0[3] = {0, 0, 0}, p1[3] = {1, 1, 1};
    cv_params_floats(ps, "p0", p0, 3);
    cv_params_floats(ps, "p1", p1, 3);
    struct cv_mat4 inv;
    if (!cv_mat4_inverse(&b->gs.ctm, &inv))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": its transform is singular", loc->file,
                       loc->line, loc->col, name);
    cv_vec4 *rows[3] = {&m->to_grid[0], &m->to_grid[1], &m->to_grid[2]};
    for (int a = 0; a < 3; a++) {
        double lo = fmin(p0[a], p1[a]), hi = fmax(p0[a], p1[a]);
        if (!(hi > lo) || !isfinite(hi - lo))
            return cv_fail(err, "%s:%d:%d: medium \"%s\": its bounds p0 p1 are empty along "
                                "axis %d", loc->file, loc->line, loc->col, name, a);
        double k = 1 / (hi - lo);
        if (lo_out)
            lo_out[a] = lo;
        if (size_out)
            size_out[a] = hi - lo;
        *rows[a] = (cv_vec4){(float)(inv.m[a][0] * k), (float)(inv.m[a][1] * k),
                             (float)(inv.m[a][2] * k), (float)((inv.m[a][3] - lo) * k)};
    }
    return true;
}

static bool resolution(struct cv_params *ps, const char *name, const struct cv_loc *loc,
                       CvMedium *m, struct cv_error *err)
{
    int n[3] = {cv_params_int(ps, "nx", 1), cv_params_int(ps, "ny", 1),
                cv_params_int(ps, "nz", 1)};
    for (int a = 0; a < 3; a++)
        if (n[a] < 1 || n[a] > 4096) {
            struct cv_param *p = cv_params_find(ps, a == 0 ? "nx" : a == 1 ? "ny" : "nz");
            return cv_fail(err, "%s:%d:%d: medium \"%s\": \"n%c\" is %d; a grid has 1 to 4096 "
                                "samples per axis", p ? p->file : loc->file,
                           p ? p->line : loc->line, p ? p->col : loc->col, name, "xyz"[a], n[a]);
        }
    if ((double)n[0] * n[1] * n[2] > 1 << 28)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": %d x %d x %d samples are too many",
                       loc->file, loc->line, loc->col, name, n[0], n[1], n[2]);
    m->res = (cv_uvec4){(uint32_t)n[0], (uint32_t)n[1], (uint32_t)n[2], 0};
    return true;
}

/* Temperature grid `grid` emits the blackbody of (lookup - off) x scale
 * above 100 K; top: the hottest temperature a lookup can give. The
 * blackbody's RGB goes to a table from 100 K to top, interpolated
 * linearly. */
void cv_b_medium_blackbody(struct cv_builder *b, CvMedium *m, uint32_t grid, double off,
                           double scale, double top)
{
    m->temperature_grids.x = grid;
    m->temperature = (cv_vec4){(float)off, (float)scale, (float)fmax(top, 101), 0};
    double *table = cv_xmalloc(CV_BLACKBODY_STEPS * 3 * sizeof(double));
    for (uint32_t i = 0; i < CV_BLACKBODY_STEPS; i++)
        cv_blackbody_sensor_rgb(100 + (fmax(top, 101) - 100) * i / (CV_BLACKBODY_STEPS - 1),
                                table + 3 * i);
    m->temperature_grids.y = cv_b_medium_floats(b, table, CV_BLACKBODY_STEPS * 3, 1);
    free(table);
}

/* A uniformgrid's temperature grid: pbrt-v4's GridMedium emits, where
 * (lookup - temperatureoffset) x temperaturescale exceeds 100 K, the
 * Lescale grid times the blackbody of that temperature (its peak
 * normalised to 1), in place of Le. The blackbody's RGB goes to a table
 * up to the hottest temperature a lookup can give (lookups are convex
 * combinations of the samples and 0), interpolated linearly. le_given:
 * the medium has a non-black Le, which pbrt-v4 refuses beside a
 * temperature grid. */
static bool temperature(struct cv_builder *b, const char *name, struct cv_params *ps,
                        const struct cv_loc *loc, bool le_given, CvMedium *m,
                        struct cv_error *err)
{
    m->temperature_grids = (cv_uvec4){CV_NO_GRID, CV_NO_GRID, 0, 0};
    struct cv_param *p = typed(ps, "temperature", CV_PARAM_FLOAT);
    double off = cv_params_float(ps, "temperatureoffset",
                                 cv_params_float(ps, "temperaturecutoff", 0));
    double scale = cv_params_float(ps, "temperaturescale", 1);
    if (!p)
        return true;
    if (le_given)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": both \"Le\" and \"temperature\" are "
                            "given", loc->file, loc->line, loc->col, name);
    size_t nxyz = (size_t)m->res.x * m->res.y * m->res.z;
    uint32_t grid;
    if (!read_grid(b, ps, name, "temperature", nxyz, 1, 1, &grid, err))
        return false;
    if (!isfinite(off) || !isfinite(scale))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": temperatureoffset and temperaturescale "
                            "must be finite", loc->file, loc->line, loc->col, name);
    double top = -off * scale;
    for (size_t i = 0; i < nxyz; i++)
        top = fmax(top, (p->nums[i] - off) * scale);
    m->Le = (cv_vec4){1, 1, 1, 0};
    m->emissive = 1;
    cv_b_medium_blackbody(b, m, grid, off, scale, top);
    return true;
}

static bool uniformgrid(struct cv_builder *b, const char *name, struct cv_params *ps,
                        const struct cv_loc *loc, const char *dir, CvMedium *m,
                        struct cv_error *err)
{
    size_t nxyz = (size_t)m->res.x * m->res.y * m->res.z;
    if (!typed(ps, "density", CV_PARAM_FLOAT))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": a uniformgrid needs \"float density\"",
                       loc->file, loc->line, loc->col, name);
    double sa[3] = {1, 1, 1}, ss[3] = {1, 1, 1}, Le[3] = {0, 0, 0};
    bool found;
    if (!cv_b_color(b, ps, "sigma_a", CV_SPEC_UNBOUNDED, dir, sa, &found, err) ||
        !cv_b_color(b, ps, "sigma_s", CV_SPEC_UNBOUNDED, dir, ss, &found, err) ||
        !cv_b_color(b, ps, "Le", CV_SPEC_ILLUMINANT, dir, Le, &found, err))
        return false;
    double scale = cv_params_float(ps, "scale", 1);
    for (int c = 0; c < 3; c++)
        if (!(sa[c] * scale >= 0) || !(ss[c] * scale >= 0) || !isfinite(sa[c] * scale) ||
            !isfinite(ss[c] * scale))
            return cv_fail(err, "%s:%d:%d: medium \"%s\": sigma_a and sigma_s must be finite "
                                "and not negative", loc->file, loc->line, loc->col, name);
    m->type = CV_MEDIUM_UNIFORMGRID;
    m->sigma_a = (cv_vec4){(float)(sa[0] * scale), (float)(sa[1] * scale),
                           (float)(sa[2] * scale), m->sigma_a.w};
    m->sigma_s = (cv_vec4){(float)(ss[0] * scale), (float)(ss[1] * scale),
                           (float)(ss[2] * scale), 0};
    /* pbrt-v4 divides Le by its photometric integral as for lights, which
     * cv_b_color's illuminant RGB already is */
    m->Le = (cv_vec4){(float)Le[0], (float)Le[1], (float)Le[2], 0};
    m->emissive = Le[0] > 0 || Le[1] > 0 || Le[2] > 0;
    uint32_t dens, les;
    if (!read_grid(b, ps, name, "density", nxyz, 1, 1, &dens, err) ||
        !read_grid(b, ps, name, "Lescale", nxyz, 1, 1, &les, err))
        return false;
    m->le_res = (cv_uvec4){m->res.x, m->res.y, m->res.z, 0};
    if (les == CV_NO_GRID) {
        /* pbrt-v4's default Lescale is a grid of one sample, which its
         * lookup fades to zero towards the bounds like any other */
        const double one = 1;
        les = cv_b_medium_floats(b, &one, 1, 1);
        m->le_res = (cv_uvec4){1, 1, 1, 0};
    }
    m->grids = (cv_uvec4){dens, dens, les, 0};
    return temperature(b, name, ps, loc, found, m, err);
}

static bool rgbgrid(struct cv_builder *b, const char *name, struct cv_params *ps,
                    const struct cv_loc *loc, CvMedium *m, struct cv_error *err)
{
    size_t nxyz = (size_t)m->res.x * m->res.y * m->res.z;
    bool has_a = typed(ps, "sigma_a", CV_PARAM_RGB), has_s = typed(ps, "sigma_s", CV_PARAM_RGB);
    if (!has_a && !has_s)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": an rgbgrid needs \"rgb sigma_a\" or "
                            "\"rgb sigma_s\"", loc->file, loc->line, loc->col, name);
    if (typed(ps, "Le", CV_PARAM_RGB) && !has_a)
        return cv_fail(err, "%s:%d:%d: medium \"%s\": an rgbgrid with \"Le\" needs "
                            "\"sigma_a\"", loc->file, loc->line, loc->col, name);
    double scale = cv_params_float(ps, "scale", 1), le_scale = cv_params_float(ps, "Lescale", 1);
    if (!(scale >= 0) || !isfinite(scale) || !isfinite(le_scale))
        return cv_fail(err, "%s:%d:%d: medium \"%s\": \"scale\" must be finite and not "
                            "negative", loc->file, loc->line, loc->col, name);
    uint32_t a, s, e;
    if (!read_grid(b, ps, name, "sigma_a", nxyz, 3, 1, &a, err) ||
        !read_grid(b, ps, name, "sigma_s", nxyz, 3, 1, &s, err) ||
        !read_grid(b, ps, name, "Le", nxyz, 3, CIE_Y_INTEGRAL, &e, err))
        return false;
    m->type = CV_MEDIUM_RGBGRID;
    float sc = (float)scale, ls = (float)le_scale;
    m->sigma_a = (cv_vec4){sc, sc, sc, m->sigma_a.w};
    m->sigma_s = (cv_vec4){sc, sc, sc, 0};
    m->Le = (cv_vec4){ls, ls, ls, 0};
    m->emissive = e != CV_NO_GRID && le_scale > 0;
    m->grids = (cv_uvec4){a, s, e, 1};
    m->le_res = m->res;
    return true;
}

bool cv_b_medium_grid(struct cv_builder *b, const char *name, const char *type,
                      struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                      CvMedium *m, struct cv_error *err)
{
    double g;
    if (!cv_b_medium_g(b, ps, name, loc, &g, err))
        return false;
    m->sigma_a.w = (float)g;
    m->temperature_grids = (cv_uvec4){CV_NO_GRID, CV_NO_GRID, 0, 0};
    bool ok;
    if (strcmp(type, "nanovdb") == 0)
        ok = cv_b_medium_nanovdb(b, name, ps, loc, dir, m, err);
    else if (!resolution(ps, name, loc, m, err) ||
             !cv_b_medium_bounds(b, ps, name, loc, m, NULL, NULL, err))
        ok = false;
    else
        ok = strcmp(type, "uniformgrid") == 0 ? uniformgrid(b, name, ps, loc, dir, m, err)
                                              : rgbgrid(b, name, ps, loc, m, err);
    if (!ok)
        return false;
    majorants(b, m);
    return true;
}
