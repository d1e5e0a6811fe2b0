/* curves_test.c: curve shapes from the scene file to the GPU hit
 * (src/scene/curves.c, src/bvh/curve_bvh.c, glsl/bvh/curves.glsl):
 * - the tree walk equals the brute force over every curve, bit for bit
 *   (t, primitive, u, v; any-hit too) on random strands of every type and
 *   basis, for rays aimed at them and rays at random;
 * - a straight curve against what its shape must give: hits exactly within
 *   half the width of its axis, t at the axis, u along it, v across it; a
 *   cylinder's normal turned across the width as pbrt-v4 turns it (by an
 *   angle linear in v, on the far side: its flat normal faces away from
 *   the ray), a flat one's along
 *   the ray, a ribbon's width shrunk by the cosine of its normal to the ray;
 * - the scene conversions: bspline and quadratic pieces, splitdepth,
 *   widths per piece, errors for malformed input;
 * - curves in an ObjectBegin definition, instanced under several
 *   transforms (a mirror and a non-uniform scale among them): the same
 *   curves as written out under each instance's transform, one ID-matte
 *   object for all, and the walk equals the brute force over them.
 * Fixed seeds. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh/curve_bvh.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"

static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double rnd(void)
{
    return cv_test_xorshift64(&rng);
}

static struct cv_scene *load(const char *text, struct cv_error *err)
{
    struct cv_scene *s = NULL;
    struct cv_scene_load_params p = {.strict = false};
    if (!cv_scene_load_string("/tmp/curves_test.pbrt", text, strlen(text), &p, &s, err))
        return NULL;
    return s;
}

struct run {
    uint32_t *out;  /* 16 words per ray (curves_test.comp) */
    uint32_t n;
};

static bool trace(struct cv_gpu *gpu, const struct cv_scene *s, const float *rays, uint32_t n, struct run *r,
                  struct cv_error *err)
{
    size_t n4;
    float *packed =
        cv_curve_bvh_pack(s->curves, s->n_curves, s->curve_xforms, s->n_curve_xforms, s->n_motions, &n4);
    GLuint cb = cv_buffer_create(n4 * 16, packed, "curves", err);
    free(packed);
    GLuint ct = cb ? cv_buffer_texture(cb, GL_RGBA32F, n4, err) : 0;
    GLuint rb = cv_buffer_create((size_t)n * 32, rays, "rays", err);
    GLuint ob = cv_buffer_create((size_t)n * 64, NULL, "results", err);
    struct cv_program *p = ct && rb && ob ? cv_program_get(gpu, "bvh/curves_test.comp", NULL, err) : NULL;
    bool ok = p != NULL;
    if (ok) {
        glBindTextureUnit(CV_TEXUNIT_CURVES, ct);
        cv_buffer_bind(rb, CV_BIND_PROBE_IN);
        cv_buffer_bind(ob, CV_BIND_PROBE_OUT);
        glProgramUniform1ui(p->id, glGetUniformLocation(p->id, "u_n_rays"), n);
        cv_program_dispatch_1d(p, n);
        r->out = malloc((size_t)n * 64);
        r->n = n;
        ok = cv_buffer_read(ob, 0, (size_t)n * 64, r->out, err);
    }
    if (ct)
        glDeleteTextures(1, &ct);
    cv_buffer_destroy(&cb);
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&ob);
    return ok;
}

static float fbits(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

static void set_ray(float *r, const double o[3], const double d[3], double tmin, double tmax)
{
    for (int k = 0; k < 3; k++) {
        r[k] = (float)o[k];
        r[4 + k] = (float)d[k];
    }
    r[3] = (float)tmin;
    r[7] = (float)tmax;
}

/* ---- walk against brute force on random strands ---- */
/* A random affine transform with non-uniform scale and shear, as pbrt-v4's
 * Transform directive writes it (columns), and applied to a point. */
static void random_warp(double m[3][4])
{
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 4; c++)
            m[r][c] = r == c ? 0.5 + 1.5 * rnd() : c == 3 ? rnd() - 0.5 : (rnd() - 0.5) * 0.8;
}

