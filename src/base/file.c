/* file.c: see file.h. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/file.h"
#include "base/limits.h"
#include "base/mem.h"

static bool check_stat(const char *path, const struct stat *st, struct cv_error *err)
{
    if (S_ISDIR(st->st_mode))
        return cv_fail(err, "%s: is a folder, not a file", path);
    if (!S_ISREG(st->st_mode))
        return cv_fail(err, "%s: not a regular file (a device, FIFO or socket)", path);
    if ((long long)st->st_size > CV_MAX_INPUT_BYTES)
        return cv_fail(err, "%s: %lld bytes, more than the %lld bytes an input file may hold",
                       path, (long long)st->st_size, CV_MAX_INPUT_BYTES);
    return true;
}

bool cv_input_check(const char *path, struct cv_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return cv_fail(err, "%s: %s", path, strerror(errno));
    return check_stat(path, &st, err);
}

/* Reads f to its end and closes it, refusing more than an input file may
 * hold; size_hint: the expected size (0: unknown). */
static bool read_all(FILE *f, const char *path, size_t size_hint, char **data, size_t *len,
                     struct cv_error *err)
{
    size_t cap = size_hint + 2 > (1 << 16) ? size_hint + 2 : (1 << 16), n = 0;
    char *buf = cv_xmalloc(cap);
    bool too_big = false;
    for (;;) {
        if (n + 1 >= cap)
            buf = cv_xrealloc(buf, cap *= 2);
        size_t got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            break;
        if ((long long)n > CV_MAX_INPUT_BYTES) { /* it grew while being read, or a pipe */
            too_big = true;
            break;
        }
    }
    bool failed = ferror(f);
    int saved = errno;
    if (f != stdin)
        fclose(f);
    if (failed || too_big) {
        free(buf);
        if (too_big)
            return cv_fail(err, "%s: more than the %lld bytes an input file may hold", path,
                           CV_MAX_INPUT_BYTES);
        return cv_fail(err, "%s: read error: %s", path, strerror(saved));
    }
    buf[n] = '\0';
    *data = buf;
    if (len)
        *len = n;
    return true;
}

bool cv_read_stdin(const char *label, char **data, size_t *len, struct cv_error *err)
{
    return read_all(stdin, label, 0, data, len, err);
}

bool cv_read_file(const char *path, char **data, size_t *len, struct cv_error *err)
{
    /* O_NONBLOCK: opening a FIFO must not wait for a writer; it is then
     * refused as not regular. (The flag means nothing for regular files.) */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0)
        return cv_fail(err, "%s: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int saved = errno;
        close(fd);
        return cv_fail(err, "%s: %s", path, strerror(saved));
    }
    if (!check_stat(path, &st, err)) {
        close(fd);
        return false;
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        int saved = errno;
        close(fd);
        return cv_fail(err, "%s: %s", path, strerror(saved));
    }
    return read_all(f, path, (size_t)st.st_size, data, len, err);
}

char *cv_path_dirname(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return cv_xstrdup(".");
    if (slash == path)
        return cv_xstrdup("/");
    size_t n = (size_t)(slash - path);
    char *d = cv_xmalloc(n + 1);
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

char *cv_path_join(const char *dir, const char *rel)
{
    if (rel[0] == '/' || !dir || !dir[0])
        return cv_xstrdup(rel);
    size_t n = strlen(dir);
    return cv_xasprintf("%s%s%s", dir, dir[n - 1] == '/' ? "" : "/", rel);
}

bool cv_mkdir_parents(const char *path, struct cv_error *err)
{
    char *dir = cv_path_dirname(path);
    bool ok = true;
    for (char *p = dir + 1; ok; p++) {
        bool end = *p == '\0';
        if (*p != '/' && !end)
            continue;
        *p = '\0';
        struct stat st;
        if (stat(dir, &st) != 0) {
            if (mkdir(dir, 0777) != 0 && errno != EEXIST)
                ok = cv_fail(err, "%s: cannot create folder: %s", dir, strerror(errno));
        } else if (!S_ISDIR(st.st_mode)) {
            ok = cv_fail(err, "%s: not a folder", dir);
        }
        if (end)
            break;
        *p = '/';
    }
    free(dir);
    return ok;
}

bool cv_path_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

char *cv_path_normalize(const char *path)
{
    char *joined;
    if (path[0] == '/') {
        joined = cv_xstrdup(path);
    } else {
        char *cwd = getcwd(NULL, 0);
        joined = cv_xasprintf("%s/%s", cwd ? cwd : ".", path);
        free(cwd);
    }
    /* out never outgrows joined: each component is copied at most once */
    char *out = cv_xmalloc(strlen(joined) + 2);
    size_t n = 0;
    for (char *p = joined; *p;) {
        while (*p == '/')
            p++;
        char *end = p;
        while (*end && *end != '/')
            end++;
        size_t len = (size_t)(end - p);
        if (len == 0 || (len == 1 && p[0] == '.')) {
            /* nothing */
        } else if (len == 2 && p[0] == '.' && p[1] == '.') {
            while (n > 0 && out[n - 1] != '/')
                n--;
            if (n > 0)
                n--;
        } else {
            out[n++] = '/';
            memcpy(out + n, p, len);
            n += len;
        }
        p = end;
    }
    if (n == 0)
        out[n++] = '/';
    out[n] = '\0';
    free(joined);
    return out;
}
