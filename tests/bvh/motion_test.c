/* motion_test.c: moving shapes from the scene file to the GPU hit
 * (src/scene/animated.c, src/bvh/motion_bvh.c, glsl/bvh/motion.glsl):
 * - the walk through the top tree and the shapes' trees equals the brute
 *   force over every moving triangle, bit for bit (t, triangle,
 *   barycentrics; any-hit too), at several times over the motion and
 *   before and after it, for rays aimed at where the shapes are at that
 *   time and rays at random;
 * - each hit lies on its triangle as the host's pbrt-v4 interpolation
 *   (cv_animated_at, in double) places it at that time: the point the
 *   barycentrics give is the point o + t d, so the shader's transform is
 *   the host's (a rotation slerped, not vertices lerped);
 * - rays aimed at a shape's place at one time miss it at another;
 * - moving curves (shapes, and instances of curve objects, beside moving
 *   triangles): the walk equals the brute force bit for bit, and each
 *   curve hit lies within half the width of its curve as the host's
 *   interpolation places it at that time.
 * Fixed seeds. */
#include "config.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bvh/curve_bvh.h"
#include "bvh/motion_bvh.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/scene.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"

/* the moving shapes: 0 an instanced box, 1 a sphere, 2 a cylinder */
#define MOTION_N 12
#define MOTION_SHAPE(k) ((k) == 1 ? 1 : (k) % 2 == 0 ? 0 : 2)
static uint64_t rng = 0x9e3779b97f4a7c15ull;
static double rnd(void)
{
    return cv_test_xorshift64(&rng);
}

static float fbits(uint32_t u)
{
    float f;
    memcpy(&f, &u, 4);
    return f;
}

/* 12 words per ray: (t, prim, b1, b2) of the walk, of the brute force,
 * then (any walk, any brute, -, -), from motion_test.comp's four
 * programs */
static uint32_t *trace(struct cv_gpu *gpu, const struct cv_scene *s, const float *rays, uint32_t n,
                       float time, struct cv_error *err)
{
    size_t n4, nc4 = 0;
    float *packed = cv_motion_bvh_pack(s, &n4);
    GLuint mb = cv_buffer_create(n4 * 16, packed, "motion", err);
    free(packed);
    GLuint mt = mb ? cv_buffer_texture(mb, GL_RGBA32F, n4, err) : 0;
    /* the curves' buffer, moving shapes' curves in it, where there are any */
    GLuint cb = 0, ct = 0;
    if (s->n_curves) {
        float *c4 =
            cv_curve_bvh_pack(s->curves, s->n_curves, s->curve_xforms, s->n_curve_xforms, s->n_motions, &nc4);
        cb = cv_buffer_create(nc4 * 16, c4, "curves", err);
        free(c4);
        ct = cb ? cv_buffer_texture(cb, GL_RGBA32F, nc4, err) : 0;
        if (!ct)
            mt = 0;
    }
    GLuint rb = mt ? cv_buffer_create((size_t)n * 32, rays, "rays", err) : 0;
    GLuint ob = rb ? cv_buffer_create((size_t)n * 16, NULL, "results", err) : 0;
    uint32_t *out = ob ? calloc((size_t)n * 12, sizeof(uint32_t)) : NULL, *one = malloc((size_t)n * 16);
    for (int q = 0; q < 4 && out; q++) {
        char def[32];
        snprintf(def, sizeof(def), "MOTION_QUERY=%d", q);
        const char *defs[] = {def, s->n_curves ? "CV_HAS_CURVES" : NULL, NULL};
        struct cv_program *p = cv_program_get(gpu, "bvh/motion_test.comp", defs, err);
        if (!p) {
            free(out);
            out = NULL;
            break;
        }
        glBindTextureUnit(CV_TEXUNIT_MOTION, mt);
        if (ct)
            glBindTextureUnit(CV_TEXUNIT_CURVES, ct);
        cv_buffer_bind(rb, CV_BIND_PROBE_IN);
        cv_buffer_bind(ob, CV_BIND_PROBE_OUT);
        glProgramUniform1ui(p->id, glGetUniformLocation(p->id, "u_n_rays"), n);
        glProgramUniform1f(p->id, glGetUniformLocation(p->id, "u_time"), time);
        cv_program_dispatch_1d(p, n);
        if (!cv_buffer_read(ob, 0, (size_t)n * 16, one, err)) {
            free(out);
            out = NULL;
            break;
        }
        for (uint32_t i = 0; i < n; i++) {
            if (q < 2)
                memcpy(out + 12 * i + 4 * q, one + 4 * i, 16);
            else
                out[12 * i + 8 + (q - 2)] = one[4 * i + 1];
        }
    }
    free(one);
    if (mt)
        glDeleteTextures(1, &mt);
    if (ct)
        glDeleteTextures(1, &ct);
    cv_buffer_destroy(&cb);
    cv_buffer_destroy(&mb);
    cv_buffer_destroy(&rb);
    cv_buffer_destroy(&ob);
    return out;
}

