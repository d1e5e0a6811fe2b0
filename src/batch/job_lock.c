/* job_lock.c: see job_lock.h. */
#include <errno.h>
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

#include "base/file.h"
#include "base/mem.h"
#include "batch/job_lock.h"

struct cv_job_lock {
    int fd;
};

/* "dir/base" -> "dir/.base.lock", hidden like the temporary files. */
static char *lock_path(const struct cv_job *job)
{
    char *out = cv_job_output_path(job, NULL);
    char *slash = strrchr(out, '/');
    char *path = slash ? cv_xasprintf("%.*s/.%s.lock", (int)(slash - out), out, slash + 1)
                       : cv_xasprintf(".%s.lock", out);
    free(out);
    return path;
}

enum cv_lock_status cv_job_lock_take(const struct cv_job *job, struct cv_job_lock **lock,
                                     struct cv_error *err)
{
    *lock = NULL;
    char *path = lock_path(job);
    if (!cv_mkdir_parents(path, err)) {
        free(path);
        return CV_LOCK_FAILED;
    }
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd < 0) {
        cv_fail(err, "%s: cannot open the job's lock file: %s", path, strerror(errno));
        free(path);
        return CV_LOCK_FAILED;
    }
    int rc;
    do
        rc = flock(fd, LOCK_EX | LOCK_NB);
    while (rc != 0 && errno == EINTR);
    if (rc != 0) {
        int saved = errno;
        close(fd);
        if (saved == EWOULDBLOCK) {
            free(path);
            return CV_LOCK_BUSY;
        }
        cv_fail(err, "%s: cannot lock: %s", path, strerror(saved));
        free(path);
        return CV_LOCK_FAILED;
    }
    free(path);
    *lock = cv_xcalloc(1, sizeof(**lock));
    (*lock)->fd = fd;
    return CV_LOCK_TAKEN;
}

void cv_job_lock_release(struct cv_job_lock **lock)
{
    if (!lock || !*lock)
        return;
    close((*lock)->fd); /* closing the last descriptor drops the flock */
    free(*lock);
    *lock = NULL;
}
