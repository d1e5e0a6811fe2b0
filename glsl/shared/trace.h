/* glsl/shared/trace.h: the wavefront path tracer's work items and queue
 * block, shared by the host (src/trace) and the stage shaders (glsl/trace).
 * Every queue is an SSBO array plus a counter in CvTraceQueues; the stage
 * that fills a queue bumps the counter with atomicAdd, and the last work
 * group to finish that stage turns the counters into the next stages'
 * indirect dispatch arguments (queue_args.glsl), so the host never reads a
 * count back between bounces and no dispatch of its own does that work.
 *
 * Paths are regenerated: each pixel of the crop owns K path slots (K =
 * u_pass.paths_per_pixel, chosen by the host), and when a slot's path ends (escaped,
 * absorbed, roulette, maximum depth) the stage that ends it starts the
 * slot's next sample of the pass (regenerate.glsl) among the rays of the
 * next iteration. The wave stays full until slots run out of samples, so
 * an iteration is one bounce of paths of mixed depths, and a pass of k
 * samples takes about k / K times the mean path length in iterations
 * instead of k times the maximum depth.
 *
 * Slot s belongs to crop pixel s % P (P pixels in the crop) and takes that
 * pixel's samples j with j % K == s / P, in order; each slot has a film
 * entry of its own, and resolving sums a pixel's K entries in slot order.
 * So film updates need no atomics, and a pixel's samples add up in the
 * same order however a render is split into passes. More than one slot a
 * pixel is for small films: the traversal stages only reach their rate
 * with a few million rays in flight, more than a film of a million pixels
 * holds (bench/RESULTS.md, "Paths in flight per pixel"). */
#ifndef CV_SHARED_TRACE_H
#define CV_SHARED_TRACE_H

#include "shared/common.h"
#include "shared/bindings.h"

/* Every stage shader runs this many invocations per group. */
#define CV_TRACE_GROUP 64

/* Binding points: CV_BIND_QUEUES .. CV_BIND_RESOLVED (bindings.h). Few
 * buffers, each holding related queues, because Mesa counts every declared
 * storage block against its limit of 16 per shader.
 * - CV_BIND_RAYS: the ray queue, double-buffered by depth parity: with
 *   capacity n (path slots), rays of depth d sit at
 *   [((d + 1) & 1) * n, ...) and the bounce rays go to [(d & 1) * n, ...).
 * - CV_BIND_HITS: hits at [0, n) (two bins, from both ends: CV_Q_HITS_B),
 *   escaped rays at [n, 2n) (their .ray only: a ray index; rlpath alone
 *   queues them, the path integrator's intersect stage handles misses),
 *   the third bin's hits from the end of that half (CV_Q_HITS_C): hits and
 *   misses together are at most n.
 * Items refer to rays by their index within the iteration's half. */

/* Queue counters (slots of CvTraceQueues.count). */
#define CV_Q_RAYS_IN 0u
#define CV_Q_RAYS_OUT 1u
#define CV_Q_HITS 2u
#define CV_Q_ESCAPED 3u
#define CV_Q_SHADOW 4u
/* Tickets: how many work groups of the intersect and of the shade stage
 * have finished; the last one prepares the next stages (queue_args.glsl)
 * and sets its ticket back to 0. */
#define CV_Q_TICKET_INTERSECT 5u
#define CV_Q_TICKET_SHADE 7u
/* Hits of the second bin (CV_HIT_BINS in intersect.comp: materials other
 * than diffuse, but those of the third bin): they fill the hit queue from
 * its end, hits[n - 1 - k]. The path integrator shades each bin with a
 * program of its own (CV_SHADE_BIN in trace/shade.comp), the first one's
 * code cut down to diffuse surfaces; a shade stage built without
 * CV_SHADE_BIN (rlpath's) meets the CV_Q_HITS hits, then these, then the
 * third bin's (cv_hit_slot in common.glsl). 0 without binning. */
#define CV_Q_HITS_B 6u
/* Hits of the third bin (materials that may take the coated walk,
 * glsl/trace/bsdf/layered.glsl): hits[2n - 1 - k], shaded by a program of
 * their own (CV_SHADE_BIN=2), which the host builds only for scenes that
 * have such materials, so that the walk's code and registers stay out of
 * the other bins' kernels. Which bin a material's hits go to: the host's
 * one decision (src/trace/shade_bins.c), in CvMaterial.flags
 * (CV_MATF_SHADE_BIN_SHIFT). */