static size_t put_warp(char *text, size_t cap, const double m[3][4])
{
    size_t len = (size_t)snprintf(text, cap, "Transform [");
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++)
            len += (size_t)snprintf(text + len, cap - len, " %.6f", r < 3 ? m[r][c] : c == 3 ? 1.0 : 0.0);
    return len + (size_t)snprintf(text + len, cap - len, " ]\n");
}

static void warp_point(const double m[3][4], double p[3])
{
    double q[3];
    for (int r = 0; r < 3; r++)
        q[r] = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
    memcpy(p, q, sizeof(q));
}

/* warped: each strand under a transform of its own, which is no
 * similarity, so kept in its object space (the tree's boxes are its
 * boxes' images) */
static void test_random(struct cv_gpu *gpu, bool warped)
{
    static const char *types[] = {"flat", "cylinder", "ribbon"};
    static const char *bases[] = {"bspline", "bezier"};
    size_t cap = 1 << 20, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "WorldBegin\n");
    int n_strands = 36;
    double aim[64][3];
    int n_aim = 0;
    for (int sidx = 0; sidx < n_strands; sidx++) {
        const char *type = types[sidx % 3], *basis = bases[(sidx / 3) % 2];
        int degree = (sidx / 6) % 2 ? 2 : 3;
        int ncp = strcmp(basis, "bezier") == 0 ? 1 + degree * 3 : 7;
        double base[3] = {rnd() * 4 - 2, rnd() * 4 - 2, rnd() * 4 - 2}, warp[3][4];
        if (warped) {
            random_warp(warp);
            len += (size_t)snprintf(text + len, cap - len, "AttributeBegin\n");
            len += put_warp(text + len, cap - len, warp);
        }
        len += (size_t)snprintf(text + len, cap - len,
                                "Shape \"curve\" \"string type\" \"%s\" \"string basis\" \"%s\" \"integer degree\" %d"
                                " \"float width0\" %g \"float width1\" %g \"integer splitdepth\" %d \"point3 P\" [",
                                type, basis, degree, 0.05 + 0.2 * rnd(), 0.01 + 0.1 * rnd(), sidx % 4);
        double p[3] = {base[0], base[1], base[2]};
        for (int k = 0; k < ncp; k++) {
            for (int c = 0; c < 3; c++)
                p[c] += rnd() * 0.8 - 0.4;
            len += (size_t)snprintf(text + len, cap - len, " %.6f %.6f %.6f", p[0], p[1], p[2]);
            if (n_aim < 64 && k == ncp / 2) {
                memcpy(aim[n_aim], p, sizeof(p));
                if (warped)
                    warp_point(warp, aim[n_aim]);
                n_aim++;
            }
        }
        len += (size_t)snprintf(text + len, cap - len, " ]");
        if (strcmp(type, "ribbon") == 0) {
            int nseg = strcmp(basis, "bezier") == 0 ? (ncp - 1) / degree : ncp - degree;
            len += (size_t)snprintf(text + len, cap - len, " \"normal N\" [");
            for (int k = 0; k <= nseg; k++)
                len += (size_t)snprintf(text + len, cap - len, " %.4f %.4f %.4f", rnd() - 0.5, rnd() - 0.5, 0.5 + rnd());
            len += (size_t)snprintf(text + len, cap - len, " ]");
        }
        len += (size_t)snprintf(text + len, cap - len, "\n%s", warped ? "AttributeEnd\n" : "");
    }
    struct cv_error err = {{0}};
    struct cv_scene *s = load(text, &err);
    free(text);
    const char *what = warped ? "sheared, unevenly scaled strands" : "strands";
    if (!tap_ok(s != NULL && s->n_curves > 0, "random %s load (%u primitives)%s%s", what, s ? s->n_curves : 0,
                s ? "" : ": ", s ? "" : err.msg))
        return;
    if (warped) {
        uint32_t kept = 0;
        for (uint32_t i = 0; i < s->n_curves; i++)
            kept += (s->curves[i].info.y >> CV_CURVE_XF_SHIFT) != 0;
        tap_ok(kept == s->n_curves && s->n_curve_xforms == (uint32_t)n_strands,
               "each is kept in its object space, one transform a strand (%u of %u, %u transforms)", kept,
               s->n_curves, s->n_curve_xforms);
    }
    uint32_t n = 8192;
    float *rays = calloc((size_t)n * 8, sizeof(float));
    for (uint32_t i = 0; i < n; i++) {
        double o[3] = {rnd() * 10 - 5, rnd() * 10 - 5, rnd() * 10 - 5}, d[3];
        if (i % 4 != 3) {
            /* towards a control point of a strand, jittered by about a width */
            const double *a = aim[i % n_aim];
            for (int c = 0; c < 3; c++)
                d[c] = a[c] + (rnd() - 0.5) * 0.6 - o[c];
        } else {
            for (int c = 0; c < 3; c++)
                d[c] = rnd() - 0.5;
        }
        /* some rays start inside the strands' region, some end early */
        double tmin = i % 5 == 0 ? 0.3 : 0, tmax = i % 7 == 0 ? 0.6 : 1e30;
        set_ray(rays + 8 * i, o, d, tmin, tmax);
    }
    struct run r = {0};
    if (!tap_ok(trace(gpu, s, rays, n, &r, &err), "GPU run: %s", err.msg)) {
        cv_scene_destroy(&s);
        free(rays);
        return;
    }
    uint32_t hits = 0, diff = 0, any_diff = 0, any_wrong = 0;
    for (uint32_t i = 0; i < n; i++) {
        const uint32_t *o = r.out + 16 * i;
        if (o[1] != 0xffffffffu)
            hits++;
        if (memcmp(o, o + 4, 16) != 0) {
            if (diff < 3)
                tap_diag("ray %u: walk t %.9g prim %x u %.9g v %.9g, brute t %.9g prim %x u %.9g v %.9g", i,
                         fbits(o[0]), o[1], fbits(o[2]), fbits(o[3]), fbits(o[4]), o[5], fbits(o[6]), fbits(o[7]));
            diff++;
        }
        if (o[8] != o[9])
            any_diff++;
        if (o[8] != (o[5] != 0xffffffffu))
            any_wrong++;
    }
    tap_ok(hits > n / 8, "rays hit the %s (%u of %u)", what, hits, n);
    tap_ok(diff == 0, "%s: closest hit through the curve tree equals the brute force (%u of %u differ)", what, diff,
           n);
    tap_ok(any_diff == 0 && any_wrong == 0,
           "%s: any-hit through the tree equals the brute force (%u differ) and the closest query (%u differ)", what,
           any_diff, any_wrong);
    free(r.out);
    free(rays);
    cv_scene_destroy(&s);
}

