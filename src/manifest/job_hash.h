/* job_hash.h: the settings hash that --resume compares. A job's settings are
 * written as a canonical text (one "key=value" line per setting, fixed order,
 * "-" for unset, floats with %.9g so the same float always prints the same)
 * and hashed with FNV-1a 64 (offset basis 0xcbf29ce484222325, prime
 * 0x100000001b3, over the bytes of the text). Not a cryptographic hash: it
 * only has to notice that a job changed, not resist someone forging one. */
#ifndef CV_MANIFEST_JOB_HASH_H
#define CV_MANIFEST_JOB_HASH_H

#include <stddef.h>
#include <stdint.h>

#include "manifest/manifest.h"

#define CV_FNV1A64_BASIS UINT64_C(0xcbf29ce484222325)

/* Continues an FNV-1a 64 hash h over n bytes (start with CV_FNV1A64_BASIS). */
uint64_t cv_fnv1a64(uint64_t h, const void *data, size_t n);

/* Newly allocated canonical text of the render-affecting settings: all but
 * name, output and formats. Paths as written in the manifest (scene_as_written,
 * color.config as the job holds it), so that the text does not depend on the
 * working folder; the scene file enters by size [bytes] and mtime [whole
 * seconds, since copies often drop the fraction]. */
char *cv_job_settings_text(const struct cv_job *job, long long scene_size,
                           long long scene_mtime);

/* Newly allocated 16 lowercase hex digits of the hash of that text. */
char *cv_job_settings_hash(const struct cv_job *job, long long scene_size,
                           long long scene_mtime);

/* The same with the scene file's stamp taken from its stat: the one place
 * that decides which of its fields enter (size, whole-second mtime). */
struct stat;
char *cv_job_settings_hash_stat(const struct cv_job *job, const struct stat *scene);

#endif
