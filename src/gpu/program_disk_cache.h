/* program_disk_cache.h: linked program binaries kept on disk between runs
 * (GL 4.1 glGetProgramBinary / glProgramBinary), so that a fresh process,
 * farm node or container sharing the folder skips the driver's compile of
 * the big compute shaders. Entries are keyed by the driver (GL_VENDOR,
 * GL_RENDERER, GL_VERSION) and the fully assembled source, defines
 * included. Anything wrong with an entry (truncated, corrupt, other format,
 * refused by the driver) is a miss, never an error: the caller rebuilds and
 * the entry is rewritten. Files are written to a temporary name in the same
 * folder and renamed, so concurrent processes never read half a file. */
#ifndef CV_GPU_PROGRAM_DISK_CACHE_H
#define CV_GPU_PROGRAM_DISK_CACHE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "gpu/context.h"

/* The folder: $CAVALRY_CACHE_DIR, else $XDG_CACHE_HOME/cavalry, else
 * $HOME/.cache/cavalry (empty or relative XDG/HOME values are skipped).
 * NULL when CAVALRY_CACHE_DIR is "off" or no variable gives one. Newly
 * allocated; the folder is not created here. */
char *cv_program_disk_cache_dir(void);

/* The binaries NVIDIA hands back hold its assembly, which its driver turns
 * into machine code on first use in every process unless its own disk
 * cache has it. So that one shared folder spares a fresh process both
 * steps, that cache goes to the "driver" subfolder of ours, unless the
 * user placed it (__GL_SHADER_DISK_CACHE_PATH) or there is no folder.
 * Sets the environment: call before the first EGL call of the process. */
void cv_program_disk_cache_place_driver_cache(void);

/* Counts since the cache was opened; what tests and -v logs look at. */
struct cv_program_disk_stats {
    bool enabled;          /* a folder is in use and the driver has formats */
    int n_formats;         /* GL_NUM_PROGRAM_BINARY_FORMATS */
    unsigned hits;         /* programs loaded from disk */
    unsigned misses;       /* no entry: compiled from source */
    unsigned rejected;     /* an entry was there but unusable: compiled */
    unsigned writes;       /* entries written */
};

struct cv_program_disk_cache;

/* Opens the cache for the current context (reads the environment and the
 * driver's binary formats, creates the folder). Never fails: when disabled
 * the returned cache does nothing but still reports its stats. */
struct cv_program_disk_cache *cv_program_disk_cache_open(const struct cv_gpu_info *info);
/* Accepts NULL; clears the pointer. */
void cv_program_disk_cache_close(struct cv_program_disk_cache **dc);

bool cv_program_disk_cache_enabled(const struct cv_program_disk_cache *dc);
void cv_program_disk_cache_stats(const struct cv_program_disk_cache *dc,
                                 struct cv_program_disk_stats *out);

/* A linked program for `source` (the assembled text given to the
 * compiler), or 0 on a miss; `label` names it in debug logs. Counts a hit,
 * a miss or a rejection. Leaves no GL error behind. */
GLuint cv_program_disk_cache_load(struct cv_program_disk_cache *dc, const char *source,
                                  const char *label);
/* Stores the binary of `prog`, which was linked from `source` with
 * GL_PROGRAM_BINARY_RETRIEVABLE_HINT set. Failures are logged at debug
 * level only. */
void cv_program_disk_cache_store(struct cv_program_disk_cache *dc, const char *source,
                                 GLuint prog, const char *label);

/* On-disk layout, in the host's byte order (a binary only serves the
 * machine's own driver anyway): this header; key_len bytes of key, which is
 * "cavalry program binary <version>\n<vendor>\n<renderer>\n<GL version>\n"
 * then the source; binary_len bytes of program binary. The name is a hash
 * of the key: program-<32 hex digits>.bin. Exposed for tests that damage
 * entries on purpose. */
#define CV_PROGRAM_FILE_MAGIC "CVPRGBN"
#define CV_PROGRAM_FILE_VERSION 1u
struct cv_program_file_header {
    char magic[8];         /* CV_PROGRAM_FILE_MAGIC with its NUL */
    uint32_t version;      /* CV_PROGRAM_FILE_VERSION */
    uint32_t format;       /* the GLenum glGetProgramBinary returned */
    uint32_t key_len;
    uint32_t binary_len;
    uint64_t checksum;     /* cv_program_file_checksum over key then binary */
};

/* FNV-1a 64 continued from h (start with CV_FNV_OFFSET). */
#define CV_FNV_OFFSET 0xcbf29ce484222325ull
uint64_t cv_program_file_checksum(uint64_t h, const void *data, size_t len);

#endif
