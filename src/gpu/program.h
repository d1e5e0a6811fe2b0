/* program.h: compute programs built from glsl/ files. The loader resolves
 * #include "..." (relative to the including file, then to glsl/), joins
 * lines continued by a backslash (as C does; not every driver does), injects
 * #defines after #version, and maps driver logs ("0(42)", "0:42(7)") back
 * to glsl/<file>:<line>. Programs are cached per context by path and defines,
 * so a batch compiles each once, and their linked binaries on disk (see
 * program_disk_cache.h: $CAVALRY_CACHE_DIR, else $XDG_CACHE_HOME/cavalry,
 * else ~/.cache/cavalry), so the next process on the machine need not
 * compile at all.
 *
 * A build has two halves: a request (assembly, the disk cache, then compile
 * and link handed to the driver) and the first use (cv_program_get: the
 * status query, which waits for the driver, and the binary's store). Where
 * the driver has GL_KHR_parallel_shader_compile (or the ARB one), a stage
 * requests every program it will need before it gets the first, so the
 * driver compiles them side by side in its threads, and while the CPU
 * goes on with other work. Elsewhere a request does nothing and
 * cv_program_get builds synchronously. */
#ifndef CV_GPU_PROGRAM_H
#define CV_GPU_PROGRAM_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "gpu/context.h"
#include "gpu/program_disk_cache.h"

struct cv_program {
    GLuint id;
    uint32_t local_size[3];  /* the shader's local_size_x/y/z */
    char *path;
};

/* Totals over this context's programs (cv_program_build_stats). */
struct cv_program_build_stats {
    bool parallel;            /* builds are requested ahead (see above) */
    unsigned requested;       /* cv_program_request calls that started a build */
    unsigned compiled;        /* built from source (counted at first use) */
    unsigned cache_hits;      /* loaded from the disk cache */
    unsigned failed;          /* builds that failed (counted at first use) */
    unsigned unused;          /* requested, not (yet) got */
    double build_ms;          /* sum over programs of the calling thread's time */
    double assemble_ms, load_ms, compile_ms, link_ms, wait_ms, store_ms;
    char slowest[192];        /* "path [defines]" of the costliest build */
    double slowest_ms;
};

struct cv_program_cache *cv_program_cache_create(void);
void cv_program_cache_destroy(struct cv_program_cache **cache);

/* Returns the program for glsl/<path> with `defines` ("NAME=VALUE" or
 * "NAME", NULL-terminated array, may be NULL), compiling it on first use.
 * The program stays owned by the cache. */
struct cv_program *cv_program_get(struct cv_gpu *gpu, const char *path,
                                  const char *const *defines, struct cv_error *err);

/* Starts building the program cv_program_get(gpu, path, defines) will
 * return, without waiting for the driver. Any failure is kept and reported
 * by that cv_program_get; a program requested and never got is no error.
 * Does nothing without parallel compilation or when the program is known. */
void cv_program_request(struct cv_gpu *gpu, const char *path, const char *const *defines);

/* The totals so far; unused counts requests not (yet) followed by a get. */
void cv_program_build_stats(const struct cv_gpu *gpu, struct cv_program_build_stats *out);

/* true: no request starts a build (the knob CAVALRY_PARALLEL_COMPILE=0,
 * to measure each program's own compile time). Call before any program. */
void cv_program_set_serial(struct cv_gpu *gpu, bool serial);

/* Generated GLSL spliced into a file: the line of glsl/<path> that begins
 * with `marker` is replaced by `text`, whose lines logs name as the file
 * `name` (e.g. OpenColorIO's function in glsl/color/display.comp). */
struct cv_glsl_splice {
    const char *marker;
    const char *text;
    const char *name;
};

/* cv_program_get for a file with generated text spliced in; cached (in
 * memory and on disk) by path, defines and the text. A file without the
 * marker line fails. */
struct cv_program *cv_program_get_spliced(struct cv_gpu *gpu, const char *path,
                                          const char *const *defines,
                                          const struct cv_glsl_splice *splice,
                                          struct cv_error *err);

/* cv_program_request for cv_program_get_spliced. */
void cv_program_request_spliced(struct cv_gpu *gpu, const char *path,
                                const char *const *defines,
                                const struct cv_glsl_splice *splice);

/* The disk cache's counts for this context (all zero and enabled false
 * before the first cv_program_get, or when the cache is off). */
void cv_program_cache_stats(const struct cv_gpu *gpu, struct cv_program_disk_stats *out);

/* The assembled source (includes expanded, defines injected, #line
 * directives naming file numbers); *names receives the file table (index
 * = GLSL source-string number), NULL-terminated. Exposed for tests. */
bool cv_glsl_assemble(const char *path, const char *const *defines, char **source,
                      char ***names, struct cv_error *err);

/* Rewrites a driver's info log so each location reads glsl/<file>:<line>. */
char *cv_glsl_map_log(const char *log, char *const *names);

/* Dispatches enough workgroups to cover n_x * n_y * n_z invocations of the
 * program's local size, then issues a shader-storage memory barrier: SSBO
 * writes are not visible to the next dispatch without it. */
void cv_program_dispatch(const struct cv_program *prog, uint32_t n_x, uint32_t n_y, uint32_t n_z);

/* One dispatch per call of ceil(n / local_size_x) groups, splitting across
 * the y dimension when n exceeds the driver's group-count limit. */
void cv_program_dispatch_1d(const struct cv_program *prog, uint64_t n);

/* glDispatchComputeIndirect with the groups at `offset` in the bound
 * GL_DISPATCH_INDIRECT_BUFFER, then a memory barrier for shader storage and
 * indirect commands (the next stage's arguments are written by shaders) plus
 * `barriers`. */
void cv_program_dispatch_indirect(const struct cv_program *prog, GLintptr offset,
                                  GLbitfield barriers);

/* Sets the program's uint uniform `name` (no binding needed; a name the
 * compiler dropped is ignored, as GL ignores location -1). */
void cv_program_set_uint(const struct cv_program *prog, const char *name, uint32_t v);

#endif
