/* program.c: see program.h. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/clock.h"
#include "base/log.h"
#include "base/mem.h"
#include "gpu/gl_check.h"
#include "gpu/glsl_source.h"
#include "gpu/program.h"
#include "gpu/program_disk_cache.h"

#define CV_GLSL_MAX_FILES 256
/* Mesa reports some errors inside an included file with source-string 0,
 * so the file is encoded in the line number too: file f, line l is emitted
 * as line f * CV_GLSL_LINE_STRIDE + l. */
#define CV_GLSL_LINE_STRIDE 100000

/* Where one program's build time went, in milliseconds of the calling
 * thread (with parallel compilation, compile and link only hand the work
 * over and `wait` is the time its first use blocked). */
struct program_times {
    double requested_at_ms;   /* monotonic clock */
    double assemble_ms, load_ms, compile_ms, link_ms, wait_ms, store_ms;
};

/* A program between its request and its first use: the driver may still
 * be compiling it in its own threads. */
struct pending {
    GLuint shader, program;
    char *src;                /* assembled: the disk cache's key */
    char **names;             /* file table for log mapping */
    bool parallel;            /* submitted without status queries */
};

/* Programs are allocated one by one: callers keep the pointers while the
 * cache grows. */
struct cache_entry {
    char *key;
    char *path;
    char *label;                  /* path and defines, for logs */
    struct cv_program *prog;
    struct pending *pending;      /* non-NULL: submitted, not yet waited for */
    char *error;                  /* a failed build, reported at each use */
    bool from_disk;
    bool used;                    /* got by cv_program_get at least once */
    bool accounted;               /* counted in the stats */
    struct program_times times;
};

struct cv_program_cache {
    struct cache_entry *entries;
    size_t n, cap;
    /* Opened at the first request, when the context is current. */
    bool opened;
    struct cv_program_disk_cache *disk;
    bool parallel;                /* requests compile ahead in the driver's threads */
    bool serial;                  /* cv_program_set_serial: never ahead */
    struct cv_program_build_stats stats;
    double made_ms;               /* cv_seconds() at creation, in ms: the log's time origin */
};

static void free_pending(struct pending **pd);

struct cv_program_cache *cv_program_cache_create(void)
{
    struct cv_program_cache *c = cv_xcalloc(1, sizeof(struct cv_program_cache));
    c->made_ms = 1e3 * cv_seconds();
    return c;
}

void cv_program_cache_destroy(struct cv_program_cache **cache)
{
    if (!cache || !*cache)
        return;
    for (size_t i = 0; i < (*cache)->n; i++) {
        struct cache_entry *e = &(*cache)->entries[i];
        free_pending(&e->pending);
        if (e->prog->id)
            glDeleteProgram(e->prog->id);
        free(e->key);
        free(e->path);
        free(e->label);
        free(e->error);
        free(e->prog->path);
        free(e->prog);
    }
    free((*cache)->entries);
    cv_program_disk_cache_close(&(*cache)->disk);
    free(*cache);
    *cache = NULL;
}

/* ---- assembly ---------------------------------------------------------- */

struct strbuf {
    char *s;
    size_t len, cap;
};

