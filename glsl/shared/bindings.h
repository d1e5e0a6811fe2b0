/* glsl/shared/bindings.h: shader storage buffer binding points, shared by
 * the C host and GLSL. Scene buffers keep fixed slots so that BVH and trace
 * shaders can include each other's GLSL. GL guarantees only 8 storage blocks
 * per compute shader (llvmpipe and NVIDIA offer 16 or more): keep any one
 * shader's set small. */
#ifndef CV_SHARED_BINDINGS_H
#define CV_SHARED_BINDINGS_H

#define CV_BIND_VERTICES 0     /* CvVertex[] */
#define CV_BIND_TRIANGLES 1    /* CvTriangle[] */
#define CV_BIND_TRI_LIGHT 2    /* int[]: light index of each triangle, -1 */
#define CV_BIND_MATERIALS 3    /* CvMaterial[] */
#define CV_BIND_TEXTURES 4     /* CvTexture[] */
#define CV_BIND_TEXELS 5       /* uvec2[]: half RGBA */
#define CV_BIND_LIGHTS 6       /* CvLight[] */
#define CV_BIND_LIGHT_CDF 7    /* float[]: light selection CDF by power */
#define CV_BIND_BVH_NODES 8    /* src/bvh node layout (glsl/bvh/layout.h) */
#define CV_BIND_BVH_PRIMS 9    /* src/bvh leaf primitive order */
/* CvBvhTri[]: leaf-ordered triangle positions (glsl/shared/bvh.h); above
 * the stage-private range so no stage's own buffers displace it. */
#define CV_BIND_BVH_TRIS 26
/* 10 and above (but 26): stage-private (bvh build scratch, trace queues, film). */
#define CV_BIND_STAGE0 10

#endif