static void apply(const double m[3][4], const double p[3], double out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2] + m[r][3];
}

/* the moving shape that triangle prim belongs to */
static const struct cv_motion *motion_of(const struct cv_scene *s, uint32_t prim)
{
    for (uint32_t g = 0; g < s->n_motions; g++)
        if (prim >= s->motions[g].first && prim < s->motions[g].first + s->motions[g].count)
            return &s->motions[g];
    return NULL;
}

/* A scene of moving shapes: a sphere, cylinders and instanced boxes under
 * random translations, large turns about random axes and scales between
 * TransformTimes 0 1, and a static floor. One sphere (16128 triangles):
 * llvmpipe ends a loop after 65535 turns, which the brute force over
 * several would pass. */
/* Ray i of a batch for trace(): origin o, direction d; every fifth ray
 * starts past 0 and every seventh ends short, so the walks' t ranges are
 * checked too. */
static void put_ray(float *rays, uint32_t i, const double o[3], const double d[3])
{
    float *r = rays + 8 * i;
    for (int k = 0; k < 3; k++) {
        r[k] = (float)o[k];
        r[4 + k] = (float)d[k];
    }
    r[3] = i % 5 == 0 ? 0.3f : 0.0f;
    r[7] = i % 7 == 0 ? 0.6f : 1e30f;
}

/* How trace()'s walks compared with its brute force over a batch. */
struct agreement {
    uint32_t diff;       /* closest hits that differ */
    uint32_t any_diff;   /* any-hit answers that differ */
    uint32_t any_wrong;  /* any-hit answers against the closest hit's */
    uint32_t total;
};

/* Counts ray i's record h (trace(): walk, brute force, any-hit pair). */
static void agree(struct agreement *a, const uint32_t *h, float time, uint32_t i)
{
    a->total++;
    if (memcmp(h, h + 4, 16) != 0) {
        if (a->diff < 3)
            tap_diag("time %g ray %u: walk t %.9g prim %x, brute t %.9g prim %x", time, i, fbits(h[0]), h[1],
                     fbits(h[4]), h[5]);
        a->diff++;
    }
    if (h[8] != h[9])
        a->any_diff++;
    if (h[8] != (h[5] != 0xffffffffu))
        a->any_wrong++;
}

