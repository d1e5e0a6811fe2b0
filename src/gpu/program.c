/* program.c: see program.h. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

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

/* Programs are allocated one by one: callers keep the pointers while the
 * cache grows. */
struct cache_entry {
    char *key;
    struct cv_program *prog;
};

struct cv_program_cache {
    struct cache_entry *entries;
    size_t n, cap;
    /* Opened at the first request, when the context is current. */
    struct cv_program_disk_cache *disk;
};

struct cv_program_cache *cv_program_cache_create(void)
{
    return cv_xcalloc(1, sizeof(struct cv_program_cache));
}

void cv_program_cache_destroy(struct cv_program_cache **cache)
{
    if (!cache || !*cache)
        return;
    for (size_t i = 0; i < (*cache)->n; i++) {
        struct cache_entry *e = &(*cache)->entries[i];
        if (e->prog->id)
            glDeleteProgram(e->prog->id);
        free(e->key);
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

static bool expand(struct assembly *a, int file, const char *text, int depth, int first_line,
                   struct cv_error *err)
{
    int line_no = 1;
    const char *line = text;
    while (*line) {
        const char *end = strchr(line, '\n');
        const char *next = end ? end + 1 : line + strlen(line);
        if (!end)
            end = next;
        const char *inc;
        size_t inc_len;
        if (line_no < first_line) {
            /* already emitted (the #version line) */
        } else if (!a->spliced && is_marker(a->splice, line, end)) {
            /* the generated text, numbered as a file of its own */
            if (a->n_names >= CV_GLSL_MAX_FILES - 1)
                return cv_fail(err, "glsl/%s:%d: too many files", a->names[file], line_no);
            int id = a->n_names++;
            a->names[id] = cv_xstrdup(a->splice->name);
            a->spliced = true;
            sb_addf(&a->out, "#line %d %d\n", id * CV_GLSL_LINE_STRIDE + 1, id);
            sb_add(&a->out, a->splice->text, strlen(a->splice->text));
            sb_addf(&a->out, "\n#line %d %d\n", file * CV_GLSL_LINE_STRIDE + line_no + 1, file);
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
                    sb_addf(&a->out, "#line %d %d\n", file * CV_GLSL_LINE_STRIDE + line_no + 1,
                            file);
                }
            }
            free(body);
            free(rel);
            free(cand[0]);
            free(cand[1]);
            if (!ok)
                return false;
        } else {
            sb_add(&a->out, line, (size_t)(next - line));
            if (next == end && *end == '\0' && end > line)
                sb_add(&a->out, "\n", 1);
        }
        line = next;
        line_no++;
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

/* Fills out from a linked program. */
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

static bool build(struct cv_program_disk_cache *disk, const char *path,
                  const char *const *defines, const struct cv_glsl_splice *splice,
                  struct cv_program *out, struct cv_error *err)
{
    char *src, **names;
    if (!assemble(path, defines, splice, &src, &names, err))
        return false;
    GLuint cached = cv_program_disk_cache_load(disk, src, path);
    if (cached) {
        adopt(cached, path, out);
        free(src);
        free_names(names);
        if (cv_gl_check(err, "loading glsl/%s from the program cache", path))
            return true;
        glDeleteProgram(cached);
        free(out->path);
        *out = (struct cv_program){0};
        return false;
    }
    GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
    const GLchar *srcs[1] = {src};
    glShaderSource(sh, 1, srcs, NULL);
    glCompileShader(sh);
    GLint status = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &status);
    char *raw = shader_log(sh);
    char *log = cv_glsl_map_log(raw, names);
    free(raw);
    bool ok = true;
    if (!status) {
        ok = cv_fail(err, "compiling glsl/%s failed:\n%s", path, log);
    } else {
        if (log[0])
            cv_debug("glsl/%s compiler log:\n%s", path, log);
        GLuint prog = glCreateProgram();
        if (cv_program_disk_cache_enabled(disk))
            glProgramParameteri(prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
        glAttachShader(prog, sh);
        glLinkProgram(prog);
        glGetProgramiv(prog, GL_LINK_STATUS, &status);
        if (!status) {
            char *plog = program_log(prog);
            char *mapped = cv_glsl_map_log(plog, names);
            ok = cv_fail(err, "linking glsl/%s failed:\n%s", path, mapped);
            free(plog);
            free(mapped);
            glDeleteProgram(prog);
        } else {
            adopt(prog, path, out);
        }
    }
    glDeleteShader(sh);
    ok = ok && cv_gl_check(err, "building glsl/%s", path);
    /* Only after the check: the store reads glGetError for its own calls. */
    if (ok)
        cv_program_disk_cache_store(disk, src, out->id, path);
    free(log);
    free(src);
    free_names(names);
    return ok;
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
    struct cv_program_cache *c = gpu->programs;
    for (size_t i = 0; i < c->n; i++) {
        if (strcmp(c->entries[i].key, key.s) == 0) {
            free(key.s);
            return c->entries[i].prog;
        }
    }
    if (!c->disk)
        c->disk = cv_program_disk_cache_open(&gpu->info);
    struct cv_program prog = {0};
    if (!build(c->disk, path, defines, splice, &prog, err)) {
        free(key.s);
        return NULL;
    }
    struct cache_entry e = {.key = key.s, .prog = cv_xmalloc(sizeof(prog))};
    *e.prog = prog;
    CV_PUSH(c->entries, c->n, c->cap, e);
    return e.prog;
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
