/* buf_test.c: a typed buffer (gpu/buf.h) keeps its size and use: it reads
 * back what it was made with, refuses a read outside itself or when it was
 * not made host-readable (the error names it), and destroy clears it. */
#include <stdint.h>
#include <string.h>

#include "gpu/buf.h"
#include "tests/gpu/gpu_test_util.h"

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    uint32_t data[64], back[64];
    for (uint32_t i = 0; i < 64; i++)
        data[i] = i * 2654435761u;
    struct cv_buf *b = cv_buf_create(gpu, &(struct cv_buf_params){.size = sizeof(data),
                                                                  .storable = true,
                                                                  .host_readable = true,
                                                                  .initial = data,
                                                                  .label = "test data"},
                                     &err);
    if (!tap_ok(b != NULL, "created: %s", err.msg))
        return tap_done();
    tap_ok(b->params.size == sizeof(data) && b->params.storable && b->params.host_readable &&
               b->params.initial == NULL && strcmp(b->params.label, "test data") == 0,
           "knows its size, use and label");
    tap_ok(cv_buf_read(b, 0, sizeof(back), back, &err) && memcmp(back, data, sizeof(data)) == 0,
           "reads back its initial contents");
    tap_ok(cv_buf_read(b, 32 * 4, 32 * 4, back, &err) && memcmp(back, &data[32], 32 * 4) == 0,
           "reads a slice at an offset");
    cv_error_clear(&err);
    tap_ok(!cv_buf_read(b, 60 * 4, 8 * 4, back, &err) && strstr(err.msg, "test data") &&
               strstr(err.msg, "holds 256"),
           "a read past the end fails: %s", err.msg);

    struct cv_buf *z = cv_buf_create(gpu, &(struct cv_buf_params){.size = 16, .label = "gpu only"},
                                     &err);
    cv_error_clear(&err);
    tap_ok(z && !cv_buf_read(z, 0, 16, back, &err) && strstr(err.msg, "gpu only"),
           "a buffer not made host-readable is not read: %s", err.msg);
    cv_buf_destroy(&b);
    cv_buf_destroy(&z);
    cv_buf_destroy(&z);
    tap_ok(b == NULL && z == NULL, "destroy clears the pointer and accepts NULL");
    cv_gpu_destroy(&gpu);
    return tap_done();
}