static struct cv_scene *make_scene(double centres[][3], int *n_centres)
{
    size_t cap = 1 << 16, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len,
                            "WorldBegin\nShape \"trianglemesh\" \"point3 P\" [-20 -5 -20 20 -5 -20 20 -5 20 -20 -5 20]"
                            " \"integer indices\" [0 1 2 0 2 3]\n"
                            "ObjectBegin \"box\"\nShape \"trianglemesh\" \"point3 P\" [-1 -0.3 -0.2 1 -0.3 -0.2 1 0.3 -0.2"
                            " -1 0.3 -0.2 -1 -0.3 0.2 1 -0.3 0.2 1 0.3 0.2 -1 0.3 0.2] \"integer indices\" [0 1 2 0 2 3 "
                            "4 6 5 4 7 6 0 4 5 0 5 1 3 2 6 3 6 7 0 3 7 0 7 4 1 5 6 1 6 2]\nObjectEnd\n");
    int n = 0;
    for (int k = 0; k < MOTION_N; k++) {
        double c[3] = {rnd() * 12 - 6, rnd() * 6 - 3, rnd() * 12 - 6};
        memcpy(centres[n++], c, sizeof(c));
        len += (size_t)snprintf(text + len, cap - len,
                                "AttributeBegin\nTranslate %.4f %.4f %.4f\nActiveTransform EndTime\n"
                                "Translate %.4f %.4f %.4f\nRotate %.2f %.3f %.3f %.3f\nScale %.3f %.3f %.3f\n"
                                "ActiveTransform All\n%s\nAttributeEnd\n",
                                c[0], c[1], c[2], rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 2 - 1, rnd() * 340 - 170,
                                rnd() - 0.5, rnd() - 0.5, rnd() - 0.5, 0.6 + rnd(), 0.6 + rnd(), 0.6 + rnd(),
                                MOTION_SHAPE(k) == 0 ? "ObjectInstance \"box\""
                                : MOTION_SHAPE(k) == 1 ? "Shape \"sphere\" \"float radius\" 0.8"
                                             : "Shape \"cylinder\" \"float radius\" 0.4 \"float zmin\" -1 "
                                               "\"float zmax\" 1");
    }
    *n_centres = n;
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params p = {.strict = true};
    if (!cv_scene_load_string("/tmp/motion_test.pbrt", text, len, &p, &s, &err))
        tap_diag("load: %s", err.msg);
    free(text);
    return s;
}

static void test_walk(struct cv_gpu *gpu)
{
    double centres[16][3];
    int n_c = 0;
    struct cv_scene *s = make_scene(centres, &n_c);
    if (!tap_ok(s && s->n_motions == MOTION_N && cv_scene_static_triangles(s) == 2 && s->warnings == 0,
                "12 moving shapes load in strict mode after 2 static triangles (%u)", s ? s->n_motions : 0)) {
        cv_scene_destroy(&s);
        return;
    }
    static const float times[] = {0.0f, 0.3f, 0.5f, 0.77f, 1.0f, -0.5f, 1.5f};
    uint32_t n = 1024;
    float *rays = calloc((size_t)n * 8, sizeof(float));
    struct agreement a = {0};
    uint32_t hits = 0, off_plane = 0;
    double worst = 0;
    for (size_t ti = 0; ti < sizeof(times) / sizeof(times[0]); ti++) {
        float time = times[ti];
        for (uint32_t i = 0; i < n; i++) {
            double o[3] = {rnd() * 30 - 15, rnd() * 10 + 6, rnd() * 30 - 15}, d[3];
            if (i % 4 != 3) {
                /* at the centre of a shape where it is at this time, jittered */
                const struct cv_motion *m = &s->motions[i % s->n_motions];
                double mt[3][4], zero[3] = {0, 0, 0}, c[3];
                cv_animated_at(&m->xf, time, mt);
                apply(mt, zero, c);
                for (int k = 0; k < 3; k++)
                    d[k] = c[k] + (rnd() - 0.5) * 1.6 - o[k];
            } else {
                for (int k = 0; k < 3; k++)
                    d[k] = rnd() - 0.5;
            }
            put_ray(rays, i, o, d);
        }
        struct cv_error err = {{0}};
        uint32_t *out = trace(gpu, s, rays, n, time, &err);
        if (!tap_ok(out != NULL, "GPU run at time %g: %s", time, err.msg))
            break;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t *w = out + 12 * i;
            agree(&a, w, time, i);
            if (w[1] == 0xffffffffu)
                continue;
            hits++;
            /* the hit against the host's transform at this time */
            const struct cv_motion *m = motion_of(s, w[1]);
            if (!m) {
                off_plane++;
                continue;
            }
            double mt[3][4], P[3][3], b1 = fbits(w[2]), b2 = fbits(w[3]), t = fbits(w[0]);
            cv_animated_at(&m->xf, time, mt);
            const CvTriangle *tri = &s->triangles[w[1]];
            const uint32_t idx[3] = {tri->idx.x, tri->idx.y, tri->idx.z};
            for (int k = 0; k < 3; k++) {
                const cv_vec4 *v = &s->vertices[idx[k]].pos_u;
                double p[3] = {v->x, v->y, v->z};
                apply(mt, p, P[k]);
            }
            const float *r = rays + 8 * i;
            double e = 0;
            for (int k = 0; k < 3; k++) {
                double bary = (1 - b1 - b2) * P[0][k] + b1 * P[1][k] + b2 * P[2][k];
                e = fmax(e, fabs(bary - (r[k] + t * r[4 + k])));
            }
            worst = fmax(worst, e);
            if (e > 1e-3)
                off_plane++;
        }
        free(out);
    }
    tap_ok(hits > a.total / 4, "rays hit the moving shapes (%u of %u)", hits, a.total);
    tap_ok(a.diff == 0, "closest hit through the trees equals the brute force at 7 times (%u of %u differ)", a.diff,
           a.total);
    tap_ok(a.any_diff == 0 && a.any_wrong == 0,
           "any-hit through the trees equals the brute force (%u differ) and the closest query (%u differ)",
           a.any_diff, a.any_wrong);
    tap_ok(off_plane == 0, "every hit lies where pbrt-v4's interpolation puts its triangle (%u off, worst %.2g)",
           off_plane, worst);
    free(rays);
    cv_scene_destroy(&s);
}

