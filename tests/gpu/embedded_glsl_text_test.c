/* embedded_glsl_text_test.c: the GLSL compiled into the binary (glsl_embedded.c,
 * made by src/gpu/embed_glsl.sh) is each file under glsl/ byte for byte.
 * Every other test reads the tree through CAVALRY_DATA_DIR, so a quoting
 * slip in the embedding (a backslash line continuation that mawk's gsub
 * halved broke every continued #define of the installed binary) would pass
 * them all; this test compares the two copies. No GPU needed. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/file.h"
#include "gpu/glsl_source.h"
#include "tests/tap.h"

int main(void)
{
    const char *dir = getenv("CAVALRY_DATA_DIR");
    if (!dir || !dir[0]) {
        return tap_skip_all("CAVALRY_DATA_DIR names no source tree");
    }
    size_t n = 0, differ = 0, continued = 0;
    for (const struct cv_glsl_file *f = cv_glsl_files; f->path; f++) {
        char *path = cv_xasprintf("%s/glsl/%s", dir, f->path), *text = NULL;
        struct cv_error err = {{0}};
        bool read = cv_read_file(path, &text, NULL, &err);
        bool same = read && strcmp(text, f->text) == 0;
        if (!same) {
            differ++;
            tap_ok(false, "glsl/%s embedded as it is in the tree%s%s", f->path,
                   read ? "" : ": ", read ? "" : err.msg);
        }
        if (read && strstr(text, "\\\n"))
            continued++;
        n++;
        free(text);
        free(path);
    }
    tap_ok(n > 100, "%zu files embedded", n);
    tap_ok(differ == 0, "every embedded file equals the tree's (%zu differ)", differ);
    tap_ok(continued > 0, "the files compared include %zu with backslash continuations",
           continued);
    return tap_done();
}