/* ---- a straight curve along x, seen from +z ---- */
/* Under "Scale 1 sy 1" (sy 1: none): pbrt-v4 takes the width in object
 * space, so the curve is sy times as wide in y, its v and normals those of
 * object space carried out (normals by the inverse transpose). */
static void test_straight(struct cv_gpu *gpu, double sy)
{
    static const char *const kinds[] = {"flat", "cylinder", "ribbon"};
    for (int kind = 0; kind < 3; kind++) {
        char text[512], xf[64] = "", label[64] = "";
        if (sy != 1) {
            snprintf(xf, sizeof(xf), "Scale 1 %g 1\n", sy);
            snprintf(label, sizeof(label), "under Scale 1 %g 1, ", sy);
        }
        /* ribbon: normal tilted 60 degrees from the ray (towards +y): width halves */
        snprintf(text, sizeof(text),
                 "WorldBegin\n%sShape \"curve\" \"string type\" \"%s\" \"point3 P\" [-1 0 0 -0.3333333 0 0 0.3333333 0 0 "
                 "1 0 0] \"float width\" 0.2 %s\n",
                 xf, kinds[kind], kind == 2 ? "\"normal N\" [0 0.8660254 0.5 0 0.8660254 0.5]" : "");
        struct cv_error err = {{0}};
        struct cv_scene *s = load(text, &err);
        if (!tap_ok(s && s->n_curves == 8, "%s%s straight curve loads (%u primitives)%s", label, kinds[kind],
                    s ? s->n_curves : 0, s ? "" : err.msg))
            continue;
        /* half the width: in object space, and seen along -z */
        double half_o = kind == 2 ? 0.05 : 0.1, half = half_o * sy;
        uint32_t n = 1024;
        float *rays = calloc((size_t)n * 8, sizeof(float));
        double *off = calloc(n, sizeof(double)), *xs = calloc(n, sizeof(double));
        for (uint32_t i = 0; i < n; i++) {
            xs[i] = -0.95 + 1.9 * rnd();
            off[i] = (rnd() * 2 - 1) * half * 1.3;
            double o[3] = {xs[i], off[i], 5}, d[3] = {0, 0, -1};
            set_ray(rays + 8 * i, o, d, 0, 1e30);
        }
        struct run r = {0};
        if (!tap_ok(trace(gpu, s, rays, n, &r, &err), "GPU run: %s", err.msg)) {
            cv_scene_destroy(&s);
            continue;
        }
        uint32_t wrong_hit = 0, bad_t = 0, bad_u = 0, bad_v = 0, bad_n = 0, hits = 0;
        double worst_v = 0, worst_n = 0;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t *o = r.out + 16 * i;
            bool hit = o[1] != 0xffffffffu;
            double a = fabs(off[i]);
            /* a margin of float rounding at the edge */
            if (fabs(a - half) > 1e-5 && hit != (a < half))
                wrong_hit++;
            if (!hit)
                continue;
            hits++;
            float t = fbits(o[0]), u = fbits(o[2]), v = fbits(o[3]);
            if (fabs(t - 5) > 1e-5)
                bad_t++;
            /* u: the piece's own parameter, pieces of 1/8 (splitdepth 3) */
            if (fabs(u - (xs[i] + 1) / 2) > 1e-4)
                bad_u++;
            double dv = fabs(fabs(v - 0.5) - a / (2 * half));  /* the same fraction in object space */
            worst_v = fmax(worst_v, dv);
            if (dv > 1e-4)
                bad_v++;
            double nx = fbits(o[12]), ny = fbits(o[13]), nz = fbits(o[14]), dn;
            /* the object-space normal (0, ey, ez), carried out: (0, ey / sy, ez) */
            double ey, ez;
            if (kind == 0) {
                ey = 0;  /* faces the ray */
                ez = 1;
            } else if (kind == 1) {
                /* pbrt-v4's tube: turned from the flat normal by an angle
                 * linear in the offset, 90 degrees at the edges, on the
                 * side away from the ray (its flat normal faces away too) */
                double ang = M_PI / 2 * off[i] / half;
                ey = sin(ang);
                ez = -cos(ang);
            } else {
                ey = 0.8660254;
                ez = 0.5;
            }
            ey /= sy;
            dn = 1 - fabs(ny * ey + nz * ez) / sqrt(ey * ey + ez * ez);
            dn = fmax(dn, fabs(nx));
            worst_n = fmax(worst_n, dn);
            if (dn > 1e-3)
                bad_n++;
        }
        tap_ok(wrong_hit == 0 && hits > n / 2,
               "%s%s: hit exactly within %.2f of the axis (%u wrong of %u, %u hits)", label, kinds[kind], half, wrong_hit,
               n, hits);
        tap_ok(bad_t == 0 && bad_u == 0, "%s%s: t at the axis, u along it (%u, %u off)", label, kinds[kind], bad_t,
               bad_u);
        tap_ok(bad_v == 0, "%s%s: |v - 0.5| = offset / width (worst %.2g)", label, kinds[kind], worst_v);
        tap_ok(bad_n == 0, "%s%s: normal %s (worst 1 - |cos| %.2g)", label, kinds[kind],
               kind == 0 ? "faces the ray" : kind == 1 ? "of a round tube" : "the ribbon's", worst_n);
        free(r.out);
        free(rays);
        free(off);
        free(xs);
        cv_scene_destroy(&s);
    }
}

