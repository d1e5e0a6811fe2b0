/* shapes.c: every pbrt shape becomes triangles.
 *
 * Quadrics (sphere, disk, cylinder) are tessellated rather than intersected
 * analytically, so that the BVH and the shaders deal with one primitive:
 * SEGMENTS steps around phi (and half as many in theta for the sphere) keep
 * the silhouette within 1 - cos(pi/128) = 3e-4 of the radius (sub-pixel for
 * any sensible framing), and the vertices carry the analytic normals and pbrt's
 * (u, v) parameterisation, so shading matches the true surface.
 * Bilinear patches become two triangles each (exact when planar); a v3
 * heightfield becomes its grid of triangles.
 * loopsubdiv is subdivided on load with Loop's rules (boundaries kept as
 * creases); vertex normals are the area-weighted face normals of the result
 * rather than pbrt's limit-surface normals, and positions are not pushed to
 * the limit surface. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/builder.h"
#include "scene/ply.h"

#define SEGMENTS 128

struct geo {
    float *P, *N, *uv;
    uint32_t *idx;
    size_t nv, nt, cap_p, cap_n, cap_uv, cap_i;
};

static void geo_free(struct geo *g)
{
    free(g->P);
    free(g->N);
    free(g->uv);
    free(g->idx);
}

static void push_vertex(struct geo *g, const double p[3], const double n[3], double u, double v)
{
    g->P = cv_xgrow(g->P, &g->cap_p, (g->nv + 1) * 3, sizeof(float));
    g->N = cv_xgrow(g->N, &g->cap_n, (g->nv + 1) * 3, sizeof(float));
    g->uv = cv_xgrow(g->uv, &g->cap_uv, (g->nv + 1) * 2, sizeof(float));
    for (int c = 0; c < 3; c++) {
        g->P[g->nv * 3 + c] = (float)p[c];
        g->N[g->nv * 3 + c] = (float)n[c];
    }
    g->uv[g->nv * 2] = (float)u;
    g->uv[g->nv * 2 + 1] = (float)v;
    g->nv++;
}

static bool same_pos(const struct geo *g, uint32_t a, uint32_t b)
{
    return g->P[a * 3] == g->P[b * 3] && g->P[a * 3 + 1] == g->P[b * 3 + 1] &&
           g->P[a * 3 + 2] == g->P[b * 3 + 2];
}

static void push_tri(struct geo *g, uint32_t a, uint32_t b, uint32_t c)
{
    /* tessellation collapses at poles and disk centres: drop those */
    if (same_pos(g, a, b) || same_pos(g, b, c) || same_pos(g, a, c))
        return;
    g->idx = cv_xgrow(g->idx, &g->cap_i, (g->nt + 1) * 3, sizeof(uint32_t));
    g->idx[g->nt * 3] = a;
    g->idx[g->nt * 3 + 1] = b;
    g->idx[g->nt * 3 + 2] = c;
    g->nt++;
}

/* Grid of (nu+1) x (nv+1) vertices, two triangles per cell with a winding
 * whose geometric normal follows dp/du x dp/dv. */
static void grid_tris(struct geo *g, uint32_t base, int nu, int nv, bool flip)
{
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = base + (uint32_t)(j * (nu + 1) + i), b = a + 1;
            uint32_t c = a + (uint32_t)(nu + 1), d = c + 1;
            if (flip) {
                push_tri(g, a, c, b);
                push_tri(g, b, c, d);
            } else {
                push_tri(g, a, b, c);
                push_tri(g, b, d, c);
            }
        }
}

