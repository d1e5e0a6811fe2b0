/* enums.h: the values a manifest names and later stages take: integrators,
 * EXR compressions, output formats and AOVs. Each enum has one table of
 * names (enums.c); the manifest reads them, the tracer and the writers take
 * the values, metadata and messages print the names. */
#ifndef CV_MANIFEST_ENUMS_H
#define CV_MANIFEST_ENUMS_H

#include <stdbool.h>
#include <stddef.h>

/* Light transport algorithm; the zero value is the default. */
enum cv_integrator {
    CV_INTEGRATOR_PATH = 0,    /* unidirectional path tracing with NEE and MIS */
    CV_INTEGRATOR_RLPATH,      /* path guided by a learned Q-table (trace/rlpath.h) */
    CV_INTEGRATOR_VOLPATH,     /* path with participating media (glsl/trace/medium) */
    CV_INTEGRATOR_BDPT,        /* bidirectional path tracing (trace/bdpt.h) */
    CV_INTEGRATOR_COUNT
};

enum cv_exr_compression {
    CV_EXR_ZIP = 0,  /* the default: lossless, good on noisy renders */
    CV_EXR_NONE,
    CV_EXR_ZIPS,
    CV_EXR_PIZ,
    CV_EXR_RLE,
    CV_EXR_DWAA,     /* lossy; needs OpenEXR >= 3.2 (cv_exr_compression_supported) */
    CV_EXR_DWAB,     /* lossy; likewise */
    CV_EXR_COMPRESSION_COUNT
};

/* rlpath.guide: what the learned table guides by. */
enum cv_rl_guide {
    CV_RL_GUIDE_ALL = 0,       /* all learned radiance (the default) */
    CV_RL_GUIDE_INDIRECT,      /* the learned radiance less lamps seen directly */
    CV_RL_GUIDE_COUNT
};

/* rlpath.method: how the guide learns. */
enum cv_rl_method {
    CV_RL_METHOD_QLEARN = 0,   /* Dahm and Keller's Q-table (the default) */
    CV_RL_METHOD_SDTREE,       /* Müller et al.'s spatial-directional trees */
    CV_RL_METHOD_COUNT
};

/* rlpath.filter: the sdtree method's training splat filters; the values
 * are CV_SD_FILTER_* bits (glsl/shared/sdtree.h). */
enum cv_rl_filter {
    CV_RL_FILTER_NONE = 0,        /* nearest leaf and quadrant */
    CV_RL_FILTER_SPATIAL,         /* Müller et al.'s spatial box filter */
    CV_RL_FILTER_DIRECTIONAL,     /* ... the directional one */
    CV_RL_FILTER_BOTH,
    CV_RL_FILTER_COUNT
};

enum cv_format_bits {
    CV_FORMAT_EXR = 1u << 0,
    CV_FORMAT_PNG = 1u << 1,
};

enum cv_aov_bits {
    CV_AOV_ALBEDO = 1u << 0,
    CV_AOV_NORMAL = 1u << 1,
    CV_AOV_DEPTH = 1u << 2,
    CV_AOV_OBJECT_ID = 1u << 3,       /* first hit's object, sample 0 (scene.h) */
    CV_AOV_MATERIAL_ID = 1u << 4,
    CV_AOV_CRYPTO_OBJECT = 1u << 5,   /* Cryptomatte layers CryptoObject00.. */
    CV_AOV_CRYPTO_MATERIAL = 1u << 6, /* CryptoMaterial00.. */
};

/* A table of names: names[i] is value i (for bit sets: bit 1 << i). */
struct cv_names {
    const char *const *names;
    size_t count;
};

extern const struct cv_names cv_integrator_names;
/* Every compression the EXR writer knows, in enum order. */
extern const struct cv_names cv_exr_compression_names;
/* The compressions a manifest offers: a subset, by name (exr.compression). */
extern const struct cv_names cv_manifest_compression_names;
extern const struct cv_names cv_rl_guide_names;
extern const struct cv_names cv_rl_method_names;
extern const struct cv_names cv_rl_filter_names;
extern const struct cv_names cv_format_names;   /* file extensions: "exr", "png" */
extern const struct cv_names cv_aov_names;

/* Name of value v, or NULL when out of range. */
const char *cv_name_of(const struct cv_names *t, unsigned v);
/* Name of the single bit `bit`, or NULL when it is not one bit in range. */
const char *cv_name_of_bit(const struct cv_names *t, unsigned bit);
/* Index of name in t, or -1. */
int cv_name_find(const struct cv_names *t, const char *name);

const char *cv_integrator_name(enum cv_integrator integrator);
const char *cv_exr_compression_name(enum cv_exr_compression c);
const char *cv_format_ext(unsigned format_bit);     /* "exr", "png" */
const char *cv_aov_name(unsigned aov_bit);          /* "albedo", "normal", "depth" */

#endif
