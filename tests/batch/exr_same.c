/* exr_same.c: whether two EXR files hold the same RGBA pixels bit for bit,
 * for the shell tests (exr_same A B). Exit 0 when they do, 1 when they
 * differ or cannot be read. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "output/exr_read.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: exr_same A B\n");
        return 2;
    }
    float *px[2] = {NULL, NULL};
    uint32_t w[2] = {0, 0}, h[2] = {0, 0};
    struct cv_error err = {{0}};
    for (int i = 0; i < 2; i++) {
        if (!cv_exr_read_rgba(argv[1 + i], &px[i], &w[i], &h[i], &err)) {
            fprintf(stderr, "%s\n", err.msg);
            free(px[0]);
            return 1;
        }
    }
    int rc = 0;
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "sizes differ: %ux%u, %ux%u\n", w[0], h[0], w[1], h[1]);
        rc = 1;
    } else if (memcmp(px[0], px[1], (size_t)w[0] * h[0] * 4 * sizeof(float)) != 0) {
        fprintf(stderr, "pixels differ\n");
        rc = 1;
    }
    free(px[0]);
    free(px[1]);
    return rc;
}