/* ---- conversions on the host ---- */
static bool near3(const cv_vec4 *v, double x, double y, double z)
{
    return fabs(v->x - x) < 1e-5 && fabs(v->y - y) < 1e-5 && fabs(v->z - z) < 1e-5;
}

static void test_conversions(void)
{
    struct cv_error err = {{0}};
    struct cv_scene *s = load("WorldBegin\nShape \"curve\" \"string basis\" \"bspline\" \"point3 P\" "
                              "[0 0 0 3 0 0 6 6 0 9 0 0 12 0 0] \"float width0\" 1 \"float width1\" 0.5 "
                              "\"integer splitdepth\" 1\n",
                              &err);
    if (tap_ok(s && s->n_curves == 4, "cubic bspline of 5 points: 2 pieces x 2 (%u)", s ? s->n_curves : 0)) {
        const CvCurve *c = s->curves;
        /* the first piece's Bezier points: (p0 + 4 p1 + p2) / 6, (2 p1 + p2) / 3, (p1 + 2 p2) / 3, (p1 + 4 p2 + p3) / 6 */
        tap_ok(near3(&c[0].cp[0], 3, 1, 0) && near3(&c[0].cp[1], 4, 2, 0) && near3(&c[0].cp[2], 5, 4, 0) &&
                   near3(&c[0].cp[3], 6, 4, 0),
               "bspline blossomed to Bezier points");
        tap_ok(fabs(c[0].cp[0].w - 1) < 1e-6 && fabs(c[0].cp[1].w - 0.75) < 1e-6 && fabs(c[2].cp[0].w - 0.75) < 1e-6 &&
                   fabs(c[2].cp[1].w - 0.5) < 1e-6,
               "widths interpolated per piece");
        tap_ok(c[0].cp[2].w == 0 && c[0].cp[3].w == 0.5f && c[1].cp[2].w == 0.5f && c[1].cp[3].w == 1,
               "splitdepth 1: two u ranges per piece");
        tap_ok(near3(&c[3].cp[3], 9, 1, 0), "last piece ends at (p2 + 4 p3 + p4) / 6");
    }
    cv_scene_destroy(&s);
    s = load("WorldBegin\nShape \"curve\" \"integer degree\" 2 \"point3 P\" [0 0 0 3 3 0 6 0 0 9 9 0 12 0 0]"
             " \"integer splitdepth\" 0\n",
             &err);
    if (tap_ok(s && s->n_curves == 2, "quadratic Bezier of 5 points: 2 pieces (%u)", s ? s->n_curves : 0))
        tap_ok(near3(&s->curves[0].cp[1], 2, 2, 0) && near3(&s->curves[0].cp[2], 4, 2, 0) &&
                   near3(&s->curves[1].cp[0], 6, 0, 0),
               "quadratic raised to cubic");
    cv_scene_destroy(&s);
    static const struct {
        const char *text, *expect;
    } bad[] = {
        {"Shape \"curve\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0 4 0 0]", "the degree 3 Bezier basis needs 4 + n * 3"},
        {"Shape \"curve\" \"integer degree\" 4 \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]", "degree 4"},
        {"Shape \"curve\" \"string basis\" \"catmull\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]", "basis \"catmull\""},
        {"Shape \"curve\" \"string type\" \"ribbon\" \"point3 P\" [0 0 0 1 0 0 2 0 0 3 0 0]", "ribbon curves need 2 normals"},
    };
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); i++) {
        char text[512];
        snprintf(text, sizeof(text), "WorldBegin\n%s\n", bad[i].text);
        struct cv_error e = {{0}};
        s = load(text, &e);
        tap_ok(!s && strstr(e.msg, bad[i].expect) && strstr(e.msg, ":2:1: curve:"), "error: %s", e.msg);
        cv_scene_destroy(&s);
    }
}

