/* workers.c: see workers.h. The parent's side (start the workers, hand out
 * jobs, replay their events) and the worker's (ask for jobs, send the log). */
#define _GNU_SOURCE /* fopencookie */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "batch/progress.h"
#include "batch/progress_wire.h"
#include "batch/signals.h"
#include "batch/workers.h"
#include "manifest/manifest.h"

/* ---- the worker's side ---- */

struct cv_worker_link {
    FILE *out;           /* standard output: a socket to the parent */
    int fd;
    char line[4096];     /* the log line being written */
    size_t len;
};

static struct cv_worker_link the_link;

/* The log's stream in a worker: each whole line becomes a log message. */
static ssize_t log_write(void *cookie, const char *buf, size_t size)
{
    struct cv_worker_link *l = cookie;
    for (size_t i = 0; i < size; i++) {
        if (buf[i] != '\n' && l->len + 1 < sizeof(l->line)) {
            l->line[l->len++] = buf[i];
            continue;
        }
        if (buf[i] != '\n')  /* an overlong line goes in pieces */
            l->line[l->len++] = buf[i];
        l->line[l->len] = '\0';
        cv_wire_send(l->out, CV_WIRE_LOG, l->line);
        l->len = 0;
    }
    return (ssize_t)size;
}

struct cv_worker_link *cv_worker_attach(void)
{
    struct cv_worker_link *l = &the_link;
    l->out = stdout;
    l->fd = STDOUT_FILENO;
    FILE *log = fopencookie(l, "w", (cookie_io_functions_t){.write = log_write});
    if (log) {
        setvbuf(log, NULL, _IOLBF, 0);
        cv_log_set_stream(log);
    }
    cv_signals_as_worker();
    return l;
}

/* "claim" out; the parent's answer, a selection index or "none", back. */
static bool claim(struct cv_worker_link *l, size_t n_jobs, size_t *k)
{
    if (!cv_wire_send(l->out, CV_WIRE_CLAIM))
        return false;
    char reply[32];
    size_t n = 0;
    for (;;) {
        ssize_t r = read(l->fd, reply + n, 1);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return false;  /* the parent is gone */
        if (reply[n] == '\n' || ++n == sizeof(reply) - 1)
            break;
    }
    reply[n] = '\0';
    char *end;
    unsigned long v = strtoul(reply, &end, 10);
    if (end == reply || *end || v >= n_jobs)
        return false;  /* "none" */
    *k = v;
    return true;
}

bool cv_batch_next_job(struct cv_worker_link *link, size_t n_jobs, size_t *next, size_t *k)
{
    if (link)
        return claim(link, n_jobs, k);
    if (*next >= n_jobs)
        return false;
    *k = (*next)++;
    return true;
}

/* ---- the parent's side ---- */

struct worker {
    pid_t pid;
    int fd;              /* the socket; -1 once the worker has closed it */
    int gpu;             /* the device asked for, then the one it opened; -1: unknown */
    bool opened_gpu;
    bool claimed;        /* has asked for a job: past validating the batch */
    bool foreign;        /* selected other jobs than the first worker: gets none */
    long job;            /* selection index it renders; -1: none */
    char *buf;           /* bytes read, not yet a whole line */
    size_t len, cap;
    int status;          /* waitpid's */
};

struct parent {
    const struct cv_batch_options *opt;
    const struct cv_workers_params *wp;
    struct cv_progress *progress;
    struct worker *w;
    size_t n;
    char **jobs;         /* the selection, from the first batch_started */
    size_t n_jobs;
    bool have_jobs;
    size_t next;         /* the next job to hand out */
    bool stop;           /* hand out no more (--fail-fast) */
    bool signalled;      /* the parent's signal went to the workers */
    unsigned failed;
    char **seen;         /* log lines and errors of the workers' validation, shown once */
    size_t n_seen, cap_seen;
};

/* Every worker validates the same manifest and scenes: what one says about
 * them the others would repeat. True for text a worker said before. */
