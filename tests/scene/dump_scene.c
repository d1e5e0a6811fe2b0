/* dump_scene.c: loads a pbrt file and prints cv_scene_dump, for the shell
 * tests (cavalry-batch --dump-scene is wired by the CLI stage). Exit 1 on a
 * load error, printed on stderr. --strict turns warnings into errors. */
#include <stdio.h>
#include <string.h>

#include "scene/dump.h"
#include "scene/scene.h"

int main(int argc, char **argv)
{
    struct cv_scene_load_params params = {0};
    int i = 1;
    if (argc > 1 && strcmp(argv[1], "--strict") == 0) {
        params.strict = true;
        i++;
    }
    if (i != argc - 1) {
        fprintf(stderr, "usage: dump_scene [--strict] FILE.pbrt\n");
        return 2;
    }
    struct cv_scene *s = NULL;
    struct cv_error err = {0};
    if (!cv_scene_load(argv[i], &params, &s, &err)) {
        fprintf(stderr, "error: %s\n", err.msg);
        return 1;
    }
    cv_scene_dump(s, stdout);
    cv_scene_destroy(&s);
    return 0;
}
