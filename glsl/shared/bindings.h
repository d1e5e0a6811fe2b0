/* glsl/shared/bindings.h: every shader storage buffer binding point, by
 * name, shared by the C host and GLSL: host and shader agree on a name,
 * never on a number. Scene buffers keep fixed slots so that BVH and trace
 * shaders can include each other's GLSL. Each stage's own buffers take
 * slots from CV_BIND_STAGE0 up; stages never run at the same time, so
 * their ranges overlap, and within a stage a slot keeps one role from
 * kernel to kernel where it can (the host then binds it once). GL
 * guarantees only 8 storage blocks per compute shader (llvmpipe and NVIDIA
 * offer 16 or more): keep any one shader's set small. */
#ifndef CV_SHARED_BINDINGS_H
#define CV_SHARED_BINDINGS_H

/* ---- GPU checks, run before any scene is bound (src/gpu/storage.c,
 * glsl/gpu, tests/gpu) ---- */
#define CV_BIND_CHECK_IN 0     /* selftest.comp's input; storage_probe.comp's large buffer */
#define CV_BIND_CHECK_OUT 1    /* selftest.comp's output; storage_probe.comp's probe words */

/* ---- Scene (src/trace/scene_upload.c, src/bvh) ---- */
#define CV_BIND_VERTICES 0     /* CvVertex[] */
#define CV_BIND_TRIANGLES 1    /* CvTriangle[] */
#define CV_BIND_TRI_LIGHT 2    /* int[]: light index of each triangle, -1 */
#define CV_BIND_MATERIALS 3    /* CvMaterial[] */
#define CV_BIND_TEXTURES 4     /* CvTexture[] */
#define CV_BIND_TEXELS 5       /* uvec2[]: half RGBA */
#define CV_BIND_LIGHTS 6       /* CvLight[] */
/* 7: free (the light selection CDF is a buffer texture: CV_TEXUNIT_LIGHT_CDF) */
#define CV_BIND_BVH_NODES 8    /* the 4-wide nodes (glsl/shared/bvh.h: CvBvhNode4) */
#define CV_BIND_BVH_PRIMS 9    /* src/bvh leaf primitive order */
/* CvBvhTri[]: leaf-ordered triangle positions (glsl/shared/bvh.h); above
 * the stage-private range so no stage's own buffers displace it. */
#define CV_BIND_BVH_TRIS 26
/* 27, 29 and 30: free (the ID-matte objects, the media and the grid
 * media's samples are buffer textures: CV_TEXUNIT_TRI_OBJECT,
 * CV_TEXUNIT_MEDIA, CV_TEXUNIT_MEDIUM_GRIDS) */

/* Texture units of the scene's read-only tables, read as buffer textures
 * (texelFetch): a kernel may use only 16 storage blocks (Mesa's limit),
 * which one with curves, media, alpha cut-outs, moving shapes and measured
 * materials together would pass; texture units are not counted there. */
/* r32f: the subsurface profiles (glsl/shared/bssrdf.h) */
#define CV_TEXUNIT_BSSRDF 0
/* rgba32f: the curves and their tree (glsl/bvh/curves.glsl,
 * src/bvh/curve_bvh.c), bound where the scene has curves (CV_HAS_CURVES) */
#define CV_TEXUNIT_CURVES 1
/* rgba32f: the moving shapes, their transforms and trees
 * (glsl/bvh/motion.glsl, src/bvh/motion_bvh.c), bound where the scene has
 * them (CV_HAS_MOTION) */
#define CV_TEXUNIT_MOTION 2
/* r32ui: the measured BRDFs' tables (glsl/shared/measured.h), declared only
 * where a material is measured (else CV_NO_MEASURED) */
#define CV_TEXUNIT_MEASURED 3
/* rgba32f: conductors' spectral Fresnel tables (glsl/shared/conductor_fresnel.h),
 * bound where the scene has one (CV_CONDUCTOR_TABLES) */
#define CV_TEXUNIT_CONDUCTOR_FRESNEL 4
/* r32f: the light selection CDF by power (glsl/trace/light/light_buffers.glsl):
 * bdpt's kernel, with alpha and ID mattes, would pass 16 blocks otherwise */
#define CV_TEXUNIT_LIGHT_CDF 5
/* r32ui: each triangle's ID-matte object (src/scene/scene.h), read by the
 * mattes (glsl/trace/matte.glsl); bound where the scene's triangles fit a
 * buffer texture (trace/scene_upload.h) */
#define CV_TEXUNIT_TRI_OBJECT 6
/* rgba32f: participating media (glsl/shared/medium.h), CV_MEDIUM_TEXELS a
 * medium, bound where the scene has media */
#define CV_TEXUNIT_MEDIA 7
/* rgba32f, four floats a texel: grid media's samples and majorant grids
 * (glsl/shared/medium.h), bound where the scene has grid media */