static bool said_before(struct parent *P, const struct worker *w, const char *text)
{
    if (w->claimed)
        return false;
    for (size_t i = 0; i < P->n_seen; i++)
        if (strcmp(P->seen[i], text) == 0)
            return true;
    CV_PUSH(P->seen, P->n_seen, P->cap_seen, cv_xstrdup(text));
    return false;
}

static void reply(struct worker *w, const char *text)
{
    size_t n = strlen(text), off = 0;
    while (off < n) {
        ssize_t r = write(w->fd, text + off, n - off);
        if (r < 0 && errno == EINTR)
            continue;
        if (r <= 0)
            return;  /* it has gone: its end of file comes next */
        off += (size_t)r;
    }
}

static void hand_out(struct parent *P, struct worker *w)
{
    w->claimed = true;
    if (P->stop || P->signalled || cv_signals_interrupted() || !P->have_jobs || w->foreign ||
        P->next >= P->n_jobs) {
        reply(w, "none\n");
        return;
    }
    w->job = (long)P->next++;
    char text[32];
    snprintf(text, sizeof(text), "%ld\n", w->job);
    reply(w, text);
}

static void batch_started(struct parent *P, struct worker *w, const struct cv_wire_msg *m)
{
    size_t n;
    const char *const *jobs = cv_wire_list(m, 1, &n);
    if (P->have_jobs) {
        bool same = n == P->n_jobs;
        for (size_t i = 0; same && i < n; i++)
            same = strcmp(jobs[i], P->jobs[i]) == 0;
        if (!same) {
            /* the manifest changed between the workers' reads */
            w->foreign = true;
            cv_error_log("worker %zu selected other jobs than worker 0: it renders none",
                         (size_t)(w - P->w));
        }
        return;
    }
    P->have_jobs = true;
    P->n_jobs = n;
    P->jobs = cv_xcalloc(n ? n : 1, sizeof(char *));
    for (size_t i = 0; i < n; i++)
        P->jobs[i] = cv_xstrdup(jobs[i]);
    cv_progress_source(P->progress, -1, -1);
    cv_progress_batch_started(P->progress, cv_wire_str(m, 0), jobs, n);
}

static void job_ended(struct parent *P, struct worker *w, const struct cv_wire_msg *m)
{
    const char *job = cv_wire_str(m, 0);
    size_t n_out;
    const char *const *outputs = cv_wire_list(m, 7, &n_out);
    struct cv_job_report r = {
        .outcome = (enum cv_job_outcome)cv_wire_uint(m, 1),
        .spp = cv_wire_uint(m, 2),
        .seconds = cv_wire_double(m, 3),
        .scene_seconds = cv_wire_double(m, 4),
        .render_seconds = cv_wire_double(m, 5),
        .detail = cv_wire_str(m, 6),
        .outputs = outputs,
        .n_outputs = n_out,
    };
    if (r.outcome > CV_JOB_SKIPPED)
        r.outcome = CV_JOB_FAILED;
    cv_progress_job_ended(P->progress, job ? job : "?", &r);
    if (w->job >= 0 && job && strcmp(job, P->jobs[w->job]) == 0)
        w->job = -1;
    /* A partial image is a time limit reached, or a signal: to the batch,
     * or to this worker alone, whose exit status then says so (outcome). */
    if (r.outcome == CV_JOB_FAILED) {
        P->failed++;
        P->stop |= P->opt->fail_fast;
    }
}

