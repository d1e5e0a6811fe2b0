/* contrib/amd_regs/assemble.c: prints a kernel assembled as the host does
 * (cv_glsl_assemble), argv[1] the kernel, the rest its defines. */
#include <stdio.h>
#include <stdlib.h>
#include "gpu/program.h"
#include "base/error.h"
int main(int argc, char **argv)
{
    const char *defs[32];
    int n = 0;
    for (int i = 2; i < argc && n < 31; i++)
        defs[n++] = argv[i];
    defs[n] = NULL;
    struct cv_error err = {{0}};
    char *src = NULL, **names = NULL;
    if (!cv_glsl_assemble(argv[1], defs, &src, &names, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    fputs(src, stdout);
    return 0;
}