#define CV_TEXUNIT_MEDIUM_GRIDS 8
/* rgba32f: rlpath's sdtree table (glsl/shared/sdtree.h), read at every
 * guided vertex: a buffer texture, whose fetches take the texture cache
 * where a read-only image's loads need not */
#define CV_TEXUNIT_SD_TREE 9
/* rgba32f: rlpath's guide table (glsl/shared/rlpath.h) as the shade
 * stages read it (rebuild.comp writes it through image unit
 * CV_IMAGE_RL_GUIDE), for the same reason */
#define CV_TEXUNIT_RL_GUIDE 10
/* rgba32f: pages 1, 2 ... of a grid store that one buffer texture does not
 * hold (trace/scene_upload.c), at units CV_TEXUNIT_MEDIUM_GRID_PAGES + page
 * - 1 up to GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS; the units below stay the
 * other tables' */
#define CV_TEXUNIT_MEDIUM_GRID_PAGES 16

/* 10 to 25: stage-private, named below per stage. */
#define CV_BIND_STAGE0 10

/* ---- Path tracer (src/trace/render.c, glsl/trace; glsl/shared/trace.h
 * says what the queues hold) ---- */
#define CV_BIND_QUEUES (CV_BIND_STAGE0 + 0)    /* CvTraceQueues */
#define CV_BIND_RAYS (CV_BIND_STAGE0 + 1)      /* CvRayItem[2n] */
#define CV_BIND_HITS (CV_BIND_STAGE0 + 2)      /* CvHitItem[2n] */
#define CV_BIND_SHADOW (CV_BIND_STAGE0 + 3)    /* CvShadowItem[n] */
#define CV_BIND_FILM (CV_BIND_STAGE0 + 4)      /* CvFilmPixel[n] */
/* float[]: environment map distributions (glsl/shared/envmap.h,
 * src/trace/envmap_dist.h), bound with the scene */
#define CV_BIND_ENV_DIST (CV_BIND_STAGE0 + 5)
#define CV_BIND_RESOLVED (CV_BIND_STAGE0 + 6)  /* vec4[n]: resolve output */
/* uint[n * CV_MATTE_WORDS]: coverage and ID mattes per path slot
 * (glsl/shared/trace.h), only with alpha or ID AOVs */
#define CV_BIND_MATTE (CV_BIND_STAGE0 + 7)
/* vec4[n]: volpath's channel ratios of each path slot's path
 * (glsl/trace/medium/track.glsl) */
#define CV_BIND_MEDIUM_PATHS (CV_BIND_STAGE0 + 8)
/* bdpt's subpath vertices (CvBdptVertex[], glsl/shared/bdpt.h) and its
 * splat film (uint[3 * pixels]: float bits, light tracing's t = 1 strategy) */
#define CV_BIND_BDPT_VERTICES (CV_BIND_STAGE0 + 9)
#define CV_BIND_BDPT_SPLAT (CV_BIND_STAGE0 + 10)
/* the guide's choice after training (glsl/trace/guide_choice.comp): the
 * film's pixel sums at three moments (vec4[3 * pixels]), and the
 * reduction's sums (float[], one a group) */
#define CV_BIND_CHOICE_PIXELS (CV_BIND_STAGE0 + 11)
#define CV_BIND_CHOICE_SUMS (CV_BIND_STAGE0 + 14)

/* ---- Exclusive prefix scan (src/bvh/scan.c; glsl/bvh/scan_*.comp) ---- */
#define CV_BIND_SCAN_DATA (CV_BIND_STAGE0 + 0)   /* uint[]: summed in place */
#define CV_BIND_SCAN_SUMS (CV_BIND_STAGE0 + 1)   /* uint[]: per-block sums */

/* ---- Radix sort (src/bvh/radix_sort.c; glsl/bvh/radix_*.comp) ---- */
#define CV_BIND_SORT_KEYS (CV_BIND_STAGE0 + 0)
#define CV_BIND_SORT_VALS (CV_BIND_STAGE0 + 1)
#define CV_BIND_SORT_COUNTS (CV_BIND_STAGE0 + 2)  /* digit counts, then offsets */
#define CV_BIND_SORT_KEYS_OUT (CV_BIND_STAGE0 + 3)
#define CV_BIND_SORT_VALS_OUT (CV_BIND_STAGE0 + 4)

/* ---- Binary BVH build (src/bvh/bvh.c, bounds.c; glsl/bvh/bounds,
 * morton, hierarchy, refit, treelet, layout, emit, leaf_slots,
 * leaf_tris.comp) ---- */
