/* builder.h: the graphics state behind the parser (transform stack,
 * attributes, named materials/textures/media, object instances) and the
 * flat scene it grows. Internal to src/scene: the parser calls one cv_b_*
 * function per directive; shapes, materials, textures, lights and the camera
 * each live in their own file but share this state. */
#ifndef CV_SCENE_BUILDER_H
#define CV_SCENE_BUILDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "scene/params.h"
#include "scene/scene.h"
#include "scene/transform.h"

struct cv_loc {
    const char *file;
    int line, col;
};

struct cv_area_state {
    bool on;
    double L[3];         /* already multiplied by scale (and power, per shape) */
    double power;        /* v4 "power" (watts), <= 0 when absent */
    bool twosided;
    int tex;             /* emission texture or -1 */
    uint32_t source;     /* its directive (cv_scene.light_sources) */
};

struct cv_gstate {
    struct cv_mat4 ctm;
    bool reverse;
    int material;        /* index into scene materials, -1: default */
    struct cv_area_state area;
    bool transform_only; /* pushed by TransformBegin */
    /* pbrt's two transforms: ctm at the start time, ctm_end at the end time
     * (TransformTimes); transform directives change those that `active`
     * (ActiveTransform) names. Geometry and lights use ctm: only the
     * camera moves (a differing ctm_end elsewhere warns). */
    struct cv_mat4 ctm_end;
    unsigned active;     /* CV_XFORM_START | CV_XFORM_END */
    int medium_inside, medium_outside; /* MediumInterface: media numbers, 0 vacuum */
};

/* A material copied for a MediumInterface (media.c). */
struct cv_media_copy {
    uint32_t base, word, copy;
};
#define CV_XFORM_START 1u
#define CV_XFORM_END 2u

/* A mesh in object space handed to cv_b_emit_mesh; arrays are borrowed. */
struct cv_mesh {
    size_t n_verts, n_tris;
    const float *P;        /* 3 per vertex */
    const float *N;        /* 3 per vertex or NULL */
    const float *uv;       /* 2 per vertex or NULL */
    const uint32_t *idx;   /* 3 per triangle, all < n_verts (checked by caller) */
    bool analytic;         /* tessellated quadric: N flips on handedness too (pbrt) */
    const char *name;      /* the object's name for ID mattes (scene.h); NULL: "file:line" */
    uint32_t object;       /* 1 + an object id made before (instances); 0: a new object */
};

struct cv_named {
    char *name;
    int index;
};

struct cv_object {
    char *name;
    CvVertex *v;
    size_t nv, cap_v;
    CvTriangle *t;
    size_t nt, cap_t;
    CvCurve *c;             /* curves in the definition's space (curves.c) */
    size_t nc, cap_c;
    uint32_t matte_object;  /* 1 + its object id in the scene (scene.h); 0 before an instance */
};

struct cv_coordsys {
    char *name;
    struct cv_mat4 m, m_end;     /* at the start and end times */
};

struct cv_builder {
    struct cv_scene *s;
    size_t cap_v, cap_t, cap_m, cap_tex, cap_texel, cap_l;
    size_t cap_object_names;
    size_t cap_curves;
    size_t cap_curve_xforms;

    struct cv_gstate gs;
    struct cv_gstate *stack;
    size_t n_stack, cap_stack;
    struct cv_loc *stack_loc;    /* where each push happened */

    struct cv_named *materials_named;
    size_t n_materials_named, cap_materials_named;
    struct cv_named *float_tex, *spec_tex;
    size_t n_float_tex, cap_float_tex, n_spec_tex, cap_spec_tex;
    struct cv_named *media_named;  /* name -> medium number (media.c) */
    size_t n_media_named, cap_media_named, cap_media;
    struct cv_media_copy *media_copies;
    size_t n_media_copies, cap_media_copies;
    size_t cap_medium_grids;       /* capacity of s->medium_grids (media_grid.c) */
    struct cv_coordsys *coordsys;
    size_t n_coordsys, cap_coordsys;
    struct cv_object *objects;
    size_t n_objects, cap_objects;
    int cur_object;              /* -1 outside ObjectBegin */

