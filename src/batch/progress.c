/* progress.c: see progress.h. The OpenJD lines follow the Open Job
 * Description specification ("How Jobs Are Run": an action's stdout lines
 * "openjd_progress: <number>" with a percentage in [0, 100],
 * "openjd_status: <message>" and "openjd_fail: <message>"), the prefixes the
 * openjd-adaptor-runtime and Deadline Cloud workers parse. */
#include <errno.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/log.h"
#include "base/mem.h"
#include "batch/progress.h"
#include "batch/progress_wire.h"

struct job_row {
    char *name;
    enum cv_job_outcome outcome;
    uint32_t spp;
    double seconds;
    char *detail;        /* outputs space-separated, or why skipped or failed */
};

/* The job a worker runs (index 0 in a single process), for the OpenJD
 * percentage and the bar of a multi-GPU batch. */
struct running {
    char *job;           /* NULL: none */
    double percent;
};

struct cv_progress {
    enum cv_progress_mode mode;
    FILE *tty, *json;
    bool line_open;      /* a \r-updated bar is on screen */
    bool json_lost;      /* a write to the machine stream failed: reported, no more tried */
    struct job_row *rows;
    size_t n_rows, cap_rows;
    char **selected;     /* the batch's jobs, for "never started" */
    bool *reached;
    size_t n_selected;
    int last_openjd;     /* the last openjd_progress percentage printed; -1: none */
    int worker, gpu;     /* cv_progress_source; -1: none */
    struct running *running;
    size_t n_running, cap_running;
};

static const char *const mode_names[] = {"auto", "bar", "json", "none", "openjd"};
const char cv_progress_mode_names[] = "auto, bar, json, openjd, none";

static const char *const phase_names[CV_PHASE_COUNT] = {
    [CV_PHASE_MANIFEST_READ] = "manifest_read",
    [CV_PHASE_SCENE_LOAD] = "scene_load",
    [CV_PHASE_GPU_OPEN] = "gpu_open",
    [CV_PHASE_BVH_BUILD] = "bvh_build",
    [CV_PHASE_PROGRAM_COMPILE] = "program_compile",
    [CV_PHASE_RENDER] = "render",
    [CV_PHASE_COLOUR] = "colour",
    [CV_PHASE_WRITE] = "write",
};