#define CV_Q_HITS_C 8u

/* Indirect dispatch slots (args[slot] = groups x, y, z, unused); the byte
 * offset of slot s in the buffer is CV_ARGS_BYTES(s). CV_ARGS_HITS covers
 * the CV_Q_HITS hits, CV_ARGS_HITS_B the CV_Q_HITS_B ones, CV_ARGS_HITS_C
 * the CV_Q_HITS_C ones: the path integrator shades each bin with its own
 * program (trace/shade.comp). CV_ARGS_HITS_ALL covers every bin, for a
 * shade stage built without CV_SHADE_BIN (rlpath's). */
#define CV_ARGS_RAYS 0u
#define CV_ARGS_HITS 1u
#define CV_ARGS_ESCAPED 2u
#define CV_ARGS_SHADOW 3u
#define CV_ARGS_HITS_B 4u
#define CV_ARGS_HITS_ALL 5u   /* every bin's hits */
#define CV_ARGS_HITS_C 6u
#define CV_ARGS_OFFSET 48
#define CV_ARGS_BYTES(s) (CV_ARGS_OFFSET + 16 * (s))

/* Statistic slots: 64-bit totals kept as (lo, hi) pairs by the last work
 * group of a stage (queue_args.glsl). An iteration mixes camera and bounce rays, so the
 * closest-hit rays are counted together; the host knows the camera rays
 * (one per pixel sample). */
#define CV_STAT_EXTEND 0u      /* every closest-hit ray, camera rays included */
#define CV_STAT_SHADOW 1u
/* Radiance samples dropped for a NaN or infinite value (x alone: a count,
 * added to by any stage, cv_film_reject in common.glsl): 0 unless a bug. */
#define CV_STAT_NONFINITE 2u
/* closest-hit rays that found a surface (or a medium event): with
 * CV_STAT_EXTEND, the fraction of rays that left the scene, by which the
 * host chooses where misses start their slots' next samples (render.c) */
#define CV_STAT_HITS 3u

CV_STRUCT(CvTraceQueues) {
    CV_UINT count[12];     /* CV_Q_* counters and tickets; a scalar array because llvmpipe's atomics on
                            * vector components returned duplicate slots */
    cv_uvec4 args[7];      /* indirect dispatch arguments, CV_ARGS_* */
    cv_uvec4 stats[4];     /* CV_STAT_*: x lo, y hi */
} CV_END(CvTraceQueues)
CV_CHECK_SIZE(CvTraceQueues, 224);

/* Ray flags (CvRayItem.beta.w, as a float holding the integer): these bits,
 * the ray's depth (0 for camera rays) from bit CV_RAYF_DEPTH_SHIFT (11
 * bits: max_depth is at most 1024), and from bit CV_RAYF_MEDIUM_SHIFT the
 * medium the ray travels in (glsl/shared/medium.h; 0 outside volpath), all
 * below 2^24 so the float holds them exactly. */
#define CV_RAYF_SPECULAR 1u        /* the last bounce was specular (no MIS on emission) */
#define CV_RAYF_ALBEDO_DONE 2u     /* the albedo AOV has been written for this sample */
/* a BSSRDF probe segment, not a ray (glsl/trace/sss_vertex.glsl): o.xyz its
 * start, d.xyz the vector to its end, d.w the material its exits have */
#define CV_RAYF_PROBE 4u
#define CV_RAYF_MASK 255u
#define CV_RAYF_DEPTH_SHIFT 8u
#define CV_RAYF_DEPTH_MASK 2047u
#define CV_RAYF_MEDIUM_SHIFT 19u

/* A path's next ray. o.w: its path slot (a float holding the integer:
 * exact below 2^24, which the host enforces; integer bit patterns would be
 * denormals that some GPUs flush); d.w: the density (solid angle) that
 * next-event estimation at the previous vertex weighs d against
 * (glsl/trace/path_vertex.glsl: the bounce's, or the BSDF's alone), 0 for
 * camera rays and after specular bounces; beta.rgb: path throughput;
 * beta.w: CV_RAYF_* bits and depth. */
