/* bsdf_sites_test.c: the coated walk (glsl/trace/bsdf/layered.glsl) is
 * inlined once per estimator (f, pdf, the walk out: cv_layered_estimate
 * folds each) in each kernel that shades coated materials, and not at all
 * in the shade bins that never meet one (issue 26: program build time).
 * GLSL compilers inline every call, so a function's code appears in a
 * kernel once per call path from main(): this test assembles each shipped
 * kernel as the host does (gpu/program.h: includes, defines), keeps the
 * lines the preprocessor keeps (#if, #ifdef ... with the defines of the
 * source and of the build), finds the function definitions and their
 * calls, and counts the call paths from main() to each of the walk's
 * functions; and that bin 2 built for coated materials alone
 * (CV_BSDF_WALK_ONLY) has none of the other types' samplers. It needs no
 * GPU. What it does not see: calls made through a
 * function-like macro, and overloads, which it merges by name (an upper
 * bound). With CAVALRY_DATA_DIR pointing at another tree it measures that
 * tree's GLSL (3ce19e9's path shade kernel counts 9 copies of
 * cv_lay_coat_sample). */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "gpu/program.h"
#include "tests/tap.h"

static char *dupn(const char *s, size_t n)
{
    char *d = cv_xmalloc(n + 1);
    memcpy(d, s, n);
    d[n] = 0;
    return d;
}

/* ---- a small preprocessor: object-like macros, conditionals ---- */

#define MAX_MACROS 2048
struct macros {
    char *name[MAX_MACROS];
    char *value[MAX_MACROS];
    int n;
};

static int macro_find(const struct macros *m, const char *name, size_t len)
{
    for (int i = 0; i < m->n; i++)
        if (strlen(m->name[i]) == len && strncmp(m->name[i], name, len) == 0)
            return i;
    return -1;
}

static void macro_define(struct macros *m, const char *name, size_t len, const char *value)
{
    int i = macro_find(m, name, len);
    if (i < 0) {
        if (m->n == MAX_MACROS)
            return;
        i = m->n++;
        m->name[i] = dupn(name, len);
    } else {
        free(m->value[i]);
    }
    m->value[i] = cv_xstrdup(value);
}

static void macro_undef(struct macros *m, const char *name, size_t len)
{
    int i = macro_find(m, name, len);
    if (i < 0)
        return;
    free(m->name[i]);
    free(m->value[i]);
    m->name[i] = m->name[m->n - 1];
    m->value[i] = m->value[m->n - 1];
    m->n--;
}

/* #if expressions: defined, integers, identifiers (their value, else 0),
 * ! && || == != < > <= >= + - and parentheses. */
struct expr {
    const char *p;
    const struct macros *m;
    int depth;
};

static long ex_or(struct expr *e);

static void ex_space(struct expr *e)
{
    while (*e->p == ' ' || *e->p == '\t')
        e->p++;
}

static bool ex_ident(struct expr *e, const char **s, size_t *len)
{
    ex_space(e);
    if (!isalpha((unsigned char)*e->p) && *e->p != '_')
        return false;
    *s = e->p;
    while (isalnum((unsigned char)*e->p) || *e->p == '_')
        e->p++;
    *len = (size_t)(e->p - *s);
    return true;
}

static long ex_value_of(struct expr *e, const char *s, size_t len)
{
    int i = macro_find(e->m, s, len);
    if (i < 0 || e->depth > 8)
        return 0;
    struct expr sub = {e->m->value[i], e->m, e->depth + 1};
    return ex_or(&sub);
}

static long ex_unary(struct expr *e)
{
    ex_space(e);
    if (*e->p == '!') {
        e->p++;
        return !ex_unary(e);
    }
    if (*e->p == '-') {
        e->p++;
        return -ex_unary(e);
    }
    if (*e->p == '(') {
        e->p++;
        long v = ex_or(e);
        ex_space(e);
        if (*e->p == ')')
            e->p++;
        return v;
    }
    if (isdigit((unsigned char)*e->p)) {
        long v = strtol(e->p, (char **)&e->p, 0);
        while (*e->p == 'u' || *e->p == 'U')
            e->p++;
        return v;
    }
    const char *s;
    size_t len;
    if (!ex_ident(e, &s, &len))
        return 0;
    if (len == 7 && strncmp(s, "defined", 7) == 0) {
        ex_space(e);
        bool paren = *e->p == '(';
        if (paren)
            e->p++;
        const char *n;
        size_t nl;
        long v = ex_ident(e, &n, &nl) && macro_find(e->m, n, nl) >= 0;
        ex_space(e);
        if (paren && *e->p == ')')
            e->p++;
        return v;
    }
    return ex_value_of(e, s, len);
}

