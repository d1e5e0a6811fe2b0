/* atomic_file.h: write a file so that its final name only ever holds a
 * complete file. Data goes to a hidden temporary file in the same folder
 * (".NAME.XXXXXX.tmp", same filesystem, so the rename is atomic), is synced
 * to disk, and is renamed over the final name on commit. On any failure the
 * temporary file is removed and an existing file under the final name is
 * left untouched. A process killed mid-write leaves only its hidden
 * temporary file. A symbolic link under the final name is replaced, not
 * followed. */
#ifndef CV_OUTPUT_ATOMIC_FILE_H
#define CV_OUTPUT_ATOMIC_FILE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

struct cv_atomic_file;

/* Creates the temporary file next to path, first removing path's stale
 * temporary files (".NAME.xxxxxx.tmp", left by a killed writer). The error names the folder and
 * the reason (no such directory, permission denied, read-only filesystem). */
bool cv_atomic_open(const char *path, struct cv_atomic_file **out, struct cv_error *err);

/* Writes all of buf at the current end of what was written so far. */
bool cv_atomic_write(struct cv_atomic_file *f, const void *buf, size_t len,
                     struct cv_error *err);
/* Writes all of buf at byte offset (pwrite semantics, for writers that seek
 * back, like OpenEXR's offset table). Safe to call from several threads. */
bool cv_atomic_write_at(struct cv_atomic_file *f, const void *buf, size_t len,
                        uint64_t offset, struct cv_error *err);

/* The final path and the temporary one (owned by f). */
const char *cv_atomic_path(const struct cv_atomic_file *f);
const char *cv_atomic_temp_path(const struct cv_atomic_file *f);

/* Syncs, closes and renames the temporary file over the final name, then
 * syncs the folder. Always frees *f and sets it to NULL; on failure the
 * temporary file is removed. A write error seen earlier makes commit fail. */
bool cv_atomic_commit(struct cv_atomic_file **f, struct cv_error *err);

/* Closes and removes the temporary file; accepts NULL and *f == NULL. */
void cv_atomic_abort(struct cv_atomic_file **f);

/* Bytes that writes may still take before they fail with errno `errnum`
 * (e.g. ENOSPC), as they would on a full disk: tests pass one to see how a
 * writer fails. Every file given the same limit draws on it. */
struct cv_write_limit {
    long long bytes;
    int errnum;
};

/* Makes f's later writes draw on `limit` (NULL: no limit, the default);
 * the caller keeps it alive until f is committed or aborted. */
void cv_atomic_set_limit(struct cv_atomic_file *f, struct cv_write_limit *limit);

#endif
