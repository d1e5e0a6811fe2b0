/* keys.h: every manifest key, declared once (cavalry-manifest(5)). Each row
 * of cv_manifest_keys says the key's dotted name, type, range or names,
 * default, where it lives in struct cv_job, how defaults merge into a job
 * and whether (and how) it enters the settings hash. The reader
 * (job_parse.c), the merge, the hash (job_hash.c), `cavalry-batch
 * --list-keys` and the man-page test all walk this table; a new key is a
 * new row (and its field in struct cv_job). */
#ifndef CV_MANIFEST_KEYS_H
#define CV_MANIFEST_KEYS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "manifest/enums.h"

/* Row ids, in table order: the order of "valid keys" lists and of the hash
 * text. Sections (color, exr, ...) come right before their keys. */
enum cv_key_id {
    CV_K_NAME,
    CV_K_SCENE,
    CV_K_OUTPUT,
    CV_K_FORMATS,
    CV_K_RESOLUTION,
    CV_K_CROP,
    CV_K_SPP,
    CV_K_TIME_LIMIT,
    CV_K_INTEGRATOR,
    CV_K_MAX_DEPTH,
    CV_K_SEED,
    CV_K_COLOR,
    CV_K_COLOR_CONFIG,
    CV_K_COLOR_DISPLAY,
    CV_K_COLOR_VIEW,
    CV_K_COLOR_LOOK,
    CV_K_COLOR_EXPOSURE,
    CV_K_AOVS,
    CV_K_EXR,
    CV_K_EXR_HALF,
    CV_K_EXR_COMPRESSION,
    CV_K_PNG,
    CV_K_PNG_BITS,
    CV_K_CAMERA,
    CV_K_CAMERA_FOV,
    CV_K_CAMERA_LOOKAT,
    CV_K_RLPATH,
    CV_K_RLPATH_GRID,
    CV_K_RLPATH_DIRECTIONS,
    CV_K_RLPATH_MIX,
    CV_K_RLPATH_GUIDE,
    CV_K_RLPATH_TRAIN,
    CV_K_MATRIX,
    CV_K_ENV,
    CV_K_ENV_SCALE,
    CV_K_ENV_ROTATE,
    CV_K_LIGHTS,
    CV_K_LIGHTS_SCALE,
    CV_K_ENV_FILE,
    CV_K_ALPHA,
    CV_K_RLPATH_METHOD,
    CV_K_RLPATH_FILTER,
    CV_K_RLPATH_FALLBACK,
    CV_K_COUNT
};

enum cv_key_type {
    CV_KT_SECTION,     /* a mapping of the rows named "<name>.*" */
    CV_KT_STRING,      /* char * (NULL: unset) */
    CV_KT_U32,         /* uint32_t in [min, max] */
    CV_KT_FLOAT,       /* float in [min, max] */
    CV_KT_DURATION,    /* double [seconds] > 0: 90, "90s", "1.5m", "2h" */
    CV_KT_BOOL,        /* bool */
    CV_KT_ENUM,        /* an enum (unsigned in size), one of names */
    CV_KT_BITS,        /* unsigned: a list of names, bit i for values' name i */
    CV_KT_RESOLUTION,  /* uint32_t[2]: [w, h] or "WxH", each side in [min, max] */
    CV_KT_LOOKAT,      /* float[9]: eye, at, up, as pbrt's LookAt */
    CV_KT_CROP,        /* float[4]: x0, x1, y0, y1, film fractions, as pbrt's
                        * cropwindow; hashed only when set */
    CV_KT_MATRIX,      /* a mapping of job keys to lists of their values: the
                        * job is expanded over them (manifest/matrix.h) */
    CV_KT_ROTATE,      /* float[4]: degrees, then the axis, as pbrt's Rotate */
    CV_KT_LIGHT_SCALES, /* struct cv_job_light_scales: light index -> factor */
};

enum cv_key_merge {
    CV_MERGE_FROM_DEFAULTS,  /* unset in the job: taken from `defaults` */
    CV_MERGE_JOB_ONLY,       /* never in `defaults` (name) */
};

enum cv_key_hash {
    CV_HASH_NO,              /* does not change the pixels (name, output, formats) */
    CV_HASH_YES,             /* "key=value", or "key=-" when unset */
    CV_HASH_OFF_DEFAULT,     /* only when set to other than the default: keys added
                              * later, so that older jobs keep their hashes */
    CV_HASH_WITH_STAMP,      /* the value, then the named file's size and mtime */
};

/* Where a value came from in the manifest (1-based; 0: not given). */
struct cv_key_at {
    unsigned line, col;
};

struct cv_key {
    const char *name;              /* dotted: "color.view" */
    enum cv_key_type type;
    const char *help;              /* one line, for --list-keys */
    double min, max;               /* U32, FLOAT, RESOLUTION: inclusive range */
    /* ENUM, BITS: the names a manifest accepts, in the order messages list
     * them; values: the enum's own table that a name maps into (NULL:
     * the index in names is the value). */
    const struct cv_names *names, *values;
    size_t offset;                 /* of the value in struct cv_job */
    size_t has;                    /* of its bool has_ flag; 0: none (strings, sections) */
    /* Output settings hold a value after loading: def when unset. Render
     * settings stay unset ("the scene's") instead. */
    bool fill_default;
    double def;                    /* default value, enum value or bits */
    const char *def_text;          /* the default in words, as the man page has it */
    enum cv_key_merge merge;
    enum cv_key_hash hash;
    bool allow_empty;              /* BITS: an empty list is valid */
    /* A rule beyond type and range: false with a message (the whole
     * "key: ..." text) in msg. value points at the read value: const char *
     * for strings, long long for U32, double for FLOAT. */
    bool (*check)(const void *value, char *msg, size_t n);
};

extern const struct cv_key cv_manifest_keys[CV_K_COUNT];

/* The row named `dotted`, or NULL. */
const struct cv_key *cv_key_find(const char *dotted);
/* The part after the last dot: "view" of "color.view". */
const char *cv_key_leaf(const struct cv_key *k);
/* Whether a job's matrix may vary k: every value key but name, output and
 * matrix itself (cavalry-manifest(5), "Matrix"). */
bool cv_key_in_matrix(const struct cv_key *k);
/* Whether k sits directly in section (NULL: the job's own level). */
bool cv_key_in(const struct cv_key *k, const struct cv_key *section);
/* "name<TAB>type<TAB>default<TAB>help" for every key, one a line. */
void cv_keys_print(FILE *out);

#endif
