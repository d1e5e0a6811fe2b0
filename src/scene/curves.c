/* curves.c: pbrt-v4's Shape "curve" onto CvCurve: bezier and bspline
 * bases of degree 2 and 3 become cubic Bezier pieces (quadratics raised to
 * cubics, uniform b-splines blossomed to Bezier points, as pbrt-v4's
 * Curve::Create), the widths interpolated per piece, each piece split into
 * 2^splitdepth primitives over its u range. pbrt-v4 intersects a curve
 * in its object space. Under a similarity (rotation, mirror, one scale,
 * translation) that is the same as intersecting it in render space with
 * its width scaled, so such curves go to render space; under any other
 * transform a curve keeps its object-space points, widths and normals and
 * names its transform (CvCurveXform), with which the renderer carries the
 * ray there and the hit's frame back. Inside an
 * ObjectBegin definition they go to the definition's space, placed again
 * by each instance (builder.c, cv_b_instance); a moving curve's stay in
 * its object space (scene.h, cv_motion). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/builder.h"

static void lerp3(double t, const double a[3], const double b[3], double out[3])
{
    for (int c = 0; c < 3; c++)
        out[c] = (1 - t) * a[c] + t * b[c];
}

/* The cubic Bezier points of piece `seg` from the input points cp. */
static void piece(const double *cp, int seg, int degree, bool bspline, double out[4][3])
{
    if (!bspline) {
        const double *p = cp + 3 * (size_t)seg * degree;
        if (degree == 3) {
            memcpy(out, p, 12 * sizeof(double));
        } else {
            memcpy(out[0], p, 3 * sizeof(double));
            lerp3(2.0 / 3, p, p + 3, out[1]);
            lerp3(1.0 / 3, p + 3, p + 6, out[2]);
            memcpy(out[3], p + 6, 3 * sizeof(double));
        }
        return;
    }
    const double *p = cp + 3 * (size_t)seg;
    if (degree == 2) {
        double q[3][3];
        lerp3(0.5, p, p + 3, q[0]);
        memcpy(q[1], p + 3, 3 * sizeof(double));
        lerp3(0.5, p + 3, p + 6, q[2]);
        memcpy(out[0], q[0], 3 * sizeof(double));
        lerp3(2.0 / 3, q[0], q[1], out[1]);
        lerp3(1.0 / 3, q[1], q[2], out[2]);
        memcpy(out[3], q[2], 3 * sizeof(double));
        return;
    }
    double p122[3], p223[3], p233[3], p334[3];
    lerp3(2.0 / 3, p, p + 3, p122);
    lerp3(1.0 / 3, p + 3, p + 6, p223);
    lerp3(2.0 / 3, p + 3, p + 6, p233);
    lerp3(1.0 / 3, p + 6, p + 9, p334);
    lerp3(0.5, p122, p223, out[0]);
    memcpy(out[1], p223, 3 * sizeof(double));
    memcpy(out[2], p233, 3 * sizeof(double));
    lerp3(0.5, p233, p334, out[3]);
}

static void normalize3(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int c = 0; c < 3; c++)
            v[c] /= l;
}

