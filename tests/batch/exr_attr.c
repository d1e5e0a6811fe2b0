/* exr_attr.c: prints a string attribute of an EXR file, for the shell
 * tests (exr_attr FILE NAME). Exit 1 when it cannot. */
#include <stdio.h>
#include <stdlib.h>

#include "output/exr_read.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: exr_attr FILE NAME\n");
        return 2;
    }
    char *value = NULL;
    struct cv_error err = {{0}};
    if (!cv_exr_read_attribute_string(argv[1], argv[2], &value, &err)) {
        fprintf(stderr, "%s\n", err.msg);
        return 1;
    }
    printf("%s\n", value);
    free(value);
    return 0;
}
