/* atomic_file_test.c: a committed file appears whole under its name; every
 * failure (no folder, a file where a folder should be, an unwritable
 * place, a full disk mid-write, a rename that cannot happen) reports the
 * path and reason and leaves neither a temporary nor a changed old file. */
#include <errno.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/error.h"
#include "base/file.h"
#include "base/mem.h"
#include "output/atomic_file.h"
#include "tests/output/output_helpers.h"
#include "tests/tap.h"

static bool has(const struct cv_error *err, const char *part)
{
    bool ok = strstr(err->msg, part) != NULL;
    if (!ok)
        tap_diag("message: %s (wanted \"%s\")", err->msg, part);
    return ok;
}

static void test_commit(const char *dir)
{
    char *path = cv_xasprintf("%s/a.txt", dir);
    struct cv_error err = { { 0 } };
    struct cv_atomic_file *f = NULL;
    tap_ok(cv_atomic_open(path, &f, &err), "open in a writable folder");
    const char *temp = cv_atomic_temp_path(f);
    const char *base = strrchr(temp, '/') + 1;
    tap_ok(strncmp(base, ".a.txt.", 7) == 0 && strcmp(base + strlen(base) - 4, ".tmp") == 0,
           "temporary name is hidden, .a.txt.XXXXXX.tmp (%s)", base);
    tap_ok(!cv_path_exists(path), "final name absent before commit");
    tap_ok(cv_atomic_write(f, "hello ", 6, &err) && cv_atomic_write(f, "world", 5, &err),
           "sequential writes");
    tap_ok(cv_atomic_write_at(f, "W", 1, 6, &err), "positioned write");
    tap_ok(cv_atomic_commit(&f, &err) && f == NULL, "commit succeeds and clears the handle");
    tap_ok(file_is(path, "hello World"), "final file holds what was written");
    TAP_EQ_INT(count_entries(dir), 1, "only the final file in the folder");

    /* Replacing an existing file. */
    tap_ok(cv_atomic_open(path, &f, &err) && cv_atomic_write(f, "new", 3, &err)
               && cv_atomic_commit(&f, &err),
           "second commit replaces the file");
    tap_ok(file_is(path, "new"), "replaced content");
    struct stat st;
    mode_t mask = umask(0);
    umask(mask);
    int st_rc = stat(path, &st);
    tap_ok(st_rc == 0 && (st.st_mode & 0777) == (0666 & ~mask),
           "file mode follows the umask (%o)", (unsigned)(st.st_mode & 0777));

    /* Abort leaves the old file and no temporary. */
    tap_ok(cv_atomic_open(path, &f, &err) && cv_atomic_write(f, "xxxxx", 5, &err), "reopen");
    cv_atomic_abort(&f);
    tap_ok(f == NULL && file_is(path, "new") && count_entries(dir) == 1,
           "abort keeps the old file and removes the temporary");
    cv_atomic_abort(&f);
    cv_atomic_abort(NULL);
    tap_ok(true, "abort accepts NULL");
    free(path);
}

/* Tries to create path in a folder without write permission. Root ignores
 * permissions, so as root the attempt runs in a child that has dropped to
 * the unprivileged "nobody" ids first. True when the open failed, as it
 * must; the message is in err. */
static bool open_in_read_only(const char *path, struct cv_error *err)
{
    struct cv_atomic_file *f = NULL;
    if (geteuid() != 0) {
        bool ok = cv_atomic_open(path, &f, err);
        cv_atomic_abort(&f);
        return !ok;
    }
    int fds[2];
    if (pipe(fds) != 0)
        return false;
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        if (setgid(65534) != 0 || setuid(65534) != 0)
            _exit(2);
        bool ok = cv_atomic_open(path, &f, err);
        cv_atomic_abort(&f);
        if (write(fds[1], err->msg, strlen(err->msg)) < 0)
            _exit(3);
        _exit(ok ? 1 : 0);
    }
    close(fds[1]);
    memset(err->msg, 0, sizeof(err->msg));
    ssize_t got = read(fds[0], err->msg, sizeof(err->msg) - 1);
    (void)got;
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 2)
        tap_diag("could not drop root privileges for this check");
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

