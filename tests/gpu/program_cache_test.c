/* program_cache_test.c: the disk cache of program binaries. A first
 * compile writes an entry, a fresh context loads it and the program still
 * computes right; damaged entries (truncated, corrupt binary) are rebuilt and
 * rewritten; other defines make other entries; CAVALRY_CACHE_DIR=off writes
 * nothing. Where the driver offers no binary formats, the cache must do
 * nothing and everything still works. Programs requested ahead
 * (cv_program_request) hit the cache the same way. */
/* nftw needs the X/Open extension. */
#define _XOPEN_SOURCE 700
#include "config.h"

#include <dirent.h>
#include <ftw.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/file.h"
#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

static char *cache_dir;

/* Number of program-*.bin entries; *first receives one's path. */
static int count_entries(const char *dir, char **first)
{
    DIR *d = opendir(dir);
    int n = 0;
    if (!d)
        return 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (strncmp(e->d_name, "program-", 8) != 0)
            continue;
        if (strstr(e->d_name, ".tmp.")) {
            tap_diag("leftover temporary file %s", e->d_name);
            n += 1000;
        }
        if (first && !n)
            *first = cv_xasprintf("%s/%s", dir, e->d_name);
        n++;
    }
    closedir(d);
    return n;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    return remove(path);
}

/* The driver may put its own cache below the temporary XDG folder too. */
static void remove_tree(const char *dir)
{
    nftw(dir, remove_one, 16, FTW_DEPTH | FTW_PHYS);
}

static void remove_tree_files(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.')
            continue;
        char *p = cv_xasprintf("%s/%s", dir, e->d_name);
        unlink(p);
        free(p);
    }
    closedir(d);
}

/* Runs glsl/gpu/selftest.comp with SELFTEST_MUL=mul and checks every
 * element; returns the program's disk stats at the end. */
static struct cv_program_disk_stats run_selftest(struct cv_gpu *gpu, unsigned mul,
                                                 const char *what)
{
    struct cv_error err = {{0}};
    char def[32];
    snprintf(def, sizeof(def), "SELFTEST_MUL=%uu", mul);
    const char *defines[] = {def, NULL};
    struct cv_program_disk_stats st = {0};
    struct cv_program *prog = cv_program_get(gpu, "gpu/selftest.comp", defines, &err);
    if (!tap_ok(prog != NULL, "%s: selftest.comp (x%u) ready: %s", what, mul,
                prog ? "yes" : err.msg))
        return st;
    tap_ok(prog->local_size[0] == 64, "%s: local size 64 (%u)", what, prog->local_size[0]);
    const uint32_t n = 1003;
    uint32_t in[1003], out[1003];
    uint32_t state = 12345;
    for (uint32_t i = 0; i < n; i++) {
        state = state * 1664525u + 1013904223u;
        in[i] = state;
    }
    GLuint b_in = cv_buffer_create(sizeof(in), in, "selftest in", &err);
    GLuint b_out = cv_buffer_create(sizeof(out), NULL, "selftest out", &err);
    cv_buffer_bind(b_in, CV_BIND_CHECK_IN);
    cv_buffer_bind(b_out, CV_BIND_CHECK_OUT);
    glUseProgram(prog->id);
    glUniform1ui(glGetUniformLocation(prog->id, "u_count"), n);
    cv_program_dispatch_1d(prog, n);
    bool read = cv_buffer_read(b_out, 0, sizeof(out), out, &err);
    uint32_t bad = 0;
    for (uint32_t i = 0; read && i < n; i++)
        bad += out[i] != in[i] * mul + i;
    tap_ok(read && bad == 0, "%s: every element equals in*%u+i (%u wrong)", what, mul, bad);
    cv_buffer_destroy(&b_in);
    cv_buffer_destroy(&b_out);
    cv_program_cache_stats(gpu, &st);
    return st;
}

static struct cv_gpu *reopen(struct cv_gpu **gpu)
{
    cv_gpu_destroy(gpu);
    return test_gpu_open(CV_BACKEND_AUTO);
}

static void check_dir_resolution(void)
{
    const char *saved_home = getenv("HOME");
    char *home = saved_home ? cv_xstrdup(saved_home) : NULL;
    setenv("CAVALRY_CACHE_DIR", "/x/c", 1);
    setenv("XDG_CACHE_HOME", "/x/xdg", 1);
    setenv("HOME", "/x/home", 1);
    char *d = cv_program_disk_cache_dir();
    tap_ok(d && strcmp(d, "/x/c") == 0, "CAVALRY_CACHE_DIR wins (%s)", d ? d : "NULL");
    free(d);
    unsetenv("CAVALRY_CACHE_DIR");
    d = cv_program_disk_cache_dir();
    tap_ok(d && strcmp(d, "/x/xdg/cavalry") == 0, "then $XDG_CACHE_HOME/cavalry (%s)",
           d ? d : "NULL");
    free(d);
    setenv("XDG_CACHE_HOME", "relative", 1);
    d = cv_program_disk_cache_dir();
    tap_ok(d && strcmp(d, "/x/home/.cache/cavalry") == 0,
           "a relative XDG_CACHE_HOME is skipped for $HOME/.cache/cavalry (%s)", d ? d : "NULL");
    free(d);
    unsetenv("XDG_CACHE_HOME");
    unsetenv("HOME");
    d = cv_program_disk_cache_dir();
    tap_ok(d == NULL, "no variable: no cache");
    free(d);
    setenv("CAVALRY_CACHE_DIR", "off", 1);
    setenv("HOME", "/x/home", 1);
    d = cv_program_disk_cache_dir();
    tap_ok(d == NULL, "CAVALRY_CACHE_DIR=off: no cache");
    free(d);
    if (home)
        setenv("HOME", home, 1);
    else
        unsetenv("HOME");
    free(home);
}