static void handle_line(struct parent *P, struct worker *w, char *line)
{
    struct cv_wire_msg m;
    size_t wi = (size_t)(w - P->w);
    if (!cv_wire_parse(line, &m)) {
        cv_debug("worker %zu: not a message: %s", wi, line);
        return;
    }
    cv_progress_source(P->progress, (int)wi, w->gpu);
    switch (m.verb) {
    case CV_WIRE_BATCH_STARTED:
        batch_started(P, w, &m);
        break;
    case CV_WIRE_PHASE:
        if (cv_wire_uint(&m, 1) < CV_PHASE_COUNT)
            cv_progress_phase(P->progress, cv_wire_str(&m, 0),
                              (enum cv_phase)cv_wire_uint(&m, 1), cv_wire_str(&m, 2));
        break;
    case CV_WIRE_ERROR:
        if (!said_before(P, w, cv_wire_str(&m, 0) ? cv_wire_str(&m, 0) : ""))
            cv_progress_error(P->progress, cv_wire_str(&m, 0));
        break;
    case CV_WIRE_JOB_STARTED:
        cv_progress_job_started(P->progress, cv_wire_str(&m, 0), cv_wire_uint(&m, 1),
                                cv_wire_uint(&m, 2), cv_wire_uint(&m, 3));
        break;
    case CV_WIRE_UPDATE:
        cv_progress_update(P->progress, cv_wire_str(&m, 0), cv_wire_uint(&m, 1),
                           cv_wire_uint(&m, 2), cv_wire_double(&m, 3), cv_wire_double(&m, 4),
                           cv_wire_double(&m, 5), cv_wire_double(&m, 6));
        break;
    case CV_WIRE_JOB_ENDED:
        job_ended(P, w, &m);
        break;
    case CV_WIRE_GPU:
        w->gpu = cv_wire_int(&m, 0);
        w->opened_gpu = true;
        break;
    case CV_WIRE_LOG: {
        const char *text = cv_wire_str(&m, 0) ? cv_wire_str(&m, 0) : "";
        if (said_before(P, w, text))
            break;
        /* one write per line: the workers' lines do not mix */
        char *out = w->gpu >= 0 ? cv_xasprintf("worker %zu (gpu %d): %s\n", wi, w->gpu, text)
                                : cv_xasprintf("worker %zu: %s\n", wi, text);
        fputs(out, stderr);
        free(out);
        break;
    }
    case CV_WIRE_CLAIM:
        hand_out(P, w);
        break;
    case CV_WIRE_VERB_COUNT:
        break;
    }
    cv_wire_msg_clear(&m);
}

/* "killed by signal 11", "exited with status 70". */
static char *describe_exit(int status)
{
    if (WIFSIGNALED(status))
        return cv_xasprintf("was killed by signal %d", WTERMSIG(status));
    return cv_xasprintf("exited with status %d", WEXITSTATUS(status));
}

/* The worker has closed its end: it has exited or is about to. */
static void worker_ended(struct parent *P, struct worker *w)
{
    close(w->fd);
    w->fd = -1;
    while (waitpid(w->pid, &w->status, 0) < 0 && errno == EINTR)
        ;
    size_t wi = (size_t)(w - P->w);
    enum cv_batch_status s;
    char *why = describe_exit(w->status);
    if (w->job < 0) {
        /* a crash between jobs, or a program that did not start */
        if (!WIFEXITED(w->status) || !P->wp->status_of_exit(WEXITSTATUS(w->status), &s))
            cv_error_log("worker %zu (gpu %d) %s", wi, w->gpu, why);
        free(why);
        return;
    }
    /* The job it had never ended: the parent reports it, once. */
    const char *name = P->jobs[w->job];
    char *msg = cv_xasprintf("job \"%s\": worker %zu (gpu %d) %s before the job ended", name, wi,
                             w->gpu, why);
    cv_error_log("%s", msg);
    cv_progress_source(P->progress, (int)wi, w->gpu);
    cv_progress_job_ended(P->progress, name,
                          &(struct cv_job_report){.outcome = CV_JOB_FAILED, .detail = msg});
    P->failed++;
    P->stop |= P->opt->fail_fast;
    w->job = -1;
    free(why);
    free(msg);
}

static void read_worker(struct parent *P, struct worker *w)
{
    w->buf = cv_xgrow(w->buf, &w->cap, w->len + 65536, 1);
    ssize_t r = read(w->fd, w->buf + w->len, 65536);
    if (r < 0 && errno == EINTR)
        return;
    if (r <= 0) {
        worker_ended(P, w);
        return;
    }
    w->len += (size_t)r;
    size_t start = 0;
    for (size_t i = 0; i < w->len; i++) {
        if (w->buf[i] != '\n')
            continue;
        w->buf[i] = '\0';
        handle_line(P, w, w->buf + start);
        start = i + 1;
    }
    memmove(w->buf, w->buf + start, w->len - start);
    w->len -= start;
}

/* The worker's command line: the parent's options, "--worker=GPU" (which
 * overrides --gpu, --workers and --progress), the manifest. */
