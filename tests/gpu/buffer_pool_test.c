/* buffer_pool_test.c: the GPU context's scratch pool hands a buffer back
 * out after put (the smallest idle one that holds the request), never hands
 * out one that is out already, makes a new one when none fits, trim
 * deletes only the idle ones, and settle deletes only the idle ones not
 * handed out since the last settle. */
#include "config.h"

#include <stdint.h>

#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "tests/gpu/gpu_test_util.h"

static GLint64 size_of(GLuint buf)
{
    GLint64 s = 0;
    glGetNamedBufferParameteri64v(buf, GL_BUFFER_SIZE, &s);
    return s;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_buffer_pool *pool = cv_buffer_pool_create();

    GLuint big = cv_buffer_pool_get(pool, 1 << 20, "big", &err);
    GLuint small = cv_buffer_pool_get(pool, 4096, "small", &err);
    tap_ok(big && small && big != small, "two buffers handed out (%u, %u)", big, small);
    tap_ok(size_of(big) >= (1 << 20) && size_of(small) >= 4096, "each holds its request");
    GLuint third = cv_buffer_pool_get(pool, 100, "third", &err);
    tap_ok(third && third != big && third != small, "a busy buffer is not handed out again");

    GLuint b = big, s = small;
    cv_buffer_pool_put(pool, &b);
    cv_buffer_pool_put(pool, &s);
    tap_ok(b == 0 && s == 0, "put clears the caller's name");
    GLuint again = cv_buffer_pool_get(pool, 1000, "again", &err);
    tap_ok(again == small, "the smallest idle buffer that holds the request comes back");
    GLuint again_big = cv_buffer_pool_get(pool, 5000, "again big", &err);
    tap_ok(again_big == big, "a larger request takes the larger idle buffer");
    GLuint fresh = cv_buffer_pool_get(pool, 2 << 20, "fresh", &err);
    tap_ok(fresh && fresh != big && fresh != small && fresh != third,
           "a request no idle buffer holds makes a new one");

    cv_buffer_pool_put(pool, &again_big);
    cv_buffer_pool_trim(pool);
    tap_ok(!glIsBuffer(big), "trim deletes the idle buffer");
    tap_ok(glIsBuffer(small) && glIsBuffer(third) && glIsBuffer(fresh),
           "trim keeps the buffers handed out");
    GLuint after = cv_buffer_pool_get(pool, 1 << 20, "after", &err);
    tap_ok(after && after != small && after != third && after != fresh,
           "after trim a request makes a new buffer");

    /* settle: `after` and `fresh` stay out; `again` (the small one) and
     * `third` go back. All were handed out since the pool began, so the
     * first settle keeps the idle two; the second, with only the small one
     * taken in between, deletes `third`. */
    GLuint kept_small = again, kept_third = third;
    cv_buffer_pool_put(pool, &again);
    cv_buffer_pool_put(pool, &third);
    size_t idle = cv_buffer_pool_settle(pool);
    tap_ok(glIsBuffer(kept_small) && glIsBuffer(kept_third),
           "settle keeps idle buffers handed out since the pool began");
    tap_ok(idle == (size_t)(size_of(kept_small) + size_of(kept_third)),
           "settle returns the idle bytes it keeps (%zu)", idle);
    GLuint retake = cv_buffer_pool_get(pool, 1000, "retake", &err);
    tap_ok(retake == kept_small, "the idle small buffer comes back after settle");
    cv_buffer_pool_put(pool, &retake);
    idle = cv_buffer_pool_settle(pool);
    tap_ok(glIsBuffer(kept_small) && !glIsBuffer(kept_third),
           "settle deletes the idle buffer not handed out since the last settle");
    tap_ok(glIsBuffer(after) && glIsBuffer(fresh), "settle keeps the buffers handed out");
    tap_ok(idle == (size_t)size_of(kept_small), "settle counts only what it keeps (%zu)", idle);
    tap_ok(cv_buffer_pool_settle(NULL) == 0, "settle accepts no pool");

    /* get_within: an idle buffer larger than `most` stays idle. */
    size_t made = cv_buffer_pool_created(pool);
    GLuint over = cv_buffer_pool_get_within(pool, 1000, 2000, "within", &err);
    tap_ok(over && over != kept_small && cv_buffer_pool_created(pool) == made + 1,
           "get_within passes over an idle buffer beyond its bound (%lld bytes) and makes one",
           (long long)size_of(kept_small));
    GLuint fits = cv_buffer_pool_get_within(pool, 1000, 4096, "within", &err);
    tap_ok(fits == kept_small && cv_buffer_pool_created(pool) == made + 1,
           "get_within takes an idle buffer within its bound");
    cv_buffer_pool_put(pool, &over);
    cv_buffer_pool_put(pool, &fits);

    /* Without a pool: plain buffers that put deletes. */
    GLuint plain = cv_buffer_pool_get(NULL, 64, "plain", &err);
    tap_ok(plain && glIsBuffer(plain), "no pool: a new buffer");
    cv_buffer_pool_put(NULL, &plain);
    tap_ok(plain == 0, "no pool: put deletes it");

    /* The context's own pool exists and is destroyed with it. */
    tap_ok(gpu->scratch != NULL, "the GPU context has a scratch pool");
    cv_buffer_pool_destroy(&pool);
    tap_ok(pool == NULL, "destroy clears the pointer");
    cv_buffer_pool_destroy(&pool);
    tap_ok(!glGetError(), "no GL error");
    cv_gpu_destroy(&gpu);
    return tap_done();
}