/* Rewrites the entry at path with one byte of its binary flipped and the
 * file's checksum made to match, so only the driver can notice. */
static bool corrupt_binary(const char *path)
{
    char *data = NULL;
    size_t len = 0;
    struct cv_error err = {{0}};
    if (!cv_read_file(path, &data, &len, &err))
        return false;
    struct cv_program_file_header h;
    bool ok = len > sizeof(h);
    if (ok) {
        memcpy(&h, data, sizeof(h));
        ok = h.binary_len > 16 && len == sizeof(h) + h.key_len + h.binary_len;
    }
    if (ok) {
        char *bin = data + sizeof(h) + h.key_len;
        for (uint32_t i = h.binary_len / 2; i < h.binary_len / 2 + 8; i++)
            bin[i] ^= 0x5a;
        h.checksum = cv_program_file_checksum(CV_FNV_OFFSET, data + sizeof(h),
                                              h.key_len + (size_t)h.binary_len);
        memcpy(data, &h, sizeof(h));
        FILE *f = fopen(path, "wb");
        ok = f && fwrite(data, 1, len, f) == len;
        if (f)
            ok &= fclose(f) == 0;
    }
    free(data);
    return ok;
}

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/* The driver's own cache goes below ours unless the user placed it. */
static void check_driver_cache_placement(const char *root)
{
    char *ours = cv_xasprintf("%s/placed", root);
    char *want = cv_xasprintf("%s/driver", ours);
    setenv("CAVALRY_CACHE_DIR", ours, 1);
    unsetenv("__GL_SHADER_DISK_CACHE_PATH");
    cv_program_disk_cache_place_driver_cache();
    const char *v = getenv("__GL_SHADER_DISK_CACHE_PATH");
    struct stat st;
    tap_ok(v && strcmp(v, want) == 0 && stat(want, &st) == 0 && S_ISDIR(st.st_mode),
           "driver cache placed in %s (%s)", want, v ? v : "unset");
    setenv("__GL_SHADER_DISK_CACHE_PATH", "/x/user", 1);
    cv_program_disk_cache_place_driver_cache();
    v = getenv("__GL_SHADER_DISK_CACHE_PATH");
    tap_ok(v && strcmp(v, "/x/user") == 0, "a user's __GL_SHADER_DISK_CACHE_PATH stays (%s)",
           v ? v : "unset");
    unsetenv("__GL_SHADER_DISK_CACHE_PATH");
    setenv("CAVALRY_CACHE_DIR", "off", 1);
    cv_program_disk_cache_place_driver_cache();
    tap_ok(!getenv("__GL_SHADER_DISK_CACHE_PATH"), "CAVALRY_CACHE_DIR=off: driver cache left alone");
    unsetenv("CAVALRY_CACHE_DIR");
    free(want);
    free(ours);
}

