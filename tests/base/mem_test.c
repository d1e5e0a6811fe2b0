/* mem_test.c: an allocation that fails calls the handler the program set
 * (cavalry-batch's exits with its documented status) with the size asked
 * for, instead of exiting from inside the library. */
#include <setjmp.h>
#include <stdint.h>
#include <stdlib.h>

#include "base/mem.h"
#include "tests/tap.h"

#if defined(__SANITIZE_ADDRESS__)
/* ASan would report the failed allocation instead of returning NULL. */
const char *__asan_default_options(void);
const char *__asan_default_options(void)
{
    return "allocator_may_return_null=1";
}
#endif

static jmp_buf back;
static size_t asked;

static void handler(size_t size)
{
    asked = size;
    longjmp(back, 1);
}

int main(void)
{
    /* more than any address space holds */
    size_t huge = SIZE_MAX / 2;
    cv_mem_set_out_of_memory(handler);
    volatile bool reached = false;
    if (setjmp(back) == 0) {
        void *p = cv_xmalloc(huge);
        free(p);
        reached = true;
    }
    tap_ok(!reached && asked == huge, "cv_xmalloc calls the handler with %zu bytes", asked);
    asked = 0;
    reached = false;
    if (setjmp(back) == 0) {
        void *p = cv_xrealloc(NULL, huge);
        free(p);
        reached = true;
    }
    tap_ok(!reached && asked == huge, "cv_xrealloc calls the handler with %zu bytes", asked);
    cv_mem_set_out_of_memory(NULL);
    void *small = cv_xmalloc(16);
    tap_ok(small != NULL, "a small allocation succeeds");
    free(small);
    return tap_done();
}
