/* progress.c: see progress.h. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"
#include "base/mem.h"
#include "batch/progress.h"

struct job_row {
    char *name;
    enum cv_job_outcome outcome;
    uint32_t spp;
    double seconds;
    char *detail;
};

struct cv_progress {
    enum cv_progress_mode mode;
    FILE *tty, *json;
    bool line_open;      /* a \r-updated bar is on screen */
    bool json_lost;      /* a write to the JSON stream failed: reported, no more tried */
    struct job_row *rows;
    size_t n_rows, cap_rows;
};

static const char *outcome_name(enum cv_job_outcome o)
{
    switch (o) {
    case CV_JOB_DONE: return "done";
    case CV_JOB_PARTIAL: return "partial";
    case CV_JOB_FAILED: return "failed";
    case CV_JOB_SKIPPED: return "skipped";
    }
    return "?";
}

bool cv_progress_mode_parse(const char *name, enum cv_progress_mode *mode)
{
    static const char *const names[] = {"auto", "bar", "json", "none"};
    for (size_t i = 0; i < CV_ARRAY_SIZE(names); i++) {
        if (strcmp(name, names[i]) == 0) {
            *mode = (enum cv_progress_mode)i;
            return true;
        }
    }
    return false;
}

struct cv_progress *cv_progress_create(enum cv_progress_mode mode, FILE *tty, FILE *json)
{
    struct cv_progress *p = cv_xcalloc(1, sizeof(*p));
    if (mode == CV_PROGRESS_AUTO)
        mode = isatty(fileno(tty)) ? CV_PROGRESS_BAR : CV_PROGRESS_NONE;
    p->mode = mode;
    p->tty = tty;
    p->json = json;
    return p;
}

void cv_progress_destroy(struct cv_progress **p)
{
    if (!p || !*p)
        return;
    for (size_t i = 0; i < (*p)->n_rows; i++) {
        free((*p)->rows[i].name);
        free((*p)->rows[i].detail);
    }
    free((*p)->rows);
    free(*p);
    *p = NULL;
}

void cv_json_string(FILE *out, const char *s)
{
    fputc('"', out);
    for (const unsigned char *c = (const unsigned char *)(s ? s : ""); *c; c++) {
        switch (*c) {
        case '"': fputs("\\\"", out); break;
        case '\\': fputs("\\\\", out); break;
        case '\n': fputs("\\n", out); break;
        case '\r': fputs("\\r", out); break;
        case '\t': fputs("\\t", out); break;
        default:
            if (*c < 0x20)
                fprintf(out, "\\u%04x", *c);
            else
                fputc(*c, out);
        }
    }
    fputc('"', out);
}

/* JSON events are written only while the stream takes them. */
static bool json_on(const struct cv_progress *p)
{
    return p->mode == CV_PROGRESS_JSON && !p->json_lost;
}

static void json_begin(struct cv_progress *p, const char *event, const char *job)
{
    fprintf(p->json, "{\"event\":\"%s\"", event);
    if (job) {
        fputs(",\"job\":", p->json);
        cv_json_string(p->json, job);
    }
}

/* A reader that went away (SIGPIPE is ignored, so EPIPE), a full disk: the
 * render goes on, but whoever watches the stream must learn why it stopped. */
static void json_end(struct cv_progress *p)
{
    fputs("}\n", p->json);
    if (fflush(p->json) != 0 || ferror(p->json)) {
        cv_warn("progress stream: write failed (%s); no more progress events are written",
                strerror(errno));
        p->json_lost = true;
    }
}

static void close_line(struct cv_progress *p)
{
    if (p->line_open) {
        fputc('\n', p->tty);
        p->line_open = false;
    }
}

void cv_progress_job_started(struct cv_progress *p, const char *job, unsigned index,
                             unsigned total, uint32_t target_spp)
{
    if (json_on(p)) {
        json_begin(p, "job_started", job);
        fprintf(p->json, ",\"index\":%u,\"total\":%u,\"target_spp\":%u", index, total, target_spp);
        json_end(p);
    } else if (p->mode == CV_PROGRESS_BAR) {
        close_line(p);
        fprintf(p->tty, "[%u/%u] %s\n", index, total, job);
    }
}

static void human_rate(char *buf, size_t n, double v)
{
    if (v >= 1e9)
        snprintf(buf, n, "%.2f Grays/s", v / 1e9);
    else if (v >= 1e6)
        snprintf(buf, n, "%.1f Mrays/s", v / 1e6);
    else if (v > 0)
        snprintf(buf, n, "%.0f krays/s", v / 1e3);
    else
        snprintf(buf, n, "-");
}

