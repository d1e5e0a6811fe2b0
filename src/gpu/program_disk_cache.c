/* program_disk_cache.c: see program_disk_cache.h. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/file.h"
#include "base/log.h"
#include "base/mem.h"
#include "gpu/program_disk_cache.h"

struct cv_program_disk_cache {
    char *dir;             /* NULL when disabled */
    GLint *formats;
    int n_formats;
    char *driver;          /* the key's driver part */
    struct cv_program_disk_stats stats;
};

uint64_t cv_program_file_checksum(uint64_t h, const void *data, size_t len)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < len; i++) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

/* Only absolute values count: XDG says relative ones are to be ignored,
 * and a relative HOME would follow the working directory around. */
static const char *abs_env(const char *name)
{
    const char *v = getenv(name);
    return v && v[0] == '/' ? v : NULL;
}

char *cv_program_disk_cache_dir(void)
{
    const char *v = getenv("CAVALRY_CACHE_DIR");
    if (v && strcmp(v, "off") == 0)
        return NULL;
    if (v && v[0])
        return cv_xstrdup(v);
    if ((v = abs_env("XDG_CACHE_HOME")))
        return cv_xasprintf("%s/cavalry", v);
    if ((v = abs_env("HOME")))
        return cv_xasprintf("%s/.cache/cavalry", v);
    return NULL;
}

void cv_program_disk_cache_place_driver_cache(void)
{
    if (getenv("__GL_SHADER_DISK_CACHE_PATH"))
        return;
    char *dir = cv_program_disk_cache_dir();
    if (!dir)
        return;
    char *sub = cv_path_join(dir, "driver");
    char *probe = cv_path_join(sub, "x");
    struct cv_error err = {{0}};
    if (cv_mkdir_parents(probe, &err))
        setenv("__GL_SHADER_DISK_CACHE_PATH", sub, 0);
    else
        cv_debug("program cache: %s unusable for the driver's cache (%s)", sub, err.msg);
    free(probe);
    free(sub);
    free(dir);
}

struct cv_program_disk_cache *cv_program_disk_cache_open(const struct cv_gpu_info *info)
{
    struct cv_program_disk_cache *dc = cv_xcalloc(1, sizeof(*dc));
    GLint n = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &n);
    dc->stats.n_formats = n;
    char *dir = cv_program_disk_cache_dir();
    if (!dir) {
        cv_debug("program cache: no folder (CAVALRY_CACHE_DIR=off or no HOME): disabled");
        return dc;
    }
    if (n <= 0) {
        cv_debug("program cache: %s offers no program binary formats: disabled", info->renderer);
        free(dir);
        return dc;
    }
    char *probe = cv_path_join(dir, "x");
    struct cv_error err = {{0}};
    bool ok = cv_mkdir_parents(probe, &err);
    free(probe);
    if (!ok || access(dir, R_OK | X_OK) != 0) {
        cv_debug("program cache: %s unusable (%s): disabled", dir,
                 ok ? strerror(errno) : err.msg);
        free(dir);
        return dc;
    }
    dc->dir = dir;
    dc->n_formats = n;
    dc->formats = cv_xcalloc((size_t)n, sizeof(GLint));
    glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, dc->formats);
    dc->driver = cv_xasprintf("cavalry program binary %u\n%s\n%s\n%s\n", CV_PROGRAM_FILE_VERSION,
                              info->vendor, info->renderer, info->version);
    dc->stats.enabled = true;
    cv_debug("program cache: %s (%d binary format%s)", dir, n, n == 1 ? "" : "s");
    return dc;
}

void cv_program_disk_cache_close(struct cv_program_disk_cache **dc)
{
    if (!dc || !*dc)
        return;
    free((*dc)->dir);
    free((*dc)->formats);
    free((*dc)->driver);
    free(*dc);
    *dc = NULL;
}

bool cv_program_disk_cache_enabled(const struct cv_program_disk_cache *dc)
{
    return dc && dc->stats.enabled;
}