#define CV_BIND_BUILD_BOUNDS (CV_BIND_STAGE0 + 0)   /* vec4[2]: centroid bounds (morton) */
#define CV_BIND_BUILD_KEYS (CV_BIND_STAGE0 + 0)     /* uint[]: sorted Morton keys (hierarchy) */
#define CV_BIND_BUILD_VALS (CV_BIND_STAGE0 + 0)     /* uint[]: triangles in key order (refit, layout) */
#define CV_BIND_BUILD_SLOT_OF (CV_BIND_STAGE0 + 0)  /* uint[]: leaf slot of each reference */
#define CV_BIND_MORTON_KEYS (CV_BIND_STAGE0 + 1)    /* morton's output keys, then values */
#define CV_BIND_MORTON_VALS (CV_BIND_STAGE0 + 2)
#define CV_BIND_BUILD_NODES (CV_BIND_STAGE0 + 1)    /* CvBvhBuildNode[] */
#define CV_BIND_BUILD_COUNTERS (CV_BIND_STAGE0 + 2) /* uint[]: refit visit counters */
#define CV_BIND_BUILD_OFFSETS (CV_BIND_STAGE0 + 2)  /* uint[]: layout's node offsets */
#define CV_BIND_BUILD_LEFTS (CV_BIND_STAGE0 + 3)    /* uint[]: left turns per node (layout, emit) */
#define CV_BIND_LEAF_BOXES (CV_BIND_STAGE0 + 3)     /* vec4[2n]: triangle boxes (bounds, morton, refit) */
#define CV_BIND_TREELET_STAMPS (CV_BIND_STAGE0 + 3) /* uint[]: per-round change stamps */
#define CV_BIND_TREELET_SCHEDULE (CV_BIND_STAGE0 + 4)
#define CV_BIND_BUILD_STARTS (CV_BIND_STAGE0 + 4)   /* uint[]: final leaves per slot (layout) */
#define CV_BIND_EMIT_INFO (CV_BIND_STAGE0 + 4)      /* uint[]: emit's statistics */
#define CV_BIND_EMIT_LEAVES (CV_BIND_STAGE0 + 5)    /* uint[]: the starts, prefix-summed */
#define CV_BIND_BOUNDS_OUT (CV_BIND_STAGE0 + 1)     /* vec4[2]: bounds.comp's result */
#define CV_BIND_BOUNDS_DONE (CV_BIND_STAGE0 + 2)    /* uint: bounds.comp's finished groups */

/* ---- Triangle splitting (src/bvh/split.c; glsl/bvh/split_*.comp); the
 * reference triangles share the build's slot 2 with leaf_tris.comp ---- */
#define CV_BIND_SPLIT_BOUNDS (CV_BIND_STAGE0 + 0)   /* vec4[2]: the scene box */
#define CV_BIND_SPLIT_SUM_IN (CV_BIND_STAGE0 + 0)   /* float[]: split_sum's level */
#define CV_BIND_SPLIT_COUNTS (CV_BIND_STAGE0 + 1)   /* float priorities, then uint counts, offsets */
#define CV_BIND_SPLIT_SUM_OUT (CV_BIND_STAGE0 + 1)
#define CV_BIND_SPLIT_SUMS (CV_BIND_STAGE0 + 2)     /* float[]: priority sums */
#define CV_BIND_SPLIT_REF_TRIS (CV_BIND_STAGE0 + 2) /* uint[]: triangle of each reference */
#define CV_BIND_SPLIT_REF_BOXES (CV_BIND_STAGE0 + 3)

/* ---- Widening to 4-wide nodes (src/bvh/widen.c; glsl/bvh/widen*) ---- */
#define CV_BIND_WIDEN_BIN (CV_BIND_STAGE0 + 0)      /* CvBvhNode[]: the binary nodes */
#define CV_BIND_WIDEN_INFO (CV_BIND_STAGE0 + 1)
#define CV_BIND_WIDEN_QUEUE (CV_BIND_STAGE0 + 2)
#define CV_BIND_WIDEN_FLAGS (CV_BIND_STAGE0 + 3)    /* flags, then (scanned) ranks */
#define CV_BIND_WIDEN_NEED (CV_BIND_STAGE0 + 4)
#define CV_BIND_WIDEN_COST (CV_BIND_STAGE0 + 5)    /* vec4[]: per binary node (widen.glsl) */
#define CV_BIND_WIDEN_UP (CV_BIND_STAGE0 + 6)      /* uint[]: parents, then arrivals */

/* ---- Colour pass (src/color/color_pass.c; glsl/color/display.comp) ---- */
#define CV_BIND_COLOR_IN (CV_BIND_STAGE0 + 0)       /* vec4[]: linear RGBA */
#define CV_BIND_COLOR_OUT (CV_BIND_STAGE0 + 1)      /* vec4[]: display RGBA */

/* ---- Test probes (tests/; glsl/trace/test, glsl/bvh/rays_test.comp) ---- */
#define CV_BIND_PROBE_IN (CV_BIND_STAGE0 + 0)
#define CV_BIND_PROBE_OUT (CV_BIND_STAGE0 + 1)
/* rlpath/test_sample.comp runs beside the rlpath bindings: above them */
#define CV_BIND_RL_PROBE_OUT (CV_BIND_STAGE0 + 12)
#define CV_BIND_RL_PROBE_IN (CV_BIND_STAGE0 + 13)

#endif
