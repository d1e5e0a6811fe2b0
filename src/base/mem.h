/* mem.h: allocation that cannot return NULL. Running out of memory is not an
 * input error a caller could act on, so these do not return then: they call
 * the handler the program set (cavalry-batch's prints and exits with its
 * documented status, cli/exit_codes.h) or, without one, print and abort.
 * Bad input never reaches them as a size without being checked first. */
#ifndef CV_BASE_MEM_H
#define CV_BASE_MEM_H

#include <stddef.h>

/* Called with the size asked for when an allocation fails; must not return
 * (if it does, the process aborts). NULL: the default, print and abort.
 * Only main sets one. */
typedef void (*cv_out_of_memory_fn)(size_t size);
void cv_mem_set_out_of_memory(cv_out_of_memory_fn fn);

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