void cv_program_disk_cache_stats(const struct cv_program_disk_cache *dc,
                                 struct cv_program_disk_stats *out)
{
    static const struct cv_program_disk_stats none = {0};
    *out = dc ? dc->stats : none;
}

/* The file's key is the driver part then the source; its name two
 * differently seeded hashes of that (the key inside settles collisions). */
static char *entry_path(const struct cv_program_disk_cache *dc, const char *source)
{
    uint64_t a = cv_program_file_checksum(CV_FNV_OFFSET, dc->driver, strlen(dc->driver));
    a = cv_program_file_checksum(a, source, strlen(source));
    uint64_t b = cv_program_file_checksum(0x84222325cbf29ce4ull, source, strlen(source));
    b = cv_program_file_checksum(b, dc->driver, strlen(dc->driver));
    return cv_xasprintf("%s/program-%016llx%016llx.bin", dc->dir, (unsigned long long)a,
                        (unsigned long long)b);
}

static uint64_t entry_checksum(const struct cv_program_disk_cache *dc, const char *source,
                               const void *bin, size_t bin_len)
{
    uint64_t h = cv_program_file_checksum(CV_FNV_OFFSET, dc->driver, strlen(dc->driver));
    h = cv_program_file_checksum(h, source, strlen(source));
    return cv_program_file_checksum(h, bin, bin_len);
}

/* Why the entry at data cannot serve, or NULL when it can. */
static const char *check_entry(const struct cv_program_disk_cache *dc, const char *source,
                               const char *data, size_t len, struct cv_program_file_header *h)
{
    if (len < sizeof(*h))
        return "shorter than its header";
    memcpy(h, data, sizeof(*h));
    if (memcmp(h->magic, CV_PROGRAM_FILE_MAGIC, sizeof(h->magic)) != 0)
        return "not a program binary file";
    if (h->version != CV_PROGRAM_FILE_VERSION)
        return "another file version";
    size_t driver_len = strlen(dc->driver), source_len = strlen(source);
    if (h->key_len != driver_len + source_len)
        return "another key (hash collision)";
    if (len != sizeof(*h) + (size_t)h->key_len + h->binary_len)
        return "truncated or overlong";
    const char *key = data + sizeof(*h);
    if (memcmp(key, dc->driver, driver_len) != 0 || memcmp(key + driver_len, source, source_len))
        return "another key (hash collision or other driver)";
    const char *bin = key + h->key_len;
    if (entry_checksum(dc, source, bin, h->binary_len) != h->checksum)
        return "checksum mismatch (corrupt)";
    for (int i = 0; i < dc->n_formats; i++)
        if ((GLenum)dc->formats[i] == h->format)
            return NULL;
    return "binary format the driver does not offer";
}

GLuint cv_program_disk_cache_load(struct cv_program_disk_cache *dc, const char *source,
                                  const char *label)
{
    if (!cv_program_disk_cache_enabled(dc))
        return 0;
    char *path = entry_path(dc, source);
    if (!cv_path_exists(path)) {
        dc->stats.misses++;
        cv_debug("program cache: glsl/%s not cached (%s)", label, path);
        free(path);
        return 0;
    }
    char *data = NULL;
    size_t len = 0;
    struct cv_error err = {{0}};
    struct cv_program_file_header h;
    const char *why = NULL;
    GLuint prog = 0;
    if (!cv_read_file(path, &data, &len, &err)) {
        why = err.msg;
    } else if (!(why = check_entry(dc, source, data, len, &h))) {
        prog = glCreateProgram();
        /* A driver may report a refused binary through KHR_debug as an
         * error; here it is an expected miss, so the group mutes it. */
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "program cache load");
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_FALSE);
        glProgramBinary(prog, h.format, data + sizeof(h) + h.key_len, (GLsizei)h.binary_len);
        GLint status = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &status);
        glPopDebugGroup();
        /* A refused binary is a miss; its error must not reach the caller's
         * cv_gl_check. */
        GLenum e = glGetError();
        if (!status || e != GL_NO_ERROR) {
            why = e != GL_NO_ERROR ? "the driver raised an error loading it"
                                   : "the driver refused it (driver update?)";
            glDeleteProgram(prog);
            prog = 0;
        }
    }
    if (prog) {
        dc->stats.hits++;
        cv_debug("program cache: glsl/%s loaded from %s", label, path);
    } else {
        dc->stats.rejected++;
        cv_debug("program cache: glsl/%s: ignoring %s: %s; rebuilding", label, path, why);
    }
    free(data);
    free(path);
    return prog;
}