bool cv_b_curve(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc, struct cv_error *err)
{
    double width = cv_params_float(ps, "width", 1);
    double w0 = cv_params_float(ps, "width0", width), w1 = cv_params_float(ps, "width1", width);
    int degree = cv_params_int(ps, "degree", 3);
    const char *basis = cv_params_string(ps, "basis", "bezier");
    const char *type = cv_params_string(ps, "type", "flat");
    int split = cv_params_int(ps, "splitdepth", 3);
    struct cv_param *P = cv_params_array(ps, "P");
    struct cv_param *N = cv_params_array(ps, "N");
#define FAIL(...) cv_fail(err, "%s:%d:%d: curve: " __VA_ARGS__)
    if (degree != 2 && degree != 3)
        return FAIL("degree %d: only 2 and 3 are supported", loc->file, loc->line, loc->col, degree);
    bool bspline = strcmp(basis, "bspline") == 0;
    if (!bspline && strcmp(basis, "bezier") != 0)
        return FAIL("basis \"%s\": only \"bezier\" and \"bspline\" are supported", loc->file, loc->line,
                    loc->col, basis);
    uint32_t ctype;
    if (strcmp(type, "flat") == 0) {
        ctype = CV_CURVE_FLAT;
    } else if (strcmp(type, "cylinder") == 0) {
        ctype = CV_CURVE_CYLINDER;
    } else if (strcmp(type, "ribbon") == 0) {
        ctype = CV_CURVE_RIBBON;
    } else {
        ctype = CV_CURVE_CYLINDER;
        if (!cv_b_warn(b, err, loc, "curve: unknown type \"%s\"; \"cylinder\" used (as pbrt-v4)", type))
            return false;
    }
    if (!P || P->n_nums % 3 != 0)
        return FAIL("needs \"point3 P\"", loc->file, loc->line, loc->col);
    long ncp = (long)(P->n_nums / 3), nseg;
    if (!bspline) {
        if (ncp < degree + 1 || (ncp - 1 - degree) % degree != 0)
            return FAIL("%ld control points: the degree %d Bezier basis needs %d + n * %d", loc->file, loc->line,
                        loc->col, ncp, degree, degree + 1, degree);
        nseg = (ncp - 1) / degree;
    } else {
        if (ncp < degree + 1)
            return FAIL("%ld control points: the degree %d b-spline basis needs at least %d", loc->file,
                        loc->line, loc->col, ncp, degree, degree + 1);
        nseg = ncp - degree;
    }
    if (N && ctype != CV_CURVE_RIBBON) {
        if (!cv_b_warn(b, err, loc, "curve: normals \"N\" are only used by \"ribbon\" curves"))
            return false;
        N = NULL;
    } else if (ctype == CV_CURVE_RIBBON && (!N || N->n_nums != 3 * (size_t)(nseg + 1))) {
        return FAIL("ribbon curves need %ld normals \"N\" (one per piece end)", loc->file, loc->line, loc->col,
                    nseg + 1);
    }
    if (split < 0 || split > 10)
        return FAIL("splitdepth %d outside 0..10", loc->file, loc->line, loc->col, split);
    uint32_t mat = cv_b_current_material(b);
    uint32_t word = mat | (b->gs.reverse ? CV_TRI_REVERSE : 0u);
    /* one ID-matte object per Shape directive, as a triangle mesh's;
     * inside a definition, each instance's (cv_b_instance) */
    uint32_t object = b->cur_object >= 0 ? 0 : cv_b_add_object_at(b, loc);
    /* the pieces in object space, then placed by the CTM */
    size_t per = (size_t)1 << split;
    CvCurve *pieces = cv_xcalloc((size_t)nseg * per, sizeof(CvCurve));
    for (long seg = 0; seg < nseg; seg++) {
        double bz[4][3];
        piece(P->nums, (int)seg, degree, bspline, bz);
        CvCurve c;
        memset(&c, 0, sizeof(c));
        for (int k = 0; k < 4; k++)
            c.cp[k] = (cv_vec4){(float)bz[k][0], (float)bz[k][1], (float)bz[k][2], 0};
        double t0 = (double)seg / nseg, t1 = (double)(seg + 1) / nseg;
        c.cp[0].w = (float)((1 - t0) * w0 + t0 * w1);
        c.cp[1].w = (float)((1 - t1) * w0 + t1 * w1);
        if (N) {
            const double *n = N->nums + 3 * seg;
            c.n0 = (cv_vec4){(float)n[0], (float)n[1], (float)n[2], 0};
            c.n1 = (cv_vec4){(float)n[3], (float)n[4], (float)n[5], 0};
        }
        c.info = (cv_uvec4){word, ctype, object, 0};
        for (size_t k = 0; k < per; k++) {
            c.cp[2].w = (float)((double)k / per);
            c.cp[3].w = (float)((double)(k + 1) / per);
            pieces[(size_t)seg * per + k] = c;
        }
    }
    bool ok = cv_b_place_curves(b, pieces, (size_t)nseg * per, &b->gs.ctm, UINT32_MAX, loc, err);
    free(pieces);
    return ok;
}

/* A ribbon's normals n0, n1 through inv's transpose (NULL: as they
 * are), unit length, with the angle between them in n0.w and 1 / its sine
 * in n1.w (0 for none), for the slerp. */