static void sb_add(struct strbuf *b, const char *s, size_t n)
{
    b->s = cv_xgrow(b->s, &b->cap, b->len + n + 1, 1);
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

static void sb_addf(struct strbuf *b, const char *fmt, int a, int c)
{
    char tmp[64];
    int n = snprintf(tmp, sizeof(tmp), fmt, a, c);
    sb_add(b, tmp, (size_t)n);
}

/* dir + "/" + rel with "." and ".." folded, newly allocated. */
static char *normalize_join(const char *dir, const char *rel)
{
    char *joined = dir[0] ? cv_xasprintf("%s/%s", dir, rel) : cv_xstrdup(rel);
    char **parts = NULL;
    size_t n = 0, cap = 0;
    for (char *save, *tok = strtok_r(joined, "/", &save); tok; tok = strtok_r(NULL, "/", &save)) {
        if (strcmp(tok, ".") == 0)
            continue;
        if (strcmp(tok, "..") == 0) {
            if (n)
                n--;
            continue;
        }
        CV_PUSH(parts, n, cap, tok);
    }
    struct strbuf b = {0};
    for (size_t i = 0; i < n; i++) {
        if (i)
            sb_add(&b, "/", 1);
        sb_add(&b, parts[i], strlen(parts[i]));
    }
    free(parts);
    free(joined);
    return b.s ? b.s : cv_xstrdup("");
}

struct assembly {
    char **names;
    int n_names;
    struct strbuf out;
    const struct cv_glsl_splice *splice;  /* NULL: none */
    bool spliced;                         /* the marker was found */
};

/* Does the line [line, end) begin with the splice's marker? */
static bool is_marker(const struct cv_glsl_splice *sp, const char *line, const char *end)
{
    size_t n = sp ? strlen(sp->marker) : 0;
    return sp && (size_t)(end - line) >= n && strncmp(line, sp->marker, n) == 0;
}

/* `#include "x"` on this line? Returns the name's start and length. */
static bool parse_include(const char *line, const char *end, const char **name, size_t *len)
{
    const char *p = line;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p >= end || *p++ != '#')
        return false;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if ((size_t)(end - p) < 7 || strncmp(p, "include", 7) != 0)
        return false;
    p += 7;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p >= end || *p != '"')
        return false;
    const char *q = memchr(p + 1, '"', (size_t)(end - p - 1));
    if (!q)
        return false;
    *name = p + 1;
    *len = (size_t)(q - p - 1);
    return true;
}

/* The logical line at p: a physical line whose newline follows a backslash
 * goes on into the next, as in a C preprocessor's phase 2. Every driver then
 * sees joined lines (NVIDIA's GLSL compiler does not join a #define's).
 * Returns where the next line starts; [*s, *e) is the line without its
 * newline, in *joined (the caller frees it) where lines were joined, and
 * *extra counts the newlines joined away. */
static const char *logical_line(const char *p, const char **s, const char **e, char **joined,
                                int *extra)
{
    const char *q = p, *end, *next;
    *extra = 0;
    for (;;) {
        const char *nl = strchr(q, '\n');
        if (!nl) {
            end = next = q + strlen(q);
            break;
        }
        if (nl > p && nl[-1] == '\\') {
            (*extra)++;
            q = nl + 1;
            continue;
        }
        end = nl;
        next = nl + 1;
        break;
    }
    *joined = NULL;
    *s = p;
    *e = end;
    if (*extra) {
        char *j = cv_xmalloc((size_t)(end - p) + 1), *w = j;
        for (const char *r = p; r < end; r++) {
            if (r[0] == '\\' && r + 1 < end && r[1] == '\n')
                r++;
            else
                *w++ = *r;
        }
        *w = '\0';
        *joined = j;
        *s = j;
        *e = w;
    }
    return next;
}