    bool strict;
    bool world;                  /* after WorldBegin */
    bool camera_set;
    struct cv_mat4 camera_to_world, camera_to_world_end;
    double transform_times[2];   /* TransformTimes start, end */
    double shutter[2];           /* the camera's shutteropen, shutterclose */
    /* camera and film parameters, applied when the scene is finished */
    uint32_t cam_type;
    double fov, lensradius, focaldistance, frameaspect, screen[4];
    bool has_screen;
    int xres, yres;
    double crop[4];
    double iso, exposure_time, film_exposure_time;
    int default_material;        /* created on first use, -1 before */
    char *color_space;
    struct cv_named *images;     /* "path|srgb" -> texture index */
    size_t n_images, cap_images;
    char *main_dir;              /* folder of the top-level scene file */
    char *root;                  /* real path every file read must lie in; NULL: any */
    char **paths;                /* every file read, kept for locations */
    size_t n_paths, cap_paths;
    uint32_t light_source;       /* the directive of the lights added next */
    size_t cap_motions;
    struct cv_mat4 motion_ctm;   /* the start transform of the moving shape being emitted */
    struct cv_mat4 motion_pivot; /* object space from emitted space: the camera's position
                                  * for a moving instance, else identity (render_origin) */
    uint32_t motion_nt0, motion_nv0, motion_nc0;
    struct cv_named *measured_files; /* path -> word offset in the scene's measured tables */
    size_t n_measured_files, cap_measured_files, cap_measured;
    size_t cap_light_sources;
};

/* Reports a warning with location; false (err set) when strict. */
bool cv_b_warn(struct cv_builder *b, struct cv_error *err, const struct cv_loc *loc,
               const char *fmt, ...) CV_PRINTF(4, 5);
/* Warns about every parameter no lookup used. */
bool cv_b_check_unused(struct cv_builder *b, struct cv_params *ps, const char *directive,
                       struct cv_error *err);

void cv_b_init(struct cv_builder *b, struct cv_scene *s, bool strict);
void cv_b_free(struct cv_builder *b);
/* Fills the camera, bounds, light powers; trims arrays. */
bool cv_b_finish(struct cv_builder *b, struct cv_error *err);

/* Appends a mesh with the current transform, material, area light. */
bool cv_b_emit_mesh(struct cv_builder *b, const struct cv_mesh *m, const struct cv_loc *loc,
                    struct cv_error *err);
/* Copies object `index` with the current transform (flattened instancing). */
/* Moving shapes (scene.h, cv_motion): whether what the current
 * transforms place now (a shape of `type`, or an instance when type is
 * NULL) moves, or, where Cavalry cannot move it, is placed at its start
 * transform (*why says why; NULL when the transforms agree). */
bool cv_b_can_move(struct cv_builder *b, const char *type, const char **why);
/* Between these two, geometry is emitted in object space (the start
 * transform set aside); the end records what was emitted as one moving
 * shape. An instance (`instance` true) is emitted relative to the camera's
 * position and its transforms interpolated about it, as pbrt-v4 does
 * (builder.c, render_origin). */
void cv_b_motion_begin(struct cv_builder *b, bool instance);
void cv_b_motion_end(struct cv_builder *b);
bool cv_b_instance(struct cv_builder *b, int index, const struct cv_loc *loc, struct cv_error *err);
uint32_t cv_b_add_material(struct cv_builder *b, const CvMaterial *m, const char *name);
/* Records where material `index` was made ("file:line", for ID mattes). */
void cv_b_material_at(struct cv_builder *b, int index, const struct cv_loc *loc);
/* A new ID-matte object (scene.h) named `name`; its id. */
uint32_t cv_b_add_object(struct cv_builder *b, const char *name);
/* The same, named "file:line" after the directive at loc. */
uint32_t cv_b_add_object_at(struct cv_builder *b, const struct cv_loc *loc);
int cv_b_add_texture(struct cv_builder *b, const CvTexture *t);
uint32_t cv_b_add_light(struct cv_builder *b, const CvLight *l, float power);
/* Records a light directive (scene.h: light_sources); returns its index. */
uint32_t cv_b_light_source(struct cv_builder *b, const char *type, bool area,
                           const struct cv_loc *loc);
/* A file named in the scene: relative to the folder of the file that names
 * it (dir); failing that, relative to the top-level file's folder, which is
 * what pbrt itself does for nested includes. Newly allocated. NULL, with
 * err naming the path, when the file is no regular file within the input
 * size limit, or lies outside the scene root (symbolic links and ".."
 * resolved); the caller adds the location. */
char *cv_b_resolve(struct cv_builder *b, const char *dir, const char *name, struct cv_error *err);
/* Confines every file read to the folder root (--scene-root); false, with
 * err set, when root is no folder. */
bool cv_b_set_root(struct cv_builder *b, const char *root, struct cv_error *err);
/* path lies inside the scene root (true when there is none). */
bool cv_b_check_root(struct cv_builder *b, const char *path, struct cv_error *err);
int cv_b_lookup(const struct cv_named *v, size_t n, const char *name);
void cv_b_set_named(struct cv_named **v, size_t *n, size_t *cap, const char *name, int index);