static void test_read_only_dir(const char *dir)
{
    char *ro = cv_xasprintf("%s/ro", dir);
    mkdir(ro, 0555);
    chmod(ro, 0555);
    chmod(dir, 0755); /* let the unprivileged child reach ro */
    char *p = cv_xasprintf("%s/x.exr", ro);
    struct cv_error err = { { 0 } };
    tap_ok(open_in_read_only(p, &err), "read-only folder refuses the file%s",
           geteuid() == 0 ? " (as nobody)" : "");
    tap_ok(has(&err, p) && has(&err, strerror(EACCES)), "error names path and EACCES");
    TAP_EQ_INT(count_entries(ro), 0, "read-only folder stays empty");
    chmod(dir, 0700);
    rmdir(ro);
    free(p);
    free(ro);
}

static void test_open_failures(const char *dir)
{
    struct cv_error err = { { 0 } };
    struct cv_atomic_file *f = NULL;

    char *missing = cv_xasprintf("%s/no/such/dir/x.exr", dir);
    tap_ok(!cv_atomic_open(missing, &f, &err) && f == NULL, "no such folder fails");
    tap_ok(has(&err, missing) && has(&err, strerror(ENOENT)), "error names path and reason");
    free(missing);

    char *plain = cv_xasprintf("%s/plain", dir);
    put_file(plain, "x");
    char *under = cv_xasprintf("%s/x.png", plain);
    tap_ok(!cv_atomic_open(under, &f, &err), "a file where a folder is expected fails");
    tap_ok(has(&err, under) && has(&err, strerror(ENOTDIR)), "error says not a directory");
    free(under);
    unlink(plain);
    free(plain);

    /* /proc refuses new files even to root: a real unwritable place. */
    tap_ok(!cv_atomic_open("/proc/cavalry-test.exr", &f, &err), "/proc refuses the write");
    tap_ok(has(&err, "/proc/cavalry-test.exr"), "error names the path (%s)", err.msg);

    test_read_only_dir(dir);
    TAP_EQ_INT(count_entries(dir), 0, "nothing left behind by failed opens");
}

static void test_disk_full(const char *dir)
{
    char *path = cv_xasprintf("%s/full.exr", dir);
    put_file(path, "old");
    struct cv_error err = { { 0 } };
    struct cv_atomic_file *f = NULL;
    static char block[4096];
    memset(block, 'z', sizeof(block));
    tap_ok(cv_atomic_open(path, &f, &err), "open");
    struct cv_write_limit full = {5000, ENOSPC};
    cv_atomic_set_limit(f, &full);
    bool w1 = cv_atomic_write(f, block, sizeof(block), &err);
    bool w2 = cv_atomic_write(f, block, sizeof(block), &err);
    tap_ok(w1 && !w2, "the write that crosses the limit fails");
    tap_ok(has(&err, path) && has(&err, strerror(ENOSPC)), "error names path and ENOSPC");
    tap_ok(!cv_atomic_commit(&f, &err) && f == NULL, "commit after a failed write fails");
    tap_ok(has(&err, strerror(ENOSPC)), "commit reports the write error");
    tap_ok(file_is(path, "old"), "old file under the final name untouched");
    TAP_EQ_INT(count_entries(dir), 1, "no temporary left");
    unlink(path);
    free(path);
}

static void test_rename_failure(const char *dir)
{
    /* A folder under the final name: rename(2) of a file over it fails. */
    char *path = cv_xasprintf("%s/isdir.exr", dir);
    mkdir(path, 0755);
    struct cv_error err = { { 0 } };
    struct cv_atomic_file *f = NULL;
    tap_ok(cv_atomic_open(path, &f, &err) && cv_atomic_write(f, "abc", 3, &err), "open, write");
    tap_ok(!cv_atomic_commit(&f, &err) && f == NULL, "commit onto a folder fails");
    tap_ok(has(&err, path) && has(&err, strerror(EISDIR)), "error names path and reason");
    TAP_EQ_INT(count_entries(dir), 1, "temporary removed, folder kept");
    rmdir(path);
    free(path);
}

int main(void)
{
    char *dir = scratch_dir("atomic");
    test_commit(dir);
    remove_scratch(dir);
    dir = scratch_dir("atomic");
    test_open_failures(dir);
    test_disk_full(dir);
    test_rename_failure(dir);
    remove_scratch(dir);
    return tap_done();
}
