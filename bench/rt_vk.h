/* rt_vk.h: rt_probe's second back end: rays traced on the RT cores through
 * a Vulkan ray-tracing pipeline (VK_KHR_acceleration_structure +
 * VK_KHR_ray_tracing_pipeline; ray queries are not used). One BLAS over the
 * triangles (opaque), a TLAS of one instance, a raygen shader reading the
 * rays of bench/rays.h from a storage buffer and writing what
 * glsl/trace/test/trace_probe.comp writes. Its own Vulkan device, beside
 * Cavalry's GL context; nothing is shared between the two. */
#ifndef CV_BENCH_RT_VK_H
#define CV_BENCH_RT_VK_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"

struct rt_vk;

struct rt_vk_info {
    char device[256];
    char driver[520];      /* the driver's name and version string */
    double blas_ms, tlas_ms;   /* GPU time of the builds (timestamp queries) */
    double blas_mb;            /* the BLAS's size, uncompacted */
};

/* A device with ray-tracing pipelines and the acceleration structures of
 * n_tris triangles: idx, 3 per triangle, index n_vertices vertices of
 * `stride` bytes whose first three floats are the position (the scene's
 * own vertex array). False with err set when no such device is found or a
 * step fails. */
bool rt_vk_create(const void *vertices, uint32_t stride, uint32_t n_vertices, const uint32_t *idx,
                  uint32_t n_tris, struct rt_vk **out, struct rt_vk_info *info,
                  struct cv_error *err);

/* Traces n rays (32 bytes each: origin, tmin, direction, tmax) once untimed,
 * then `repeats` times, one launch each: ms[k] the GPU time of launch k.
 * any: any-hit queries (the first hit ends the ray, no closest-hit
 * shader). results: 2 words per ray, (t bits, prim) as trace_probe.comp. */
bool rt_vk_trace(struct rt_vk *v, const void *rays, uint32_t n, bool any, int repeats,
                 double *ms, uint32_t *results, struct cv_error *err);

/* Accepts NULL; clears the pointer. */
void rt_vk_destroy(struct rt_vk **v);

#endif
