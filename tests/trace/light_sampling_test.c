/* light_sampling_test.c: the shipped light-sampling GLSL against its pdfs.
 * 1-2. Environment maps (pbrt-v3 lat-long and pbrt-v4 equal-area, rotated):
 *      chi-square of sampled directions against cv_env_pdf over the sphere,
 *      sampled pdf / radiance equal cv_env_pdf / cv_env_Le, the pdf
 *      integrates to 1, and E[Le / pdf] matches the integral of Le.
 * 3.   A constant environment, an area triangle, a point and a spot light
 *      picked by a power CDF: the non-delta samples' histogram against the
 *      mixture pdf (environment from cv_env_pdf, triangle from a CPU ray
 *      cast), sampled area pdfs equal cv_light_pdf_area, delta lights picked
 *      with their probability and with radiance I / d^2 (spot: smoothstep).
 * Fixed seeds; alpha 0.01 with Šidák correction over the chi-square runs. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/envmap.h"
#include "glsl/shared/scene.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/trace/bsdf_stats.h"
#include "trace/envmap_dist.h"

#define N 200000
#define N_CHI2 4

static uint16_t half_from_float(float f)
{
    union { float f; uint32_t u; } v = {f};
    uint32_t sign = (v.u >> 16) & 0x8000u;
    int32_t e = (int32_t)((v.u >> 23) & 0xff) - 127 + 15;
    uint32_t m = v.u & 0x7fffffu;
    if (e <= 0)
        return (uint16_t)sign;  /* tiny values flush to zero: fine for test images */
    if (e >= 31)
        return (uint16_t)(sign | 0x7c00u);
    return (uint16_t)(sign | ((uint32_t)e << 10) | ((m + 0x1000u) >> 13));
}

struct gpu_scene {
    GLuint lights, cdf, env, vertices, triangles, textures, texels, in, out;
    GLuint cdf_tex;  /* cdf as the kernels read it (CV_TEXUNIT_LIGHT_CDF) */
};

static void destroy_scene(struct gpu_scene *s)
{
    GLuint *b[] = {&s->lights, &s->cdf, &s->env, &s->vertices, &s->triangles, &s->textures, &s->texels,
                   &s->in, &s->out};
    for (size_t i = 0; i < CV_ARRAY_SIZE(b); i++)
        cv_buffer_destroy(b[i]);
    if (s->cdf_tex)
        glDeleteTextures(1, &s->cdf_tex);
    s->cdf_tex = 0;
}

static bool run(struct cv_program *prog, struct gpu_scene *s, unsigned mode, unsigned seed, const float p[3],
                unsigned light, const float n_light[3], const float *in, size_t n, float *out,
                struct cv_error *err)
{
    size_t out_floats = n * (mode == 0 ? 8 : 4);
    cv_buffer_destroy(&s->in);
    cv_buffer_destroy(&s->out);
    s->in = cv_buffer_create(in ? n * 16 : 16, in, "light probe in", err);
    s->out = cv_buffer_create(out_floats * sizeof(float), NULL, "light probe out", err);
    if (!s->in || !s->out)
        return false;
    cv_buffer_bind(s->vertices, CV_BIND_VERTICES);
    cv_buffer_bind(s->triangles, CV_BIND_TRIANGLES);
    cv_buffer_bind(s->textures, CV_BIND_TEXTURES);
    cv_buffer_bind(s->texels, CV_BIND_TEXELS);
    cv_buffer_bind(s->lights, CV_BIND_LIGHTS);
    if (!s->cdf_tex && !(s->cdf_tex = cv_buffer_texture(s->cdf, GL_R32F, 1, err)))
        return false;
    glBindTextureUnit(CV_TEXUNIT_LIGHT_CDF, s->cdf_tex);
    cv_buffer_bind(s->env, CV_BIND_ENV_DIST);
    cv_buffer_bind(s->in, CV_BIND_PROBE_IN);
    cv_buffer_bind(s->out, CV_BIND_PROBE_OUT);
    GLuint id = prog->id;
    glUseProgram(id);
    glUniform1ui(glGetUniformLocation(id, "u_mode"), mode);
    glUniform1ui(glGetUniformLocation(id, "u_count"), (GLuint)n);
    glUniform1ui(glGetUniformLocation(id, "u_seed"), seed);
    glUniform1ui(glGetUniformLocation(id, "u_light"), light);
    glUniform3f(glGetUniformLocation(id, "u_p"), p[0], p[1], p[2]);
    glUniform3f(glGetUniformLocation(id, "u_n_light"), n_light[0], n_light[1], n_light[2]);
    cv_program_dispatch_1d(prog, n);
    return cv_buffer_read(s->out, 0, out_floats * sizeof(float), out, err);
}