static double clampd(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

static bool sphere(struct cv_params *ps, struct geo *g)
{
    double r = cv_params_float(ps, "radius", 1);
    double zmin = clampd(cv_params_float(ps, "zmin", -r), -r, r);
    double zmax = clampd(cv_params_float(ps, "zmax", r), -r, r);
    double phimax = clampd(cv_params_float(ps, "phimax", 360), 0, 360) * M_PI / 180;
    if (zmin > zmax) {
        double t = zmin; zmin = zmax; zmax = t;
    }
    double tmin = acos(clampd(zmin / r, -1, 1)), tmax = acos(clampd(zmax / r, -1, 1));
    int nu = SEGMENTS, nv = SEGMENTS / 2;
    for (int j = 0; j <= nv; j++) {
        double v = (double)j / nv, th = tmin + v * (tmax - tmin);
        for (int i = 0; i <= nu; i++) {
            double u = (double)i / nu, ph = u * phimax;
            double st = fabs(sin(th)) < 1e-12 ? 0 : sin(th); /* exact poles */
            double n[3] = {st * cos(ph), st * sin(ph), cos(th)};
            double p[3] = {r * n[0], r * n[1], r * n[2]};
            if (r < 0)
                n[0] = -n[0], n[1] = -n[1], n[2] = -n[2];
            push_vertex(g, p, n, u, v);
        }
    }
    /* v runs from zmin (south) up: dp/du x dp/dv points outward */
    grid_tris(g, 0, nu, nv, false);
    return r != 0 && phimax > 0;
}

static bool disk(struct cv_params *ps, struct geo *g)
{
    double h = cv_params_float(ps, "height", 0), r = cv_params_float(ps, "radius", 1);
    double ri = cv_params_float(ps, "innerradius", 0);
    double phimax = clampd(cv_params_float(ps, "phimax", 360), 0, 360) * M_PI / 180;
    int nu = SEGMENTS;
    double n[3] = {0, 0, 1};
    for (int j = 0; j <= 1; j++) {
        double rr = j == 0 ? r : ri;
        for (int i = 0; i <= nu; i++) {
            double u = (double)i / nu, ph = u * phimax;
            double p[3] = {rr * cos(ph), rr * sin(ph), h};
            push_vertex(g, p, n, u, j);
        }
    }
    /* v grows inward: dp/du x dp/dv is +z */
    grid_tris(g, 0, nu, 1, false);
    return r != ri && phimax > 0;
}

static bool cylinder(struct cv_params *ps, struct geo *g)
{
    double r = cv_params_float(ps, "radius", 1);
    double zmin = cv_params_float(ps, "zmin", -1), zmax = cv_params_float(ps, "zmax", 1);
    double phimax = clampd(cv_params_float(ps, "phimax", 360), 0, 360) * M_PI / 180;
    int nu = SEGMENTS;
    for (int j = 0; j <= 1; j++)
        for (int i = 0; i <= nu; i++) {
            double u = (double)i / nu, ph = u * phimax;
            double n[3] = {cos(ph), sin(ph), 0};
            double p[3] = {r * n[0], r * n[1], j ? zmax : zmin};
            push_vertex(g, p, n, u, j);
        }
    grid_tris(g, 0, nu, 1, zmax < zmin);
    return r != 0 && zmin != zmax && phimax > 0;
}

/* pbrt-v3 heightfield: Pz over the unit square, nu x nv samples. */
static bool heightfield(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                        struct geo *g, struct cv_error *err)
{
    int nu = cv_params_int(ps, "nu", -1), nv = cv_params_int(ps, "nv", -1);
    struct cv_param *z = cv_params_array(ps, "Pz");
    if (nu < 2 || nv < 2 || !z || (double)nu * nv != (double)z->n_nums)
        return cv_fail(err, "%s:%d:%d: heightfield needs nu, nv >= 2 and nu*nv \"float Pz\" values",
                       loc->file, loc->line, loc->col);
    (void)b;
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            double u = (double)i / (nu - 1), v = (double)j / (nv - 1);
            double p[3] = {u, v, z->nums[(size_t)j * nu + i]};
            g->P = cv_xgrow(g->P, &g->cap_p, (g->nv + 1) * 3, sizeof(float));
            g->uv = cv_xgrow(g->uv, &g->cap_uv, (g->nv + 1) * 2, sizeof(float));
            for (int c = 0; c < 3; c++)
                g->P[g->nv * 3 + c] = (float)p[c];
            g->uv[g->nv * 2] = (float)u;
            g->uv[g->nv * 2 + 1] = (float)v;
            g->nv++;
        }
    for (int j = 0; j < nv - 1; j++)
        for (int i = 0; i < nu - 1; i++) {
            uint32_t a = (uint32_t)(j * nu + i), c = a + (uint32_t)nu;
            push_tri(g, a, a + 1, c + 1);
            push_tri(g, a, c + 1, c);
        }
    return true;
}