static long ex_add(struct expr *e)
{
    long v = ex_unary(e);
    for (;;) {
        ex_space(e);
        if (*e->p == '+' || (*e->p == '-' && e->p[1] != '-')) {
            char op = *e->p++;
            long w = ex_unary(e);
            v = op == '+' ? v + w : v - w;
        } else {
            return v;
        }
    }
}

static long ex_cmp(struct expr *e)
{
    long v = ex_add(e);
    for (;;) {
        ex_space(e);
        const char *p = e->p;
        if (p[0] == '=' && p[1] == '=') {
            e->p += 2;
            v = v == ex_add(e);
        } else if (p[0] == '!' && p[1] == '=') {
            e->p += 2;
            v = v != ex_add(e);
        } else if (p[0] == '<' && p[1] == '=') {
            e->p += 2;
            v = v <= ex_add(e);
        } else if (p[0] == '>' && p[1] == '=') {
            e->p += 2;
            v = v >= ex_add(e);
        } else if (p[0] == '<') {
            e->p++;
            v = v < ex_add(e);
        } else if (p[0] == '>') {
            e->p++;
            v = v > ex_add(e);
        } else {
            return v;
        }
    }
}

static long ex_and(struct expr *e)
{
    long v = ex_cmp(e);
    for (;;) {
        ex_space(e);
        if (e->p[0] != '&' || e->p[1] != '&')
            return v;
        e->p += 2;
        long w = ex_cmp(e);
        v = v && w;
    }
}

static long ex_or(struct expr *e)
{
    long v = ex_and(e);
    for (;;) {
        ex_space(e);
        if (e->p[0] != '|' || e->p[1] != '|')
            return v;
        e->p += 2;
        long w = ex_and(e);
        v = v || w;
    }
}

/* Strips comments in place (strings do not occur in our GLSL). */
static void strip_comments(char *s)
{
    char *w = s;
    for (char *r = s; *r;) {
        if (r[0] == '/' && r[1] == '/') {
            while (*r && *r != '\n')
                r++;
        } else if (r[0] == '/' && r[1] == '*') {
            r += 2;
            while (*r && !(r[0] == '*' && r[1] == '/'))
                r++;
            if (*r)
                r += 2;
            *w++ = ' ';
        } else {
            *w++ = *r++;
        }
    }
    *w = 0;
}

/* The lines of src the GLSL preprocessor keeps (directives dropped). */
static char *preprocess(const char *src)
{
    char *text = cv_xstrdup(src);
    strip_comments(text);
    struct macros m = {.n = 0};
    macro_define(&m, "GL_core_profile", 15, "1");
    size_t cap = strlen(text) + 1, n = 0;
    char *out = cv_xmalloc(cap);
    /* per #if level: whether its branch is live, whether one was taken */
    bool live[64] = {true}, taken[64] = {true};
    int level = 0;
    for (char *line = text; line && *line;) {
        char *end = strchr(line, '\n');
        if (end)
            *end = 0;
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        bool on = live[level];
        if (*p == '#') {
            p++;
            while (*p == ' ')
                p++;
            char *arg = p;
            while (isalpha((unsigned char)*arg))
                arg++;
            size_t dl = (size_t)(arg - p);
            while (*arg == ' ' || *arg == '\t')
                arg++;
            const char *id = arg;
            size_t il = 0;
            while (isalnum((unsigned char)id[il]) || id[il] == '_')
                il++;
            if ((dl == 2 && !strncmp(p, "if", 2)) || (dl == 5 && !strncmp(p, "ifdef", 5)) ||
                (dl == 6 && !strncmp(p, "ifndef", 6))) {
                bool v;
                if (dl == 2) {
                    struct expr e = {arg, &m, 0};
                    v = ex_or(&e) != 0;
                } else {
                    v = (macro_find(&m, id, il) >= 0) == (dl == 5);
                }
                if (level < 63) {
                    level++;
                    live[level] = on && v;
                    taken[level] = v;
                }
            } else if (dl == 4 && !strncmp(p, "elif", 4)) {
                struct expr e = {arg, &m, 0};
                bool v = !taken[level] && ex_or(&e) != 0;
                live[level] = live[level - 1] && v;
                taken[level] = taken[level] || v;
            } else if (dl == 4 && !strncmp(p, "else", 4)) {
                live[level] = live[level - 1] && !taken[level];
                taken[level] = true;
            } else if (dl == 5 && !strncmp(p, "endif", 5)) {
                if (level > 0)
                    level--;
            } else if (on && dl == 6 && !strncmp(p, "define", 6) && il > 0) {
                const char *v = id + il;
                if (*v == '(') {
                    macro_define(&m, id, il, "");  /* function-like: defined, not expanded */
                } else {
                    while (*v == ' ' || *v == '\t')
                        v++;
                    macro_define(&m, id, il, v);
                }
            } else if (on && dl == 5 && !strncmp(p, "undef", 5)) {
                macro_undef(&m, id, il);
            }
        } else if (on) {
            size_t len = strlen(line);
            memcpy(out + n, line, len);
            n += len;
            out[n++] = '\n';
        }
        line = end ? end + 1 : NULL;
    }
    out[n] = 0;
    for (int i = 0; i < m.n; i++) {
        free(m.name[i]);
        free(m.value[i]);
    }
    free(text);
    return out;
}