int main(void)
{
    check_dir_resolution();

    const char *tmp = getenv("TMPDIR") && getenv("TMPDIR")[0] ? getenv("TMPDIR") : "/tmp";
    char *templ = cv_xasprintf("%s/cv_progcache_XXXXXX", tmp);
    if (!mkdtemp(templ)) {
        free(templ);
        return tap_skip_all("cannot make a temporary folder");
    }
    check_driver_cache_placement(templ);
    /* A folder below the temporary one: the cache must create it. */
    cache_dir = cv_xasprintf("%s/cache", templ);
    setenv("CAVALRY_CACHE_DIR", cache_dir, 1);

    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_program_disk_stats st = run_selftest(gpu, 3, "first run");
    if (st.n_formats == 0) {
        tap_diag("%s offers no program binary formats (GL_NUM_PROGRAM_BINARY_FORMATS = 0): "
                 "the disk cache is a no-op here; checking only that",
                 gpu->info.renderer);
        tap_ok(!st.enabled && st.hits + st.misses + st.writes + st.rejected == 0,
               "no formats: cache disabled, nothing counted");
        tap_ok(count_entries(cache_dir, NULL) == 0, "no formats: nothing written");
        st = run_selftest(gpu = reopen(&gpu), 3, "second context");
        cv_gpu_destroy(&gpu);
        remove_tree(templ);
        free(cache_dir);
        free(templ);
        return tap_done();
    }
    tap_diag("%d program binary format(s)", st.n_formats);
    tap_ok(st.enabled && st.misses == 1 && st.hits == 0 && st.writes == 1,
           "first compile: a miss and a write (miss %u hit %u write %u)", st.misses, st.hits,
           st.writes);
    char *entry = NULL;
    tap_ok(count_entries(cache_dir, &entry) == 1 && entry, "one entry in the folder");
    long size = entry ? file_size(entry) : -1;

    /* Requested first (compiling ahead, gpu/program.h), as the renderer
     * does: still a hit; a request never got writes nothing. */
    gpu = reopen(&gpu);
    const char *defs9[] = {"SELFTEST_MUL=9u", NULL};
    const char *defs3r[] = {"SELFTEST_MUL=3u", NULL};
    cv_program_request(gpu, "gpu/selftest.comp", defs3r);
    cv_program_request(gpu, "gpu/selftest.comp", defs9);
    st = run_selftest(gpu, 3, "second context");
    struct cv_program_build_stats bs;
    cv_program_build_stats(gpu, &bs);
    /* the unused request looked on disk too */
    unsigned ahead = bs.parallel ? 1u : 0u;
    tap_ok(st.hits == 1 && st.misses == ahead && st.rejected == 0 && st.writes == 0,
           "second context loads from disk (hit %u miss %u rejected %u write %u)", st.hits,
           st.misses, st.rejected, st.writes);
    tap_ok(bs.cache_hits == 1 && bs.unused == ahead,
           "build stats: one hit, the unused request counted (%u, %u)", bs.cache_hits, bs.unused);
    tap_ok(count_entries(cache_dir, NULL) == 1, "a request never got writes no entry");
    struct cv_error err = {{0}};
    const char *defs3[] = {"SELFTEST_MUL=3u", NULL};
    struct cv_program *p1 = cv_program_get(gpu, "gpu/selftest.comp", defs3, &err);
    tap_ok(p1 && p1 == cv_program_get(gpu, "gpu/selftest.comp", defs3, &err),
           "in-memory cache still serves the same program");
    cv_program_cache_stats(gpu, &st);
    tap_ok(st.hits == 1, "in-memory hits do not touch the disk (%u)", st.hits);

    st = run_selftest(gpu, 5, "other defines");
    tap_ok(st.misses == 1 + ahead && st.writes == 1, "other defines: a miss and a write");
    tap_ok(count_entries(cache_dir, NULL) == 2, "other defines: a second entry");

    /* Truncated entry. */
    cv_gpu_destroy(&gpu);
    if (entry)
        tap_ok(truncate(entry, size / 2) == 0, "entry truncated");
    st = run_selftest(gpu = test_gpu_open(CV_BACKEND_AUTO), 3, "truncated entry");
    tap_ok(st.rejected == 1 && st.hits == 0 && st.writes == 1,
           "truncated entry ignored and rewritten (rejected %u hit %u write %u)", st.rejected,
           st.hits, st.writes);
    tap_ok(entry && file_size(entry) == size, "rewritten entry has its full size (%ld)",
           entry ? file_size(entry) : -1);

    /* A binary the driver must refuse, behind a matching checksum. */
    cv_gpu_destroy(&gpu);
    tap_ok(entry && corrupt_binary(entry), "entry's binary corrupted");
    st = run_selftest(gpu = test_gpu_open(CV_BACKEND_AUTO), 3, "corrupt binary");
    tap_ok(st.rejected + st.hits == 1 && st.writes == st.rejected,
           "corrupt binary: refused and rewritten, or accepted and still correct "
           "(rejected %u hit %u write %u)",
           st.rejected, st.hits, st.writes);
    if (st.hits)
        tap_diag("the driver accepted the damaged binary (the output check above still held)");

    /* Garbage where a file should be. */
    cv_gpu_destroy(&gpu);
    FILE *f = entry ? fopen(entry, "wb") : NULL;
    if (f) {
        fputs("not a program", f);
        fclose(f);
    }
    st = run_selftest(gpu = test_gpu_open(CV_BACKEND_AUTO), 3, "garbage entry");
    tap_ok(st.rejected == 1 && st.writes == 1, "garbage entry ignored and rewritten");
    st = run_selftest(gpu = reopen(&gpu), 3, "after the rewrite");
    tap_ok(st.hits == 1 && st.rejected == 0, "the rewritten entry loads");

    /* off: nothing anywhere. */
    cv_gpu_destroy(&gpu);
    remove_tree_files(cache_dir);
    char *xdg = cv_xasprintf("%s/xdg", templ);
    setenv("XDG_CACHE_HOME", xdg, 1);
    setenv("CAVALRY_CACHE_DIR", "off", 1);
    st = run_selftest(gpu = test_gpu_open(CV_BACKEND_AUTO), 3, "CAVALRY_CACHE_DIR=off");
    tap_ok(!st.enabled && st.hits + st.misses + st.writes + st.rejected == 0,
           "off: disabled, nothing counted");
    char *xdg_cav = cv_xasprintf("%s/cavalry", xdg);
    tap_ok(count_entries(cache_dir, NULL) == 0 && !cv_path_exists(xdg_cav), "off: nothing written");
    cv_gpu_destroy(&gpu);

    free(xdg_cav);
    free(xdg);
    free(entry);
    remove_tree(templ);
    free(cache_dir);
    free(templ);
    return tap_done();
}