/* ---- Loop subdivision ---- */

struct edge_map {
    uint64_t *keys;     /* (min << 32 | max) + 1; 0 empty */
    uint32_t *val;
    size_t cap;
};

static uint32_t edge_get(struct edge_map *m, uint32_t a, uint32_t b, uint32_t next, bool *isnew)
{
    if (a > b) {
        uint32_t t = a; a = b; b = t;
    }
    uint64_t k = (((uint64_t)a << 32) | b) + 1;
    size_t h = (size_t)((k * 0x9E3779B97F4A7C15ull) >> 17) & (m->cap - 1);
    while (m->keys[h] && m->keys[h] != k)
        h = (h + 1) & (m->cap - 1);
    if (m->keys[h]) {
        *isnew = false;
        return m->val[h];
    }
    m->keys[h] = k;
    m->val[h] = next;
    *isnew = true;
    return next;
}

static bool loop_subdivide(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                           struct geo *g, struct cv_error *err)
{
    int levels = cv_params_int(ps, "levels", cv_params_int(ps, "nlevels", 3));
    struct cv_param *P = cv_params_array(ps, "P"), *I = cv_params_array(ps, "indices");
    if (!P || !I || P->n_nums % 3 || I->n_nums % 3)
        return cv_fail(err, "%s:%d:%d: loopsubdiv needs \"point3 P\" and \"integer indices\"",
                       loc->file, loc->line, loc->col);
    if (levels < 0)
        levels = 0;
    size_t nv = P->n_nums / 3, nt = I->n_nums / 3;
    /* bound the work a (broken or hostile) file can ask for */
    if (nt > 0 && ((double)nt * pow(4, levels) > (double)(1 << 24)))
        return cv_fail(err, "%s:%d:%d: loopsubdiv with %d levels would exceed 2^24 triangles",
                       loc->file, loc->line, loc->col, levels);
    double *pos = cv_xmalloc((nv ? nv : 1) * 3 * sizeof(double));
    uint32_t *tri = cv_xmalloc((nt ? nt : 1) * 3 * sizeof(uint32_t));
    for (size_t i = 0; i < nv * 3; i++)
        pos[i] = P->nums[i];
    for (size_t i = 0; i < nt * 3; i++) {
        double v = I->nums[i];
        if (v < 0 || v >= (double)nv) {
            free(pos);
            free(tri);
            return cv_fail(err, "%s:%d:%d: loopsubdiv index %g out of range", loc->file,
                           loc->line, loc->col, v);
        }
        tri[i] = (uint32_t)v;
    }
    for (int level = 0; level < levels; level++) {
        struct edge_map em;
        em.cap = 16;
        while (em.cap < nt * 4)
            em.cap *= 2;
        em.keys = cv_xcalloc(em.cap, sizeof(uint64_t));
        em.val = cv_xmalloc(em.cap * sizeof(uint32_t));
        size_t ne = 0;
        uint32_t *tedge = cv_xmalloc(nt * 3 * sizeof(uint32_t));
        for (size_t t = 0; t < nt; t++)
            for (int k = 0; k < 3; k++) {
                bool isnew;
                tedge[t * 3 + k] = edge_get(&em, tri[t * 3 + k], tri[t * 3 + (k + 1) % 3], (uint32_t)ne, &isnew);
                if (isnew)
                    ne++;
            }
        /* per edge: endpoints, opposite sum, face count */
        uint32_t *ea = cv_xmalloc(ne * 2 * sizeof(uint32_t));
        double *eopp = cv_xcalloc(ne * 3, sizeof(double));
        int *ecount = cv_xcalloc(ne, sizeof(int));
        for (size_t t = 0; t < nt; t++)
            for (int k = 0; k < 3; k++) {
                uint32_t e = tedge[t * 3 + k], a = tri[t * 3 + k], c = tri[t * 3 + (k + 1) % 3],
                         o = tri[t * 3 + (k + 2) % 3];
                ea[e * 2] = a;
                ea[e * 2 + 1] = c;
                for (int d = 0; d < 3; d++)
                    eopp[e * 3 + d] += pos[o * 3 + d];
                ecount[e]++;
            }
        /* per vertex: neighbour sums (all, and along boundary edges) */
        double *nsum = cv_xcalloc(nv * 3, sizeof(double)), *bsum = cv_xcalloc(nv * 3, sizeof(double));
        int *val = cv_xcalloc(nv, sizeof(int)), *bval = cv_xcalloc(nv, sizeof(int));
        for (size_t e = 0; e < ne; e++) {
            uint32_t a = ea[e * 2], c = ea[e * 2 + 1];
            bool boundary = ecount[e] != 2;
            for (int d = 0; d < 3; d++) {
                nsum[a * 3 + d] += pos[c * 3 + d];
                nsum[c * 3 + d] += pos[a * 3 + d];
                if (boundary) {
                    bsum[a * 3 + d] += pos[c * 3 + d];
                    bsum[c * 3 + d] += pos[a * 3 + d];
                }
            }
            val[a]++;
            val[c]++;
            if (boundary) {
                bval[a]++;
                bval[c]++;
            }
        }
        size_t nv2 = nv + ne;
        double *pos2 = cv_xmalloc(nv2 * 3 * sizeof(double));
        for (size_t v = 0; v < nv; v++) {
            for (int d = 0; d < 3; d++) {
                double p = pos[v * 3 + d];
                if (bval[v] == 2)
                    p = 0.75 * p + 0.125 * bsum[v * 3 + d];
                else if (bval[v] == 0 && val[v] > 0) {
                    int n = val[v];
                    double beta = n == 3 ? 3.0 / 16 : 3.0 / (8.0 * n);
                    p = (1 - n * beta) * p + beta * nsum[v * 3 + d];
                }
                pos2[v * 3 + d] = p;
            }
        }
        for (size_t e = 0; e < ne; e++)
            for (int d = 0; d < 3; d++) {
                double a = pos[ea[e * 2] * 3 + d], c = pos[ea[e * 2 + 1] * 3 + d];
                pos2[(nv + e) * 3 + d] = ecount[e] == 2 ? 0.375 * (a + c) + 0.125 * eopp[e * 3 + d]
                                                        : 0.5 * (a + c);
            }
        uint32_t *tri2 = cv_xmalloc(nt * 12 * sizeof(uint32_t));
        for (size_t t = 0; t < nt; t++) {
            uint32_t a = tri[t * 3], bb = tri[t * 3 + 1], c = tri[t * 3 + 2];
            uint32_t ab = (uint32_t)nv + tedge[t * 3], bc = (uint32_t)nv + tedge[t * 3 + 1],
                     ca = (uint32_t)nv + tedge[t * 3 + 2];
            uint32_t q[12] = {a, ab, ca, ab, bb, bc, ca, bc, c, ab, bc, ca};
            memcpy(tri2 + t * 12, q, sizeof(q));
        }
        free(em.keys); free(em.val); free(tedge); free(ea); free(eopp); free(ecount);
        free(nsum); free(bsum); free(val); free(bval); free(pos); free(tri);
        pos = pos2;
        tri = tri2;
        nv = nv2;
        nt *= 4;
    }
    /* area-weighted normals following the winding */
    double *nrm = cv_xcalloc(nv * 3 + 1, sizeof(double));
    for (size_t t = 0; t < nt; t++) {
        const double *a = &pos[tri[t * 3] * 3], *bb = &pos[tri[t * 3 + 1] * 3], *c = &pos[tri[t * 3 + 2] * 3];
        double e1[3] = {bb[0] - a[0], bb[1] - a[1], bb[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; k++)
            for (int d = 0; d < 3; d++)
                nrm[tri[t * 3 + k] * 3 + d] += n[d];
    }
    g->P = cv_xmalloc((nv ? nv : 1) * 3 * sizeof(float));
    g->N = cv_xmalloc((nv ? nv : 1) * 3 * sizeof(float));
    for (size_t v = 0; v < nv; v++) {
        double *n = &nrm[v * 3], l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int d = 0; d < 3; d++) {
            g->P[v * 3 + d] = (float)pos[v * 3 + d];
            g->N[v * 3 + d] = (float)(l > 0 ? n[d] / l : 0);
        }
    }
    g->idx = tri;
    g->nv = nv;
    g->nt = nt;
    free(nrm);
    free(pos);
    (void)b;
    return true;
}