static char **worker_argv(const struct cv_workers_params *wp, int gpu)
{
    char **av = cv_xcalloc((size_t)wp->n_options + 4, sizeof(char *));
    size_t n = 0;
    av[n++] = wp->argv[0];
    av[n++] = gpu >= 0 ? cv_xasprintf("--worker=%d", gpu) : cv_xstrdup("--worker=default");
    for (int i = 1; i <= wp->n_options; i++)
        av[n++] = wp->argv[i];
    av[n++] = wp->argv[wp->n_options + 1];
    av[n] = NULL;
    return av;
}

/* Starts worker i. stdin_data: the manifest read from standard input, fed
 * to the worker's (NULL: the worker reads /dev/null). Signals are blocked
 * here; the worker gets the mask the parent had (old). */
static bool start_worker(struct parent *P, size_t i, const char *stdin_data, size_t stdin_len,
                         const sigset_t *old, struct cv_error *err)
{
    struct worker *w = &P->w[i];
    int gpu = P->wp->gpus[i % P->wp->n_gpus];
    *w = (struct worker){.pid = -1, .fd = -1, .gpu = gpu, .job = -1};
    int sv[2], in[2] = {-1, -1};
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0)
        return cv_fail(err, "worker %zu: socketpair: %s", i, strerror(errno));
    if (stdin_data && pipe2(in, O_CLOEXEC) != 0) {
        close(sv[0]);
        close(sv[1]);
        return cv_fail(err, "worker %zu: pipe: %s", i, strerror(errno));
    }
    char **av = worker_argv(P->wp, gpu);
    /* this very program, under its own name (ps and top show it) */
    char self[4096];
    ssize_t self_len = readlink("/proc/self/exe", self, sizeof(self) - 1);
    self[self_len > 0 ? self_len : 0] = '\0';
    pid_t parent = getpid();
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        /* Only async-signal-safe calls until exec. If the parent dies, the
         * worker goes too: no render without anyone to report it. */
        prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (getppid() != parent)
            _exit(127);
        int null = stdin_data ? in[0] : open("/dev/null", O_RDONLY);
        if (dup2(sv[1], STDOUT_FILENO) < 0 || null < 0 || dup2(null, STDIN_FILENO) < 0)
            _exit(127);
        sigprocmask(SIG_SETMASK, old, NULL);
        if (self[0])
            execv(self, av);
        execvp(av[0], av);
        _exit(127);
    }
    int saved = errno;
    free(av[1]);
    free(av);
    close(sv[1]);
    if (in[0] >= 0)
        close(in[0]);
    if (pid < 0) {
        close(sv[0]);
        if (in[1] >= 0)
            close(in[1]);
        return cv_fail(err, "worker %zu: fork: %s", i, strerror(saved));
    }
    w->pid = pid;
    w->fd = sv[0];
    if (in[1] >= 0) {
        /* It reads all of it first thing; if it dies first, EPIPE ends this
         * (SIGPIPE is ignored) and its end of file says the rest. */
        for (size_t off = 0; off < stdin_len;) {
            ssize_t r = write(in[1], stdin_data + off, stdin_len - off);
            if (r < 0 && errno == EINTR)
                continue;
            if (r <= 0)
                break;
            off += (size_t)r;
        }
        close(in[1]);
    }
    return true;
}

static bool any_alive(const struct parent *P)
{
    for (size_t i = 0; i < P->n; i++)
        if (P->w[i].fd >= 0)
            return true;
    return false;
}