/* ---- curves inside ObjectBegin, instanced ---- */
static const char *const tuft_shapes =
    "Translate 0.1 0 0.2\n"
    "Shape \"curve\" \"string type\" \"flat\" \"point3 P\" [0 0 0 0.3 0.5 0.1 -0.2 1 0 0.1 1.5 0.2]"
    " \"float width0\" 0.2 \"float width1\" 0.1\n"
    "ReverseOrientation\n"
    "Shape \"curve\" \"string type\" \"ribbon\" \"integer degree\" 2 \"point3 P\" [0.5 0 0 0.6 0.7 0.2 0.4 1.4 0]"
    " \"normal N\" [0 0 1 0.5 0.2 1] \"float width\" 0.15 \"integer splitdepth\" 2\n"
    "Shape \"curve\" \"string type\" \"cylinder\" \"string basis\" \"bspline\""
    " \"point3 P\" [-0.5 0 0 -0.4 0.4 0.1 -0.6 0.8 0 -0.5 1.2 -0.1 -0.4 1.6 0] \"float width\" 0.1\n";
static const char *const tuft_places[] = {
    "Translate 1 2 3\nRotate 30 1 1 0\nScale 2 2 2\n",
    "Translate -2 0 1\nScale -1 1 1\n",
    "Rotate 90 0 0 1\nScale 1 3 1\n",
};

