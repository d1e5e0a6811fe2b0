/* buffer_pool.c: see buffer_pool.h. A small array: a build asks for a
 * dozen buffers at most. */
#include <stdint.h>
#include <stdlib.h>

#include "base/mem.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"

struct entry {
    GLuint buf;
    size_t bytes;
    bool busy;
    bool used;  /* handed out since the last settle */
};

struct cv_buffer_pool {
    struct entry *e;
    size_t n, cap;
    size_t created;
};

struct cv_buffer_pool *cv_buffer_pool_create(void)
{
    return cv_xcalloc(1, sizeof(struct cv_buffer_pool));
}

GLuint cv_buffer_pool_get(struct cv_buffer_pool *pool, size_t bytes, const char *label,
                          struct cv_error *err)
{
    return cv_buffer_pool_get_within(pool, bytes, SIZE_MAX, label, err);
}

GLuint cv_buffer_pool_get_within(struct cv_buffer_pool *pool, size_t bytes, size_t most,
                                 const char *label, struct cv_error *err)
{
    if (bytes == 0)
        bytes = 4;
    if (!pool)
        return cv_buffer_create_uninit(bytes, label, err);
    struct entry *best = NULL;
    for (size_t i = 0; i < pool->n; i++) {
        struct entry *e = &pool->e[i];
        if (!e->busy && e->bytes >= bytes && e->bytes <= most && (!best || e->bytes < best->bytes))
            best = e;
    }
    if (best) {
        best->busy = best->used = true;
        return best->buf;
    }
    GLuint buf = cv_buffer_create_uninit(bytes, label, err);
    if (!buf)
        return 0;
    if (pool->n == pool->cap) {
        pool->cap = pool->cap ? 2 * pool->cap : 16;
        pool->e = cv_xrealloc(pool->e, pool->cap * sizeof(*pool->e));
    }
    pool->e[pool->n++] = (struct entry){.buf = buf, .bytes = bytes, .busy = true, .used = true};
    pool->created++;
    return buf;
}

size_t cv_buffer_pool_created(const struct cv_buffer_pool *pool)
{
    return pool ? pool->created : 0;
}

size_t cv_buffer_pool_idle(const struct cv_buffer_pool *pool)
{
    size_t idle = 0;
    for (size_t i = 0; pool && i < pool->n; i++)
        idle += pool->e[i].busy ? 0 : pool->e[i].bytes;
    return idle;
}

void cv_buffer_pool_put(struct cv_buffer_pool *pool, GLuint *buf)
{
    if (!buf || !*buf)
        return;
    for (size_t i = 0; pool && i < pool->n; i++) {
        if (pool->e[i].buf == *buf) {
            pool->e[i].busy = false;
            *buf = 0;
            return;
        }
    }
    /* Not one of ours (or no pool): delete it rather than leak it. */
    cv_buffer_destroy(buf);
}

void cv_buffer_pool_trim(struct cv_buffer_pool *pool)
{
    size_t k = 0;
    for (size_t i = 0; i < pool->n; i++) {
        if (pool->e[i].busy)
            pool->e[k++] = pool->e[i];
        else
            cv_buffer_destroy(&pool->e[i].buf);
    }
    pool->n = k;
}

size_t cv_buffer_pool_settle(struct cv_buffer_pool *pool)
{
    size_t k = 0, idle = 0;
    for (size_t i = 0; pool && i < pool->n; i++) {
        struct entry e = pool->e[i];
        if (!e.busy && !e.used) {
            cv_buffer_destroy(&e.buf);
            continue;
        }
        if (!e.busy)
            idle += e.bytes;
        e.used = false;
        pool->e[k++] = e;
    }
    if (pool)
        pool->n = k;
    return idle;
}

void cv_buffer_pool_destroy(struct cv_buffer_pool **pool)
{
    if (!pool || !*pool)
        return;
    for (size_t i = 0; i < (*pool)->n; i++)
        cv_buffer_destroy(&(*pool)->e[i].buf);
    free((*pool)->e);
    free(*pool);
    *pool = NULL;
}