CV_STRUCT(CvRayItem) {
    cv_vec4 o;
    cv_vec4 d;
    cv_vec4 beta;
} CV_END(CvRayItem)
CV_CHECK_SIZE(CvRayItem, 48);

/* A closest hit: ray indexes the input ray queue; b1, b2 barycentrics of
 * vertices 1 and 2; t along the unit ray direction. prim CV_HIT_MEDIUM: a
 * scattering event in the ray's medium at t (volpath; trace/medium). */
#define CV_HIT_MEDIUM 0xffffffffu
/* A probe segment's result (CV_RAYF_PROBE rays; glsl/trace/sss_probe.glsl):
 * the exit chosen among the material's surfaces along it, pad0 their
 * count; prim CV_HIT_PROBE_MISS where there was none. */
#define CV_HIT_PROBE_MISS 0xfffffffeu
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

/* A next-event shadow ray: o.w: tmax; d.w: path slot (as in CvRayItem);
 * L.rgb: the contribution (MIS-weighted, divided by the light pdf) added to
 * the slot's film entry when unoccluded; L.w: in a scene with alpha
 * cut-outs, the sample index of the path that sent it, for the alpha tests
 * (CvFilmPixel.normal.w has moved on when that path ended). m.x: the
 * medium the ray starts in (volpath: the contribution is multiplied by the
 * transmittance along it, trace/shadow.comp); m.y: with moving shapes
 * (CV_HAS_MOTION), the path's time (trace/path_time.glsl); m.z: under
 * rlpath's sdtree method, the depth of the vertex that sent it; m.w: the
 * filter weight of that path's sample (+1 or -1), for the same reason as
 * L.w. */
CV_STRUCT(CvShadowItem) {
    cv_vec4 o;
    cv_vec4 d;
    cv_vec4 L;
    cv_vec4 m;
} CV_END(CvShadowItem)
CV_CHECK_SIZE(CvShadowItem, 64);

/* A path slot's sums over its samples (a pixel's are the sum of its K
 * slots'), each sample weighted by its filter weight w (+1 or -1:
 * trace/filter.glsl), as pbrt-v4's film weighs by f / pdf. L.rgb:
 * radiance; L.w: the weights' sum. AOVs (divide by L.w), written only
 * when the renderer keeps them: albedo.rgb: albedo at the first
 * non-specular hit; albedo.w: camera distance to the first hit (0 when the
 * ray escaped); normal.xyz: shading normal at the first hit. normal.w: the
 * sample index of the slot's path in flight plus 1, times its filter
 * weight (a float holding the integer, as CvRayItem.o.w; the host keeps
 * sample counts below 2^24). */
CV_STRUCT(CvFilmPixel) {
    cv_vec4 L;
    cv_vec4 albedo;
    cv_vec4 normal;
} CV_END(CvFilmPixel)
CV_CHECK_SIZE(CvFilmPixel, 48);

/* Coverage and ID mattes, per path slot, for a job with alpha or ID AOVs
 * (CV_BIND_MATTE; trace/matte.glsl writes them at each camera ray's first
 * hit, for the matte stage and bdpt's camera subpaths): CV_MATTE_STRIDE
 * uints a slot (the host defines it: CV_MATTE_WORDS
 * without Cryptomatte, CV_MATTE_WORDS_CRYPTO with it), slot s from
 * s * CV_MATTE_STRIDE on, all starting at 0:
 * - [CV_MATTE_COVERAGE]: the filter weight of the slot's camera rays that
 *   hit a surface (float bits; against CvFilmPixel.L.w: alpha);
 * - [CV_MATTE_OBJECT_ID], [CV_MATTE_MATERIAL_ID]: 1 + the object and the
 *   material at the first hit of the pixel's sample 0 (in slot 0 of the
 *   pixel), 0 where it escaped: the ID AOVs, one sample unfiltered, as
 *   Cycles' IndexOB and IndexMA;
 * - from CV_MATTE_CRYPTO_OBJECT and CV_MATTE_CRYPTO_MATERIAL, CV_MATTE_RANK
 *   pairs (1 + id, summed filter weight as float bits), in the order the
 *   ids were first met; an id met with every pair taken loses that
 *   sample's weight, as in Cycles. The host merges a pixel's slots and
 *   ranks the ids by weight (src/trace/matte_read.c). */