/* A bar 2 long turning 90 degrees about z: at time 0.5 it lies at 45
 * degrees and is still 2 long (slerp), where its vertices lerped would
 * make it 1.41 long; a ray down -z at 1.9 along the diagonal hits it, one
 * at its place at time 0 misses it. */
static void test_arc(struct cv_gpu *gpu)
{
    const char *text = "WorldBegin\nActiveTransform EndTime\nRotate 90 0 0 1\nActiveTransform All\n"
                       "Shape \"trianglemesh\" \"point3 P\" [0 -0.05 0 2 -0.05 0 2 0.05 0 0 0.05 0]"
                       " \"integer indices\" [0 1 2 0 2 3]\n";
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params p = {.strict = true};
    if (!tap_ok(cv_scene_load_string("/tmp/arc.pbrt", text, strlen(text), &p, &s, &err) && s->n_motions == 1,
                "a turning bar loads: %s", err.msg)) {
        cv_scene_destroy(&s);
        return;
    }
    float rays[16] = {1.3435029f, 1.3435029f, 1, 0, 0, 0, -1, 1e30f, 1.5f, 0, 1, 0, 0, 0, -1, 1e30f};
    uint32_t *out = trace(gpu, s, rays, 2, 0.5f, &err);
    if (tap_ok(out != NULL, "GPU run: %s", err.msg))
        tap_ok(out[1] != 0xffffffffu && fabsf(fbits(out[0]) - 1) < 1e-5f && out[13] == 0xffffffffu,
               "at half time the bar lies on the arc, full length (hit at 1.9: t %g), not where it was "
               "(%s)", fbits(out[0]), out[13] == 0xffffffffu ? "missed" : "hit");
    free(out);
    cv_scene_destroy(&s);
}

/* The same bar as an object instance turning 90 degrees about z, with the
 * camera at (4, 0, 5): pbrt-v4 interpolates render-from-instance, the
 * instance's transform conjugated by the camera's position, so at half
 * time the instance's point (4, 0, 5) lies halfway along the chord from
 * (4, 0, 5) to (0, 4, 5), and the bar, still at 45 degrees, runs from
 * (2, 2) - (2.83, 2.83) to 2 further along: through (-0.4, -0.4), not
 * through (1.3, 1.3) where a turn about the origin puts it. */
