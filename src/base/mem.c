/* mem.c: see mem.h. */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

static cv_out_of_memory_fn on_out_of_memory;

void cv_mem_set_out_of_memory(cv_out_of_memory_fn fn)
{
    on_out_of_memory = fn;
}

static void out_of_memory(size_t size)
{
    if (on_out_of_memory)
        on_out_of_memory(size);
    fprintf(stderr, "error: out of memory (asked for %zu bytes)\n", size);
    abort();
}

void *cv_xmalloc(size_t size)
{
    void *p = malloc(size ? size : 1);
    if (!p)
        out_of_memory(size);
    return p;
}

void *cv_xcalloc(size_t count, size_t size)
{
    void *p = calloc(count ? count : 1, size ? size : 1);
    if (!p)
        out_of_memory(count * size);
    return p;
}

void *cv_xrealloc(void *ptr, size_t size)
{
    void *p = realloc(ptr, size ? size : 1);
    if (!p)
        out_of_memory(size);
    return p;
}

void *cv_xgrow(void *ptr, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap)
        return ptr;
    size_t ncap = *cap ? *cap : 8;
    while (ncap < need) {
        if (ncap > SIZE_MAX / 2 / elem)
            out_of_memory(SIZE_MAX);
        ncap *= 2;
    }
    *cap = ncap;
    return cv_xrealloc(ptr, ncap * elem);
}

char *cv_xstrdup(const char *s)
{
    size_t n = strlen(s) + 1;
    return memcpy(cv_xmalloc(n), s, n);
}

char *cv_xasprintf(const char *fmt, ...)
{
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *s = cv_xmalloc((size_t)(n < 0 ? 0 : n) + 1);
    vsnprintf(s, (size_t)n + 1, fmt, ap2);
    va_end(ap2);
    return s;
}