/* Curve c of scene s as the tree sees it: control point v (or a ribbon
 * normal's direction, with normal) carried out of the curve's own object
 * space where it keeps one. */
static cv_vec4 placed(const struct cv_scene *s, const CvCurve *c, const cv_vec4 *v, bool normal)
{
    uint32_t xf = c->info.y >> CV_CURVE_XF_SHIFT;
    if (!xf)
        return *v;
    const CvCurveXform *x = &s->curve_xforms[xf - 1];
    double o[3];
    for (int r = 0; r < 3; r++)
        o[r] = normal ? (&x->to_object[0].x)[r] * v->x + (&x->to_object[1].x)[r] * v->y +
                            (&x->to_object[2].x)[r] * v->z
                      : x->to_world[r].x * v->x + x->to_world[r].y * v->y + x->to_world[r].z * v->z +
                            x->to_world[r].w;
    double l = normal ? sqrt(o[0] * o[0] + o[1] * o[1] + o[2] * o[2]) : 1;
    return (cv_vec4){(float)(o[0] / l), (float)(o[1] / l), (float)(o[2] / l), v->w};
}

/* Curves a of scene sa and b of sb are the same shape in the tree's
 * space. Widths and the ribbon's angle are compared as stored: the
 * definition's own transform (tuft_shapes) is a translation, so an
 * instance's curve and its written-out twin keep them in spaces of the
 * same scale. */
static bool near_curve(const struct cv_scene *sa, const CvCurve *a, const struct cv_scene *sb, const CvCurve *b)
{
    for (int k = 0; k < 4; k++) {
        cv_vec4 p = placed(sa, a, &a->cp[k], false), q = placed(sb, b, &b->cp[k], false);
        if (!near3(&p, q.x, q.y, q.z) || fabsf(a->cp[k].w - b->cp[k].w) > 1e-5f)
            return false;
    }
    bool ribbon = (a->info.y & CV_CURVE_TYPE_MASK) == CV_CURVE_RIBBON;
    cv_vec4 n0a = a->n0, n0b = b->n0, n1a = a->n1, n1b = b->n1; /* unused but for ribbons */
    if (ribbon) {
        n0a = placed(sa, a, &a->n0, true);
        n0b = placed(sb, b, &b->n0, true);
        n1a = placed(sa, a, &a->n1, true);
        n1b = placed(sb, b, &b->n1, true);
    }
    return near3(&n0a, n0b.x, n0b.y, n0b.z) && near3(&n1a, n1b.x, n1b.y, n1b.z) &&
           fabsf(a->n0.w - b->n0.w) < 1e-5f && fabsf(a->n1.w - b->n1.w) < 1e-3f * fabsf(b->n1.w) + 1e-6f &&
           a->info.x == b->info.x && (a->info.y & CV_CURVE_TYPE_MASK) == (b->info.y & CV_CURVE_TYPE_MASK) &&
           (a->info.y >> CV_CURVE_XF_SHIFT != 0) == (b->info.y >> CV_CURVE_XF_SHIFT != 0);
}