static bool expand(struct assembly *a, int file, const char *text, int depth, int first_line,
                   struct cv_error *err)
{
    int line_no = 1;
    for (const char *at = text; *at;) {
        const char *line, *end;
        char *joined;
        int extra;
        const char *next = logical_line(at, &line, &end, &joined, &extra);
        /* the line after this one, in the file's own numbering */
        int after = line_no + extra + 1;
        const char *inc;
        size_t inc_len;
        if (line_no < first_line) {
            /* already emitted (the #version line) */
        } else if (!a->spliced && is_marker(a->splice, line, end)) {
            /* the generated text, numbered as a file of its own */
            if (a->n_names >= CV_GLSL_MAX_FILES - 1) {
                free(joined);
                return cv_fail(err, "glsl/%s:%d: too many files", a->names[file], line_no);
            }
            int id = a->n_names++;
            a->names[id] = cv_xstrdup(a->splice->name);
            a->spliced = true;
            sb_addf(&a->out, "#line %d %d\n", id * CV_GLSL_LINE_STRIDE + 1, id);
            sb_add(&a->out, a->splice->text, strlen(a->splice->text));
            sb_addf(&a->out, "\n#line %d %d\n", file * CV_GLSL_LINE_STRIDE + after, file);
        } else if (parse_include(line, end, &inc, &inc_len)) {
            char *rel = cv_xmalloc(inc_len + 1);
            memcpy(rel, inc, inc_len);
            rel[inc_len] = '\0';
            char *dir = strrchr(a->names[file], '/')
                            ? cv_xasprintf("%.*s", (int)(strrchr(a->names[file], '/') - a->names[file]),
                                           a->names[file])
                            : cv_xstrdup("");
            char *cand[2] = {normalize_join(dir, rel), normalize_join("", rel)};
            free(dir);
            char *body = NULL;
            int which = -1;
            struct cv_error e2;
            for (int c = 0; c < 2 && which < 0; c++)
                if (cv_glsl_read(cand[c], &body, &e2))
                    which = c;
            bool ok = true;
            if (which < 0) {
                ok = cv_fail(err, "glsl/%s:%d: cannot include \"%s\": not found", a->names[file],
                             line_no, rel);
            } else {
                int seen = -1;
                for (int i = 0; i < a->n_names; i++)
                    if (strcmp(a->names[i], cand[which]) == 0)
                        seen = i;
                if (seen >= 0) {
                    /* each file once, like #pragma once; keep line numbers */
                    sb_add(&a->out, "\n", 1);
                } else if (depth > 32 || a->n_names >= CV_GLSL_MAX_FILES - 1) {
                    ok = cv_fail(err, "glsl/%s:%d: includes nested too deeply", a->names[file],
                                 line_no);
                } else {
                    int id = a->n_names++;
                    a->names[id] = cv_xstrdup(cand[which]);
                    sb_addf(&a->out, "#line %d %d\n", id * CV_GLSL_LINE_STRIDE + 1, id);
                    ok = expand(a, id, body, depth + 1, 1, err);
                    sb_addf(&a->out, "#line %d %d\n", file * CV_GLSL_LINE_STRIDE + after, file);
                }
            }
            free(body);
            free(rel);
            free(cand[0]);
            free(cand[1]);
            if (!ok) {
                free(joined);
                return false;
            }
        } else {
            sb_add(&a->out, line, (size_t)(end - line));
            /* one newline per physical line: later lines keep their numbers */
            for (int i = 0; i <= extra; i++)
                sb_add(&a->out, "\n", 1);
        }
        free(joined);
        at = next;
        line_no = after;
    }
    return true;
}

static bool assemble(const char *path, const char *const *defines,
                     const struct cv_glsl_splice *splice, char **source, char ***names,
                     struct cv_error *err)
{
    char *text;
    if (!cv_glsl_read(path, &text, err))
        return false;
    struct assembly a = {.names = cv_xcalloc(CV_GLSL_MAX_FILES, sizeof(char *)), .n_names = 1,
                         .splice = splice};
    a.names[0] = cv_xstrdup(path);

    /* #version must come first; the defines follow it. */
    int first_line = 1;
    const char *p = text;
    while (*p == ' ' || *p == '\t')
        p++;
    if (strncmp(p, "#version", 8) == 0) {
        const char *e = strchr(p, '\n');
        size_t n = e ? (size_t)(e - text) + 1 : strlen(text);
        sb_add(&a.out, text, n);
        if (!e)
            sb_add(&a.out, "\n", 1);
        first_line = 2;
    } else {
        sb_add(&a.out, "#version 450 core\n", 18);
    }
    for (const char *const *d = defines; d && *d; d++) {
        const char *eq = strchr(*d, '=');
        sb_add(&a.out, "#define ", 8);
        if (eq) {
            sb_add(&a.out, *d, (size_t)(eq - *d));
            sb_add(&a.out, " ", 1);
            sb_add(&a.out, eq + 1, strlen(eq + 1));
        } else {
            sb_add(&a.out, *d, strlen(*d));
        }
        sb_add(&a.out, "\n", 1);
    }
    sb_addf(&a.out, "#line %d %d\n", first_line, 0);
    bool ok = expand(&a, 0, text, 0, first_line, err);
    free(text);
    if (ok && splice && !a.spliced)
        ok = cv_fail(err, "glsl/%s: the line \"%s\" is missing", path, splice->marker);
    if (!ok) {
        for (int i = 0; i < a.n_names; i++)
            free(a.names[i]);
        free(a.names);
        free(a.out.s);
        return false;
    }
    *source = a.out.s;
    *names = a.names;
    return true;
}

bool cv_glsl_assemble(const char *path, const char *const *defines, char **source, char ***names,
                      struct cv_error *err)
{
    return assemble(path, defines, NULL, source, names, err);
}

static void free_names(char **names)
{
    for (char **n = names; n && *n; n++)
        free(*n);
    free(names);
}

/* ---- log mapping ------------------------------------------------------- */

static bool read_uint(const char **p, int *v)
{
    if (!isdigit((unsigned char)**p))
        return false;
    long x = strtol(*p, (char **)p, 10);
    *v = (int)x;
    return true;
}

