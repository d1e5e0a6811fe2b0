/* scene.h: the flat scene that every later stage reads. The parser and
 * builder (src/scene) fill it from pbrt-v3/v4 files; the GPU struct types
 * come from glsl/shared/scene.h so the arrays upload as they are. */
#ifndef CV_SCENE_SCENE_H
#define CV_SCENE_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "glsl/shared/medium.h"
#include "glsl/shared/scene.h"
#include "scene/animated.h"

/* The renderer's ids (glsl/shared/scene.h); names and defaults:
 * scene/filter.h. */
enum cv_filter_type {
    CV_FILTER_BOX = CV_FILTER_ID_BOX,
    CV_FILTER_TRIANGLE = CV_FILTER_ID_TRIANGLE,
    CV_FILTER_GAUSSIAN = CV_FILTER_ID_GAUSSIAN,
    CV_FILTER_MITCHELL = CV_FILTER_ID_MITCHELL,
    CV_FILTER_SINC = CV_FILTER_ID_SINC,
    CV_FILTER_COUNT
};

/* pbrt's defaults when the scene names no Sampler pixelsamples / Integrator
 * maxdepth. */
#define CV_DEFAULT_SPP 16u
#define CV_DEFAULT_MAX_DEPTH 5u

/* What the scene file asks of the render; the manifest may override it. */
struct cv_render_settings {
    uint32_t width, height;          /* full film resolution [pixels] */
    double crop[4];                  /* crop window x0, x1, y0, y1 in [0,1] */
    uint32_t spp;                    /* sampler pixelsamples, >= 1 */
    uint32_t max_depth;              /* integrator maxdepth, >= 1 */
    char *integrator;                /* "path", "volpath", ... as written; NULL: none */
    char *integrator_at;             /* "file:line:col" of the Integrator directive */
    char *sampler;                   /* "halton", "sobol", "independent", ... */
    char *film_filename;             /* as written, may be NULL */
    enum cv_filter_type filter;
    float filter_radius[2];          /* [pixels] */
    float filter_sigma;              /* gaussian */
    float filter_b, filter_c;        /* mitchell */
    float filter_tau;                /* sinc (Lanczos) */
    float exposure;                  /* film iso/exposure scale folded in, 1 by default */
};

/* Importer conventions the later stages rely on (beyond glsl/shared/scene.h):
 * - Vertex normals are stored as pbrt stores them: transformed to world
 *   space, normalised, and already negated for ReverseOrientation (and, for
 *   tessellated quadrics, for a handedness swap too). CV_TRI_REVERSE is for
 *   the geometric normal of triangles without vertex normals; with normals,
 *   face the geometric normal towards the shading normal, as pbrt does.
 * - The geometric normal of a triangle is cross(p1 - p0, p2 - p0).
 * - Image texels: row 0 is the top row of the file; pbrt looks images up at
 *   (u, 1 - v). 8-bit sources flagged CV_TEXF_SRGB were decoded to linear.
 * - coatedconductor: eta.xyz is the conductor's eta, eta.w the coat's.
 * - Area lights: L is radiance with "scale" and "power" applied; L.w the
 *   triangle's world-space area. light_power: luminance flux (area: Y(L) *
 *   area * pi * sides; point: 4 pi Y(I); spot: cone-weighted; distant and
 *   infinite: from the scene's bounding sphere).
 * - Infinite lights come first in lights[] (in file order), then the others
 *   (in file order): the GPU sums the environment over the leading infinite
 *   lights alone (glsl/trace/light/light.glsl). tri_light indices follow.
 * - Instanced objects are flattened (copied per instance), curves too.
 * - Quadrics are tessellated (see shapes.c for the accuracy).
 * - Moving shapes (below) keep object-space vertices; their triangles come
 *   after every static one. Their curves keep object-space control points
 *   and widths, in any place among the curves, CvCurve.info.w naming the
 *   shape. */

/* A shape (or object instance) under an animated transform, pbrt-v4's
 * AnimatedPrimitive: triangles [first, first + count), vertices
 * [first_vertex, first_vertex + n_vertices) and curves [first_curve,
 * first_curve + n_curves) are in its object space (an instance's moved
 * by minus the camera's position, about which pbrt-v4 interpolates it:
 * builder.c, render_origin), xf takes them to world space at a ray's time
 * (scene/animated.h); their
 * CV_TRI_REVERSE is ReverseOrientation alone, the renderer flipping for a
 * transform that swaps handedness at that time (glsl/bvh/motion.glsl). lo,
 * hi: the world-space box the shape stays in while it moves. */
struct cv_motion {
    uint32_t first, count;
    uint32_t first_vertex, n_vertices;
    uint32_t first_curve, n_curves;
    struct cv_animated xf;
    float lo[3], hi[3];
};

struct cv_scene {
    CvVertex *vertices;
    uint32_t n_vertices;
    CvTriangle *triangles;
    uint32_t n_triangles;
    int32_t *tri_light;              /* per triangle: light index or -1 */
    CvCurve *curves;                 /* curve primitives (src/scene/curves.c) */
    uint32_t n_curves;
    CvCurveXform *curve_xforms;      /* object spaces of curves under non-similarity transforms */
    uint32_t n_curve_xforms;
    struct cv_motion *motions;       /* moving shapes, their triangles in this order */
    uint32_t n_motions;

    CvMaterial *materials;
    uint32_t n_materials;
    char **material_names;           /* per material: name for reports, may be NULL entries */
    char **material_at;              /* per material: "file:line" of its directive, or NULL */