static CvLight light_init(unsigned type)
{
    CvLight l;
    memset(&l, 0, sizeof(l));
    l.type = type;
    l.tex = -1;
    l.to_light[0] = (cv_vec4){1, 0, 0, 0};
    l.to_light[1] = (cv_vec4){0, 1, 0, 0};
    l.to_light[2] = (cv_vec4){0, 0, 1, 0};
    return l;
}

/* Rotation rows: about x by a, then about z by b. */
static void rotation(CvLight *l, double a, double b)
{
    double ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b);
    /* R = Rz(b) * Rx(a) */
    double r[3][3] = {{cb, -sb * ca, sb * sa}, {sb, cb * ca, -cb * sa}, {0, sa, ca}};
    for (int i = 0; i < 3; i++)
        l->to_light[i] = (cv_vec4){(float)r[i][0], (float)r[i][1], (float)r[i][2], 0};
}

static void empty_geometry(struct gpu_scene *s, struct cv_error *err)
{
    CvVertex v[3];
    memset(v, 0, sizeof(v));
    CvTriangle t = {{0, 1, 2, 0}};
    s->vertices = cv_buffer_create(sizeof(v), v, "vertices", err);
    s->triangles = cv_buffer_create(sizeof(t), &t, "triangles", err);
}

/* Chi-square, consistency and integral checks of an environment map. */
static void env_test(struct cv_program *prog, bool equal_area, double alpha)
{
    struct cv_error err = {{0}};
    const char *nm = equal_area ? "equal-area map" : "lat-long map";
    uint32_t w = equal_area ? 32 : 48, h = equal_area ? 32 : 24;
    float *img = cv_xmalloc((size_t)w * h * 4 * sizeof(float));
    uint32_t *tex = cv_xmalloc((size_t)w * h * 2 * sizeof(uint32_t));
    for (uint32_t y = 0; y < h; y++)
        for (uint32_t x = 0; x < w; x++) {
            float *t = img + ((size_t)y * w + x) * 4;
            float base = 0.2f + 0.8f * (float)y / h + 0.3f * (float)x / w;
            bool spot = abs((int)x - (int)(w / 4)) <= 1 && abs((int)y - (int)(h / 3)) <= 1;
            bool black = x >= w / 2 && x < w / 2 + 3;  /* zero-radiance strip */
            t[0] = black ? 0 : base * (spot ? 40 : 1);
            t[1] = black ? 0 : base * 0.7f * (spot ? 30 : 1);
            t[2] = black ? 0 : base * 0.4f;
            t[3] = 1;
            uint16_t hs[4];
            for (int c = 0; c < 4; c++)
                hs[c] = half_from_float(t[c]);
            tex[2 * ((size_t)y * w + x)] = hs[0] | ((uint32_t)hs[1] << 16);
            tex[2 * ((size_t)y * w + x) + 1] = hs[2] | ((uint32_t)hs[3] << 16);
            /* the distribution is built from what the GPU will read */
            for (int c = 0; c < 3; c++) {
                uint16_t hv = hs[c];
                int e = (hv >> 10) & 31;
                t[c] = e ? ldexpf(1.0f + (hv & 1023) / 1024.0f, e - 15) : 0;
            }
        }
    size_t n_dist = cv_envmap_dist_floats(w, h);
    float *dist = cv_xmalloc(n_dist * sizeof(float));
    tap_ok(cv_envmap_dist_build(img, w, h, 4, equal_area, dist, &err), "%s: distribution built: %s", nm,
           err.msg);
    CvTexture tx;
    memset(&tx, 0, sizeof(tx));
    tx.type = CV_TEX_IMAGE;
    tx.flags = equal_area ? CV_TEXF_WRAP_OCTAHEDRAL : CV_TEXF_WRAP_LATLONG;   /* as the loader sets */
    tx.levels = 1;
    tx.width = w;
    tx.height = h;
    tx.tex_a = tx.tex_b = tx.amount_tex = -1;
    tx.scale = 1;
    tx.uv_map = (cv_vec4){1, 1, 0, 0};
    CvLight l = light_init(CV_LIGHT_INFINITE_MAP);
    l.flags = equal_area ? CV_LIGHTF_EQUAL_AREA : 0;
    l.tex = 0;
    l.prim = 0;
    l.L = (cv_vec4){2, 2, 2, 0};
    rotation(&l, 0.5, 0.3);
    float cdf = 1;
    struct gpu_scene s = {0};
    empty_geometry(&s, &err);
    s.lights = cv_buffer_create(sizeof(l), &l, "lights", &err);
    s.cdf = cv_buffer_create(sizeof(cdf), &cdf, "cdf", &err);
    s.env = cv_buffer_create(n_dist * sizeof(float), dist, "env dist", &err);
    s.textures = cv_buffer_create(sizeof(tx), &tx, "textures", &err);
    s.texels = cv_buffer_create((size_t)w * h * 8, tex, "texels", &err);

    float p[3] = {0, 0, 0}, nz[3] = {0, 0, 1};
    float *samples = cv_xmalloc((size_t)N * 8 * sizeof(float));
    float *dirs = cv_xmalloc((size_t)N * 4 * sizeof(float));
    float *eval = cv_xmalloc((size_t)N * 4 * sizeof(float));
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = cv_xmalloc(n_grid * 4 * sizeof(float));
    if (!tap_ok(run(prog, &s, 0, equal_area ? 7 : 8, p, 0, nz, NULL, N, samples, &err) &&
                    run(prog, &s, 1, 0, p, 0, nz, grid, n_grid, grid_out, &err),
                "%s: GPU runs: %s", nm, err.msg))
        goto done;
    for (size_t i = 0; i < N; i++)
        memcpy(dirs + 4 * i, samples + 8 * i, 4 * sizeof(float));
    if (!tap_ok(run(prog, &s, 1, 0, p, 0, nz, dirs, N, eval, &err), "%s: eval run: %s", nm, err.msg))
        goto done;
    double observed[CHI_CELLS] = {0}, cell[CHI_CELLS], est = 0;
    size_t failed = 0, bad_pdf = 0, bad_L = 0;
    for (size_t i = 0; i < N; i++) {
        const float *sm = samples + 8 * i, *e = eval + 4 * i;
        if (sm[3] <= 0) {
            failed++;
            continue;
        }
        observed[stats_cell(sm)] += 1;
        if (fabs(sm[3] - e[3]) > 1e-3 * sm[3])
            bad_pdf++;
        if (fabs(sm[4] - e[0]) > 1e-3 * fmax(e[0], 1e-3))
            bad_L++;
        est += sm[4] / sm[3];
    }
    est /= N;
    stats_integrate(grid_out + 3, 4, cell);
    double integral_L = 0;
    {
        double tmp[CHI_CELLS];
        stats_integrate(grid_out, 4, tmp);
        for (int i = 0; i < CHI_CELLS; i++)
            integral_L += tmp[i];
    }
    struct stats_chi2 r = stats_chi2_test(observed, cell, N);
    /* A sample on a map cell's edge may round into the neighbour cell when
     * mapped back (most often near the lat-long poles, where cells are
     * thin); allow 0.1 %. */
    tap_ok(bad_pdf <= N / 1000, "%s: sampled pdf equals cv_env_pdf (%zu of %d differ)", nm, bad_pdf, N);
    tap_ok(bad_L <= N / 5000, "%s: sampled radiance equals cv_env_Le (%zu differ)", nm, bad_L);
    /* the pdf is 0 only exactly at a lat-long pole (sin theta = 0) */
    tap_ok(failed <= N / 20000, "%s: sampling fails rarely (%zu)", nm, failed);
    tap_ok(fabs(r.total_expected - 1) < 0.01, "%s: pdf integrates to 1 (%.4f)", nm, r.total_expected);
    tap_ok(!r.zero_cell_hit, "%s: no samples where the pdf is 0", nm);
    tap_ok(fabs(est / integral_L - 1) < 0.01, "%s: E[Le/pdf] %.4f matches the integral of Le %.4f", nm, est,
           integral_L);
    tap_ok(r.p_value >= alpha, "%s: chi2 %.1f dof %d p %.3g", nm, r.chi2, r.dof, r.p_value);
done:
    free(img);
    free(tex);
    free(dist);
    free(samples);
    free(dirs);
    free(eval);
    free(grid);
    free(grid_out);
    destroy_scene(&s);
}