/* Directives (see the files named). */
/* Shape "curve" with the current transform and material (curves.c). */
bool cv_b_curve(struct cv_builder *b, struct cv_params *ps, const struct cv_loc *loc, struct cv_error *err);
/* Appends curves src[0..n) placed by M to the open object definition, or
 * else to the scene: carried by M (control points, widths by its scale,
 * ribbon normals) when M is a similarity and src are not kept in their
 * object space, else kept there with M composed into their CvCurveXform
 * (glsl/shared/scene.h); CV_TRI_REVERSE flips in their words when M swaps
 * handedness, and object (when not UINT32_MAX) becomes their ID-matte
 * object. (curves.c) */
bool cv_b_place_curves(struct cv_builder *b, const CvCurve *src, size_t n, const struct cv_mat4 *M,
                       uint32_t object, const struct cv_loc *loc, struct cv_error *err);
/* The material index new shapes get (pbrt's default diffuse made on first use). */
uint32_t cv_b_current_material(struct cv_builder *b);
bool cv_b_shape(struct cv_builder *b, const char *type, struct cv_params *ps,
                const struct cv_loc *loc, const char *dir, struct cv_error *err);  /* shapes.c */
bool cv_b_material(struct cv_builder *b, const char *type, const char *name,
                   struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                   struct cv_error *err, int *out);                              /* materials.c */
bool cv_b_texture(struct cv_builder *b, const char *name, const char *kind, const char *cls,
                  struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                  struct cv_error *err);                                         /* texture.c */
/* Loads an image file as an image texture (mip-mapped); srgb: decode 8-bit
 * sources as sRGB. Returns the index or -1 (err set). Cached by path. */
int cv_b_image_texture(struct cv_builder *b, const char *file, const char *dir, bool srgb,
                       const struct cv_loc *loc, struct cv_error *err);
/* The same for a pbrt-v4 parameter that asks for `srgb` (its "encoding",
 * or linear for a normal map): pbrt-v4 decodes every 8-bit format but PNG
 * from sRGB whatever is asked (cv_image_always_srgb), so a linear request
 * for one is read as sRGB, with a warning at loc saying so. */
int cv_b_image_texture_v4(struct cv_builder *b, const char *file, const char *dir, bool srgb,
                          const char *what, const struct cv_loc *loc, struct cv_error *err);
/* Texture `id` times rgb, as a new texture: a copy of its node with the
 * factor in its scale where rgb is grey and the node does not invert
 * (texture.glsl's cv_tex_finish multiplies each node's result by its
 * scale), else a scale node over it. For a material's "scale" on a
 * textured colour. Returns the new index. */
int cv_b_texture_times(struct cv_builder *b, int id, const double rgb[3]);
bool cv_b_light(struct cv_builder *b, const char *type, struct cv_params *ps,
                const struct cv_loc *loc, const char *dir, struct cv_error *err); /* lights.c */
bool cv_b_area_light(struct cv_builder *b, const char *type, struct cv_params *ps,
                     const struct cv_loc *loc, const char *dir, struct cv_error *err);
bool cv_b_medium(struct cv_builder *b, const char *name, struct cv_params *ps,
                 const struct cv_loc *loc, const char *dir, struct cv_error *err); /* media.c */
/* MediumInterface inside outside ("" is vacuum) into the graphics state. */
/* pbrt-v4's "uniformgrid", "rgbgrid" and "nanovdb" media into *m, their
 * grids appended to the scene's grid buffer; the medium's transform is the
 * current CTM. */
bool cv_b_medium_grid(struct cv_builder *b, const char *name, const char *type,
                      struct cv_params *ps, const struct cv_loc *loc, const char *dir,
                      CvMedium *m, struct cv_error *err); /* media_grid.c */
/* A medium's Henyey-Greenstein "g" (default 0); outside (-1, 1) it warns
 * (an error with --strict) and is clamped to +-0.999. */
bool cv_b_medium_g(struct cv_builder *b, struct cv_params *ps, const char *name,
                   const struct cv_loc *loc, double *g, struct cv_error *err); /* media.c */
/* Appends n values times scale to the scene's grid buffer (as floats);
 * returns their offset. */
uint32_t cv_b_medium_floats(struct cv_builder *b, const double *v, size_t n, double scale);
/* m->to_grid from the CTM's inverse (render to medium space) and pbrt-v4's
 * Bounds3f(p0, p1) (the corners in any order), their low corner and size
 * in medium space to lo and size where not NULL; empty bounds or a
 * singular CTM are errors. */