    /* ID mattes (object IDs, Cryptomatte): each triangle's object, an
     * index into object_names. An object is one Shape directive outside
     * ObjectBegin, named by its PLY file as written (plymesh) or by
     * "file:line" of the directive (file: the base name); or an ObjectBegin
     * definition, named by its name, whose instances all share it (as
     * Blender's instances of one object share its Cryptomatte ID). Names
     * may repeat (one PLY file used twice). */
    uint32_t *tri_object;
    char **object_names;
    uint32_t n_objects;

    CvTexture *textures;
    uint32_t n_textures;
    uint32_t *texels;                /* texel slots of 2 words (glsl/shared/scene.h) */
    uint64_t n_texels;               /* in slots */

    CvLight *lights;
    uint32_t n_lights;
    float *light_power;              /* per light: power used for the sampling CDF */

    /* measured BRDFs' tables (glsl/shared/measured.h), one block per file
     * in first-use order; a CV_MAT_MEASURED material's mix_a is the word
     * offset of its block */
    uint32_t *measured;
    size_t n_measured;               /* in words */

    CvMedium *media;                 /* glsl/shared/medium.h: media[0] is vacuum */
    uint32_t n_media;                /* 0 when the scene names none */
    uint32_t camera_medium;          /* the medium the camera sits in (0: vacuum) */
    float *medium_grids;             /* grid media's samples and majorants (medium.h) */
    size_t n_medium_grids;           /* in floats; 0 without grid media */
    /* Per medium, parallel to media: "file:line:col: medium \"name\"" of its
     * MakeNamedMedium (NULL for vacuum, number 0) and where its floats end
     * in medium_grids, for errors about the grid store's size. */
    struct cv_medium_source {
        char *at;
        size_t grid_end;
    } *medium_sources;

    /* pbrt-v4's BSSRDF tables of the subsurface materials
     * (glsl/shared/bssrdf.h: CV_BSSRDF_FLOATS each), one per (g, eta):
     * bssrdf_keys[2 i], [2 i + 1] */
    float *bssrdf;
    float *bssrdf_keys;
    uint32_t n_bssrdf;

    /* Fresnel tables of the conductors given by spectra
     * (glsl/shared/conductor_fresnel.h: 4 * CV_CONDUCTOR_FRESNEL_N floats
     * each); a CV_MATF_CONDUCTOR_FRESNEL material's k.w is its index */
    float *conductor_fresnel;
    uint32_t n_conductor_fresnel;

    CvCamera camera;
    struct cv_render_settings settings;

    float bounds_min[3], bounds_max[3];
    char *path;                      /* the scene file as given */
    /* Every other file the scene reads (Include/Import, PLY, textures,
     * spectra, env maps) as opened, each once, in first-use order: for
     * --resume's hash and for outputs that would overwrite an input. */
    char **inputs;
    size_t n_inputs, cap_inputs;
    unsigned warnings;               /* warnings emitted while loading */
    /* The light directives (LightSource, AreaLightSource) in the order they
     * are read, Includes in place: a job's lights.scale names a light by
     * its index here. light_source[i]: the directive lights[i] came from
     * (an area light's every triangle has its directive's). */
    struct cv_light_source {
        char *type;                  /* "point", "infinite", "diffuse", ... as written */
        char *at;                    /* "file:line:col" of the directive */
        bool area;                   /* AreaLightSource */
    } *light_sources;
    uint32_t n_light_sources;
    uint32_t *light_source;          /* per light, parallel to lights */
};

struct cv_scene_load_params {
    bool strict;                     /* warnings become errors */
    /* NULL, or a folder every file the scene reads (itself, Include and
     * Import, PLY meshes, textures, spectra) must lie in once symbolic
     * links and ".." are resolved: for scenes from untrusted hands. */
    const char *root;
};

/* Loads a pbrt-v3 or pbrt-v4 file (syntax detected per directive). On failure
 * returns false with err naming file:line:col; *out is untouched. */
bool cv_scene_load(const char *path, const struct cv_scene_load_params *params,
                   struct cv_scene **out, struct cv_error *err);
/* The same from text in memory; name stands for the file in messages and
 * Include paths resolve relative to its folder. */
bool cv_scene_load_string(const char *name, const char *text, size_t len,
                          const struct cv_scene_load_params *params, struct cv_scene **out,
                          struct cv_error *err);
/* Accepts NULL; clears the pointer. */
void cv_scene_destroy(struct cv_scene **scene);

/* How many triangles are static: those before the moving shapes'. */
uint32_t cv_scene_static_triangles(const struct cv_scene *s);

/* The box [out_lo, out_hi] holding the box [lo, hi] of a curve's object
 * space under its transform x (its eight corners' images; curves.c). */
void cv_curve_xform_box(const CvCurveXform *x, const double lo[3], const double hi[3], double out_lo[3],
                        double out_hi[3]);

/* Texel i (counted over the mip chain, level 0 first) of image texture t,
 * as linear RGBA, whichever way it is stored. i must lie inside the
 * texture's texels. */
void cv_scene_texel(const struct cv_scene *s, const CvTexture *t, uint64_t i, float rgba[4]);
/* The average of image texture t: its last mip level (1x1). */
void cv_scene_texture_average(const struct cv_scene *s, const CvTexture *t, float rgba[4]);
/* ... and that average's luminance (CV_LUMA): what pbrt-v4 normalises an
 * image light's power or illuminance by. */
double cv_scene_texture_luminance(const struct cv_scene *s, const CvTexture *t);

#endif