/* Ray from the origin along d against triangle (a, b, c): distance or -1. */
static double ray_tri(const double d[3], const double a[3], const double b[3], const double c[3])
{
    double e1[3], e2[3], pv[3], tv[3], qv[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = b[i] - a[i];
        e2[i] = c[i] - a[i];
        tv[i] = -a[i];
    }
    pv[0] = d[1] * e2[2] - d[2] * e2[1];
    pv[1] = d[2] * e2[0] - d[0] * e2[2];
    pv[2] = d[0] * e2[1] - d[1] * e2[0];
    double det = e1[0] * pv[0] + e1[1] * pv[1] + e1[2] * pv[2];
    if (fabs(det) < 1e-12)
        return -1;
    double u = (tv[0] * pv[0] + tv[1] * pv[1] + tv[2] * pv[2]) / det;
    if (u < 0 || u > 1)
        return -1;
    qv[0] = tv[1] * e1[2] - tv[2] * e1[1];
    qv[1] = tv[2] * e1[0] - tv[0] * e1[2];
    qv[2] = tv[0] * e1[1] - tv[1] * e1[0];
    double v = (d[0] * qv[0] + d[1] * qv[1] + d[2] * qv[2]) / det;
    if (v < 0 || u + v > 1)
        return -1;
    double t = (e2[0] * qv[0] + e2[1] * qv[1] + e2[2] * qv[2]) / det;
    return t > 0 ? t : -1;
}

