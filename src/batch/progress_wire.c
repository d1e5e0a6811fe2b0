/* progress_wire.c: see progress_wire.h. */
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "batch/progress_wire.h"

/* Each verb's fields: s string, u unsigned, i int, d double, L list of
 * strings (count, then items). One table for writing and parsing. */
static const struct {
    const char *name;
    const char *fields;
} verbs[CV_WIRE_VERB_COUNT] = {
    [CV_WIRE_BATCH_STARTED] = {"batch_started", "sL"},
    [CV_WIRE_PHASE] = {"phase", "sus"},
    [CV_WIRE_ERROR] = {"error", "s"},
    [CV_WIRE_JOB_STARTED] = {"job_started", "suuu"},
    [CV_WIRE_UPDATE] = {"progress", "suudddd"},
    [CV_WIRE_JOB_ENDED] = {"job_ended", "suudddsL"},
    [CV_WIRE_GPU] = {"gpu", "i"},
    [CV_WIRE_LOG] = {"log", "s"},
    [CV_WIRE_CLAIM] = {"claim", ""},
};

static void put_string(FILE *out, const char *s)
{
    if (!s) {
        fputs("\\N", out);
        return;
    }
    for (; *s; s++) {
        switch (*s) {
        case '\\': fputs("\\\\", out); break;
        case '\t': fputs("\\t", out); break;
        case '\n': fputs("\\n", out); break;
        case '\r': fputs("\\r", out); break;
        default: fputc(*s, out);
        }
    }
}

bool cv_wire_send(FILE *out, enum cv_wire_verb verb, ...)
{
    va_list ap;
    va_start(ap, verb);
    fputs(verbs[verb].name, out);
    for (const char *f = verbs[verb].fields; *f; f++) {
        fputc('\t', out);
        switch (*f) {
        case 's': put_string(out, va_arg(ap, const char *)); break;
        case 'u': fprintf(out, "%u", va_arg(ap, unsigned)); break;
        case 'i': fprintf(out, "%d", va_arg(ap, int)); break;
        /* %.17g reads back to the same double */
        case 'd': fprintf(out, "%.17g", va_arg(ap, double)); break;
        case 'L': {
            const char *const *items = va_arg(ap, const char *const *);
            size_t n = va_arg(ap, size_t);
            fprintf(out, "%zu", n);
            for (size_t i = 0; i < n; i++) {
                fputc('\t', out);
                put_string(out, items[i]);
            }
            break;
        }
        }
    }
    va_end(ap);
    fputc('\n', out);
    return fflush(out) == 0 && !ferror(out);
}

/* Undoes put_string in place; false for \N (NULL) or a bad escape. */
static bool unescape(char *s, bool *is_null)
{
    *is_null = strcmp(s, "\\N") == 0;
    if (*is_null)
        return true;
    char *w = s;
    for (const char *r = s; *r; r++) {
        if (*r != '\\') {
            *w++ = *r;
            continue;
        }
        switch (*++r) {
        case '\\': *w++ = '\\'; break;
        case 't': *w++ = '\t'; break;
        case 'n': *w++ = '\n'; break;
        case 'r': *w++ = '\r'; break;
        default: return false;
        }
    }
    *w = '\0';
    return true;
}

static bool is_number(const char *s, const char *type)
{
    char *end;
    if (!*s)
        return false;
    if (*type == 'd')
        (void)strtod(s, &end);
    else
        (void)strtol(s, &end, 10);
    return *end == '\0' && (*type != 'u' || *s != '-');
}

bool cv_wire_parse(char *line, struct cv_wire_msg *msg)
{
    memset(msg, 0, sizeof(*msg));
    size_t cap = 0;
    char *save = line;
    for (;;) {
        char *tab = strchr(save, '\t');
        if (tab)
            *tab = '\0';
        CV_PUSH(msg->field, msg->n_fields, cap, save);
        if (!tab)
            break;
        save = tab + 1;
    }
    /* the first field is the verb */
    size_t v = 0;
    while (v < CV_WIRE_VERB_COUNT && strcmp(verbs[v].name, msg->field[0]) != 0)
        v++;
    if (v == CV_WIRE_VERB_COUNT)
        goto bad;
    msg->verb = (enum cv_wire_verb)v;
    memmove(msg->field, msg->field + 1, (msg->n_fields - 1) * sizeof(char *));
    msg->n_fields--;
    size_t i = 0;
    for (const char *f = verbs[v].fields; *f; f++) {
        if (i >= msg->n_fields)
            goto bad;
        bool is_null;
        if (*f == 's') {
            if (!unescape(msg->field[i], &is_null))
                goto bad;
            if (is_null)
                msg->field[i] = NULL;
            i++;
        } else if (*f == 'L') {
            if (!is_number(msg->field[i], "u"))
                goto bad;
            size_t n = strtoul(msg->field[i], NULL, 10);
            if (n > msg->n_fields - i - 1)
                goto bad;
            for (size_t k = 1; k <= n; k++)
                if (!unescape(msg->field[i + k], &is_null) || is_null)
                    goto bad;
            i += n + 1;
        } else {
            if (!is_number(msg->field[i], f))
                goto bad;
            i++;
        }
    }
    if (i != msg->n_fields)
        goto bad;
    return true;
bad:
    cv_wire_msg_clear(msg);
    return false;
}

void cv_wire_msg_clear(struct cv_wire_msg *msg)
{
    free(msg->field);
    memset(msg, 0, sizeof(*msg));
}

const char *cv_wire_str(const struct cv_wire_msg *m, size_t i)
{
    return i < m->n_fields ? m->field[i] : NULL;
}

unsigned cv_wire_uint(const struct cv_wire_msg *m, size_t i)
{
    return i < m->n_fields ? (unsigned)strtoul(m->field[i], NULL, 10) : 0;
}

int cv_wire_int(const struct cv_wire_msg *m, size_t i)
{
    return i < m->n_fields ? (int)strtol(m->field[i], NULL, 10) : 0;
}

double cv_wire_double(const struct cv_wire_msg *m, size_t i)
{
    return i < m->n_fields ? strtod(m->field[i], NULL) : 0;
}

const char *const *cv_wire_list(const struct cv_wire_msg *m, size_t i, size_t *n)
{
    *n = i < m->n_fields ? strtoul(m->field[i], NULL, 10) : 0;
    return (const char *const *)m->field + i + 1;
}
