/* buf.c: see buf.h. Storage and transfers are gpu/buffer.h's. */
#include <stdlib.h>

#include "base/mem.h"
#include "gpu/buf.h"
#include "gpu/buffer.h"
#include "gpu/storage.h"

struct cv_buf *cv_buf_create(struct cv_gpu *gpu, const struct cv_buf_params *p,
                             struct cv_error *err)
{
    const char *label = p->label ? p->label : "buffer";
    if (p->storable && !cv_gpu_storage_fits(gpu, p->size, label, err))
        return NULL;
    GLuint id = cv_buffer_create(p->size, p->initial, label, err);
    if (!id)
        return NULL;
    struct cv_buf *b = cv_xcalloc(1, sizeof(*b));
    b->id = id;
    b->params = *p;
    b->params.initial = NULL;
    b->params.label = cv_xstrdup(label);
    return b;
}

void cv_buf_bind(const struct cv_buf *b, unsigned binding)
{
    cv_buffer_bind(b->id, binding);
}

bool cv_buf_read(const struct cv_buf *b, size_t offset, size_t bytes, void *dst,
                 struct cv_error *err)
{
    if (!b->params.host_readable)
        return cv_fail(err, "buffer %s is not readable by the host", b->params.label);
    if (offset > b->params.size || bytes > b->params.size - offset)
        return cv_fail(err, "reading %zu bytes at %zu of buffer %s, which holds %zu", bytes,
                       offset, b->params.label, b->params.size);
    return cv_buffer_read(b->id, offset, bytes, dst, err);
}

void cv_buf_destroy(struct cv_buf **b)
{
    if (!b || !*b)
        return;
    cv_buffer_destroy(&(*b)->id);
    free((char *)(*b)->params.label);
    free(*b);
    *b = NULL;
}