/* ---- functions and calls ---- */

#define MAX_FUNCS 2048
struct funcs {
    char *name[MAX_FUNCS];
    const char *body[MAX_FUNCS];  /* from its '{' */
    size_t len[MAX_FUNCS];
    int n;
    double copies[MAX_FUNCS];
    int state[MAX_FUNCS];         /* 0 new, 1 being counted, 2 done */
};

static int func_find(const struct funcs *f, const char *s, size_t len)
{
    for (int i = 0; i < f->n; i++)
        if (strlen(f->name[i]) == len && strncmp(f->name[i], s, len) == 0)
            return i;
    return -1;
}

/* Function definitions at brace depth 0: NAME ( ... ) { ... } */
static void find_funcs(const char *s, struct funcs *f)
{
    int depth = 0;
    for (const char *p = s; *p; p++) {
        if (*p == '{') {
            depth++;
        } else if (*p == '}') {
            depth--;
        } else if (depth == 0 && *p == '(' && p > s) {
            const char *e = p;
            while (e > s && (e[-1] == ' ' || e[-1] == '\t'))
                e--;
            const char *b = e;
            while (b > s && (isalnum((unsigned char)b[-1]) || b[-1] == '_'))
                b--;
            int paren = 0;
            const char *q = p;
            for (; *q; q++) {
                if (*q == '(')
                    paren++;
                else if (*q == ')' && --paren == 0)
                    break;
            }
            if (!*q || b == e)
                continue;
            const char *r = q + 1;
            while (isspace((unsigned char)*r))
                r++;
            if (*r != '{')
                continue;
            /* the body, to its matching brace */
            int d = 0;
            const char *t = r;
            for (; *t; t++) {
                if (*t == '{')
                    d++;
                else if (*t == '}' && --d == 0)
                    break;
            }
            size_t nl = (size_t)(e - b);
            int i = func_find(f, b, nl);
            if (i < 0 && f->n < MAX_FUNCS) {
                i = f->n++;
                f->name[i] = dupn(b, nl);
                f->body[i] = r;
                f->len[i] = (size_t)(t - r);
            }
            /* (an overload: merged with the first of its name) */
            p = *t ? t : t - 1;
        }
    }
}

/* Copies of function i in the kernel: the number of call paths from
 * main(), summed over every function that calls it. */
static double calls_from(const struct funcs *f, int caller, int callee_i)
{
    const char *name = f->name[callee_i];
    size_t nl = strlen(name);
    double n = 0;
    const char *b = f->body[caller], *end = b + f->len[caller];
    for (const char *p = b; p + nl <= end; p++) {
        if (strncmp(p, name, nl) != 0)
            continue;
        if (p > b && (isalnum((unsigned char)p[-1]) || p[-1] == '_'))
            continue;
        const char *q = p + nl;
        while (q < end && isspace((unsigned char)*q))
            q++;
        if (q < end && *q == '(')
            n++;
    }
    return n;
}

static double copies(struct funcs *f, int i)
{
    if (f->state[i] == 2)
        return f->copies[i];
    if (f->state[i] == 1)
        return 0;  /* recursion does not occur in GLSL */
    f->state[i] = 1;
    double c = strcmp(f->name[i], "main") == 0 ? 1 : 0;
    for (int k = 0; k < f->n; k++) {
        if (k == i)
            continue;
        double n = calls_from(f, k, i);
        if (n > 0)
            c += n * copies(f, k);
    }
    f->state[i] = 2;
    f->copies[i] = c;
    return c;
}

/* Inlined copies of `name` in the GLSL source src. */
static double source_copies(const char *src, const char *name)
{
    char *pp = preprocess(src);
    struct funcs *f = cv_xcalloc(1, sizeof(*f));
    find_funcs(pp, f);
    int i = func_find(f, name, strlen(name));
    double c = i < 0 ? 0 : copies(f, i);
    for (int k = 0; k < f->n; k++)
        free(f->name[k]);
    free(f);
    free(pp);
    return c;
}

/* Inlined copies of `name` in the kernel `path` built with `defines`
 * (-1: the kernel does not assemble). */
static double kernel_copies(const char *path, const char *const *defines, const char *name)
{
    struct cv_error err = {{0}};
    char *src = NULL, **names = NULL;
    if (!cv_glsl_assemble(path, defines, &src, &names, &err)) {
        tap_diag("%s: %s", path, err.msg);
        return -1;
    }
    for (char **n = names; *n; n++)
        free(*n);
    free(names);
    double c = source_copies(src, name);
    free(src);
    return c;
}

