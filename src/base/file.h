/* file.h: whole-file reads and path helpers. */
#ifndef CV_BASE_FILE_H
#define CV_BASE_FILE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* Reads a whole file; *data is NUL-terminated (one extra byte) and owned by
 * the caller (free()). Only a regular file of at most CV_MAX_INPUT_BYTES
 * (base/limits.h) is read: a device or a FIFO is refused without blocking. */
bool cv_read_file(const char *path, char **data, size_t *len, struct cv_error *err);
/* Standard input read to its end with the same size cap as cv_read_file;
 * label names it in messages ("<stdin>"). */
bool cv_read_stdin(const char *label, char **data, size_t *len, struct cv_error *err);
/* The same check for files that a library opens by name (images, gzip):
 * path names a regular file within the size limit. */
bool cv_input_check(const char *path, struct cv_error *err);

/* Newly allocated directory part of path ("." when there is none). */
char *cv_path_dirname(const char *path);
/* Newly allocated dir/rel, or rel itself when rel is absolute or dir empty. */
char *cv_path_join(const char *dir, const char *rel);
bool cv_path_exists(const char *path);
/* Newly allocated absolute form of path, spelled one way: joined to the
 * working folder, "//" and "." dropped, ".." taken lexically (symbolic
 * links are not followed: two spellings of one file through a link still
 * differ). For comparing paths, not for opening them. */
char *cv_path_normalize(const char *path);
/* Creates the folders above path that do not exist yet (mkdir -p of its
 * dirname), mode 0777 less the umask. */
bool cv_mkdir_parents(const char *path, struct cv_error *err);

#endif
