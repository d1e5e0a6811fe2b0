/* rays.h: path-tracer-like query rays on a scene, the one ray set of the
 * traversal benchmarks (bvh_work counts the work of each query, rt_probe
 * times them on two back ends). Camera rays on a jittered grid, then per
 * hit a shadow ray (any hit) to a light chosen by power and a diffuse
 * bounce (cosine about the geometric normal), twice. The caller traces:
 * the generator hands each set of rays to a closest-hit function and spawns
 * the next rays from the hits it returns, so the rays follow whichever
 * traversal the tool trusts (bvh_work: its CPU walk; rt_probe: the GPU's).
 * Deterministic for a seed and a tracer. */
#ifndef CV_BENCH_RAYS_H
#define CV_BENCH_RAYS_H

#include <stdbool.h>
#include <stdint.h>

#include "glsl/shared/scene.h"
#include "scene/scene.h"

/* The scene's static triangles (the renderer's triangle tree covers them). */
struct bench_tris {
    const CvVertex *v;
    const CvTriangle *t;
    uint32_t n;
};

/* Triangle t's three corners. */
void bench_tri_pos(const struct bench_tris *m, uint32_t t, double p[3][3]);

/* A query: hits count for tmin < t < tmax; d need not be unit length. As
 * the GPU reads it: (origin, tmin), (direction, tmax), 32 bytes. */
struct bench_ray {
    float o[3], tmin, d[3], tmax;
};

struct bench_hit {
    double t;
    uint32_t prim;  /* UINT32_MAX: none */
    float b1, b2;
};

enum { BENCH_Q_CAMERA, BENCH_Q_BOUNCE1, BENCH_Q_BOUNCE2, BENCH_Q_SHADOW, BENCH_Q_TYPES };
/* "camera", "bounce1", "bounce2", "shadow": closest hit but for shadow. */
extern const char *const bench_q_names[BENCH_Q_TYPES];

struct bench_rayset {
    struct bench_ray *r;
    uint32_t n, cap;
};

/* Closest hits of rays r[0 .. n) into out; false on failure (the tracer
 * reports why). */
typedef bool (*bench_trace_fn)(void *ctx, const struct bench_ray *r, uint32_t n,
                               struct bench_hit *out);

struct bench_rays_params {
    const struct cv_scene *sc;
    const struct bench_tris *m;
    int res;               /* camera grid width; height by the film's aspect */
    uint64_t seed;
    bench_trace_fn trace;
    void *ctx;
};

/* Fills sets (zeroed by the caller) with every query type's rays; false
 * when the tracer failed. Free with bench_rays_free either way. */
bool bench_rays_make(const struct bench_rays_params *p, struct bench_rayset sets[BENCH_Q_TYPES]);
void bench_rays_free(struct bench_rayset sets[BENCH_Q_TYPES]);

#endif
