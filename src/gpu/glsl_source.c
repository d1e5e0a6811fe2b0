/* glsl_source.c: see glsl_source.h. */
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "gpu/glsl_source.h"

bool cv_glsl_read(const char *path, char **text, struct cv_error *err)
{
    const char *dir = getenv("CAVALRY_DATA_DIR");
    if (dir && dir[0]) {
        char *full = cv_xasprintf("%s/glsl/%s", dir, path);
        bool ok = cv_read_file(full, text, NULL, err);
        free(full);
        return ok;
    }
    for (const struct cv_glsl_file *f = cv_glsl_files; f->path; f++) {
        if (strcmp(f->path, path) == 0) {
            *text = cv_xstrdup(f->text);
            return true;
        }
    }
    return cv_fail(err, "glsl/%s: no such shader in this build", path);
}