/* pbrt-v4's SmoothStep, which a spot light's falloff is: a step where the
 * edges meet (conedeltaangle 0) */
static double pbrt_smoothstep(double a, double b, double x)
{
    if (a == b)
        return x < a ? 0 : 1;
    double t = fmin(fmax((x - a) / (b - a), 0), 1);
    return t * t * (3 - 2 * t);
}

/* cos_start: the spot's cos falloff start (0.9, its total width: a hard
 * edge) */
static void mixed_test(struct cv_program *prog, double alpha, float cos_start, const char *nm)
{
    struct cv_error err = {{0}};
    double A[3] = {-1, -0.5, 2}, B[3] = {1.5, -0.5, 2.5}, C[3] = {0, 1.5, 1.8};
    CvVertex v[3];
    memset(v, 0, sizeof(v));
    const double *P[3] = {A, B, C};
    for (int i = 0; i < 3; i++)
        v[i].pos_u = (cv_vec4){(float)P[i][0], (float)P[i][1], (float)P[i][2], 0};
    CvTriangle t = {{0, 1, 2, CV_TRI_REVERSE}};
    double e1[3], e2[3], nl[3];
    for (int i = 0; i < 3; i++) {
        e1[i] = B[i] - A[i];
        e2[i] = C[i] - A[i];
    }
    nl[0] = e1[1] * e2[2] - e1[2] * e2[1];
    nl[1] = e1[2] * e2[0] - e1[0] * e2[2];
    nl[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double area2 = sqrt(nl[0] * nl[0] + nl[1] * nl[1] + nl[2] * nl[2]);
    for (int i = 0; i < 3; i++)
        nl[i] = -nl[i] / area2;  /* CV_TRI_REVERSE */
    CvLight l[4];
    l[0] = light_init(CV_LIGHT_INFINITE);
    l[0].L = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
    l[1] = light_init(CV_LIGHT_AREA);
    l[1].prim = 0;
    l[1].L = (cv_vec4){3, 2, 1, (float)(area2 / 2)};
    l[2] = light_init(CV_LIGHT_POINT);
    l[2].position = (cv_vec4){0, 0, 2, 0};
    l[2].L = (cv_vec4){4, 4, 4, 0};
    l[3] = light_init(CV_LIGHT_SPOT);
    l[3].position = (cv_vec4){1, 0, 0, cos_start};  /* w: cos falloff start */
    l[3].direction = (cv_vec4){-1, 0.3f, 0, 0.9f};  /* w: cos total width */
    l[3].L = (cv_vec4){8, 8, 8, 0};
    float cdf[4] = {0.3f, 0.6f, 0.8f, 1.0f};
    struct gpu_scene s = {0};
    uint32_t texel[2] = {0, 0};
    CvTexture tx;
    memset(&tx, 0, sizeof(tx));
    float env = 0;
    s.vertices = cv_buffer_create(sizeof(v), v, "vertices", &err);
    s.triangles = cv_buffer_create(sizeof(t), &t, "triangles", &err);
    s.lights = cv_buffer_create(sizeof(l), l, "lights", &err);
    s.cdf = cv_buffer_create(sizeof(cdf), cdf, "cdf", &err);
    s.env = cv_buffer_create(sizeof(env), &env, "env", &err);
    s.textures = cv_buffer_create(sizeof(tx), &tx, "textures", &err);
    s.texels = cv_buffer_create(sizeof(texel), texel, "texels", &err);
    float p[3] = {0, 0, 0}, nlf[3] = {(float)nl[0], (float)nl[1], (float)nl[2]};
    float *samples = cv_xmalloc((size_t)N * 8 * sizeof(float));
    float *pts = cv_xmalloc((size_t)N * 4 * sizeof(float));
    float *eval = cv_xmalloc((size_t)N * 4 * sizeof(float));
    size_t n_grid;
    float *grid = stats_grid_dirs(&n_grid);
    float *grid_out = cv_xmalloc(n_grid * 4 * sizeof(float));
    if (!tap_ok(run(prog, &s, 0, 11, p, 0, nlf, NULL, N, samples, &err) &&
                    run(prog, &s, 1, 0, p, 0, nlf, grid, n_grid, grid_out, &err),
                "%s: GPU runs: %s", nm, err.msg))
        goto done;
    size_t n_area = 0, n_point = 0, n_spot = 0, n_env = 0, bad_point = 0, bad_spot = 0, bad_env = 0;
    double observed[CHI_CELLS] = {0}, cell[CHI_CELLS];
    for (size_t i = 0; i < N; i++) {
        const float *sm = samples + 8 * i;
        float *q = pts + 4 * i;
        q[0] = q[1] = q[2] = q[3] = 0;
        if (sm[3] <= 0)
            continue;
        if (sm[7] < 0) {  /* delta: point or spot */
            double d = -sm[7];
            if (fabs(sm[2] - 1) < 1e-3 && fabs(d - 2) < 1e-3) {
                n_point++;
                bad_point += fabs(sm[4] - 1.0) > 1e-4 || fabs(sm[3] - 0.2) > 1e-5;
            } else {
                n_spot++;
                /* direction from the spot to p is -x: cos to its axis */
                double ax[3] = {-1, 0.3, 0}, al = sqrt(1.09);
                double c = (-sm[0] * ax[0] - sm[1] * ax[1] - sm[2] * ax[2]) / al;
                double expect = 8 * pbrt_smoothstep(0.9f, cos_start, c) / (d * d);
                bad_spot += fabs(sm[4] - expect) > 1e-3 * fmax(expect, 1e-3) || fabs(sm[3] - 0.2) > 1e-5;
            }
            continue;
        }
        observed[stats_cell(sm)] += 1;
        if (sm[7] > 1e29) {
            n_env++;
            bad_env += fabs(sm[3] - 0.3 / (4 * M_PI)) > 1e-6 || fabs(sm[4] - 0.5) > 1e-6;
        } else {
            n_area++;
            q[0] = sm[0] * sm[7];
            q[1] = sm[1] * sm[7];
            q[2] = sm[2] * sm[7];
        }
    }
    if (!tap_ok(run(prog, &s, 2, 0, p, 1, nlf, pts, N, eval, &err), "%s: area pdf run: %s", nm, err.msg))
        goto done;
    size_t bad_area = 0;
    for (size_t i = 0; i < N; i++) {
        const float *sm = samples + 8 * i;
        if (sm[3] > 0 && sm[7] > 0 && sm[7] < 1e29 && fabs(sm[3] - eval[4 * i]) > 1e-3 * sm[3])
            bad_area++;
    }
    /* Mixture pdf of the non-delta lights per cell: the environment's from
     * cv_env_pdf on the grid, the triangle's from CPU ray casts on a finer
     * grid (its edges cut through cells). */
    size_t bad_env_pdf = 0;
    for (size_t k = 0; k < n_grid; k++)
        bad_env_pdf += fabs(grid_out[4 * k + 3] - 0.3 / (4 * M_PI)) > 1e-6;
    tap_ok(bad_env_pdf == 0, "%s: cv_env_pdf is pmf / 4 pi everywhere (%zu bad)", nm, bad_env_pdf);
    stats_integrate(grid_out + 3, 4, cell);
    const int sub = 40;
    for (int ti = 0; ti < CHI_THETA; ti++)
        for (int pi = 0; pi < CHI_PHI; pi++) {
            double acc = 0, dt = M_PI / CHI_THETA / sub, dp = 2 * M_PI / CHI_PHI / sub;
            for (int i = 0; i < sub; i++)
                for (int j = 0; j < sub; j++) {
                    double th = (ti + (i + 0.5) / sub) * M_PI / CHI_THETA;
                    double ph = (pi + (j + 0.5) / sub) * 2 * M_PI / CHI_PHI;
                    double d[3] = {sin(th) * cos(ph), sin(th) * sin(ph), cos(th)};
                    double tt = ray_tri(d, A, B, C);
                    if (tt > 0) {
                        double c = fabs(d[0] * nl[0] + d[1] * nl[1] + d[2] * nl[2]);
                        acc += 0.3 * tt * tt / (c * area2 / 2) * sin(th) * dt * dp;
                    }
                }
            cell[ti * CHI_PHI + pi] += acc;
        }
    struct stats_chi2 r = stats_chi2_test(observed, cell, N);
    double sd = sqrt(N * 0.2 * 0.8);
    tap_ok(fabs(n_point - 0.2 * N) < 5 * sd && fabs(n_spot - 0.2 * N) < 5 * sd,
           "%s: point and spot picked with probability 0.2 (%zu, %zu of %d; spot samples outside its cone "
           "count as failed)", nm, n_point, n_spot, N);
    tap_ok(bad_point == 0, "%s: point light radiance I/d^2 and pdf = pmf (%zu bad)", nm, bad_point);
    tap_ok(bad_spot == 0, "%s: spot light smoothstep falloff (%zu bad)", nm, bad_spot);
    tap_ok(bad_env == 0, "%s: constant environment radiance and pdf (%zu bad of %zu)", nm, bad_env, n_env);
    tap_ok(n_area > 0 && bad_area <= n_area / 5000, "%s: sampled area pdf equals cv_light_pdf_area (%zu of %zu)",
           nm, bad_area, n_area);
    tap_ok(fabs(r.total_expected - 0.6) < 0.006, "%s: non-delta pdf integrates to 0.6 (%.4f)", nm,
           r.total_expected);
    tap_ok(r.p_value >= alpha, "%s: chi2 %.1f dof %d p %.3g", nm, r.chi2, r.dof, r.p_value);
done:
    free(samples);
    free(pts);
    free(eval);
    free(grid);
    free(grid_out);
    destroy_scene(&s);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_program *prog = cv_program_get(gpu, "trace/test/light_probe.comp", NULL, &err);
    if (!tap_ok(prog != NULL, "light_probe.comp compiles: %s", prog ? "" : err.msg))
        return tap_done();
    struct cv_program *shade = cv_program_get(gpu, "trace/test/shade_compile.comp", NULL, &err);
    tap_ok(shade != NULL, "material and light code compile together in one shader: %s",
           shade ? "yes" : err.msg);
    double alpha = stats_sidak(0.01, N_CHI2);
    env_test(prog, false, alpha);
    env_test(prog, true, alpha);
    mixed_test(prog, alpha, 0.95f, "mixed lights");
    mixed_test(prog, alpha, 0.9f, "mixed lights, a spot of conedeltaangle 0");
    cv_gpu_destroy(&gpu);
    return tap_done();
}