static void ribbon_normals(CvCurve *c, const struct cv_mat4 *inv)
{
    double nn[2][3];
    for (int k = 0; k < 2; k++) {
        const cv_vec4 *v = k ? &c->n1 : &c->n0;
        double o[3] = {v->x, v->y, v->z};
        if (inv)
            cv_mat4_normal(inv, o, nn[k]);
        else
            memcpy(nn[k], o, sizeof(o));
        normalize3(nn[k]);
    }
    double d = nn[0][0] * nn[1][0] + nn[0][1] * nn[1][1] + nn[0][2] * nn[1][2];
    /* pbrt-v4's AngleBetween, robust near 0 and pi */
    double e[3] = {nn[0][0] - nn[1][0], nn[0][1] - nn[1][1], nn[0][2] - nn[1][2]},
           f[3] = {nn[0][0] + nn[1][0], nn[0][1] + nn[1][1], nn[0][2] + nn[1][2]};
    double angle = d < 0 ? M_PI - 2 * asin(fmin(1, sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) / 2))
                         : 2 * asin(fmin(1, sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) / 2));
    c->n0 = (cv_vec4){(float)nn[0][0], (float)nn[0][1], (float)nn[0][2], (float)angle};
    c->n1 = (cv_vec4){(float)nn[1][0], (float)nn[1][1], (float)nn[1][2], angle > 0 ? (float)(1 / sin(angle)) : 0};
}

/* Whether M's 3x3 is one scale times a rotation or mirror (its columns
 * orthogonal and of one length), to rounding. */
