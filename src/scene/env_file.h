/* env_file.h: the images a batch's jobs name in env.file
 * (cavalry-manifest(5)), each read once however many jobs name it, and
 * read as the importer reads a pbrt environment map (LightSource
 * "infinite"): same decoders, mip chain and texel layout, same file checks
 * (--scene-root). An image is held as a scene of its own: its textures,
 * texels and one infinite light, which scene/relight.c swaps in for the
 * job's scene's environment. */
#ifndef CV_SCENE_ENV_FILE_H
#define CV_SCENE_ENV_FILE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "scene/scene.h"

struct cv_env_files {
    struct cv_scene_load_params params;  /* the batch's: strict, root */
    struct cv_env_file {
        char *path;
        struct cv_scene *scene;          /* owned */
    } *files;
    size_t n, cap;
};

/* The image at path (as opened: the manifest's folder joined), loaded at
 * its first request; false with err on a file that cannot be read. */
bool cv_env_files_get(struct cv_env_files *c, const char *path, const struct cv_scene **out,
                      struct cv_error *err);
/* Frees every image; the cache may be used again. */
void cv_env_files_clear(struct cv_env_files *c);

/* The image's light and texture in its scene (out of cv_env_files_get). */
const CvLight *cv_env_file_light(const struct cv_scene *env);

#endif
