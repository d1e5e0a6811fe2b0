/* atomic_file.c: see atomic_file.h. The temporary file is created with
 * open(O_EXCL, 0666) rather than mkstemp so that the finished image gets the
 * usual permissions under the user's umask instead of mkstemp's 0600. */
#include <errno.h>
#include <dirent.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "base/file.h"
#include "base/mem.h"
#include "output/atomic_file.h"

struct cv_atomic_file {
    char *path;
    char *temp;
    int fd;
    uint64_t end;     /* bytes written so far, for cv_atomic_write */
    int write_errno;  /* first write failure, so commit cannot succeed */
    struct cv_write_limit *limit;  /* NULL: none (tests set one) */
};

void cv_atomic_set_limit(struct cv_atomic_file *f, struct cv_write_limit *limit)
{
    f->limit = limit;
}

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

/* A name that differs between processes and between calls; O_EXCL makes a
 * collision harmless (we try again), so it need not be unpredictable. */
static char *temp_name(const char *dir, const char *base, unsigned attempt)
{
    static const char digits[] = "abcdefghijklmnopqrstuvwxyz0123456789";
    static unsigned long counter;
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    unsigned long long x = (unsigned long long)getpid() * 0x9E3779B97F4A7C15ull
                           ^ (unsigned long long)ts.tv_nsec ^ ((unsigned long long)++counter << 32)
                           ^ attempt;
    char suffix[7];
    for (int i = 0; i < 6; i++) {
        suffix[i] = digits[x % 36];
        x /= 36;
    }
    suffix[6] = '\0';
    if (strcmp(dir, ".") == 0)
        return cv_xasprintf(".%s.%s.tmp", base, suffix);
    return cv_xasprintf("%s/.%s.%s.tmp", dir, base, suffix);
}

/* Whether name is one of temp_name's names for base: ".BASE.xxxxxx.tmp". */
static bool is_temp_of(const char *name, const char *base)
{
    size_t nb = strlen(base);
    if (name[0] != '.' || strncmp(name + 1, base, nb) != 0 || name[1 + nb] != '.')
        return false;
    const char *suffix = name + 2 + nb;
    for (int i = 0; i < 6; i++)
        if (!((suffix[i] >= 'a' && suffix[i] <= 'z') || (suffix[i] >= '0' && suffix[i] <= '9')))
            return false;
    return strcmp(suffix + 6, ".tmp") == 0;
}

/* Removes temporary files of path left by a writer that was killed (SIGKILL,
 * a lost node): this writer replaces path anyway. A scan of one folder per
 * output written. */
static void remove_stale_temps(const char *dir, const char *base)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (!is_temp_of(e->d_name, base))
            continue;
        char *p = cv_xasprintf("%s/%s", dir, e->d_name);
        unlink(p);
        free(p);
    }
    closedir(d);
}

bool cv_atomic_open(const char *path, struct cv_atomic_file **out, struct cv_error *err)
{
    *out = NULL;
    const char *base = base_name(path);
    if (*base == '\0')
        return cv_fail(err, "%s: not a file name", path);
    char *dir = cv_path_dirname(path);
    remove_stale_temps(dir, base);
    for (unsigned attempt = 0; attempt < 100; attempt++) {
        char *temp = temp_name(dir, base, attempt);
        int fd = open(temp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            struct cv_atomic_file *f = cv_xcalloc(1, sizeof(*f));
            f->path = cv_xstrdup(path);
            f->temp = temp;
            f->fd = fd;
            *out = f;
            free(dir);
            return true;
        }
        int e = errno;
        free(temp);
        if (e != EEXIST) {
            cv_fail(err, "%s: cannot create a file in %s: %s", path, dir, strerror(e));
            free(dir);
            return false;
        }
    }
    cv_fail(err, "%s: cannot find a free temporary name in %s", path, dir);
    free(dir);
    return false;
}

bool cv_atomic_write_at(struct cv_atomic_file *f, const void *buf, size_t len,
                        uint64_t offset, struct cv_error *err)
{
    const char *p = buf;
    while (len > 0) {
        size_t n = len;
        ssize_t got;
        if (f->limit && (long long)n > f->limit->bytes)
            n = f->limit->bytes > 0 ? (size_t)f->limit->bytes : 0;
        if (n == 0) {
            errno = f->limit->errnum;
            got = -1;
        } else {
            got = pwrite(f->fd, p, n, (off_t)offset);
        }
        if (got < 0) {
            if (errno == EINTR)
                continue;
            if (!f->write_errno)
                f->write_errno = errno;
            return cv_fail(err, "%s: write failed: %s", f->path, strerror(errno));
        }
        if (f->limit)
            f->limit->bytes -= got;
        p += got;
        len -= (size_t)got;
        offset += (uint64_t)got;
        if (offset > f->end)
            f->end = offset;
    }
    return true;
}

bool cv_atomic_write(struct cv_atomic_file *f, const void *buf, size_t len,
                     struct cv_error *err)
{
    return cv_atomic_write_at(f, buf, len, f->end, err);
}

const char *cv_atomic_path(const struct cv_atomic_file *f)
{
    return f->path;
}

const char *cv_atomic_temp_path(const struct cv_atomic_file *f)
{
    return f->temp;
}

static void free_file(struct cv_atomic_file **f)
{
    free((*f)->path);
    free((*f)->temp);
    free(*f);
    *f = NULL;
}

void cv_atomic_abort(struct cv_atomic_file **f)
{
    if (!f || !*f)
        return;
    if ((*f)->fd >= 0)
        close((*f)->fd);
    unlink((*f)->temp);
    free_file(f);
}

/* Makes the rename itself durable; a folder that cannot be opened or synced
 * (some network filesystems) does not make the image any less complete. */
static void sync_dir(const char *path)
{
    char *dir = cv_path_dirname(path);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
    free(dir);
}

bool cv_atomic_commit(struct cv_atomic_file **fp, struct cv_error *err)
{
    struct cv_atomic_file *f = *fp;
    if (f->write_errno) {
        cv_fail(err, "%s: write failed: %s", f->path, strerror(f->write_errno));
        cv_atomic_abort(fp);
        return false;
    }
    /* A full disk or a failing device often shows only here, on delayed
     * allocation or write-back. */
    if (fsync(f->fd) != 0 && errno != EINVAL && errno != EROFS) {
        cv_fail(err, "%s: cannot sync to disk: %s", f->path, strerror(errno));
        cv_atomic_abort(fp);
        return false;
    }
    int fd = f->fd;
    f->fd = -1;
    if (close(fd) != 0) {
        cv_fail(err, "%s: write failed on close: %s", f->path, strerror(errno));
        cv_atomic_abort(fp);
        return false;
    }
    if (rename(f->temp, f->path) != 0) {
        cv_fail(err, "%s: cannot rename %s to it: %s", f->path, f->temp, strerror(errno));
        cv_atomic_abort(fp);
        return false;
    }
    sync_dir(f->path);
    free_file(fp);
    return true;
}