/* A bilinear patch p00 p10 p01 p11 (corners 0-3) as two triangles, and
 * the (u, v) pbrt-v4 gives its corners where the mesh has none. */
static const uint32_t patch_tris[6] = {0, 1, 3, 0, 3, 2};
static const float patch_corner_uv[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};

/* Meshes without "uv" whose faces include bilinear patches: a
 * bilinearmesh, or a PLY mesh with quads, which pbrt-v4 makes patches
 * (v0 v1 v2 v3 as p00 p10 p11 p01: its util/mesh.cpp). pbrt-v4 gives each
 * patch its own (u, v), patch_corner_uv, where a triangle's default
 * (0, 0) (1, 0) (1, 1) would shear the patch's second triangle, and keeps
 * that default for triangles. The mesh then needs a uv per vertex, so each
 * face gets vertices of its own (normals copied): a patch four, a
 * triangle three with the default (trace/geometry.glsl). A patch is two
 * triangles, (p00 p10 p11) at quad_first[i] and (p00 p11 p01) after it;
 * quad_first NULL: every two triangles are one (a bilinearmesh). */
static bool face_uv(struct geo *g, const size_t *quad_first, size_t n_quads,
                    const struct cv_loc *loc, struct cv_error *err)
{
    size_t nv = (g->nt - 2 * n_quads) * 3 + n_quads * 4;
    if (nv > 0xffffffffu)
        return cv_fail(err, "%s:%d:%d: too many vertices", loc->file, loc->line, loc->col);
    static const float tri_uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    float *P = cv_xmalloc((nv * 3 + 1) * sizeof(float)), *uv = cv_xmalloc((nv * 2 + 1) * sizeof(float));
    float *N = g->N ? cv_xmalloc((nv * 3 + 1) * sizeof(float)) : NULL;
    size_t v = 0, q = 0;
    for (size_t t = 0; t < g->nt; t++) {
        uint32_t *f = g->idx + t * 3, corner[4];
        bool quad = q < n_quads && (!quad_first || quad_first[q] == t);
        int n = quad ? 4 : 3;
        if (quad) {   /* f holds p00 p10 p11, then p00 p11 p01 */
            uint32_t patch[4] = {f[0], f[1], f[5], f[2]};
            memcpy(corner, patch, sizeof(patch));
        } else {
            memcpy(corner, f, 3 * sizeof(uint32_t));
        }
        for (int k = 0; k < n; k++) {
            memcpy(&P[(v + k) * 3], &g->P[(size_t)corner[k] * 3], 3 * sizeof(float));
            if (N)
                memcpy(&N[(v + k) * 3], &g->N[(size_t)corner[k] * 3], 3 * sizeof(float));
            memcpy(&uv[(v + k) * 2], quad ? patch_corner_uv[k] : tri_uv[k], 2 * sizeof(float));
        }
        for (int k = 0; k < (quad ? 6 : 3); k++)
            f[k] = (uint32_t)v + (quad ? patch_tris[k] : (uint32_t)k);
        if (quad) {
            t++;
            q++;
        }
        v += (size_t)n;
    }
    free(g->P);
    free(g->N);
    g->P = P;
    g->N = N;
    g->uv = uv;
    g->nv = nv;
    return true;
}