char *cv_glsl_map_log(const char *log, char *const *names)
{
    int n_names = 0;
    while (names[n_names])
        n_names++;
    struct strbuf b = {0};
    for (const char *line = log; *line;) {
        const char *end = strchr(line, '\n');
        const char *next = end ? end + 1 : line + strlen(line);
        const char *p = line;
        int file, ln, col = -1;
        bool mapped = false;
        /* Mesa "F:L(C): msg", NVIDIA "F(L) : msg" */
        if (read_uint(&p, &file) && file >= 0 && file < n_names) {
            if (*p == ':' && (p++, read_uint(&p, &ln))) {
                if (*p == '(' && (p++, read_uint(&p, &col)) && *p == ')')
                    p++;
                mapped = true;
            } else if (*p == '(' && (p++, read_uint(&p, &ln)) && *p == ')') {
                p++;
                mapped = true;
            }
        }
        if (mapped && ln >= CV_GLSL_LINE_STRIDE && ln / CV_GLSL_LINE_STRIDE < n_names) {
            file = ln / CV_GLSL_LINE_STRIDE;
            ln %= CV_GLSL_LINE_STRIDE;
        }
        if (mapped) {
            while (*p == ' ')
                p++;
            if (*p == ':')
                p++;
            while (*p == ' ')
                p++;
            char head[512];
            int n = col >= 0 ? snprintf(head, sizeof(head), "glsl/%s:%d:%d: ", names[file], ln, col)
                             : snprintf(head, sizeof(head), "glsl/%s:%d: ", names[file], ln);
            sb_add(&b, head, (size_t)n);
            sb_add(&b, p, (size_t)(next - p));
        } else {
            sb_add(&b, line, (size_t)(next - line));
        }
        line = next;
    }
    return b.s ? b.s : cv_xstrdup("");
}

/* ---- compiling --------------------------------------------------------- */

static char *shader_log(GLuint sh)
{
    GLint len = 0;
    glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
    char *log = cv_xcalloc(1, (size_t)len + 1);
    if (len > 0)
        glGetShaderInfoLog(sh, len, NULL, log);
    return log;
}

static char *program_log(GLuint prog)
{
    GLint len = 0;
    glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
    char *log = cv_xcalloc(1, (size_t)len + 1);
    if (len > 0)
        glGetProgramInfoLog(prog, len, NULL, log);
    return log;
}

/* Fills out from a linked program. Reads the program's state: with
 * parallel compilation this waits for the driver's threads. */
static void adopt(GLuint prog, const char *path, struct cv_program *out)
{
    GLint size[3] = {1, 1, 1};
    glGetProgramiv(prog, GL_COMPUTE_WORK_GROUP_SIZE, size);
    out->id = prog;
    for (int i = 0; i < 3; i++)
        out->local_size[i] = (uint32_t)size[i];
    out->path = cv_xstrdup(path);
    glObjectLabel(GL_PROGRAM, prog, -1, path);
}

/* Reads the outcome of a compile and link started by submit(): a status
 * query, which waits for the driver's threads when parallel compilation is
 * on. Deletes the shader; on failure the program too. */
static bool finish(struct cache_entry *e, struct cv_error *err)
{
    struct pending *pd = e->pending;
    GLint status = 0;
    bool ok = true;
    double t0 = 1e3 * cv_seconds();
    glGetProgramiv(pd->program, GL_LINK_STATUS, &status);
    double t1 = 1e3 * cv_seconds();
    GLint compiled = 0;
    glGetShaderiv(pd->shader, GL_COMPILE_STATUS, &compiled);
    char *raw = shader_log(pd->shader);
    char *log = cv_glsl_map_log(raw, pd->names);
    free(raw);
    if (!compiled) {
        ok = cv_fail(err, "compiling glsl/%s failed:\n%s", e->path, log);
    } else if (!status) {
        char *plog = program_log(pd->program);
        char *mapped = cv_glsl_map_log(plog, pd->names);
        ok = cv_fail(err, "linking glsl/%s failed:\n%s", e->path, mapped);
        free(plog);
        free(mapped);
    } else {
        if (log[0])
            cv_debug("glsl/%s compiler log:\n%s", e->path, log);
        adopt(pd->program, e->path, e->prog);
        pd->program = 0;   /* the entry's now */
    }
    free(log);
    glDeleteShader(pd->shader);
    pd->shader = 0;
    if (!ok) {
        glDeleteProgram(pd->program);
        pd->program = 0;
    }
    e->times.wait_ms += t1 - t0;
    return ok;
}

