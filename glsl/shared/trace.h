/* glsl/shared/trace.h: the wavefront path tracer's work items and queue
 * block, shared by the host (src/trace) and the stage shaders (glsl/trace).
 * Every queue is an SSBO array plus a counter in CvTraceQueues; the stage
 * that fills a queue bumps the counter with atomicAdd, and prepare.comp turns
 * the counters into indirect dispatch arguments, so the host never reads a
 * count back between bounces. */
#ifndef CV_SHARED_TRACE_H
#define CV_SHARED_TRACE_H

#include "shared/common.h"
#include "shared/bindings.h"

/* Every stage shader runs this many invocations per group. */
#define CV_TRACE_GROUP 64

/* Binding points (stage-private range, see bindings.h). Ray queues are
 * double-buffered by depth parity: rays of depth d are read from
 * CV_BIND_RAYS_IN and the bounce rays written to CV_BIND_RAYS_OUT; the host
 * swaps the two buffers between depths. */
#define CV_BIND_QUEUES (CV_BIND_STAGE0 + 0)    /* CvTraceQueues */
#define CV_BIND_RAYS_IN (CV_BIND_STAGE0 + 1)   /* CvRayItem[] */
#define CV_BIND_RAYS_OUT (CV_BIND_STAGE0 + 2)  /* CvRayItem[] */
#define CV_BIND_HITS (CV_BIND_STAGE0 + 3)      /* CvHitItem[] */
#define CV_BIND_ESCAPED (CV_BIND_STAGE0 + 4)   /* uint[]: indices into the input rays */
#define CV_BIND_SHADOW (CV_BIND_STAGE0 + 5)    /* CvShadowItem[] */
#define CV_BIND_FILM (CV_BIND_STAGE0 + 6)      /* vec4[]: rgb radiance sum, w: weight sum */
#define CV_BIND_AOV (CV_BIND_STAGE0 + 7)       /* CvAovPixel[] */
#define CV_BIND_RESOLVED (CV_BIND_STAGE0 + 8)  /* vec4[]: resolve output */
#define CV_BIND_ENV_DIST (CV_BIND_STAGE0 + 9)  /* environment map distribution (envmap_dist.h) */

/* Queue counters (slots of CvTraceQueues.count). */
#define CV_Q_RAYS_IN 0u
#define CV_Q_RAYS_OUT 1u
#define CV_Q_HITS 2u
#define CV_Q_ESCAPED 3u
#define CV_Q_SHADOW 4u

/* Indirect dispatch slots (args[slot] = groups x, y, z, unused); the byte
 * offset of slot s in the buffer is CV_ARGS_OFFSET + 16 * s. */
#define CV_ARGS_RAYS 0u
#define CV_ARGS_HITS 1u
#define CV_ARGS_ESCAPED 2u
#define CV_ARGS_SHADOW 3u
#define CV_ARGS_OFFSET 32

/* Statistic slots: 64-bit totals kept as (lo, hi) pairs by the single
 * prepare invocation, reset by the host at the start of a pass. */
#define CV_STAT_PRIMARY 0u
#define CV_STAT_SECONDARY 1u
#define CV_STAT_SHADOW 2u

CV_STRUCT(CvTraceQueues) {
    CV_UINT count[8];      /* CV_Q_*; a scalar array because llvmpipe's atomics on
                            * vector components returned duplicate slots */
    CV_UVEC4 args[4];      /* indirect dispatch arguments, CV_ARGS_* */
    CV_UVEC4 stats[3];     /* CV_STAT_*: x lo, y hi */
} CV_END(CvTraceQueues)
CV_CHECK_SIZE(CvTraceQueues, 144);

/* Ray flags (CvRayItem.beta.w, as a float holding the integer). */
#define CV_RAYF_SPECULAR 1u        /* the last bounce was specular (no MIS on emission) */
#define CV_RAYF_ALBEDO_DONE 2u     /* the albedo AOV has been written for this sample */

/* A path's next ray. o.w: pixel index of the crop (a float holding the
 * integer: exact below 2^24, which the host enforces; integer bit patterns
 * would be denormals that some GPUs flush); d.w: the BSDF pdf of d at the
 * previous vertex (solid angle), 0 for camera rays and after specular
 * bounces; beta.rgb: path throughput; beta.w: CV_RAYF_* bits. */
CV_STRUCT(CvRayItem) {
    CV_VEC4 o;
    CV_VEC4 d;
    CV_VEC4 beta;
} CV_END(CvRayItem)
CV_CHECK_SIZE(CvRayItem, 48);

/* A closest hit: ray indexes the input ray queue; b1, b2 barycentrics of
 * vertices 1 and 2; t along the unit ray direction. */
CV_STRUCT(CvHitItem) {
    CV_UINT ray;
    CV_UINT prim;
    CV_FLOAT b1;
    CV_FLOAT b2;
    CV_FLOAT t;
    CV_UINT pad0;
    CV_UINT pad1;
    CV_UINT pad2;
} CV_END(CvHitItem)
CV_CHECK_SIZE(CvHitItem, 32);

/* A next-event shadow ray: o.w: tmax; d.w: pixel (as in CvRayItem); L.rgb: the
 * contribution (MIS-weighted, divided by the light pdf) added to the pixel
 * when unoccluded. */
CV_STRUCT(CvShadowItem) {
    CV_VEC4 o;
    CV_VEC4 d;
    CV_VEC4 L;
} CV_END(CvShadowItem)
CV_CHECK_SIZE(CvShadowItem, 48);

/* Per-pixel AOV sums over samples (divide by the film weight):
 * albedo.rgb: albedo at the first non-specular hit; albedo.w: camera
 * distance to the first hit (0 when the ray escaped); normal.xyz: shading
 * normal at the first hit. */
CV_STRUCT(CvAovPixel) {
    CV_VEC4 albedo;
    CV_VEC4 normal;
} CV_END(CvAovPixel)
CV_CHECK_SIZE(CvAovPixel, 32);

/* Per-pass constants, in a uniform block at binding 0. */
#define CV_UBO_PASS 0
#define CV_FILTER_TABLE 64
CV_STRUCT(CvPassParams) {
    CV_UVEC4 frame;        /* x: pixels in the crop, y: crop width, z: crop height, w: sample index */
    CV_UVEC4 seed;         /* x, y: job seed lo/hi; z: sampler (0 sobol, 1 independent); w: max depth */
    CV_UVEC4 film;         /* x, y: full film resolution; z, w: crop origin */
    CV_UVEC4 misc;         /* x: depth; y: filter type; z: light count; w: flags */
    CV_VEC4 pixel_filter;        /* x, y: filter radius; z: gaussian sigma */
    CV_VEC4 cam_to_world[3];
    CV_VEC4 screen;
    CV_VEC4 lens;          /* x: radius, y: focal distance, z: tan(fov/2); w: camera type */
    CV_VEC4 filter_x[CV_FILTER_TABLE / 4 + 1]; /* gaussian inverse CDF over [0,1], x axis (65 values, padded) */
    CV_VEC4 filter_y[CV_FILTER_TABLE / 4 + 1];
} CV_END(CvPassParams)
CV_CHECK_SIZE(CvPassParams, 16 * (4 + 1 + 3 + 2 + 2 * (CV_FILTER_TABLE / 4 + 1)));

#endif