#define CV_MATTE_COVERAGE 0u
#define CV_MATTE_OBJECT_ID 1u
#define CV_MATTE_MATERIAL_ID 2u
#define CV_MATTE_WORDS 4u
#define CV_MATTE_RANK 6u    /* Cryptomatte's default depth: 3 RGBA layers */
#define CV_MATTE_CRYPTO_OBJECT CV_MATTE_WORDS
#define CV_MATTE_CRYPTO_MATERIAL (CV_MATTE_WORDS + 2u * CV_MATTE_RANK)
#define CV_MATTE_WORDS_CRYPTO (CV_MATTE_WORDS + 4u * CV_MATTE_RANK)

/* Per-pass constants, in a uniform block at binding 0 (std140: every row
 * of four scalars below fills one 16-byte row, as a vec4 would). */
#define CV_UBO_PASS 0
/* Cells of a tabulated pixel filter (trace/filter_table.h) on each axis, at
 * most: pbrt-v4's 32 a pixel of radius up to a radius of 8. */
#define CV_FILTER_CELLS 256
CV_STRUCT(CvPassParams) {
    CV_UINT n_pixels;      /* pixels in the crop */
    CV_UINT crop_w, crop_h;
    CV_UINT first_sample;  /* the pass's first sample */
    CV_UINT seed_lo, seed_hi;  /* job seed */
    CV_UINT sampler;       /* 0 sobol, 1 independent */
    CV_UINT max_depth;
    cv_uvec4 film;         /* x, y: full film resolution; z, w: crop origin */
    CV_UINT iteration;     /* its parity picks the ray queue halves */
    CV_UINT filter_type;   /* CV_FILTER_ID_* (glsl/trace/filter.glsl) */
    CV_UINT n_lights;
    CV_UINT end_sample;    /* the pass's end sample (exclusive) */
    cv_vec4 pixel_filter;        /* x, y: filter radius; z, w: cells of the tabulated
                                  * filter on x, y (floats holding integers) */
    cv_vec4 cam_to_world[3];
    cv_vec4 screen;
    CV_FLOAT lens_radius;
    CV_FLOAT focal_distance;
    CV_FLOAT tan_half_fov;
    CV_UINT camera_type;   /* CV_CAMERA_* (shared/scene.h) */
    cv_vec4 filter_x[CV_FILTER_CELLS / 4 + 1]; /* CDF of |f| over the x cells (cells + 1 values) */
    cv_vec4 filter_y[CV_FILTER_CELLS / 4 + 1];
    cv_uvec4 filter_neg[2][CV_FILTER_CELLS / 128]; /* [axis]: bit k set where f < 0 in cell k */
    CV_UINT n_paths;       /* path slots (the queues' capacity) */
    CV_UINT paths_per_pixel;   /* slots per pixel (K) */
    CV_UINT camera_rays;   /* camera rays the pass's generate stage writes */
    CV_UINT camera_medium; /* the medium camera rays start in (glsl/shared/medium.h) */
    /* The camera's motion (src/trace/camera_motion.h), pbrt-v4's
     * AnimatedTransform of camera to world: each end's transform split
     * into translation T, rotation R (a unit quaternion x, y, z, w; R[1]
     * on R[0]'s side) and scale-shear S (3x3, rows), interpolated per
     * camera ray at its time. cam_time: x, y shutter open, close; z, w
     * the transforms' start, end times. cam_moves: 0 for a still camera
     * (cam_to_world alone then). */
    cv_vec4 cam_time;
    cv_uvec4 cam_moves;    /* x: 0 or 1 */
    cv_vec4 cam_T[2];
    cv_vec4 cam_R[2];
    cv_vec4 cam_S[6];      /* rows of S[0], then of S[1] */
} CV_END(CvPassParams)
CV_CHECK_SIZE(CvPassParams, 16 * (4 + 1 + 3 + 2 + 2 * (CV_FILTER_CELLS / 4 + 1) + CV_FILTER_CELLS / 64 + 1 +
                                  12));

#endif
