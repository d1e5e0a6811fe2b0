/* record.c: flat measurement records (print and parse one JSON object per
 * line), the process clock, GL timer queries and the NVX memory counter. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <epoxy/gl.h>

#include "base/mem.h"
#include "bench/bench.h"
#include "gpu/memory.h"

static struct bench_field *add(struct bench_record *r, const char *key)
{
    for (int i = 0; i < r->n; i++)
        if (!strcmp(r->f[i].key, key))
            return &r->f[i];
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 32;
        r->f = cv_xrealloc(r->f, sizeof(*r->f) * (size_t)r->cap);
    }
    struct bench_field *f = &r->f[r->n++];
    memset(f, 0, sizeof *f);
    snprintf(f->key, sizeof f->key, "%s", key);
    return f;
}

void bench_num(struct bench_record *r, const char *key, double v)
{
    struct bench_field *f = add(r, key);
    f->is_num = true;
    f->num = v;
}

void bench_str(struct bench_record *r, const char *key, const char *v)
{
    struct bench_field *f = add(r, key);
    f->is_num = false;
    snprintf(f->str, sizeof f->str, "%s", v ? v : "");
}

void bench_unavailable(struct bench_record *r, const char *what, const char *why)
{
    char key[96];
    snprintf(key, sizeof key, "unavailable.%s", what);
    bench_str(r, key, why);
}

const struct bench_field *bench_get(const struct bench_record *r, const char *key)
{
    for (int i = 0; i < r->n; i++)
        if (!strcmp(r->f[i].key, key))
            return &r->f[i];
    return NULL;
}

void bench_json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(out, "\\%c", c);
        else if (c < 0x20)
            fprintf(out, "\\u%04x", c);
        else
            fputc(c, out);
    }
    fputc('"', out);
}

void bench_record_print(const struct bench_record *r, FILE *out)
{
    fputc('{', out);
    for (int i = 0; i < r->n; i++) {
        if (i)
            fputs(", ", out);
        bench_json_string(out, r->f[i].key);
        fputs(": ", out);
        if (!r->f[i].is_num)
            bench_json_string(out, r->f[i].str);
        else if (isfinite(r->f[i].num))
            fprintf(out, "%.6g", r->f[i].num);
        else
            fputs("null", out);
    }
    fputs("}\n", out);
    fflush(out);
}

void bench_record_free(struct bench_record *r)
{
    free(r->f);
    memset(r, 0, sizeof *r);
}

static const char *skip_ws(const char *p)
{
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r')
        p++;
    return p;
}

static const char *parse_string(const char *p, char *dst, size_t cap)
{
    if (*p != '"')
        return NULL;
    size_t n = 0;
    for (p++; *p && *p != '"'; p++) {
        char c = *p;
        if (c == '\\') {
            p++;
            if (*p == 'u') {
                unsigned v;
                if (sscanf(p + 1, "%4x", &v) != 1)
                    return NULL;
                c = (char)(v < 0x80 ? v : '?');
                p += 4;
            } else if (*p == 'n') {
                c = '\n';
            } else if (*p == 't') {
                c = '\t';
            } else if (!*p) {
                return NULL;
            } else {
                c = *p;
            }
        }
        if (n + 1 < cap)
            dst[n++] = c;
    }
    if (*p != '"')
        return NULL;
    dst[n] = '\0';
    return p + 1;
}

bool bench_record_parse(const char *line, struct bench_record *r)
{
    memset(r, 0, sizeof *r);
    const char *p = skip_ws(line);
    if (*p++ != '{')
        return false;
    for (;;) {
        p = skip_ws(p);
        if (*p == '}')
            return true;
        char key[96], sval[320];
        if (!(p = parse_string(p, key, sizeof key)))
            break;
        p = skip_ws(p);
        if (*p++ != ':')
            break;
        p = skip_ws(p);
        if (*p == '"') {
            if (!(p = parse_string(p, sval, sizeof sval)))
                break;
            bench_str(r, key, sval);
        } else if (!strncmp(p, "null", 4)) {
            bench_num(r, key, NAN);
            p += 4;
        } else {
            char *end;
            double v = strtod(p, &end);
            if (end == p)
                break;
            bench_num(r, key, v);
            p = end;
        }
        p = skip_ws(p);
        if (*p == ',')
            p++;
        else if (*p != '}')
            break;
    }
    bench_record_free(r);
    return false;
}

static double epoch_ms;

static double monotonic_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* The clock starts at the first call, which main makes on entry. */
double bench_now_ms(void)
{
    if (epoch_ms == 0)
        epoch_ms = monotonic_ms();
    return monotonic_ms() - epoch_ms;
}

void bench_reset_epoch(void)
{
    epoch_ms = monotonic_ms();
}

static double mem_peak_kib = -1, mem_total_kib = -1;

void bench_gpu_memory_sample(const struct cv_gpu *gpu)
{
    uint64_t total = 0, avail = 0;
    if (!cv_gpu_memory(gpu, &total, &avail))
        return;
    mem_total_kib = total / 1024.0;
    if ((total - avail) / 1024.0 > mem_peak_kib)
        mem_peak_kib = (total - avail) / 1024.0;
}

bool bench_gpu_memory_peak(double *used_mib, double *total_mib)
{
    if (mem_peak_kib < 0)
        return false;
    *used_mib = mem_peak_kib / 1024.0;
    *total_mib = mem_total_kib / 1024.0;
    return true;
}

void bench_timer_begin(struct bench_timer *t)
{
    glGenQueries(1, &t->query);
    glBeginQuery(GL_TIME_ELAPSED, t->query);
}

double bench_timer_end(struct bench_timer *t)
{
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 ns = 0;
    glGetQueryObjectui64v(t->query, GL_QUERY_RESULT, &ns);
    glDeleteQueries(1, &t->query);
    t->query = 0;
    if (glGetError() != GL_NO_ERROR)
        return -1;
    return (double)ns * 1e-6;
}
