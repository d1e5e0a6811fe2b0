/* scene_defines.h: the feature defines a scene's programs are built with,
 * one row each, and so their count, which sizes every list that holds them
 * (render.c's stage lists, bdpt.c's kernel list). Code for what a scene
 * lacks stays out of the kernels. A new define is one row.
 *
 * A row is X(name, when). Only render.c's stage_programs expands the
 * table: there `when` reads gs (the scene on the GPU, trace/scene_upload.h),
 * p (the job) and ops (its integrator), and `name` is read only where
 * `when` holds. */
#ifndef CV_TRACE_SCENE_DEFINES_H
#define CV_TRACE_SCENE_DEFINES_H

#include "trace/shade_bins.h"

#define CV_SCENE_DEFINES(X) \
    X("CV_EMPTY_SCENE", gs->empty) \
    X("CV_AOVS", p->aovs) \
    X("CV_HAS_ALPHA", gs->has_alpha) \
    X("CV_BSDF_BASIC", gs->basic_materials) \
    /* the texture loops' arrays live in local memory and take registers, \
     * which made the shade stages several times slower on scenes without \
     * textures (bench/RESULTS.md, "Figures behind the code") */ \
    X("CV_NO_ENV", !gs->has_env) \
    /* the spherical cameras' rays: the camera ray is made in the shade \
     * kernels too (regenerate.glsl), where every branch costs registers; \
     * generate.comp, built without these defines, has them always */ \
    X("CV_SPHERICAL_CAMERA", gs->spherical_camera) \
    /* a cut-out emitter's light samples test its alpha (light/light.glsl) */ \
    X("CV_ALPHA_EMITTERS", gs->alpha_emitters) \
    X("CV_NO_TEXTURES", !gs->has_textures) \
    /* a tree deeper than the default stack allows is traced with a larger \
     * one (bvh/bvh.h) */ \
    X(cv_bvh_stack_define(gs->bvh), cv_bvh_stack_define(gs->bvh) != NULL) \
    /* curves: their own tree beside the triangles' (glsl/bvh/curves.glsl) */ \
    X("CV_HAS_CURVES", gs->has_curves) \
    /* moving shapes: their own trees beside (glsl/bvh/motion.glsl) */ \
    X("CV_HAS_MOTION", gs->has_motion) \
    X("CV_NO_TRIANGLES", (gs->has_curves || gs->has_motion) && gs->no_triangles) \
    /* BSDF code for materials the scene lacks stays out of the shade \
     * kernels: every material of a bin pays for the registers of its \
     * largest case (bench/RESULTS.md, "Merged main against f42fcef") */ \
    X("CV_NO_HAIR", !gs->has_hair) \
    /* the coated walk (bsdf/layered.glsl), where no material takes it: \
     * path's and rlpath's shade bins leave it out by bin, and this keeps \
     * it out of the one-kernel integrators (bdpt) too */ \
    X("CV_NO_LAYERED", !(gs->shade_bins & (1u << CV_SHADE_BIN_WALK))) \
    X("CV_NO_COAT_CLOSED", !gs->has_coat_closed) \
    /* BSSRDF probes in the intersect and shade stages (sss_probe.glsl, \
     * sss_vertex.glsl): only where a material is subsurface */ \
    X("CV_HAS_SUBSURFACE", gs->has_subsurface) \
    X("CV_NO_MEASURED", !gs->has_measured) \
    /* conductors given by spectra: their Fresnel tables \
     * (glsl/shared/conductor_fresnel.h) */ \
    X("CV_CONDUCTOR_TABLES", gs->has_conductor_fresnel) \
    /* media are tracked by an integrator that renders them, in a scene \
     * that has them */ \
    X("CV_MEDIA", ops->media && gs->has_media) \
    /* grid media's lookups and majorant walk (glsl/trace/medium/grid.glsl) */ \
    X("CV_MEDIUM_GRIDS", ops->media && gs->has_medium_grids) \
    /* a grid store in pages (trace/scene_upload.h) */ \
    X(gs->grid_pages_define, ops->media && gs->grid_pages_define[0]) \
    X(gs->grid_page_texels_define, ops->media && gs->grid_page_texels_define[0]) \
    /* the cloud's noise (glsl/trace/medium/cloud.glsl) */ \
    X("CV_MEDIUM_CLOUDS", ops->media && gs->has_medium_cloud)

#define CV_SCENE_DEFINE_COUNT_ROW(name, when) +1
/* The most scene defines one program gets: one per row. */
enum { CV_SCENE_DEFINES_MAX = 0 CV_SCENE_DEFINES(CV_SCENE_DEFINE_COUNT_ROW) };

#endif
