/* rays.c: the traversal benchmarks' ray set (see rays.h). */
#include "config.h"

#include <math.h>
#include <stdlib.h>

#include "bench/rays.h"

const char *const bench_q_names[BENCH_Q_TYPES] = {"camera", "bounce1", "bounce2", "shadow"};

void bench_tri_pos(const struct bench_tris *m, uint32_t t, double p[3][3])
{
    const uint32_t *ix = &m->t[t].idx.x;
    for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
            p[j][k] = (&m->v[ix[j]].pos_u.x)[k];
}

struct gen {
    const struct bench_rays_params *p;
    uint64_t rng;
    double *light_cdf;
    double eps;  /* spawn offset along the normal [scene units] */
};

/* The spawn offset: a small fraction of the diagonal of the static
 * triangles' box, so every tracer that is handed these rays starts them
 * at the same points. */
static double spawn_offset(const struct bench_tris *m)
{
    if (!m->n)
        return 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (uint32_t t = 0; t < m->n; t++) {
        double q[3][3];
        bench_tri_pos(m, t, q);
        for (int j = 0; j < 3; j++)
            for (int k = 0; k < 3; k++) {
                lo[k] = fmin(lo[k], q[j][k]);
                hi[k] = fmax(hi[k], q[j][k]);
            }
    }
    double d2 = 0;
    for (int k = 0; k < 3; k++)
        d2 += (hi[k] - lo[k]) * (hi[k] - lo[k]);
    return 1e-5 * sqrt(d2);
}

/* xorshift64: uniform in [0, 1) */
static double rnd(struct gen *g)
{
    g->rng ^= g->rng << 13;
    g->rng ^= g->rng >> 7;
    g->rng ^= g->rng << 17;
    return (double)(g->rng >> 11) * (1.0 / 9007199254740992.0);
}

static void rs_push(struct bench_rayset *s, struct bench_ray r)
{
    if (s->n == s->cap) {
        s->cap = s->cap ? 2 * s->cap : 4096;
        s->r = realloc(s->r, s->cap * sizeof(*s->r));
    }
    s->r[s->n++] = r;
}

static void normalize(double v[3])
{
    double l = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int k = 0; k < 3; k++)
            v[k] /= l;
}