/* Starts compiling and linking pd->src. Without parallel compilation each
 * call returns when its work is done, so compile and link are timed apart;
 * with it they return at once and the cost shows at finish(). */
static void submit(struct cv_program_disk_cache *disk, struct cache_entry *e)
{
    struct pending *pd = e->pending;
    double t0 = 1e3 * cv_seconds();
    pd->shader = glCreateShader(GL_COMPUTE_SHADER);
    const GLchar *srcs[1] = {pd->src};
    glShaderSource(pd->shader, 1, srcs, NULL);
    glCompileShader(pd->shader);
    if (!pd->parallel) {
        /* The status query is what waits for a driver that compiles lazily. */
        GLint status = 0;
        glGetShaderiv(pd->shader, GL_COMPILE_STATUS, &status);
    }
    double t1 = 1e3 * cv_seconds();
    pd->program = glCreateProgram();
    if (cv_program_disk_cache_enabled(disk))
        glProgramParameteri(pd->program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glAttachShader(pd->program, pd->shader);
    glLinkProgram(pd->program);
    if (!pd->parallel) {
        GLint status = 0;
        glGetProgramiv(pd->program, GL_LINK_STATUS, &status);
    }
    double t2 = 1e3 * cv_seconds();
    e->times.compile_ms += t1 - t0;
    e->times.link_ms += t2 - t1;
}

static void free_pending(struct pending **pd)
{
    if (!*pd)
        return;
    if ((*pd)->shader)
        glDeleteShader((*pd)->shader);
    if ((*pd)->program)
        glDeleteProgram((*pd)->program);
    free((*pd)->src);
    free_names((*pd)->names);
    free(*pd);
    *pd = NULL;
}

/* First half of a build: assembly, then the disk cache, else a compile and
 * link handed to the driver. A failure is kept in the entry for its first
 * use. */
static void start(struct cv_program_cache *c, struct cache_entry *e,
                  const char *const *defines, const struct cv_glsl_splice *splice)
{
    double t0 = 1e3 * cv_seconds();
    e->times.requested_at_ms = t0;
    char *src, **names;
    struct cv_error err = {{0}};
    bool ok = assemble(e->path, defines, splice, &src, &names, &err);
    double t1 = 1e3 * cv_seconds();
    e->times.assemble_ms = t1 - t0;
    if (!ok) {
        e->error = cv_xstrdup(err.msg);
        return;
    }
    GLuint cached = cv_program_disk_cache_load(c->disk, src, e->path);
    e->times.load_ms = 1e3 * cv_seconds() - t1;
    if (cached) {
        adopt(cached, e->path, e->prog);
        e->from_disk = true;
        if (!cv_gl_check(&err, "loading glsl/%s from the program cache", e->path)) {
            glDeleteProgram(cached);
            free(e->prog->path);
            *e->prog = (struct cv_program){0};
            e->error = cv_xstrdup(err.msg);
        }
        free(src);
        free_names(names);
        return;
    }
    e->pending = cv_xcalloc(1, sizeof(*e->pending));
    e->pending->src = src;
    e->pending->names = names;
    e->pending->parallel = c->parallel;
    submit(c->disk, e);
}

/* Second half: waits for the driver, checks, stores the binary. */
static void complete(struct cv_program_cache *c, struct cache_entry *e)
{
    struct cv_error errv = {{0}}, *err = &errv;
    bool ok = finish(e, err);
    ok = ok && cv_gl_check(err, "building glsl/%s", e->path);
    double t0 = 1e3 * cv_seconds();
    /* Only after the check: the store reads glGetError for its own calls. */
    if (ok)
        cv_program_disk_cache_store(c->disk, e->pending->src, e->prog->id, e->path);
    e->times.store_ms = 1e3 * cv_seconds() - t0;
    if (!ok) {
        if (e->prog->id)
            glDeleteProgram(e->prog->id);
        free(e->prog->path);
        *e->prog = (struct cv_program){0};
        e->error = cv_xstrdup(err->msg);
    }
    free_pending(&e->pending);
}

/* One debug line a program and the totals of cv_program_build_stats. */
static void account(struct cv_program_cache *c, struct cache_entry *e)
{
    const struct program_times *t = &e->times;
    double own = t->assemble_ms + t->load_ms + t->compile_ms + t->link_ms + t->wait_ms +
                 t->store_ms;
    double now = 1e3 * cv_seconds(), since = now - t->requested_at_ms;
    struct cv_program_build_stats *s = &c->stats;
    s->build_ms += own;
    s->assemble_ms += t->assemble_ms;
    s->compile_ms += t->compile_ms;
    s->link_ms += t->link_ms;
    s->wait_ms += t->wait_ms;
    s->store_ms += t->store_ms;
    s->load_ms += t->load_ms;
    if (e->error)
        s->failed++;
    else if (e->from_disk)
        s->cache_hits++;
    else
        s->compiled++;
    if (own > s->slowest_ms) {
        s->slowest_ms = own;
        snprintf(s->slowest, sizeof(s->slowest), "%s", e->label);
    }
    cv_debug("program glsl/%s: %s: assemble %.1f ms, cache lookup %.1f ms, compile %.1f ms, "
             "link %.1f ms, wait %.1f ms, store %.1f ms; first used %.1f ms after its request "
             "(requested at %.0f ms, first used at %.0f ms of the context)",
             e->label, e->error ? "failed" : e->from_disk ? "cache hit" : "compiled",
             t->assemble_ms, t->load_ms, t->compile_ms, t->link_ms, t->wait_ms, t->store_ms,
             since, t->requested_at_ms - c->made_ms, now - c->made_ms);
}

/* The in-memory key: path, defines, splice. */
static char *entry_key(const char *path, const char *const *defines,
                       const struct cv_glsl_splice *splice)
{
    struct strbuf key = {0};
    sb_add(&key, path, strlen(path));
    for (const char *const *d = defines; d && *d; d++) {
        sb_add(&key, "\n", 1);
        sb_add(&key, *d, strlen(*d));
    }
    if (splice) {
        /* \x01 cannot begin a define: the generated text keys apart */
        sb_add(&key, "\n\x01", 2);
        sb_add(&key, splice->marker, strlen(splice->marker));
        sb_add(&key, "\n", 1);
        sb_add(&key, splice->text, strlen(splice->text));
    }
    return key.s;
}

/* "path [A B=1]" for logs. */
static char *entry_label(const char *path, const char *const *defines,
                         const struct cv_glsl_splice *splice)
{
    struct strbuf b = {0};
    sb_add(&b, path, strlen(path));
    for (const char *const *d = defines; d && *d; d++) {
        sb_add(&b, d == defines ? " [" : " ", d == defines ? 2 : 1);
        sb_add(&b, *d, strlen(*d));
        if (!d[1])
            sb_add(&b, "]", 1);
    }
    if (splice)
        sb_add(&b, " (spliced)", 10);
    return b.s;
}

/* Opens the disk cache and picks the compile mode at the first request,
 * when the context is current. */
static void open_cache(struct cv_gpu *gpu)
{
    struct cv_program_cache *c = gpu->programs;
    if (c->opened)
        return;
    c->opened = true;
    c->disk = cv_program_disk_cache_open(&gpu->info);
    bool khr = cv_gl_has_extension("GL_KHR_parallel_shader_compile");
    bool arb = !khr && cv_gl_has_extension("GL_ARB_parallel_shader_compile");
    c->parallel = !c->serial && (khr || arb);
    if (c->parallel) {
        /* as many threads as the driver will use */
        if (khr)
            glMaxShaderCompilerThreadsKHR(0xffffffffu);
        else
            glMaxShaderCompilerThreadsARB(0xffffffffu);
        glGetError();
    }
    c->stats.parallel = c->parallel;
    cv_debug("programs: %s compilation (%s)", c->parallel ? "parallel" : "serial",
             khr ? "GL_KHR_parallel_shader_compile"
                 : arb ? "GL_ARB_parallel_shader_compile"
                       : "the driver has no parallel_shader_compile extension");
}

static struct cache_entry *find(struct cv_program_cache *c, const char *key)
{
    for (size_t i = 0; i < c->n; i++)
        if (strcmp(c->entries[i].key, key) == 0)
            return &c->entries[i];
    return NULL;
}

static struct cache_entry *add(struct cv_program_cache *c, char *key, const char *path,
                               const char *const *defines, const struct cv_glsl_splice *splice)
{
    struct cache_entry e = {.key = key, .prog = cv_xcalloc(1, sizeof(struct cv_program)),
                            .path = cv_xstrdup(path),
                            .label = entry_label(path, defines, splice)};
    CV_PUSH(c->entries, c->n, c->cap, e);
    return &c->entries[c->n - 1];
}

void cv_program_request_spliced(struct cv_gpu *gpu, const char *path,
                                const char *const *defines,
                                const struct cv_glsl_splice *splice)
{
    open_cache(gpu);
    struct cv_program_cache *c = gpu->programs;
    if (!c->parallel)
        return;   /* built at first use, as without requests */
    char *key = entry_key(path, defines, splice);
    if (find(c, key)) {
        free(key);
        return;
    }
    struct cache_entry *e = add(c, key, path, defines, splice);
    c->stats.requested++;
    start(c, e, defines, splice);
    if (!e->pending)
        e->accounted = true, account(c, e);
}

void cv_program_request(struct cv_gpu *gpu, const char *path, const char *const *defines)
{
    cv_program_request_spliced(gpu, path, defines, NULL);
}

struct cv_program *cv_program_get(struct cv_gpu *gpu, const char *path,
                                  const char *const *defines, struct cv_error *err)
{
    return cv_program_get_spliced(gpu, path, defines, NULL, err);
}

struct cv_program *cv_program_get_spliced(struct cv_gpu *gpu, const char *path,
                                          const char *const *defines,
                                          const struct cv_glsl_splice *splice,
                                          struct cv_error *err)
{
    open_cache(gpu);
    struct cv_program_cache *c = gpu->programs;
    char *key = entry_key(path, defines, splice);
    struct cache_entry *e = find(c, key);
    if (e) {
        free(key);
    } else {
        e = add(c, key, path, defines, splice);
        start(c, e, defines, splice);
    }
    if (e->pending)
        complete(c, e);
    if (!e->used) {
        e->used = true;
        if (!e->accounted)
            e->accounted = true, account(c, e);
    }
    if (e->error) {
        cv_fail(err, "%s", e->error);
        return NULL;
    }
    return e->prog;
}

void cv_program_build_stats(const struct cv_gpu *gpu, struct cv_program_build_stats *out)
{
    static const struct cv_program_build_stats none = {0};
    *out = gpu && gpu->programs ? gpu->programs->stats : none;
    if (!gpu || !gpu->programs)
        return;
    out->unused = 0;
    for (size_t i = 0; i < gpu->programs->n; i++)
        out->unused += !gpu->programs->entries[i].used;
}

void cv_program_set_serial(struct cv_gpu *gpu, bool serial)
{
    gpu->programs->serial = serial;
}

void cv_program_dispatch(const struct cv_program *prog, uint32_t n_x, uint32_t n_y, uint32_t n_z)
{
    const uint32_t *l = prog->local_size;
    glUseProgram(prog->id);
    glDispatchCompute((n_x + l[0] - 1) / l[0], (n_y + l[1] - 1) / l[1], (n_z + l[2] - 1) / l[2]);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
}

void cv_program_dispatch_1d(const struct cv_program *prog, uint64_t n)
{
    if (n == 0)
        return;
    GLint max_x = 65535;
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_x);
    uint64_t groups = (n + prog->local_size[0] - 1) / prog->local_size[0];
    uint64_t gx = groups, gy = 1;
    if (groups > (uint64_t)max_x) {
        gy = (groups + (uint64_t)max_x - 1) / (uint64_t)max_x;
        gx = (groups + gy - 1) / gy;
    }
    glUseProgram(prog->id);
    glDispatchCompute((GLuint)gx, (GLuint)gy, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);
}

void cv_program_set_uint(const struct cv_program *prog, const char *name, uint32_t v)
{
    glProgramUniform1ui(prog->id, glGetUniformLocation(prog->id, name), v);
}

void cv_program_dispatch_indirect(const struct cv_program *prog, GLintptr offset,
                                  GLbitfield barriers)
{
    glUseProgram(prog->id);
    glDispatchComputeIndirect(offset);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | barriers);
}

void cv_program_cache_stats(const struct cv_gpu *gpu, struct cv_program_disk_stats *out)
{
    cv_program_disk_cache_stats(gpu && gpu->programs ? gpu->programs->disk : NULL, out);
}
