/* manifest.h: the batch manifest (cavalry-manifest(5)), read with libyaml
 * and fully validated before anything renders. A loaded manifest is a list
 * of resolved jobs: each job's matrix expanded into its jobs
 * (manifest/matrix.h), `defaults` merged under each job (nested mappings key
 * by key), paths joined to the manifest's folder, outputs templated.
 *
 * Optional render settings carry a has_ flag (or a NULL string): unset
 * means "use what the scene file says". Every key is a row of
 * manifest/keys.h, which says its type, range, default and merge rule. Output settings
 * (formats, exr, png, aovs, output) always hold a value after loading; their
 * has_ flags only tell whether the manifest set them. */
#ifndef CV_MANIFEST_MANIFEST_H
#define CV_MANIFEST_MANIFEST_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"
#include "base/limits.h"
#include "manifest/enums.h"
#include "manifest/keys.h"

/* The only manifest version this reader understands. */
#define CV_MANIFEST_VERSION 1

struct cv_job_color {
    char *config;              /* OCIO config: resolved path, or an "ocio://" URI as
                                * written; NULL = unset (the built-in default) */
    char *display;             /* NULL = the config's default display */
    char *view;                /* NULL = the display's default view */
    char *look;                /* NULL = no look */
    bool has_exposure;
    float exposure;            /* [stops], added to the scene's exposure */
};

struct cv_job_exr {
    bool has_half, has_compression;
    bool half;                 /* default true: 16-bit half channels (float on request) */
    enum cv_exr_compression compression;   /* default CV_EXR_ZIP */
};

struct cv_job_png {
    bool has_bits;
    unsigned bits;             /* 8 (default) or 16 */
};

struct cv_job_camera {
    bool has_fov;
    float fov;                 /* [degrees], full angle of the shorter image axis, (0, 180) */
    bool has_lookat;
    float eye[3], at[3], up[3];   /* world space, as pbrt's LookAt */
};

struct cv_job_rlpath {
    bool has_grid, has_directions, has_mix, has_guide, has_train;
    uint32_t grid;             /* spatial cells per axis, >= 1 */
    uint32_t directions;       /* directional bins per cell, >= 1 */
    float mix;                 /* [0,1]: share of guided vs. BSDF sampling */
    enum cv_rl_guide guide;    /* default CV_RL_GUIDE_ALL */
    uint32_t train;            /* spp during which the table learns; 0: every pass */
    bool has_method;
    enum cv_rl_method method;  /* default CV_RL_METHOD_QLEARN */
    bool has_filter;
    enum cv_rl_filter filter;  /* sdtree's splat filters; unset: trace/sdtree.c's default */
    bool has_fallback;
    bool fallback;             /* unset: true (trace/guide_choice.h) */
};

/* Overrides of the scene's environment (its LightSource "infinite"
 * lights), applied to the loaded scene's light data per job: no reload. */
struct cv_job_env {
    char *file;                /* image replacing the environment's: resolved
                                * path (manifest folder joined); NULL: the scene's */
    bool has_scale, has_rotate;
    float scale;               /* multiplies the environment's radiance, >= 0 */
    float rotate[4];           /* [degrees], then the world-space axis x, y, z, as
                                * pbrt's Rotate, applied after the scene's transform */
};

/* Per-light factors on the scene's light sources, each named by its index
 * among the scene's LightSource and AreaLightSource directives in the order
 * they are read (cavalry-manifest(5), "Lights"). */
struct cv_light_scales {
    uint32_t n;
    struct cv_light_scale {
        uint32_t light;        /* index of the light directive, from 0 */
        float scale;           /* >= 0 */
    } v[CV_MAX_LIGHT_SCALES];  /* sorted by light, each light once */
};

struct cv_job_lights {
    bool has_scale;
    struct cv_light_scales scale;
};

/* One matrix key of an expanded job (manifest/matrix.h). */
struct cv_job_axis {
    enum cv_key_id key;
    char *label;               /* the value's label, [A-Za-z0-9._-]+ */
};

struct cv_job {
    char *name;                /* unique in the manifest, [A-Za-z0-9._-]+ */
    unsigned line, col;        /* 1-based position of the job in the manifest */
    char *scene;               /* path to open: manifest folder joined with scene_as_written */
    char *scene_as_written;    /* as in the manifest, for messages and the hash */
    char *output;              /* resolved output path without extension */
    bool has_formats, has_aovs;
    unsigned formats;          /* CV_FORMAT_* bits, never 0; default CV_FORMAT_EXR */
    unsigned aovs;             /* CV_AOV_* bits; default 0 */
    bool has_alpha;
    bool alpha;                /* alpha from coverage, transparent background; default false */

    bool has_resolution;
    uint32_t width, height;    /* [pixels] */
    bool has_crop;
    float crop[4];             /* x0, x1, y0, y1: film fractions in [0, 1], x0 < x1,
                                * y0 < y1 (pbrt's cropwindow); unset: the scene's */
    bool has_spp;
    uint32_t spp;              /* samples per pixel, >= 1 */
    bool has_time_limit;
    double time_limit;         /* [seconds], > 0 */
    bool has_integrator;
    enum cv_integrator integrator;
    bool has_max_depth;
    uint32_t max_depth;        /* >= 1 */
    bool has_seed;
    uint32_t seed;

    struct cv_job_color color;
    struct cv_job_exr exr;
    struct cv_job_png png;
    struct cv_job_camera camera;
    struct cv_job_rlpath rlpath;
    bool has_matrix;           /* written with a matrix (then it is one of its
                                * expansions, with axes) */
    struct cv_job_env env;
    struct cv_job_lights lights;
    /* A job expanded from a matrix: the name of the job as written and,
     * per matrix key in written order, the label of its value; NULL and 0
     * for other jobs. Owned. */
    char *matrix_of;
    struct cv_job_axis *axes;
    size_t n_axes;

    /* Where each key's value was written (in the job, or in defaults for
     * what the job took from there); {0, 0} for keys not given. */
    struct cv_key_at at[CV_K_COUNT];

    /* 16 lowercase hex digits: FNV-1a 64 of a canonical text of every setting
     * that changes the rendered pixels or the files written (everything but
     * name, output and formats), plus the scene file's size and mtime. Equal
     * hashes mean "same render"; --resume compares it with the one stored in
     * an output's metadata. */
    char *settings_hash;
};

struct cv_manifest {
    char *path;                /* as given to cv_manifest_load */
    struct cv_job *jobs;       /* in manifest order */
    size_t n_jobs;
};

/* The name of standard input in messages and cv_manifest.path. */
#define CV_MANIFEST_STDIN "<stdin>"

/* Reads and validates the manifest at path ("-": standard input, read
 * whole with the size cap of a file; its paths are relative to the working
 * folder), including that every scene (and
 * colour config) file it names exists. On failure returns false, *out is
 * NULL and err holds every problem found, one "path:line:col: message" per
 * line, in document order. On success *out is owned by the caller. */
bool cv_manifest_load(const char *path, struct cv_manifest **out, struct cv_error *err);

/* Accepts NULL and *m == NULL; clears *m. */
void cv_manifest_destroy(struct cv_manifest **m);

/* Newly allocated "<output>.<ext>" (free()); ext without the dot, e.g. "exr";
 * NULL ext gives the output path alone. */
char *cv_job_output_path(const struct cv_job *job, const char *ext);

/* The job with this name, or NULL. */
const struct cv_job *cv_manifest_find_job(const struct cv_manifest *m, const char *name);

#endif
