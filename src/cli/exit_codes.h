/* exit_codes.h: the exit statuses of cavalry-batch, documented in
 * cavalry-batch(1). Scripts on render farms branch on these. */
#ifndef CV_CLI_EXIT_CODES_H
#define CV_CLI_EXIT_CODES_H

enum cv_exit_code {
    CV_EXIT_OK = 0,            /* every selected job rendered */
    CV_EXIT_JOBS_FAILED = 1,   /* at least one job failed; the others ran */
    CV_EXIT_USAGE = 2,         /* bad command line */
    CV_EXIT_INVALID = 3,       /* invalid manifest or scene: nothing rendered */
    CV_EXIT_NO_GPU = 4,        /* no usable GPU context */
    CV_EXIT_NO_MEMORY = 70,    /* out of host memory (base/mem.h's handler) */
    /* Stopped by SIGINT, SIGTERM or SIGHUP: partial images written; the
     * status is this plus the signal's number (130, 143, 129), as a shell
     * reports a process the signal killed. */
    CV_EXIT_SIGNAL_BASE = 128,
};

#endif
