/* env_file.c: see env_file.h. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/env_file.h"

bool cv_env_files_get(struct cv_env_files *c, const char *path, const struct cv_scene **out,
                      struct cv_error *err)
{
    for (size_t i = 0; i < c->n; i++)
        if (!strcmp(c->files[i].path, path)) {
            *out = c->files[i].scene;
            return true;
        }
    if (strpbrk(path, "\"\n"))
        return cv_fail(err, "%s: an environment image's path may not hold '\"' or a newline",
                       path);
    /* pbrt-v3's "mapname" reads any shape (latitude-longitude); relight.c
     * turns the light into pbrt-v4's equal-area kind where the scene's is */
    const char *slash = strrchr(path, '/');
    char *text = cv_xasprintf("WorldBegin\nLightSource \"infinite\" \"string mapname\" \"%s\"\n",
                              slash ? slash + 1 : path);
    struct cv_scene *s = NULL;
    bool ok = cv_scene_load_string(path, text, strlen(text), &c->params, &s, err);
    free(text);
    if (!ok)
        return false;
    if (s->n_lights != 1 || s->lights[0].type != CV_LIGHT_INFINITE_MAP) {
        cv_scene_destroy(&s);
        return cv_fail(err, "%s: not read as an environment image", path);
    }
    struct cv_env_file f = {cv_xstrdup(path), s};
    CV_PUSH(c->files, c->n, c->cap, f);
    *out = s;
    return true;
}

void cv_env_files_clear(struct cv_env_files *c)
{
    for (size_t i = 0; i < c->n; i++) {
        free(c->files[i].path);
        cv_scene_destroy(&c->files[i].scene);
    }
    free(c->files);
    c->files = NULL;
    c->n = c->cap = 0;
}

const CvLight *cv_env_file_light(const struct cv_scene *env)
{
    return &env->lights[0];
}