/* A cosine-distributed direction about n. */
static void cosine_dir(struct gen *g, const double n[3], double d[3])
{
    double u1 = rnd(g), u2 = rnd(g), r = sqrt(u1), phi = 6.283185307179586 * u2;
    double x = r * cos(phi), y = r * sin(phi), z = sqrt(fmax(0.0, 1 - u1));
    double a[3] = {fabs(n[0]) > 0.9 ? 0 : 1, fabs(n[0]) > 0.9 ? 1 : 0, 0};
    double t[3] = {a[1] * n[2] - a[2] * n[1], a[2] * n[0] - a[0] * n[2], a[0] * n[1] - a[1] * n[0]};
    normalize(t);
    double b[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
    for (int k = 0; k < 3; k++)
        d[k] = x * t[k] + y * b[k] + z * n[k];
}

/* A shadow ray from p (normal n, facing the incoming side) to a light
 * picked by power; none when the light is behind the surface. */
static void shadow_ray(struct gen *g, const double p[3], const double n[3],
                       struct bench_rayset *out)
{
    const struct cv_scene *sc = g->p->sc;
    if (sc->n_lights == 0)
        return;
    double u = rnd(g) * g->light_cdf[sc->n_lights - 1];
    uint32_t li = 0;
    while (li + 1 < sc->n_lights && g->light_cdf[li] <= u)
        li++;
    const CvLight *L = &sc->lights[li];
    double d[3], tmax = 1e30;
    if (L->type == CV_LIGHT_AREA && L->prim < g->p->m->n) {
        double q[3][3], b1 = rnd(g), b2 = rnd(g);
        if (b1 + b2 > 1) {
            b1 = 1 - b1;
            b2 = 1 - b2;
        }
        bench_tri_pos(g->p->m, L->prim, q);
        for (int k = 0; k < 3; k++)
            d[k] = (1 - b1 - b2) * q[0][k] + b1 * q[1][k] + b2 * q[2][k] - p[k];
        tmax = 0.999;
    } else if (L->type == CV_LIGHT_POINT || L->type == CV_LIGHT_SPOT) {
        for (int k = 0; k < 3; k++)
            d[k] = (&L->position.x)[k] - p[k];
        tmax = 0.999;
    } else if (L->type == CV_LIGHT_DISTANT) {
        for (int k = 0; k < 3; k++)
            d[k] = -(&L->direction.x)[k];
    } else {
        cosine_dir(g, n, d);
    }
    if (d[0] * n[0] + d[1] * n[1] + d[2] * n[2] <= 0)
        return;
    struct bench_ray r = {.tmin = 0, .tmax = (float)tmax};
    for (int k = 0; k < 3; k++) {
        r.o[k] = (float)(p[k] + g->eps * n[k]);
        r.d[k] = (float)d[k];
    }
    rs_push(out, r);
}

/* The hit point of r and its geometric normal, turned towards the ray. */
static void hit_frame(const struct bench_tris *m, const struct bench_ray *r,
                      const struct bench_hit *h, double p[3], double n[3])
{
    double q[3][3];
    bench_tri_pos(m, h->prim, q);
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        p[k] = r->o[k] + h->t * r->d[k];
        e1[k] = q[1][k] - q[0][k];
        e2[k] = q[2][k] - q[0][k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    normalize(n);
    if (n[0] * r->d[0] + n[1] * r->d[1] + n[2] * r->d[2] > 0)
        for (int k = 0; k < 3; k++)
            n[k] = -n[k];
}

static void camera_rays(struct gen *g, struct bench_rayset *out)
{
    const CvCamera *cam = &g->p->sc->camera;
    int res = g->p->res;
    double fw = cam->film.x ? cam->film.x : 1, fh = cam->film.y ? cam->film.y : 1;
    int rw = res, rh = (int)(res * fh / fw + 0.5);
    if (rh < 1)
        rh = 1;
    for (int y = 0; y < rh; y++)
        for (int x = 0; x < rw; x++) {
            double px = (x + rnd(g)) / rw, py = (y + rnd(g)) / rh;
            double sx = cam->screen.x + px * (cam->screen.y - cam->screen.x);
            double sy = cam->screen.w - py * (cam->screen.w - cam->screen.z);
            double lo[3], ld[3];
            if (cam->type == CV_CAMERA_ORTHOGRAPHIC) {
                lo[0] = sx, lo[1] = sy, lo[2] = 0;
                ld[0] = 0, ld[1] = 0, ld[2] = 1;
            } else {
                lo[0] = lo[1] = lo[2] = 0;
                ld[0] = sx * cam->lens.z, ld[1] = sy * cam->lens.z, ld[2] = 1;
            }
            struct bench_ray r = {.tmin = 0, .tmax = 1e30f};
            for (int k = 0; k < 3; k++) {
                const float *row = &cam->to_world[k].x;
                r.o[k] = (float)(row[0] * lo[0] + row[1] * lo[1] + row[2] * lo[2] + row[3]);
                r.d[k] = (float)(row[0] * ld[0] + row[1] * ld[1] + row[2] * ld[2]);
            }
            rs_push(out, r);
        }
}

/* From every hit of set `from`: a shadow ray and, when `next` is not NULL,
 * a diffuse bounce into it. */
static bool spawn(struct gen *g, const struct bench_rayset *from, struct bench_rayset *next,
                  struct bench_rayset *shadow)
{
    struct bench_hit *h = malloc(sizeof(*h) * (from->n + 1));
    bool ok = g->p->trace(g->p->ctx, from->r, from->n, h);
    for (uint32_t i = 0; ok && i < from->n; i++) {
        if (h[i].prim == UINT32_MAX || h[i].prim >= g->p->m->n)
            continue;
        double p[3], n[3], d[3];
        hit_frame(g->p->m, &from->r[i], &h[i], p, n);
        shadow_ray(g, p, n, shadow);
        if (!next)
            continue;
        cosine_dir(g, n, d);
        struct bench_ray b = {.tmin = 0, .tmax = 1e30f};
        for (int k = 0; k < 3; k++) {
            b.o[k] = (float)(p[k] + g->eps * n[k]);
            b.d[k] = (float)d[k];
        }
        rs_push(next, b);
    }
    free(h);
    return ok;
}

bool bench_rays_make(const struct bench_rays_params *p, struct bench_rayset sets[BENCH_Q_TYPES])
{
    const struct cv_scene *sc = p->sc;
    struct gen g = {.p = p, .rng = 88172645463325252ull ^ (p->seed * 0x9E3779B97F4A7C15ull),
                    .eps = spawn_offset(p->m)};
    g.light_cdf = malloc(sizeof(double) * (sc->n_lights + 1));
    double acc = 0;
    for (uint32_t i = 0; i < sc->n_lights; i++) {
        acc += sc->light_power ? fmax(sc->light_power[i], 0.0) : 1.0;
        g.light_cdf[i] = acc;
    }
    if (sc->n_lights && !(acc > 0))
        for (uint32_t i = 0; i < sc->n_lights; i++)
            g.light_cdf[i] = i + 1;
    camera_rays(&g, &sets[BENCH_Q_CAMERA]);
    bool ok = spawn(&g, &sets[BENCH_Q_CAMERA], &sets[BENCH_Q_BOUNCE1], &sets[BENCH_Q_SHADOW]) &&
              spawn(&g, &sets[BENCH_Q_BOUNCE1], &sets[BENCH_Q_BOUNCE2], &sets[BENCH_Q_SHADOW]) &&
              spawn(&g, &sets[BENCH_Q_BOUNCE2], NULL, &sets[BENCH_Q_SHADOW]);
    free(g.light_cdf);
    return ok;
}

void bench_rays_free(struct bench_rayset sets[BENCH_Q_TYPES])
{
    for (int q = 0; q < BENCH_Q_TYPES; q++) {
        free(sets[q].r);
        sets[q] = (struct bench_rayset){0};
    }
}