static bool similarity(const struct cv_mat4 *M)
{
    double g[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            g[i][j] = M->m[0][i] * M->m[0][j] + M->m[1][i] * M->m[1][j] + M->m[2][i] * M->m[2][j];
    double s2 = (g[0][0] + g[1][1] + g[2][2]) / 3;
    if (!(s2 > 0))
        return false;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            if (fabs(g[i][j] - (i == j ? s2 : 0)) > 1e-9 * s2)
                return false;
    return true;
}

static struct cv_mat4 xform_matrix(const CvCurveXform *x)
{
    struct cv_mat4 m = cv_mat4_identity();
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m.m[r][c] = (&x->to_world[r].x)[c];
    return m;
}

/* A new CvCurveXform for X (invertible); its 1-based index. */
static uint32_t add_xform(struct cv_builder *b, const struct cv_mat4 *X, const struct cv_mat4 *inv)
{
    struct cv_scene *s = b->s;
    s->curve_xforms = cv_xgrow(s->curve_xforms, &b->cap_curve_xforms, s->n_curve_xforms + 1,
                               sizeof(CvCurveXform));
    CvCurveXform *x = &s->curve_xforms[s->n_curve_xforms++];
    for (int r = 0; r < 3; r++) {
        x->to_world[r] = (cv_vec4){(float)X->m[r][0], (float)X->m[r][1], (float)X->m[r][2], (float)X->m[r][3]};
        x->to_object[r] = (cv_vec4){(float)inv->m[r][0], (float)inv->m[r][1], (float)inv->m[r][2],
                                    (float)inv->m[r][3]};
    }
    return s->n_curve_xforms;
}

void cv_curve_xform_box(const CvCurveXform *x, const double lo[3], const double hi[3], double out_lo[3],
                        double out_hi[3])
{
    double l[3] = {lo[0], lo[1], lo[2]}, h[3] = {hi[0], hi[1], hi[2]}; /* out may be in */
    for (int a = 0; a < 3; a++) {
        out_lo[a] = INFINITY;
        out_hi[a] = -INFINITY;
    }
    for (int k = 0; k < 8; k++) {
        double p[3] = {(k & 1) ? h[0] : l[0], (k & 2) ? h[1] : l[1], (k & 4) ? h[2] : l[2]};
        for (int a = 0; a < 3; a++) {
            const cv_vec4 *r = &x->to_world[a];
            double w = (double)r->x * p[0] + (double)r->y * p[1] + (double)r->z * p[2] + r->w;
            out_lo[a] = fmin(out_lo[a], w);
            out_hi[a] = fmax(out_hi[a], w);
        }
    }
}

bool cv_b_place_curves(struct cv_builder *b, const CvCurve *src, size_t n, const struct cv_mat4 *M,
                       uint32_t object, const struct cv_loc *loc, struct cv_error *err)
{
    struct cv_scene *s = b->s;
    struct cv_object *obj = b->cur_object >= 0 ? &b->objects[b->cur_object] : NULL;
    size_t n0 = obj ? obj->nc : s->n_curves;
    if (n0 + n > CV_PRIM_CURVE)
        return FAIL("more than 2^31 curve primitives", loc->file, loc->line, loc->col);
    CvCurve *dst;
    if (obj) {
        obj->c = cv_xgrow(obj->c, &obj->cap_c, n0 + n, sizeof(CvCurve));
        dst = obj->c + n0;
    } else {
        s->curves = cv_xgrow(s->curves, &b->cap_curves, n0 + n, sizeof(CvCurve));
        dst = s->curves + n0;
    }
    struct cv_mat4 inv;
    bool invertible = cv_mat4_inverse(M, &inv) && cv_mat4_det3(M) != 0;
    bool swaps = cv_mat4_det3(M) < 0;
    /* a similarity's scale carries the widths (file comment) */
    double scale = cbrt(fabs(cv_mat4_det3(M)));
    bool to_render = similarity(M) || !invertible;
    uint32_t last_src = UINT32_MAX, last_xf = 0; /* one transform per source transform */
    for (size_t i = 0; i < n; i++) {
        CvCurve c = src[i];
        uint32_t src_xf = c.info.y >> CV_CURVE_XF_SHIFT;
        if (src_xf || !to_render) {
            /* stays in its object space: the transform composed */
            if (src_xf != last_src) {
                struct cv_mat4 X = *M, Xinv;
                if (src_xf) {
                    struct cv_mat4 prev = xform_matrix(&s->curve_xforms[src_xf - 1]);
                    X = cv_mat4_mul(M, &prev);
                }
                if (!cv_mat4_inverse(&X, &Xinv) || !(cv_mat4_det3(&X) != 0))
                    return FAIL("the curve's transform is singular", loc->file, loc->line, loc->col);
                for (int r = 0; r < 3; r++)
                    for (int k = 0; k < 4; k++)
                        if (!isfinite(X.m[r][k]) || !isfinite(Xinv.m[r][k]))
                            return FAIL("the curve's transform is not finite", loc->file, loc->line, loc->col);
                if (s->n_curve_xforms >= (1u << (32 - CV_CURVE_XF_SHIFT)) - 1)
                    return FAIL("more than 2^%u curve transforms", loc->file, loc->line, loc->col,
                                32 - CV_CURVE_XF_SHIFT);
                last_xf = add_xform(b, &X, &Xinv);
                last_src = src_xf;
            }
            c.info.y = (c.info.y & CV_CURVE_TYPE_MASK) | last_xf << CV_CURVE_XF_SHIFT;
            if ((c.info.y & CV_CURVE_TYPE_MASK) == CV_CURVE_RIBBON) /* in object space, as pbrt-v4 */
                ribbon_normals(&c, NULL);
            if (swaps)
                c.info.x ^= CV_TRI_REVERSE;
            if (object != UINT32_MAX)
                c.info.z = object;
            dst[i] = c;
            continue;
        }
        for (int k = 0; k < 4; k++) {
            double p[3] = {c.cp[k].x, c.cp[k].y, c.cp[k].z}, w[3];
            cv_mat4_point(M, p, w);
            c.cp[k] = (cv_vec4){(float)w[0], (float)w[1], (float)w[2], c.cp[k].w};
            if (!isfinite(c.cp[k].x) || !isfinite(c.cp[k].y) || !isfinite(c.cp[k].z))
                return FAIL("control points are not finite after the transform", loc->file, loc->line, loc->col);
        }
        c.cp[0].w = (float)(c.cp[0].w * scale);
        c.cp[1].w = (float)(c.cp[1].w * scale);
        if ((c.info.y & CV_CURVE_TYPE_MASK) == CV_CURVE_RIBBON)
            ribbon_normals(&c, &inv);
        if (swaps)
            c.info.x ^= CV_TRI_REVERSE;
        if (object != UINT32_MAX)
            c.info.z = object;
        dst[i] = c;
    }
    if (obj)
        obj->nc = n0 + n;
    else
        s->n_curves = (uint32_t)(n0 + n);
    return true;
}
#undef FAIL
