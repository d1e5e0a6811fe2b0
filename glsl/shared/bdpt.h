/* glsl/shared/bdpt.h: the bdpt integrator's subpath vertices, shared by
 * the host (src/trace/bdpt.c, which sizes the store) and its kernel
 * (glsl/trace/bdpt/bdpt.comp). The store holds one wave of path slots
 * (trace.h; src/trace/integrator.h: a round of samples runs in dispatches
 * over waves of at most W = u_wave_paths slots, so that its size depends
 * on neither the film nor the driver's per-buffer limit): each keeps the
 * camera subpath and the light subpath of its sample in flight, vertex k
 * of the wave's slot i at [k * W + i] (neighbouring slots side by side, so
 * a work group's loads of one vertex index come together), camera vertices
 * k < CV_BDPT_CAMERA_VERTS(max_depth), then light vertices. Densities are
 * pbrt-v4's BDPT Vertex pdfFwd and pdfRev: per unit area at the vertex
 * (per solid angle towards infinite lights, as pbrt-v4 keeps them,
 * CV_BDPT_INFINITE). The t = 1 strategy (light
 * tracing) adds into the splat film, CV_BIND_BDPT_SPLAT: after a header
 * (CV_BDPT_SPLAT_HEADER), three floats a crop pixel, as uint bits summed with compare-and-swap; resolve.comp
 * adds them to the pixel's weighted sum (CV_BDPT_SPLAT). */
#ifndef CV_SHARED_BDPT_H
#define CV_SHARED_BDPT_H

#include "shared/common.h"

/* Vertices of each subpath, as pbrt-v4's BDPTIntegrator::Li allocates
 * them: the camera and maxDepth + 1 bounces; the light and maxDepth. */
#define CV_BDPT_CAMERA_VERTS(max_depth) ((max_depth) + 2u)
#define CV_BDPT_LIGHT_VERTS(max_depth) ((max_depth) + 1u)
#define CV_BDPT_VERTS(max_depth) (CV_BDPT_CAMERA_VERTS(max_depth) + CV_BDPT_LIGHT_VERTS(max_depth))

/* CvBdptVertex.id.x: the vertex type. */
#define CV_BDPT_CAMERA 0u
#define CV_BDPT_LIGHT 1u     /* a light subpath's first vertex: id.w its light */
#define CV_BDPT_SURFACE 2u   /* id.z its material; id.w 1 + its area light, 0 if none */
#define CV_BDPT_MEDIUM 3u    /* a scattering event in a medium: id.z the medium */
/* CvBdptVertex.id.y: flags. */
#define CV_BDPT_DELTA 1u        /* the bounce from here was specular (pbrt-v4's Vertex::delta) */
#define CV_BDPT_DELTA_LIGHT 2u  /* a point or spot light (no position to connect to by area) */
/* A vertex on the infinite lights (pbrt-v4's IsInfiniteLight): a light
 * subpath's start on an infinite light (id.w the light), or where a camera
 * subpath escaped (wo.xyz: back along its ray). Densities towards it are
 * per solid angle. */
#define CV_BDPT_INFINITE 4u
/* id.y bits 8..15: the medium the ray that found the vertex travelled in
 * (glsl/shared/medium.h; the camera's, the light's for the first vertex):
 * where rays leave the vertex, unless its surface is a medium transition. */
#define CV_BDPT_MEDIUM_SHIFT 8u

/* The splat film's first floats: the scene's bounding sphere (centre,
 * radius), from which light subpaths leave infinite lights (pbrt-v4's
 * disk of the scene radius); the pixels' sums follow. */
#define CV_BDPT_SPLAT_HEADER 4u

/* One subpath vertex. p.w: how far rays leaving p start off the surface
 * (cv_point_error); ng.xyz: geometric normal (0 where not on a surface:
 * the camera, point and spot lights, medium vertices); ng.w: pdfFwd; ns.xyz: shading
 * normal; ns.w: pdfRev; wo.xyz: unit direction towards the previous
 * vertex; wo.w: the material-mix number the BSDF was resolved with;
 * beta.rgb: throughput (for a light vertex its emitted radiance or
 * intensity); dpdu.xyz: surface tangent; uv.xy: surface coordinates. */
CV_STRUCT(CvBdptVertex) {
    cv_vec4 p;
    cv_vec4 ng;
    cv_vec4 ns;
    cv_vec4 wo;
    cv_vec4 beta;
    cv_vec4 dpdu;
    cv_vec4 uv;
    cv_uvec4 id;
} CV_END(CvBdptVertex)
CV_CHECK_SIZE(CvBdptVertex, 128);

#endif
