/* context.h: a headless OpenGL 4.5+ core context for compute. EGL with no
 * display and no surface (EGL_EXT_platform_device, then Mesa's surfaceless
 * platform); OSMesa as the last resort. One context serves a whole batch. */
#ifndef CV_GPU_CONTEXT_H
#define CV_GPU_CONTEXT_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "base/error.h"

enum cv_gpu_backend {
    CV_BACKEND_AUTO = 0,   /* EGL device, then EGL surfaceless, then OSMesa */
    CV_BACKEND_EGL,        /* EGL only (device, then surfaceless) */
    CV_BACKEND_OSMESA,     /* OSMesa only */
};

struct cv_gpu_params {
    int gpu_index;         /* EGL device index from --list-gpus; -1: choose */
    enum cv_gpu_backend backend;
    bool debug;            /* ask for a debug context (KHR_debug messages) */
};

/* What was found; filled once at creation. */
struct cv_gpu_info {
    char backend[32];      /* "egl-device", "egl-surfaceless", "osmesa" */
    int device_index;      /* EGL device index, -1 when not a device */
    char device[160];      /* DRM node or "software", "" when unknown */
    char vendor[128];
    char renderer[256];
    char version[128];
    int gl_major, gl_minor;
    bool software;         /* llvmpipe, softpipe, OSMesa */
    bool robust;           /* reset notification was granted */
    int max_compute_ssbo_blocks;
    int max_ssbo_bindings;
    int max_workgroup_invocations;
    long long max_ssbo_bytes;
    /* GL_MAX_TEXTURE_BUFFER_SIZE: texels one buffer texture may span (the
     * grid media's store reads it, trace/scene_upload.c; tests lower it to
     * act as a smaller driver) */
    long long max_texture_buffer_texels;
    /* GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS: samplers one kernel may use (so
     * how many pages the grid store may have) */
    int max_compute_texture_units;
    bool has_int64;        /* GL_ARB_gpu_shader_int64 */
    bool has_shader_ballot;/* GL_KHR_shader_subgroup or ARB_shader_ballot */
    bool has_nvx_memory_info;
};

struct cv_program_cache;
struct cv_buffer_pool;

/* What probes found of storage buffers beyond info.max_ssbo_bytes
 * (gpu/storage.h). */
struct cv_gpu_storage {
    uint64_t works;   /* the largest size that passed a probe, 0: none */
    uint64_t fails;   /* the smallest size that failed one, 0: none */
    unsigned probes;  /* probes run on this context */
};

struct cv_gpu {
    struct cv_gpu_info info;
    struct cv_gpu_storage storage;
    struct cv_program_cache *programs;  /* owned: see program.h */
    struct cv_buffer_pool *scratch;     /* owned: see buffer_pool.h */
    void *platform;                     /* owned by the backend file */
    void (*platform_destroy)(void *platform);
};

bool cv_gpu_create(const struct cv_gpu_params *params, struct cv_gpu **out,
                   struct cv_error *err);
/* Accepts NULL; clears the pointer. */
void cv_gpu_destroy(struct cv_gpu **gpu);

/* Prints every device the backends find (index, vendor, renderer, GL version)
 * and marks the one `params` would choose. Returns false only when none. */
bool cv_gpu_list(const struct cv_gpu_params *params, FILE *out, struct cv_error *err);

/* The devices "--gpu all" spreads a batch over, as EGL device indices, in
 * the order to use them; returns how many (at most max). Where the driver
 * gives CUDA ids (EGL_NV_device_cuda), the devices that have one, by id, so
 * that what the driver makes of CUDA_VISIBLE_DEVICES holds; else every
 * hardware device; else none, and the caller uses the one device that
 * cv_gpu_create would choose. Opens no context. */
int cv_gpu_all_devices(const struct cv_gpu_params *params, int *out, int max);

/* Checks an extension of the current context without libepoxy's helpers,
 * which cannot run under OSMesa. */
bool cv_gl_has_extension(const char *name);

#endif
