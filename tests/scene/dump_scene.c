/* dump_scene.c: loads a pbrt file and prints cv_scene_dump, for the shell
 * tests (cavalry-batch --dump-scene is wired by the CLI stage). Exit 1 on a
 * load error, printed on stderr. --strict turns warnings into errors;
 * --time prints only the load time (for the benchmark figures). */
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "scene/dump.h"
#include "scene/scene.h"

int main(int argc, char **argv)
{
    struct cv_scene_load_params params = {0};
    int i = 1;
    bool timing = false;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (strcmp(argv[i], "--strict") == 0)
            params.strict = true;
        else if (strcmp(argv[i], "--time") == 0)
            timing = true;
        else
            break;
    }
    if (i != argc - 1) {
        fprintf(stderr, "usage: dump_scene [--strict] [--time] FILE.pbrt\n");
        return 2;
    }
    struct cv_scene *s = NULL;
    struct cv_error err = {0};
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (!cv_scene_load(argv[i], &params, &s, &err)) {
        fprintf(stderr, "error: %s\n", err.msg);
        return 1;
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (timing)
        printf("%.4f s load, %u triangles\n", (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
               s->n_triangles);
    else
        cv_scene_dump(s, stdout);
    cv_scene_destroy(&s);
    return 0;
}