/* P/indices/N/uv of trianglemesh and bilinearmesh, checked. */
static bool mesh_params(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc,
                        int per_face, struct geo *g, struct cv_error *err)
{
    struct cv_param *P = cv_params_array(ps, "P"), *I = cv_params_array(ps, "indices");
    if (!P || P->n_nums % 3)
        return cv_fail(err, "%s:%d:%d: mesh needs \"point3 P\"", loc->file, loc->line, loc->col);
    size_t nv = P->n_nums / 3;
    if (nv > 0xffffffffu)
        return cv_fail(err, "%s:%d:%d: too many vertices", loc->file, loc->line, loc->col);
    size_t ni = I ? I->n_nums : 0;
    if (!I) {
        if (nv != (size_t)per_face)
            return cv_fail(err, "%s:%d:%d: mesh without \"integer indices\" must have exactly %d vertices",
                           loc->file, loc->line, loc->col, per_face);
        ni = (size_t)per_face;
    }
    if (ni % (size_t)per_face)
        return cv_fail(err, "%s:%d:%d: %zu indices is not a multiple of %d", I->file, I->line,
                       I->col, ni, per_face);
    struct cv_param *N = cv_params_array(ps, "N"), *uv = cv_params_array(ps, "uv");
    if (!uv)
        uv = cv_params_array(ps, "st");
    if (N && N->n_nums != nv * 3) {
        struct cv_loc l = {N->file, N->line, N->col};
        if (!cv_b_warn(b, err, &l, "\"N\" has %zu values for %zu vertices; ignored", N->n_nums, nv))
            return false;
        N = NULL;
    }
    if (uv && uv->n_nums != nv * 2) {
        struct cv_loc l = {uv->file, uv->line, uv->col};
        if (!cv_b_warn(b, err, &l, "\"uv\" has %zu values for %zu vertices; ignored", uv->n_nums, nv))
            return false;
        uv = NULL;
    }
    struct cv_param *S = cv_params_array(ps, "S");
    if (S && S->n_nums) {
        /* pbrt-v4 orients the shading frame by them; Cavalry by dpdu,
         * which turns anisotropic lobes and normal maps where they differ */
        struct cv_loc l = {S->file, S->line, S->col};
        if (!cv_b_warn(b, err, &l, "\"S\" (shading tangents) is not rendered: the shading frame "
                       "follows the uv parametrization (dpdu)"))
            return false;
    }
    cv_params_find(ps, "faceIndices");
    g->nv = nv;
    g->P = cv_xmalloc((nv * 3 + 1) * sizeof(float));
    for (size_t i = 0; i < nv * 3; i++)
        g->P[i] = (float)P->nums[i];
    if (N) {
        g->N = cv_xmalloc((nv * 3 + 1) * sizeof(float));
        for (size_t i = 0; i < nv * 3; i++)
            g->N[i] = (float)N->nums[i];
    }
    if (uv) {
        g->uv = cv_xmalloc((nv * 2 + 1) * sizeof(float));
        for (size_t i = 0; i < nv * 2; i++)
            g->uv[i] = (float)uv->nums[i];
    }
    size_t nf = ni / (size_t)per_face;
    g->idx = cv_xmalloc((nf * 6 + 1) * sizeof(uint32_t));
    for (size_t f = 0; f < nf; f++) {
        uint32_t q[4];
        for (int k = 0; k < per_face; k++) {
            double v = I ? I->nums[f * (size_t)per_face + (size_t)k] : k;
            if (!(v >= 0 && v < (double)nv))
                return cv_fail(err, "%s:%d:%d: index %g out of range (%zu vertices)", I->file,
                               I->line, I->col, v, nv);
            q[k] = (uint32_t)v;
        }
        if (per_face == 3) {
            memcpy(g->idx + g->nt * 3, q, 3 * sizeof(uint32_t));
            g->nt++;
        } else {
            for (int k = 0; k < 6; k++)
                g->idx[g->nt * 3 + (size_t)k] = q[patch_tris[k]];
            g->nt += 2;
        }
    }
    if (per_face == 4 && !uv)
        return face_uv(g, NULL, g->nt / 2, loc, err);
    return true;
}

