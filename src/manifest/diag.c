/* diag.c: see diag.h. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "manifest/diag.h"

void cv_diag_add(struct cv_diag *d, size_t line, size_t col, const char *fmt, ...)
{
    char body[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(body, sizeof(body), fmt, ap);
    va_end(ap);
    struct cv_diag_msg m = {
        .line = line,
        .col = col,
        .seq = d->n,
        .text = cv_xasprintf("%s:%zu:%zu: %s", d->file, line, col, body),
    };
    CV_PUSH(d->msgs, d->n, d->cap, m);
}

static int by_position(const void *a, const void *b)
{
    const struct cv_diag_msg *x = a, *y = b;
    if (x->line != y->line)
        return x->line < y->line ? -1 : 1;
    if (x->col != y->col)
        return x->col < y->col ? -1 : 1;
    return x->seq < y->seq ? -1 : x->seq > y->seq;
}

bool cv_diag_finish(struct cv_diag *d, struct cv_error *err)
{
    if (d->n == 0) {
        cv_diag_free(d);
        return true;
    }
    qsort(d->msgs, d->n, sizeof(*d->msgs), by_position);
    char *buf = err ? err->msg : NULL;
    size_t cap = err ? sizeof(err->msg) : 0, used = 0, shown = 0, distinct = 0;
    /* Room kept for the "and N more" line so that it always fits. */
    const size_t reserve = 48;
    bool full = false;
    for (size_t i = 0; i < d->n; i++) {
        if (i > 0 && strcmp(d->msgs[i].text, d->msgs[i - 1].text) == 0)
            continue;
        distinct++;
        size_t len = strlen(d->msgs[i].text);
        if (!buf || full || used + len + 1 + reserve >= cap) {
            full = true;
            continue;
        }
        if (used > 0)
            buf[used++] = '\n';
        memcpy(buf + used, d->msgs[i].text, len);
        used += len;
        buf[used] = '\0';
        shown++;
    }
    if (buf && distinct > shown)
        snprintf(buf + used, cap - used, "%s... and %zu more errors", used ? "\n" : "",
                 distinct - shown);
    cv_diag_free(d);
    return false;
}

void cv_diag_free(struct cv_diag *d)
{
    for (size_t i = 0; i < d->n; i++)
        free(d->msgs[i].text);
    free(d->msgs);
    d->msgs = NULL;
    d->n = d->cap = 0;
}
