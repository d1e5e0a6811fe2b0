/* mem.h: allocation that cannot return NULL. Running out of memory is not an
 * input error a caller could act on, so these print and exit; bad input never
 * reaches them as a size without being checked first. */
#ifndef CV_BASE_MEM_H
#define CV_BASE_MEM_H

#include <stddef.h>

void *cv_xmalloc(size_t size);
void *cv_xcalloc(size_t count, size_t size);
void *cv_xrealloc(void *ptr, size_t size);
/* Grows an array of `elem`-sized items to hold at least `need`, doubling. */
void *cv_xgrow(void *ptr, size_t *cap, size_t need, size_t elem);
char *cv_xstrdup(const char *s);
char *cv_xasprintf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

/* Appends one item to a (ptr, len, cap) array. */
#define CV_PUSH(ptr, len, cap, value)                                        \
    do {                                                                     \
        (ptr) = cv_xgrow((ptr), &(cap), (size_t)(len) + 1, sizeof(*(ptr)));  \
        (ptr)[(len)++] = (value);                                            \
    } while (0)

#define CV_ARRAY_SIZE(a) (sizeof(a) / sizeof((a)[0]))

#endif