bool cv_b_medium_bounds(struct cv_builder *b, struct cv_params *ps, const char *name,
                        const struct cv_loc *loc, CvMedium *m, double lo[3], double size[3],
                        struct cv_error *err);
/* pbrt-v4's "cloud" medium into *m, its parameters and majorant grid
 * appended to the grid buffer; the medium's transform is the current
 * CTM. */
bool cv_b_medium_cloud(struct cv_builder *b, const char *name, struct cv_params *ps,
                       const struct cv_loc *loc, const char *dir, CvMedium *m,
                       struct cv_error *err); /* media_cloud.c */
/* pbrt-v4's "nanovdb" medium into *m (type, coefficients, lattices,
 * transform; not its majorant grid, which cv_b_medium_grid adds): the
 * float grids "density" and "temperature" of its file. */
bool cv_b_medium_nanovdb(struct cv_builder *b, const char *name, struct cv_params *ps,
                         const struct cv_loc *loc, const char *dir, CvMedium *m,
                         struct cv_error *err); /* media_nanovdb.c */
/* Grid medium *m emits the blackbody of (lookup of temperature grid
 * `grid` - off) x scale above 100 K; top: the hottest a lookup gives. */
void cv_b_medium_blackbody(struct cv_builder *b, CvMedium *m, uint32_t grid, double off,
                           double scale, double top); /* media_grid.c */
bool cv_b_medium_interface(struct cv_builder *b, const char *inside, const char *outside,
                           const struct cv_loc *loc, struct cv_error *err);
/* material, or its copy carrying the current MediumInterface when that
 * separates two media. */
uint32_t cv_b_material_in_media(struct cv_builder *b, uint32_t material);
bool cv_b_camera(struct cv_builder *b, const char *type, struct cv_params *ps,
                 const struct cv_loc *loc, struct cv_error *err);                /* camera.c */
bool cv_b_film(struct cv_builder *b, const char *type, struct cv_params *ps,
               const struct cv_loc *loc, struct cv_error *err);
void cv_b_finish_camera(struct cv_builder *b);

/* Resolves a colour parameter (rgb, spectrum, blackbody) to linear RGB.
 * kind says how a spectrum is read: reflectance, unbounded (eta, k) or
 * illuminant (normalised to luminance 1, as pbrt-v4 does for lights).
 * Returns false on error; *found false when absent. (spectrum.c) */
enum cv_spectrum_kind {
    CV_SPEC_REFLECTANCE,
    CV_SPEC_UNBOUNDED,
    CV_SPEC_ILLUMINANT,
};
bool cv_b_color(struct cv_builder *b, struct cv_params *ps, const char *name,
                enum cv_spectrum_kind kind, const char *dir, double rgb[3], bool *found,
                struct cv_error *err);
/* A colour-or-texture slot: sets *tex (-1 if constant) and rgb. */
/* pbrt-v4's BlackbodySpectrum(T) (Planck's law over its peak) as its
 * cie1931 sensor records it: the CIE functions' integrals over it, not
 * normalised, to linear Rec.709. (spectrum.c) */
void cv_blackbody_sensor_rgb(double T, double rgb[3]);
bool cv_b_color_tex(struct cv_builder *b, struct cv_params *ps, const char *name,
                    enum cv_spectrum_kind kind, const char *dir, double rgb[3], int *tex,
                    struct cv_error *err);
/* An index of refraction: float, rgb (green), named glass or spectrum at 550 nm. */
bool cv_b_scalar_eta(struct cv_builder *b, struct cv_params *ps, const char *name,
                     const char *dir, double *eta, bool *found, struct cv_error *err);
/* A spectrum parameter as pbrt-v4 renders it, for what RGB cannot stand
 * for (conductors' eta and k): *pairs (malloc'd, the caller frees) and *n
 * its (lambda [nm], value) pairs, ascending (a float: one pair, a
 * constant), from a float, a named metal spectrum (cv_metal_spectrum), a
 * spectrum file or inline pairs; *pairs NULL when the parameter is absent
 * or something else (rgb, another named spectrum, a texture). Reads the
 * parameter's value only: cv_b_color reports its errors and marks it
 * used. (spectrum.c) */
bool cv_b_spectrum(struct cv_builder *b, struct cv_params *ps, const char *name,
                   const char *dir, double **pairs, size_t *n, struct cv_error *err);
/* A float-or-texture slot. */
bool cv_b_float_tex(struct cv_builder *b, struct cv_params *ps, const char *name,
                    double *val, int *tex, struct cv_error *err);

#endif