static void test_pivot(struct cv_gpu *gpu)
{
    const char *text = "LookAt 4 0 5  0 0 0  0 1 0\nCamera \"perspective\"\nWorldBegin\n"
                       "ObjectBegin \"bar\"\nShape \"trianglemesh\" \"point3 P\" [0 -0.05 0 2 -0.05 0 2 0.05 0 0 0.05 0]"
                       " \"integer indices\" [0 1 2 0 2 3]\nObjectEnd\n"
                       "ActiveTransform EndTime\nRotate 90 0 0 1\nActiveTransform All\nObjectInstance \"bar\"\n";
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params p = {.strict = true};
    if (!tap_ok(cv_scene_load_string("/tmp/pivot.pbrt", text, strlen(text), &p, &s, &err) && s->n_motions == 1,
                "a turning instance loads: %s", err.msg)) {
        cv_scene_destroy(&s);
        return;
    }
    float rays[16] = {-0.4f, -0.4f, 1, 0, 0, 0, -1, 1e30f, 1.3f, 1.3f, 1, 0, 0, 0, -1, 1e30f};
    uint32_t *out = trace(gpu, s, rays, 2, 0.5f, &err);
    if (tap_ok(out != NULL, "GPU run: %s", err.msg))
        tap_ok(out[1] != 0xffffffffu && fabsf(fbits(out[0]) - 1) < 1e-5f && out[13] == 0xffffffffu,
               "at half time the instance has turned about the camera's position (hit at (-0.4, -0.4): t %g), "
               "not about its origin (%s at (1.3, 1.3))", fbits(out[0]), out[13] == 0xffffffffu ? "missed" : "hit");
    free(out);
    cv_scene_destroy(&s);
}

/* A random strand of `type` (bspline, 7 points) near the origin. */
static size_t strand(char *text, size_t cap, const char *type)
{
    size_t len = (size_t)snprintf(text, cap,
                                  "Shape \"curve\" \"string type\" \"%s\" \"string basis\" \"bspline\""
                                  " \"float width0\" %.3f \"float width1\" %.3f \"point3 P\" [",
                                  type, 0.15 + 0.2 * rnd(), 0.05 + 0.1 * rnd());
    double p[3] = {0, -0.9, 0};
    for (int k = 0; k < 7; k++) {
        for (int c = 0; c < 3; c++)
            p[c] += c == 1 ? 0.3 : rnd() * 0.6 - 0.3;
        len += (size_t)snprintf(text + len, cap - len, " %.4f %.4f %.4f", p[0], p[1], p[2]);
    }
    len += (size_t)snprintf(text + len, cap - len, " ]");
    if (strcmp(type, "ribbon") == 0)
        len += (size_t)snprintf(text + len, cap - len, " \"normal N\" [0 0 1 0.3 0 1 -0.2 0.1 1 0 0.4 1 0.5 0 1]");
    return len + (size_t)snprintf(text + len, cap - len, "\n");
}

static void bezier(const CvCurve *c, double u, double out[3])
{
    for (int a = 0; a < 3; a++) {
        double p[4] = {(&c->cp[0].x)[a], (&c->cp[1].x)[a], (&c->cp[2].x)[a], (&c->cp[3].x)[a]};
        double q0 = p[0] + u * (p[1] - p[0]), q1 = p[1] + u * (p[2] - p[1]), q2 = p[2] + u * (p[3] - p[2]);
        double r0 = q0 + u * (q1 - q0), r1 = q1 + u * (q2 - q1);
        out[a] = r0 + u * (r1 - r0);
    }
}

/* Point x of curve c's own object space (CvCurveXform) in its shape's
 * object space (dir 0), or back (dir 1); as it is for curves without. */
static void curve_space(const struct cv_scene *s, const CvCurve *c, int dir, double x[3])
{
    uint32_t xf = c->info.y >> CV_CURVE_XF_SHIFT;
    if (!xf)
        return;
    const cv_vec4 *m = dir ? s->curve_xforms[xf - 1].to_object : s->curve_xforms[xf - 1].to_world;
    double y[3];
    for (int r = 0; r < 3; r++)
        y[r] = m[r].x * x[0] + m[r].y * x[1] + m[r].z * x[2] + m[r].w;
    memcpy(x, y, sizeof(y));
}

