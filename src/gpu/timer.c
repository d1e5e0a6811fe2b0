/* timer.c: see timer.h. Closed scopes wait as query pairs until collected;
 * the host clock, where it is used, adds to the rows at once. */
#include <stdint.h>
#include <stdlib.h>

#include <epoxy/gl.h>

#include "base/clock.h"
#include "base/log.h"
#include "base/mem.h"
#include "gpu/timer.h"

#define NO_SLOT UINT32_MAX

struct scope {
    unsigned row;
    uint32_t slot;        /* NO_SLOT: the row only */
    GLuint begin, end;    /* GL_TIMESTAMP queries (GPU clock) */
};

struct cv_gpu_timer {
    bool host_clock;      /* software renderer: host clock after glFinish */
    const char *const *names;
    unsigned n_names, n_slots;
    double *ms;           /* per row */
    double *slot_ms;      /* per row and slot */
    bool *ran;
    struct scope open;
    bool is_open;
    double host_start;    /* host clock at the open scope's begin [ms] */
    struct scope *closed; /* awaiting collection (GPU clock) */
    size_t n_closed, cap_closed;
};

struct cv_gpu_timer *cv_gpu_timer_create(const struct cv_gpu *gpu,
                                         const struct cv_gpu_timer_params *p)
{
    struct cv_gpu_timer *t = cv_xcalloc(1, sizeof(*t));
    t->host_clock = gpu->info.software;
    t->names = p->names;
    t->n_names = p->n_names;
    t->n_slots = p->n_slots;
    t->ms = cv_xcalloc(p->n_names, sizeof(*t->ms));
    t->slot_ms = cv_xcalloc((size_t)p->n_names * (p->n_slots ? p->n_slots : 1),
                            sizeof(*t->slot_ms));
    t->ran = cv_xcalloc(p->n_names, sizeof(*t->ran));
    return t;
}

static void add(struct cv_gpu_timer *t, unsigned row, uint32_t slot, double ms)
{
    t->ms[row] += ms;
    if (slot != NO_SLOT)
        t->slot_ms[(size_t)row * t->n_slots + slot] += ms;
}

void cv_gpu_timer_begin(struct cv_gpu_timer *t, unsigned row, unsigned slot)
{
    if (!t || row >= t->n_names)
        return;
    if (t->is_open && t->open.begin)  /* never closed (an error path) */
        glDeleteQueries(1, &t->open.begin);
    t->open = (struct scope){row, slot < t->n_slots ? slot : NO_SLOT, 0, 0};
    t->is_open = true;
    t->ran[row] = true;
    if (t->host_clock) {
        glFinish();
        t->host_start = 1e3 * cv_seconds();
    } else {
        glGenQueries(1, &t->open.begin);
        glQueryCounter(t->open.begin, GL_TIMESTAMP);
    }
}

void cv_gpu_timer_end(struct cv_gpu_timer *t)
{
    if (!t || !t->is_open)
        return;
    t->is_open = false;
    if (t->host_clock) {
        glFinish();
        add(t, t->open.row, t->open.slot, 1e3 * cv_seconds() - t->host_start);
        return;
    }
    glGenQueries(1, &t->open.end);
    glQueryCounter(t->open.end, GL_TIMESTAMP);
    CV_PUSH(t->closed, t->n_closed, t->cap_closed, t->open);
}

void cv_gpu_timer_collect(struct cv_gpu_timer *t)
{
    if (!t)
        return;
    for (size_t i = 0; i < t->n_closed; i++) {
        struct scope *s = &t->closed[i];
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(s->begin, GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(s->end, GL_QUERY_RESULT, &t1);
        add(t, s->row, s->slot, t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0);
        glDeleteQueries(1, &s->begin);
        glDeleteQueries(1, &s->end);
    }
    t->n_closed = 0;
}

double cv_gpu_timer_ms(const struct cv_gpu_timer *t, unsigned row)
{
    return t && row < t->n_names ? t->ms[row] : 0;
}

double cv_gpu_timer_slot_ms(const struct cv_gpu_timer *t, unsigned row, unsigned slot)
{
    if (!t || row >= t->n_names || slot >= t->n_slots)
        return 0;
    return t->slot_ms[(size_t)row * t->n_slots + slot];
}

bool cv_gpu_timer_ran(const struct cv_gpu_timer *t, unsigned row)
{
    return t && row < t->n_names && t->ran[row];
}

void cv_gpu_timer_report(struct cv_gpu_timer *t, const char *what)
{
    if (!t)
        return;
    cv_gpu_timer_collect(t);
    double total = 0;
    for (unsigned i = 0; i < t->n_names; i++)
        total += t->ms[i];
    for (unsigned i = 0; i < t->n_names; i++)
        if (t->ms[i] > 0)
            cv_info("%s %-13s %10.1f ms %5.1f %%", what, t->names[i], t->ms[i],
                    total > 0 ? 100 * t->ms[i] / total : 0);
}

void cv_gpu_timer_destroy(struct cv_gpu_timer **tp)
{
    if (!tp || !*tp)
        return;
    struct cv_gpu_timer *t = *tp;
    for (size_t i = 0; i < t->n_closed; i++) {
        glDeleteQueries(1, &t->closed[i].begin);
        glDeleteQueries(1, &t->closed[i].end);
    }
    if (t->is_open && t->open.begin)
        glDeleteQueries(1, &t->open.begin);
    free(t->closed);
    free(t->ms);
    free(t->slot_ms);
    free(t->ran);
    free(t);
    *tp = NULL;
}