void cv_progress_update(struct cv_progress *p, const char *job, uint32_t spp, uint32_t target_spp,
                        double rays_per_s, double elapsed_s, double eta_s)
{
    if (json_on(p)) {
        json_begin(p, "progress", job);
        fprintf(p->json, ",\"spp\":%u,\"target_spp\":%u,\"rays_per_s\":%.0f,\"elapsed_s\":%.3f", spp,
                target_spp, rays_per_s, elapsed_s);
        if (eta_s >= 0)
            fprintf(p->json, ",\"eta_s\":%.1f", eta_s);
        json_end(p);
    } else if (p->mode == CV_PROGRESS_BAR) {
        enum { WIDTH = 30 };
        int fill = target_spp ? (int)((double)spp / target_spp * WIDTH) : 0;
        char bar[WIDTH + 1], rate[32], eta[32] = "";
        for (int i = 0; i < WIDTH; i++)
            bar[i] = i < fill ? '#' : '.';
        bar[WIDTH] = '\0';
        human_rate(rate, sizeof(rate), rays_per_s);
        if (eta_s >= 0)
            snprintf(eta, sizeof(eta), "  ETA %.0fs", eta_s);
        fprintf(p->tty, "\r  [%s] %u/%u spp  %s  %.1fs%s   ", bar, spp, target_spp, rate, elapsed_s,
                eta);
        fflush(p->tty);
        p->line_open = true;
    }
}

void cv_progress_job_ended(struct cv_progress *p, const char *job, enum cv_job_outcome outcome,
                           uint32_t spp, double seconds, const char *detail)
{
    struct job_row row = {
        .name = cv_xstrdup(job),
        .outcome = outcome,
        .spp = spp,
        .seconds = seconds,
        .detail = detail ? cv_xstrdup(detail) : NULL,
    };
    CV_PUSH(p->rows, p->n_rows, p->cap_rows, row);
    if (json_on(p)) {
        char event[32];
        snprintf(event, sizeof(event), "job_%s", outcome == CV_JOB_DONE ? "finished"
                                                 : outcome == CV_JOB_PARTIAL ? "partial"
                                                 : outcome_name(outcome));
        json_begin(p, event, job);
        fprintf(p->json, ",\"spp\":%u,\"seconds\":%.3f", spp, seconds);
        if (detail) {
            fputs(outcome == CV_JOB_FAILED ? ",\"error\":" : ",\"detail\":", p->json);
            cv_json_string(p->json, detail);
        }
        json_end(p);
    } else if (p->mode == CV_PROGRESS_BAR) {
        close_line(p);
        fprintf(p->tty, "  %s: %u spp in %.1fs%s%s\n", outcome_name(outcome), spp, seconds,
                detail ? " - " : "", detail ? detail : "");
    }
}

void cv_progress_summary(struct cv_progress *p)
{
    unsigned counts[4] = {0};
    for (size_t i = 0; i < p->n_rows; i++)
        counts[p->rows[i].outcome]++;
    if (json_on(p)) {
        json_begin(p, "batch_finished", NULL);
        fprintf(p->json, ",\"done\":%u,\"partial\":%u,\"failed\":%u,\"skipped\":%u",
                counts[CV_JOB_DONE], counts[CV_JOB_PARTIAL], counts[CV_JOB_FAILED],
                counts[CV_JOB_SKIPPED]);
        json_end(p);
        return;
    }
    /* The table is for people and logs; -q keeps it for failures only. */
    if (cv_log_get_level() < CV_LOG_INFO && counts[CV_JOB_FAILED] == 0)
        return;
    close_line(p);
    size_t w = 4;
    for (size_t i = 0; i < p->n_rows; i++)
        if (strlen(p->rows[i].name) > w)
            w = strlen(p->rows[i].name);
    fprintf(p->tty, "\n%-*s  %-8s %8s %9s  %s\n", (int)w, "job", "status", "spp", "seconds", "output");
    for (size_t i = 0; i < p->n_rows; i++) {
        const struct job_row *r = &p->rows[i];
        fprintf(p->tty, "%-*s  %-8s %8u %9.2f  %s\n", (int)w, r->name, outcome_name(r->outcome),
                r->spp, r->seconds, r->detail ? r->detail : "");
    }
    fprintf(p->tty, "%u done, %u partial, %u failed, %u skipped\n", counts[CV_JOB_DONE],
            counts[CV_JOB_PARTIAL], counts[CV_JOB_FAILED], counts[CV_JOB_SKIPPED]);
}