static void test_instance(struct cv_gpu *gpu)
{
    char inst[4096], flat[4096];
    size_t li = (size_t)snprintf(inst, sizeof(inst), "WorldBegin\nObjectBegin \"tuft\"\n%sObjectEnd\n", tuft_shapes);
    size_t lf = (size_t)snprintf(flat, sizeof(flat), "WorldBegin\n");
    for (int k = 0; k < 3; k++) {
        li += (size_t)snprintf(inst + li, sizeof(inst) - li, "AttributeBegin\n%sObjectInstance \"tuft\"\nAttributeEnd\n",
                               tuft_places[k]);
        lf += (size_t)snprintf(flat + lf, sizeof(flat) - lf, "AttributeBegin\n%s%sAttributeEnd\n", tuft_places[k],
                               tuft_shapes);
    }
    struct cv_error err = {{0}};
    struct cv_scene *s = NULL, *f = NULL;
    struct cv_scene_load_params p = {.strict = true};
    bool ok = cv_scene_load_string("/tmp/inst.pbrt", inst, li, &p, &s, &err);
    ok = ok && cv_scene_load_string("/tmp/flat.pbrt", flat, lf, &p, &f, &err);
    if (!tap_ok(ok && s->n_curves > 0 && s->n_curves == f->n_curves && s->warnings == 0,
                "three instances of a curve object load in strict mode: as many curves as written out (%u, %u)%s%s",
                s ? s->n_curves : 0, f ? f->n_curves : 0, ok ? "" : ": ", ok ? "" : err.msg)) {
        cv_scene_destroy(&s);
        cv_scene_destroy(&f);
        return;
    }
    uint32_t same = 0, one_object = 0, kept = 0;
    for (uint32_t i = 0; i < s->n_curves; i++) {
        same += near_curve(s, &s->curves[i], f, &f->curves[i]);
        kept += (s->curves[i].info.y >> CV_CURVE_XF_SHIFT) != 0;
        one_object += s->curves[i].info.z == s->curves[0].info.z;
    }
    tap_ok(same == s->n_curves, "instanced curves equal the curves written under each instance's transform: points, "
           "widths, ribbon normals, type, material word with ReverseOrientation and the mirror (%u of %u)",
           same, s->n_curves);
    tap_ok(kept == s->n_curves / 3, "the instance under Scale 1 3 1 keeps its curves in object space, the others "
           "not (%u of %u)", kept, s->n_curves);
    tap_ok(one_object == s->n_curves && strcmp(s->object_names[s->curves[0].info.z], "tuft") == 0,
           "every instance's curves are the ID-matte object \"tuft\"");
    /* walk against brute force over the instanced curves */
    uint32_t n = 2048;
    float *rays = calloc((size_t)n * 8, sizeof(float));
    for (uint32_t i = 0; i < n; i++) {
        const CvCurve *c = &s->curves[(uint32_t)(rnd() * s->n_curves) % s->n_curves];
        double o[3] = {rnd() * 16 - 8, rnd() * 16 - 8, rnd() * 16 - 8}, d[3];
        for (int k = 0; k < 3; k++)
            d[k] = i % 4 == 3 ? rnd() - 0.5 : (&c->cp[1].x)[k] + (rnd() - 0.5) * 0.3 - o[k];
        set_ray(rays + 8 * i, o, d, i % 5 == 0 ? 0.3 : 0, i % 7 == 0 ? 0.6 : 1e30);
    }
    struct run r = {0};
    if (tap_ok(trace(gpu, s, rays, n, &r, &err), "GPU run: %s", err.msg)) {
        uint32_t hits = 0, diff = 0, any_diff = 0;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t *o = r.out + 16 * i;
            hits += o[1] != 0xffffffffu;
            diff += memcmp(o, o + 4, 16) != 0;
            any_diff += o[8] != o[9] || o[8] != (o[5] != 0xffffffffu);
        }
        tap_ok(hits > n / 8 && diff == 0 && any_diff == 0,
               "instanced curves: the walk equals the brute force (%u hits of %u; %u differ, any-hit %u)", hits, n,
               diff, any_diff);
        free(r.out);
    }
    free(rays);
    cv_scene_destroy(&s);
    cv_scene_destroy(&f);
}

int main(void)
{
    test_conversions();
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    test_straight(gpu, 1);
    test_straight(gpu, 3);
    test_random(gpu, false);
    test_random(gpu, true);
    test_instance(gpu);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
