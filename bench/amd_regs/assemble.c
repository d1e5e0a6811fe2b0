/* bench/amd_regs/assemble.c: prints a kernel assembled as the host does
 * (gpu/program.h: cv_glsl_assemble; CAVALRY_DATA_DIR picks the tree).
 *   usage: assemble KERNEL [DEFINE]... */
#include <stdio.h>
#include <stdlib.h>

#include "base/error.h"
#include "gpu/program.h"

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 33) {
        fprintf(stderr, "usage: assemble KERNEL [DEFINE]... (at most 31)\n");
        return 2;
    }
    const char *defines[32];
    int n = 0;
    for (int i = 2; i < argc; i++)
        defines[n++] = argv[i];
    defines[n] = NULL;
    struct cv_error err = {{0}};
    char *src = NULL, **names = NULL;
    if (!cv_glsl_assemble(argv[1], defines, &src, &names, &err)) {
        fprintf(stderr, "assemble: %s\n", err.msg);
        return 1;
    }
    fputs(src, stdout);
    for (char **p = names; *p; p++)
        free(*p);
    free(names);
    free(src);
    return 0;
}