static bool write_all(int fd, const void *data, size_t len)
{
    const char *p = data;
    while (len > 0) {
        ssize_t n = write(fd, p, len);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0)
            return false;
        p += n;
        len -= (size_t)n;
    }
    return true;
}

/* Writes path through a temporary file in the same folder and a rename,
 * which is atomic there: readers see the old entry or the whole new one.
 * open() rather than mkstemp() so the umask, not 0600, sets the mode of
 * a folder that several users of a farm may share. */
static bool write_atomic(const char *path, const void *a, size_t a_len, const void *b,
                         size_t b_len, const void *c, size_t c_len, const void *d, size_t d_len,
                         const char **why)
{
    static unsigned counter;
    /* Farm nodes sharing the folder over NFS may have equal pids. */
    char host[64] = "host";
    if (gethostname(host, sizeof(host)) != 0)
        snprintf(host, sizeof(host), "host");
    host[sizeof(host) - 1] = '\0';
    for (char *h = host; *h; h++)
        if (*h == '/')
            *h = '_';
    char *tmp = NULL;
    int fd = -1;
    for (int attempt = 0; attempt < 16 && fd < 0; attempt++) {
        free(tmp);
        tmp = cv_xasprintf("%s.tmp.%s.%ld.%u", path, host, (long)getpid(), counter++);
        fd = open(tmp, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0 && errno != EEXIST)
            break;
    }
    if (fd < 0) {
        *why = strerror(errno);
        free(tmp);
        return false;
    }
    bool ok = write_all(fd, a, a_len) && write_all(fd, b, b_len) && write_all(fd, c, c_len) &&
              write_all(fd, d, d_len);
    if (!ok)
        *why = strerror(errno ? errno : EIO);
    if (close(fd) != 0 && ok) {
        *why = strerror(errno);
        ok = false;
    }
    if (ok && rename(tmp, path) != 0) {
        *why = strerror(errno);
        ok = false;
    }
    if (!ok)
        unlink(tmp);
    free(tmp);
    return ok;
}

void cv_program_disk_cache_store(struct cv_program_disk_cache *dc, const char *source,
                                 GLuint prog, const char *label)
{
    if (!cv_program_disk_cache_enabled(dc))
        return;
    GLint len = 0;
    glGetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &len);
    if (len <= 0) {
        cv_debug("program cache: glsl/%s: the driver gives no binary", label);
        return;
    }
    char *bin = cv_xmalloc((size_t)len);
    GLsizei got = 0;
    GLenum format = 0;
    glGetProgramBinary(prog, len, &got, &format, bin);
    if (glGetError() != GL_NO_ERROR || got <= 0) {
        cv_debug("program cache: glsl/%s: glGetProgramBinary failed", label);
        free(bin);
        return;
    }
    struct cv_program_file_header h = {
        .magic = CV_PROGRAM_FILE_MAGIC,
        .version = CV_PROGRAM_FILE_VERSION,
        .format = format,
        .key_len = (uint32_t)(strlen(dc->driver) + strlen(source)),
        .binary_len = (uint32_t)got,
        .checksum = entry_checksum(dc, source, bin, (size_t)got),
    };
    char *path = entry_path(dc, source);
    const char *why = NULL;
    if (write_atomic(path, &h, sizeof(h), dc->driver, strlen(dc->driver), source, strlen(source),
                     bin, (size_t)got, &why)) {
        dc->stats.writes++;
        cv_debug("program cache: glsl/%s written to %s (%d bytes)", label, path, (int)got);
    } else {
        cv_debug("program cache: glsl/%s: cannot write %s: %s", label, path, why);
    }
    free(path);
    free(bin);
}