const char *cv_phase_name(enum cv_phase phase)
{
    return phase < CV_PHASE_COUNT ? phase_names[phase] : "?";
}

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
    for (size_t i = 0; i < CV_ARRAY_SIZE(mode_names); i++) {
        if (strcmp(name, mode_names[i]) == 0) {
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
    p->last_openjd = -1;
    p->worker = -1;
    p->gpu = -1;
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
    for (size_t i = 0; i < (*p)->n_selected; i++)
        free((*p)->selected[i]);
    free((*p)->selected);
    free((*p)->reached);
    for (size_t i = 0; i < (*p)->n_running; i++)
        free((*p)->running[i].job);
    free((*p)->running);
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

/* Machine lines are written only while the stream takes them. */
static bool json_on(const struct cv_progress *p)
{
    return p->mode == CV_PROGRESS_JSON && !p->json_lost;
}

static bool openjd_on(const struct cv_progress *p)
{
    return p->mode == CV_PROGRESS_OPENJD && !p->json_lost;
}

/* A worker's calls go to its parent; once the parent is gone (a write
 * fails) there is no one to tell. */
static bool wire_on(const struct cv_progress *p)
{
    return p->mode == CV_PROGRESS_WIRE && !p->json_lost;
}

#define WIRE(p, ...) ((p)->json_lost = !cv_wire_send((p)->json, __VA_ARGS__) || (p)->json_lost)

/* The running job of the worker the events come from. */
static struct running *running_slot(struct cv_progress *p)
{
    size_t w = p->worker > 0 ? (size_t)p->worker : 0;
    while (p->n_running <= w)
        CV_PUSH(p->running, p->n_running, p->cap_running, ((struct running){0}));
    return &p->running[w];
}

void cv_progress_source(struct cv_progress *p, int worker, int gpu)
{
    if (wire_on(p)) {
        WIRE(p, CV_WIRE_GPU, gpu);
        return;
    }
    p->worker = worker;
    p->gpu = gpu;
}

/* A reader that went away (SIGPIPE is ignored, so EPIPE), a full disk: the
 * render goes on, but whoever watches the stream must learn why it stopped. */
static void flush_machine(struct cv_progress *p)
{
    if (fflush(p->json) != 0 || ferror(p->json)) {
        cv_warn("progress stream: write failed (%s); no more progress events are written",
                strerror(errno));
        p->json_lost = true;
    }
}

/* Every event starts with its name and the UTC time, ISO 8601 with
 * milliseconds ("2026-01-31T12:00:00.250Z"): farm logs merge by it. */
static void json_begin(struct cv_progress *p, const char *event, const char *job)
{
    struct timespec ts;
    struct tm tm;
    clock_gettime(CLOCK_REALTIME, &ts);
    gmtime_r(&ts.tv_sec, &tm);
    char when[32];
    strftime(when, sizeof(when), "%Y-%m-%dT%H:%M:%S", &tm);
    fprintf(p->json, "{\"event\":\"%s\",\"time\":\"%s.%03ldZ\"", event, when,
            ts.tv_nsec / 1000000);
    if (job) {
        fputs(",\"job\":", p->json);
        cv_json_string(p->json, job);
    }
    if ((job || p->worker >= 0) && p->gpu >= 0)
        fprintf(p->json, ",\"gpu\":%d", p->gpu);
    if (p->worker >= 0)
        fprintf(p->json, ",\"worker\":%d", p->worker);
}

static void json_end(struct cv_progress *p)
{
    fputs("}\n", p->json);
    flush_machine(p);
}

/* One OpenJD line; a message is kept on its line. */
static void openjd_line(struct cv_progress *p, const char *kind, const char *fmt, ...)
    CV_PRINTF(3, 4);
static void openjd_line(struct cv_progress *p, const char *kind, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof(msg), fmt, ap);
    va_end(ap);
    for (char *c = msg; *c; c++)
        if (*c == '\n' || *c == '\r')
            *c = ' ';
    fprintf(p->json, "openjd_%s: %s\n", kind, msg);
    flush_machine(p);
}

/* Jobs ended so far plus the shares of those running, over the batch. */
static void openjd_progress(struct cv_progress *p)
{
    size_t total = p->n_selected ? p->n_selected : 1;
    double running = 0;
    for (size_t i = 0; i < p->n_running; i++)
        running += p->running[i].job ? p->running[i].percent / 100.0 : 0;
    double pct = ((double)p->n_rows + running) / (double)total * 100.0;
    int whole = pct < 0 ? 0 : pct > 100 ? 100 : (int)pct;
    if (whole == p->last_openjd)
        return;  /* one line per percent, not per pass */
    p->last_openjd = whole;
    openjd_line(p, "progress", "%d", whole);
}

static void mark_reached(struct cv_progress *p, const char *job)
{
    for (size_t i = 0; i < p->n_selected; i++)
        if (!p->reached[i] && strcmp(p->selected[i], job) == 0) {
            p->reached[i] = true;
            return;
        }
}

static void close_line(struct cv_progress *p)
{
    if (p->line_open) {
        fputc('\n', p->tty);
        p->line_open = false;
    }
}

void cv_progress_batch_started(struct cv_progress *p, const char *manifest,
                               const char *const *jobs, size_t n_jobs)
{
    if (p->mode == CV_PROGRESS_WIRE) {
        if (wire_on(p))
            WIRE(p, CV_WIRE_BATCH_STARTED, manifest, jobs, n_jobs);
        return;
    }
    p->selected = cv_xcalloc(n_jobs ? n_jobs : 1, sizeof(char *));
    p->reached = cv_xcalloc(n_jobs ? n_jobs : 1, sizeof(bool));
    p->n_selected = n_jobs;
    for (size_t i = 0; i < n_jobs; i++)
        p->selected[i] = cv_xstrdup(jobs[i]);
    if (json_on(p)) {
        json_begin(p, "batch_started", NULL);
        fputs(",\"manifest\":", p->json);
        cv_json_string(p->json, manifest);
        fputs(",\"jobs\":[", p->json);
        for (size_t i = 0; i < n_jobs; i++) {
            if (i)
                fputc(',', p->json);
            cv_json_string(p->json, jobs[i]);
        }
        fputc(']', p->json);
        json_end(p);
    } else if (openjd_on(p)) {
        openjd_line(p, "status", "%zu job(s) to render", n_jobs);
        openjd_progress(p);
    }
}

void cv_progress_phase(struct cv_progress *p, const char *job, enum cv_phase phase,
                       const char *what)
{
    if (!p)
        return;
    if (wire_on(p)) {
        WIRE(p, CV_WIRE_PHASE, job, (unsigned)phase, what);
    } else if (json_on(p)) {
        json_begin(p, "phase", job);
        fprintf(p->json, ",\"phase\":\"%s\"", cv_phase_name(phase));
        if (what) {
            fputs(",\"file\":", p->json);
            cv_json_string(p->json, what);
        }
        json_end(p);
    } else if (openjd_on(p)) {
        char who[32] = "";  /* each worker of a multi-GPU batch reads and opens its own */
        if (!job && p->worker >= 0)
            snprintf(who, sizeof(who), "worker %d: ", p->worker);
        openjd_line(p, "status", "%s%s%s%s%s%s", who, job ? job : "", job ? ": " : "",
                    cv_phase_name(phase), what ? " " : "", what ? what : "");
    }
}

/* "file:line:col: message": the first ":N:N: " after at least one
 * character (a file name may hold colons, rarely digits between them). */
static bool split_located(const char *s, size_t *file_len, unsigned *line, unsigned *col,
                          const char **msg)
{
    for (const char *c = s + 1; (c = strchr(c, ':')) != NULL; c++) {
        unsigned l, k;
        int n = 0;
        if (sscanf(c, ":%u:%u: %n", &l, &k, &n) == 2 && n > 0 && c[1] >= '0' && c[1] <= '9') {
            *file_len = (size_t)(c - s);
            *line = l;
            *col = k;
            *msg = c + n;
            return true;
        }
    }
    return false;
}

void cv_progress_error(struct cv_progress *p, const char *lines)
{
    if (wire_on(p)) {
        WIRE(p, CV_WIRE_ERROR, lines);
        return;
    }
    if (!json_on(p) && !openjd_on(p))
        return;  /* the log has printed them */
    const char *s = lines ? lines : "";
    do {
        const char *nl = strchr(s, '\n');
        char *one = nl ? cv_xasprintf("%.*s", (int)(nl - s), s) : cv_xstrdup(s);
        size_t file_len;
        unsigned line, col;
        const char *msg;
        if (json_on(p)) {
            json_begin(p, "error", NULL);
            if (split_located(one, &file_len, &line, &col, &msg)) {
                one[file_len] = '\0';
                fputs(",\"file\":", p->json);
                cv_json_string(p->json, one);
                fprintf(p->json, ",\"line\":%u,\"column\":%u", line, col);
            } else {
                msg = one;
            }
            fputs(",\"message\":", p->json);
            cv_json_string(p->json, msg);
            json_end(p);
        } else if (openjd_on(p)) {
            openjd_line(p, "fail", "%s", one);
        }
        free(one);
        s = nl ? nl + 1 : NULL;
    } while (s && *s);
}

void cv_progress_job_started(struct cv_progress *p, const char *job, unsigned index,
                             unsigned total, uint32_t target_spp)
{
    if (p->mode == CV_PROGRESS_WIRE) {
        if (wire_on(p))
            WIRE(p, CV_WIRE_JOB_STARTED, job, index, total, (unsigned)target_spp);
        return;
    }
    mark_reached(p, job);
    struct running *r = running_slot(p);
    free(r->job);
    *r = (struct running){.job = cv_xstrdup(job)};
    /* the bar and the OpenJD status name the device when several run */
    char where[48] = "";
    if (p->worker >= 0)
        snprintf(where, sizeof(where), " on gpu %d (worker %d)", p->gpu, p->worker);
    if (json_on(p)) {
        json_begin(p, "job_started", job);
        fprintf(p->json, ",\"index\":%u,\"total\":%u,\"target_spp\":%u", index, total, target_spp);
        json_end(p);
    } else if (openjd_on(p)) {
        openjd_line(p, "status", "job %u/%u: %s%s", index, total, job, where);
    } else if (p->mode == CV_PROGRESS_BAR) {
        close_line(p);
        fprintf(p->tty, "[%u/%u] %s%s\n", index, total, job, where);
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
                        double rays_per_s, double elapsed_s, double percent, double eta_s)
{
    if (p->mode == CV_PROGRESS_WIRE) {
        if (wire_on(p))
            WIRE(p, CV_WIRE_UPDATE, job, (unsigned)spp, (unsigned)target_spp, rays_per_s,
                 elapsed_s, percent, eta_s);
        return;
    }
    running_slot(p)->percent = percent;
    if (json_on(p)) {
        json_begin(p, "progress", job);
        fprintf(p->json,
                ",\"spp\":%u,\"target_spp\":%u,\"percent\":%.1f,\"rays_per_s\":%.0f,"
                "\"elapsed_s\":%.3f",
                spp, target_spp, percent, rays_per_s, elapsed_s);
        if (eta_s >= 0)
            fprintf(p->json, ",\"eta_s\":%.1f", eta_s);
        json_end(p);
    } else if (openjd_on(p)) {
        openjd_progress(p);
    } else if (p->mode == CV_PROGRESS_BAR && p->worker >= 0) {
        /* several jobs at once: one line with each worker's */
        fputs("\r ", p->tty);
        for (size_t i = 0; i < p->n_running; i++)
            if (p->running[i].job)
                fprintf(p->tty, " [%zu] %s %.0f%%", i, p->running[i].job, p->running[i].percent);
        fputs("   ", p->tty);
        fflush(p->tty);
        p->line_open = true;
    } else if (p->mode == CV_PROGRESS_BAR) {
        enum { WIDTH = 30 };
        int fill = (int)(percent / 100.0 * WIDTH);
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

void cv_progress_job_ended(struct cv_progress *p, const char *job, const struct cv_job_report *r)
{
    if (p->mode == CV_PROGRESS_WIRE) {
        if (wire_on(p))
            WIRE(p, CV_WIRE_JOB_ENDED, job, (unsigned)r->outcome, (unsigned)r->spp, r->seconds,
                 r->scene_seconds, r->render_seconds, r->detail, r->outputs, r->n_outputs);
        return;
    }
    mark_reached(p, job);
    struct running *slot = running_slot(p);
    free(slot->job);
    slot->job = NULL;
    slot->percent = 0;
    char *detail = NULL;
    if (r->n_outputs) {
        size_t n = 1;
        for (size_t i = 0; i < r->n_outputs; i++)
            n += strlen(r->outputs[i]) + 1;
        detail = cv_xcalloc(n, 1);
        for (size_t i = 0; i < r->n_outputs; i++) {
            if (i)
                strcat(detail, " ");
            strcat(detail, r->outputs[i]);
        }
    } else if (r->detail) {
        detail = cv_xstrdup(r->detail);
    }
    struct job_row row = {
        .name = cv_xstrdup(job),
        .outcome = r->outcome,
        .spp = r->spp,
        .seconds = r->seconds,
        .detail = detail,
    };
    CV_PUSH(p->rows, p->n_rows, p->cap_rows, row);
    if (json_on(p)) {
        char event[32];
        snprintf(event, sizeof(event), "job_%s", r->outcome == CV_JOB_DONE ? "finished"
                                                 : outcome_name(r->outcome));
        json_begin(p, event, job);
        fprintf(p->json,
                ",\"spp\":%u,\"seconds\":%.3f,\"scene_seconds\":%.3f,\"render_seconds\":%.3f",
                r->spp, r->seconds, r->scene_seconds, r->render_seconds);
        fputs(",\"outputs\":[", p->json);
        for (size_t i = 0; i < r->n_outputs; i++) {
            if (i)
                fputc(',', p->json);
            cv_json_string(p->json, r->outputs[i]);
        }
        fputc(']', p->json);
        if (r->detail) {
            fputs(r->outcome == CV_JOB_FAILED ? ",\"error\":" : ",\"detail\":", p->json);
            cv_json_string(p->json, r->detail);
        }
        json_end(p);
    } else if (openjd_on(p)) {
        openjd_line(p, "status", "%s: %s%s%s", job, outcome_name(r->outcome),
                    r->detail ? ": " : "", r->detail ? r->detail : "");
        openjd_progress(p);
    } else if (p->mode == CV_PROGRESS_BAR) {
        close_line(p);
        if (p->worker >= 0)  /* ends of several workers' jobs interleave */
            fprintf(p->tty, "  %s", job);
        fprintf(p->tty, "  %s: %u spp in %.1fs%s%s\n", outcome_name(r->outcome), r->spp,
                r->seconds, detail ? " - " : "", detail ? detail : "");
    }
}

void cv_progress_summary(struct cv_progress *p)
{
    if (p->mode == CV_PROGRESS_WIRE)
        return;  /* the parent sums up every worker's */
    unsigned counts[4] = {0};
    for (size_t i = 0; i < p->n_rows; i++)
        counts[p->rows[i].outcome]++;
    size_t never = 0;
    for (size_t i = 0; i < p->n_selected; i++)
        never += !p->reached[i];
    if (json_on(p)) {
        json_begin(p, "batch_finished", NULL);
        fprintf(p->json, ",\"done\":%u,\"partial\":%u,\"failed\":%u,\"skipped\":%u",
                counts[CV_JOB_DONE], counts[CV_JOB_PARTIAL], counts[CV_JOB_FAILED],
                counts[CV_JOB_SKIPPED]);
        fprintf(p->json, ",\"not_started\":[");
        for (size_t i = 0, k = 0; i < p->n_selected; i++) {
            if (p->reached[i])
                continue;
            if (k++)
                fputc(',', p->json);
            cv_json_string(p->json, p->selected[i]);
        }
        fputc(']', p->json);
        json_end(p);
        return;
    }
    if (openjd_on(p)) {
        openjd_line(p, "status", "%u done, %u partial, %u failed, %u skipped, %zu not started",
                    counts[CV_JOB_DONE], counts[CV_JOB_PARTIAL], counts[CV_JOB_FAILED],
                    counts[CV_JOB_SKIPPED], never);
        return;
    }
    /* The table is for people and logs; -q keeps it for failures only. */
    if (p->n_rows == 0 || (cv_log_get_level() < CV_LOG_INFO && counts[CV_JOB_FAILED] == 0))
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
    fprintf(p->tty, "%u done, %u partial, %u failed, %u skipped", counts[CV_JOB_DONE],
            counts[CV_JOB_PARTIAL], counts[CV_JOB_FAILED], counts[CV_JOB_SKIPPED]);
    if (never)
        fprintf(p->tty, ", %zu not started", never);
    fputc('\n', p->tty);
}
