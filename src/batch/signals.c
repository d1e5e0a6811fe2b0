/* signals.c: see signals.h. */
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include "batch/signals.h"

static volatile sig_atomic_t received;
static volatile sig_atomic_t as_worker;

static void on_signal(int sig)
{
    if (as_worker) {
        /* The parent has said it; a second signal ends the parent, and
         * the kernel then ends its workers (workers.c). */
        if (!received)
            received = sig;
        return;
    }
    if (received) {
        /* Asked twice: the user means it. Nothing half-written remains,
         * since every output goes through a temporary file. */
        signal(sig, SIG_DFL);
        raise(sig);
        return;
    }
    received = sig;
    static const char msg[] = "\nstopping after this pass (signal again to quit now)\n";
    ssize_t ignored = write(STDERR_FILENO, msg, sizeof(msg) - 1);
    (void)ignored;
}

void cv_signals_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    /* A reader that goes away (a pipe to "head -1", a closed log) must not
     * kill the render: writes then fail with EPIPE, which the progress
     * stream reports once. */
    sa.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &sa, NULL);
}

void cv_signals_as_worker(void)
{
    as_worker = 1;
}

bool cv_signals_interrupted(void)
{
    return received != 0;
}

int cv_signals_which(void)
{
    return received;
}