/* layered.glsl's CV_LAY_MODE_F, _PDF and _WALK, each a folded copy */
#define WALK_ESTIMATORS 3

struct kernel {
    const char *what;
    const char *path;
    const char *defines[4];
    bool walks;  /* shades coated walks: one copy per estimator; else none */
};

int main(void)
{
    /* the counter itself, on a source made for it */
    static const char toy[] = "#version 450\n#define TWO 2\n"
                              "float g(float x) { return x; } // g(\n"
                              "float f(float x) { return g(x) + g (x); }\n"
                              "#if TWO == 2 && !defined(NOPE)\n"
                              "void h() { f(1.0); }\n"
                              "#else\n"
                              "void h() { f(1.0); f(2.0); }\n"
                              "#endif\n"
                              "/* g(1.0) */ void main() { h(); f(0.0); g(3.0); }\n";
    tap_ok(source_copies(toy, "g") == 5 && source_copies(toy, "f") == 2 && source_copies(toy, "h") == 1,
           "the counter: g 5, f 2, h 1 copies (%g, %g, %g)", source_copies(toy, "g"),
           source_copies(toy, "f"), source_copies(toy, "h"));
    static const struct kernel kernels[] = {
        {"path, bin 2 (coated walk)", "trace/shade.comp", {"CV_SHADE_BIN=2", NULL}, true},
        {"volpath, bin 2", "trace/shade.comp", {"CV_SHADE_BIN=2", "CV_MEDIA", NULL}, true},
        {"path, textured scene, bin 2", "trace/shade.comp", {"CV_SHADE_BIN=2", "CV_HAS_ALPHA", NULL},
         true},
        {"path, bin 2 without mixes", "trace/shade.comp", {"CV_SHADE_BIN=2", "CV_BSDF_WALK_ONLY", NULL},
         true},
        {"rlpath's sdtree, bin 2 without mixes", "trace/rlpath/sd_shade.comp",
         {"CV_SHADE_BIN=2", "CV_BSDF_WALK_ONLY", NULL}, true},
        {"rlpath (one program, every bin)", "trace/rlpath/shade.comp", {NULL}, true},
        {"bsdf_probe test kernel", "trace/test/bsdf_probe.comp", {NULL}, true},
        {"path, bin 1 (other materials)", "trace/shade.comp", {"CV_SHADE_BIN=1", NULL}, false},
        {"volpath, bin 1", "trace/shade.comp", {"CV_SHADE_BIN=1", "CV_MEDIA", NULL}, false},
        {"path, bin 0 (diffuse)", "trace/shade.comp", {"CV_SHADE_BIN=0", NULL}, false},
    };
    /* the walk's interface samplers: the largest of its code */
    static const char *const walk_fns[] = {"cv_lay_coat_sample", "cv_lay_base_sample",
                                           "cv_lay_hg_sample"};
    /* reported only */
    static const char *const other_fns[] = {"cv_lay_coat_f", "cv_lay_coat_pdf", "cv_lay_base_f",
                                            "cv_lay_base_pdf", "cv_layered_run"};
    for (size_t k = 0; k < CV_ARRAY_SIZE(kernels); k++) {
        const struct kernel *kn = &kernels[k];
        for (size_t j = 0; j < CV_ARRAY_SIZE(walk_fns); j++) {
            double c = kernel_copies(kn->path, kn->defines, walk_fns[j]);
            double want = kn->walks ? WALK_ESTIMATORS : 0;
            tap_ok(c == want, "%s: %s inlined %g times (want %g)", kn->what, walk_fns[j], c, want);
        }
        for (size_t j = 0; j < CV_ARRAY_SIZE(other_fns); j++)
            tap_diag("%s: %s inlined %g times", kn->what, other_fns[j],
                     kernel_copies(kn->path, kn->defines, other_fns[j]));
    }
    /* the other types' samplers: in bin 2 (a mix may resolve to any
     * type), not in bin 2 without mixes */
    static const char *const type_fns[] = {"cv_plastic_sample", "cv_difftrans_sample",
                                           "cv_thin_dielectric_sample"};
    static const char *const bin2[] = {"CV_SHADE_BIN=2", NULL};
    static const char *const walk_only[] = {"CV_SHADE_BIN=2", "CV_BSDF_WALK_ONLY", NULL};
    for (size_t j = 0; j < CV_ARRAY_SIZE(type_fns); j++) {
        double all = kernel_copies("trace/shade.comp", bin2, type_fns[j]);
        double walk = kernel_copies("trace/shade.comp", walk_only, type_fns[j]);
        tap_ok(all > 0 && walk == 0, "%s: %g copies in bin 2, %g without mixes (want 0)", type_fns[j],
               all, walk);
    }
    return tap_done();
}