/* Moving curves: strands of each type as moving shapes and a moving
 * instance of a curve object, beside a moving triangle shape. The
 * object's cylinder and ribbon strands are under a non-uniform scale and a
 * shear of their own, so they stay in their object space within the
 * instance's. */
static void test_curves(struct cv_gpu *gpu)
{
    static const char *const types[] = {"flat", "cylinder", "ribbon"};
    size_t cap = 1 << 16, len = 0;
    char *text = malloc(cap);
    len += (size_t)snprintf(text + len, cap - len, "WorldBegin\nObjectBegin \"tuft\"\n");
    for (int k = 0; k < 3; k++) {
        if (k)
            len += (size_t)snprintf(text + len, cap - len, "AttributeBegin\n%s\n",
                                    k == 1 ? "Scale 1 1.5 0.6"
                                           : "ConcatTransform [1 0.3 0 0  0 1 0 0  0.4 0 0.8 0  0 0 0 1]");
        len += strand(text + len, cap - len, types[k]);
        if (k)
            len += (size_t)snprintf(text + len, cap - len, "AttributeEnd\n");
    }
    len += (size_t)snprintf(text + len, cap - len, "ObjectEnd\n");
    for (int k = 0; k < 9; k++) {
        len += (size_t)snprintf(text + len, cap - len,
                                "AttributeBegin\nTranslate %.4f %.4f %.4f\nActiveTransform EndTime\n"
                                "Translate %.4f %.4f %.4f\nRotate %.2f %.3f %.3f %.3f\nScale %.3f %.3f %.3f\n"
                                "ActiveTransform All\n",
                                rnd() * 8 - 4, rnd() * 2 - 1, rnd() * 8 - 4, rnd() - 0.5, rnd() - 0.5, rnd() - 0.5,
                                rnd() * 200 - 100, rnd() - 0.5, rnd() - 0.5, rnd() - 0.5, 0.7 + rnd() * 0.6,
                                0.7 + rnd() * 0.6, 0.7 + rnd() * 0.6);
        if (k % 3 == 2)
            len += (size_t)snprintf(text + len, cap - len, "ObjectInstance \"tuft\"\n");
        else if (k == 4)
            len += (size_t)snprintf(text + len, cap - len, "Shape \"sphere\" \"float radius\" 0.5\n");
        else
            len += strand(text + len, cap - len, types[k % 3]);
        len += (size_t)snprintf(text + len, cap - len, "AttributeEnd\n");
    }
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params p = {.strict = true};
    bool loaded = cv_scene_load_string("/tmp/motion_curves.pbrt", text, len, &p, &s, &err);
    free(text);
    if (!tap_ok(loaded && s->n_motions == 9 && s->n_curves > 0 && s->warnings == 0,
                "moving curves and moving instances of a curve object load in strict mode (%u shapes): %s",
                loaded ? s->n_motions : 0, err.msg)) {
        cv_scene_destroy(&s);
        return;
    }
    size_t nc4;
    float *c4 = cv_curve_bvh_pack(s->curves, s->n_curves, s->curve_xforms, s->n_curve_xforms, s->n_motions,
                                  &nc4);
    uint32_t curve_base;
    memcpy(&curve_base, &c4[2], 4);
    static const float times[] = {0.0f, 0.25f, 0.5f, 0.9f, 1.0f, -1.0f, 2.0f};
    uint32_t n = 1024;
    float *rays = calloc((size_t)n * 8, sizeof(float));
    struct agreement a = {0};
    uint32_t curve_hits = 0, off = 0;
    double worst = 0;
    for (size_t ti = 0; ti < sizeof(times) / sizeof(times[0]); ti++) {
        float time = times[ti];
        for (uint32_t i = 0; i < n; i++) {
            double o[3] = {rnd() * 20 - 10, rnd() * 6 + 4, rnd() * 20 - 10}, d[3];
            /* at a point of a curve where its shape puts it at this time,
             * jittered by about a width; some rays at random */
            const CvCurve *c = &s->curves[(uint32_t)(rnd() * s->n_curves) % s->n_curves];
            double mt[3][4], x[3], w[3];
            cv_animated_at(&s->motions[c->info.w - 1].xf, time, mt);
            bezier(c, rnd(), x);
            curve_space(s, c, 0, x);
            apply(mt, x, w);
            for (int k = 0; k < 3; k++)
                d[k] = i % 4 == 3 ? rnd() - 0.5 : w[k] + (rnd() - 0.5) * 0.3 - o[k];
            put_ray(rays, i, o, d);
        }
        uint32_t *out = trace(gpu, s, rays, n, time, &err);
        if (!tap_ok(out != NULL, "GPU run with curves at time %g: %s", time, err.msg))
            break;
        for (uint32_t i = 0; i < n; i++) {
            const uint32_t *h = out + 12 * i;
            agree(&a, h, time, i);
            if (h[1] == 0xffffffffu || (h[1] & CV_PRIM_CURVE) == 0)
                continue;
            curve_hits++;
            /* the hit, carried back into its curve's object space by the
             * host's transform at this time, lies within half the width
             * of the curve's point at the hit's u */
            CvCurve c;
            memcpy(&c, c4 + 4 * (curve_base + 7 * (size_t)(h[1] & ~CV_PRIM_CURVE)), sizeof(c));
            double mt[3][4], P[3], x[3];
            cv_animated_at(&s->motions[c.info.w - 1].xf, time, mt);
            const float *r = rays + 8 * i;
            double t = fbits(h[0]), u = fbits(h[2]);
            for (int k = 0; k < 3; k++)
                P[k] = r[k] + t * r[4 + k] - mt[k][3];
            /* P = A x: solve by Cramer's rule */
            double det = mt[0][0] * (mt[1][1] * mt[2][2] - mt[1][2] * mt[2][1]) -
                         mt[0][1] * (mt[1][0] * mt[2][2] - mt[1][2] * mt[2][0]) +
                         mt[0][2] * (mt[1][0] * mt[2][1] - mt[1][1] * mt[2][0]);
            for (int k = 0; k < 3; k++) {
                double A[3][3];
                for (int rr = 0; rr < 3; rr++)
                    for (int cc = 0; cc < 3; cc++)
                        A[rr][cc] = cc == k ? P[rr] : mt[rr][cc];
                x[k] = (A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                        A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                        A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0])) / det;
            }
            double axis[3], e = 0;
            curve_space(s, &c, 1, x);
            bezier(&c, u, axis);
            for (int k = 0; k < 3; k++)
                e += (x[k] - axis[k]) * (x[k] - axis[k]);
            double hw = 0.5 * (c.cp[0].w + u * (c.cp[1].w - c.cp[0].w));
            e = sqrt(e) / hw;
            worst = fmax(worst, e);
            if (e > 1.05)
                off++;
        }
        free(out);
    }
    tap_ok(curve_hits > a.total / 8, "rays hit the moving curves (%u of %u)", curve_hits, a.total);
    tap_ok(a.diff == 0, "closest hit through the trees equals the brute force, curves too (%u of %u differ)", a.diff,
           a.total);
    tap_ok(a.any_diff == 0 && a.any_wrong == 0,
           "any-hit with curves equals the brute force (%u differ) and the closest query (%u differ)", a.any_diff,
           a.any_wrong);
    uint32_t kept = 0;
    for (uint32_t i = 0; i < s->n_curves; i++)
        kept += (s->curves[i].info.y >> CV_CURVE_XF_SHIFT) != 0;
    tap_ok(kept > 0, "the instances' sheared and unevenly scaled strands stay in their object space (%u curves)",
           kept);
    tap_ok(off == 0, "every curve hit lies within half the width of its curve (in the curve's object space) where "
           "pbrt-v4's interpolation puts it (%u off; worst %.3g of the half width)", off, worst);
    free(c4);
    free(rays);
    cv_scene_destroy(&s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    test_arc(gpu);
    test_pivot(gpu);
    test_walk(gpu);
    test_curves(gpu);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