/* The batch's status from what the workers said and how they ended. */
static enum cv_batch_status outcome(const struct parent *P)
{
    if (cv_signals_interrupted())
        return CV_BATCH_INTERRUPTED;
    bool invalid = false, no_gpu = false, opened = false, crashed = false, stopped = false;
    for (size_t i = 0; i < P->n; i++) {
        const struct worker *w = &P->w[i];
        enum cv_batch_status s = CV_BATCH_JOBS_FAILED;
        if (w->pid < 0)
            continue;
        if (!WIFEXITED(w->status) || !P->wp->status_of_exit(WEXITSTATUS(w->status), &s))
            crashed = true;
        invalid |= s == CV_BATCH_INVALID;
        stopped |= s == CV_BATCH_INTERRUPTED;  /* by a signal to it alone */
        no_gpu |= s == CV_BATCH_NO_GPU;
        opened |= w->opened_gpu;
    }
    if (invalid)
        return CV_BATCH_INVALID;
    /* Jobs nobody took: every worker lost its GPU, or died. */
    bool unrun = P->have_jobs && P->next < P->n_jobs && !P->stop;
    if (unrun && no_gpu && !opened)
        return CV_BATCH_NO_GPU;
    if (P->failed || unrun || crashed || stopped)
        return CV_BATCH_JOBS_FAILED;
    return CV_BATCH_OK;
}

enum cv_batch_status cv_workers_run(const char *manifest_path, const struct cv_batch_options *opt,
                                    const struct cv_workers_params *wp)
{
    struct parent P = {.opt = opt, .wp = wp, .n = wp->n_workers};
    cv_signals_install();
    P.progress = cv_progress_create(opt->progress, stderr, stdout);
    enum cv_batch_status status = CV_BATCH_OK;
    char *input = NULL;
    size_t input_len = 0;
    struct cv_error err = {{0}};
    if (strcmp(manifest_path, "-") == 0 &&
        !cv_read_stdin(CV_MANIFEST_STDIN, &input, &input_len, &err)) {
        cv_error_log("%s", err.msg);
        cv_progress_error(P.progress, err.msg);
        status = CV_BATCH_INVALID;
        goto done;
    }
    /* Signals wait until pselect, so that none comes between the check
     * and the wait; the workers start with the mask as it was. */
    sigset_t block, old;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    sigprocmask(SIG_BLOCK, &block, &old);
    P.w = cv_xcalloc(P.n, sizeof(*P.w));
    for (size_t i = 0; i < P.n; i++) {
        if (!start_worker(&P, i, input, input_len, &old, &err)) {
            cv_error_log("%s", err.msg);
            P.n = i;  /* those started run the batch */
            break;
        }
    }
    while (any_alive(&P)) {
        if (cv_signals_interrupted() && !P.signalled) {
            P.signalled = true;
            for (size_t i = 0; i < P.n; i++)
                if (P.w[i].fd >= 0)
                    kill(P.w[i].pid, cv_signals_which());
        }
        fd_set rd;
        FD_ZERO(&rd);
        int top = -1;
        for (size_t i = 0; i < P.n; i++) {
            if (P.w[i].fd >= 0) {
                FD_SET(P.w[i].fd, &rd);
                top = P.w[i].fd > top ? P.w[i].fd : top;
            }
        }
        if (pselect(top + 1, &rd, NULL, NULL, NULL, &old) < 0) {
            if (errno == EINTR)
                continue;
            cv_error_log("waiting for the workers: %s", strerror(errno));
            break;
        }
        for (size_t i = 0; i < P.n; i++)
            if (P.w[i].fd >= 0 && FD_ISSET(P.w[i].fd, &rd))
                read_worker(&P, &P.w[i]);
    }
    /* after a failed wait: no worker is left behind */
    for (size_t i = 0; i < P.n; i++) {
        if (P.w[i].fd >= 0) {
            kill(P.w[i].pid, SIGKILL);
            worker_ended(&P, &P.w[i]);
        }
    }
    sigprocmask(SIG_SETMASK, &old, NULL);
    if (!P.n) {
        cv_progress_error(P.progress, err.msg);
        status = CV_BATCH_NO_GPU;
        goto done;
    }
    status = outcome(&P);
done:
    cv_progress_source(P.progress, -1, -1);
    cv_progress_summary(P.progress);
    cv_progress_destroy(&P.progress);
    for (size_t i = 0; i < P.n; i++)
        free(P.w[i].buf);
    free(P.w);
    for (size_t i = 0; i < P.n_jobs; i++)
        free(P.jobs[i]);
    free(P.jobs);
    for (size_t i = 0; i < P.n_seen; i++)
        free(P.seen[i]);
    free(P.seen);
    free(input);
    return status;
}