static bool apply_alpha(struct cv_builder *b, struct cv_params *ps, struct cv_error *err)
{
    double a = 1;
    int at = -1;
    if (!cv_b_float_tex(b, ps, "alpha", &a, &at, err))
        return false;
    if (a == 1 && at < 0)
        return true;
    /* a cut-out is a material property on the GPU: derive a copy */
    int cur = b->gs.material;
    CvMaterial m;
    const char *nm = NULL;
    if (cur >= 0) {
        m = b->s->materials[cur];
        nm = b->s->material_names[cur];
    } else {
        memset(&m, 0, sizeof(m));
        m.type = CV_MAT_DIFFUSE;
        m.reflectance = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
        m.displacement_tex = m.normal_tex = m.reflectance_tex = m.specular_tex = -1;
        m.roughness_u_tex = m.roughness_v_tex = m.eta_tex = m.amount_tex = -1;
        m.mix_a = m.mix_b = -1;
    }
    m.alpha = (float)a;
    m.alpha_tex = at;
    char *name = cv_xasprintf("%s+alpha", nm ? nm : "(anonymous)");
    b->gs.material = (int)cv_b_add_material(b, &m, name);
    free(name);
    return true;
}

bool cv_b_shape(struct cv_builder *b, const char *type, struct cv_params *ps,
                const struct cv_loc *loc, const char *dir, struct cv_error *err)
{
    struct geo g = {0};
    struct cv_ply_mesh ply = {0};
    struct cv_mesh m = {0};
    bool ok = true, analytic = false;
    int saved_material = b->gs.material;
    if (!apply_alpha(b, ps, err))
        return false;
    if (strcmp(type, "trianglemesh") == 0) {
        ok = mesh_params(b, ps, loc, 3, &g, err);
    } else if (strcmp(type, "bilinearmesh") == 0) {
        ok = mesh_params(b, ps, loc, 4, &g, err);
    } else if (strcmp(type, "plymesh") == 0) {
        const char *file = cv_params_string(ps, "filename", NULL);
        if (!file) {
            ok = cv_fail(err, "%s:%d:%d: plymesh has no \"string filename\"", loc->file, loc->line, loc->col);
        } else {
            char *path = cv_b_resolve(b, dir, file, err);
            ok = path && cv_ply_read(path, &ply, err);
            free(path);
            if (!ok)
                cv_error_prefix(err, "%s:%d:%d: plymesh \"%s\"", loc->file, loc->line, loc->col, file);
            if (ok && cv_params_find(ps, "displacement"))
                ok = cv_b_warn(b, err, loc, "plymesh displacement is not supported; ignored");
            cv_params_float(ps, "edgelength", 1);
        }
        if (ok) {
            g.P = ply.P; g.N = ply.N; g.uv = ply.uv; g.idx = ply.idx;
            g.nv = ply.n_verts; g.nt = ply.n_tris;
            ply.P = ply.N = ply.uv = NULL;
            ply.idx = NULL;
            if (!g.uv && ply.n_quads)
                ok = face_uv(&g, ply.quad_first, ply.n_quads, loc, err);
            if (ok && ply.n_polys)
                ok = cv_b_warn(b, err, loc, "plymesh \"%s\": %zu faces of more than 4 vertices split "
                               "into triangles (pbrt-v4 skips them)", file, ply.n_polys);
        }
    } else if (strcmp(type, "sphere") == 0) {
        analytic = true;
        if (!sphere(ps, &g))
            g.nt = 0;
    } else if (strcmp(type, "disk") == 0) {
        analytic = true;
        if (!disk(ps, &g))
            g.nt = 0;
    } else if (strcmp(type, "cylinder") == 0) {
        analytic = true;
        if (!cylinder(ps, &g))
            g.nt = 0;
    } else if (strcmp(type, "heightfield") == 0) {
        ok = heightfield(b, ps, loc, &g, err);
    } else if (strcmp(type, "loopsubdiv") == 0) {
        ok = loop_subdivide(b, ps, loc, &g, err);
    } else if (strcmp(type, "curve") == 0) {
        ok = cv_b_curve(b, ps, loc, err);
        if (ok && b->gs.area.on)
            ok = cv_b_warn(b, err, loc, "curves do not emit light: pbrt-v4 cannot sample a point on a curve "
                           "(its Curve::Sample is not implemented), so there is no reference; the area light is ignored");
    } else {
        for (size_t i = 0; i < ps->n; i++)
            ps->v[i].used = true;
        ok = cv_b_warn(b, err, loc, "shape \"%s\" is not supported; skipped", type);
    }
    if (ok && g.nt) {
        m.n_verts = g.nv;
        m.n_tris = g.nt;
        m.P = g.P;
        m.N = g.N;
        m.uv = g.uv;
        m.idx = g.idx;
        m.analytic = analytic;
        /* exporters write one PLY file per object of the DCC's scene */
        if (strcmp(type, "plymesh") == 0)
            m.name = cv_params_string(ps, "filename", NULL);
        ok = cv_b_emit_mesh(b, &m, loc, err);
    }
    geo_free(&g);
    cv_ply_free(&ply);
    b->gs.material = saved_material;
    return ok;
}
