/* parse.c: the directive loop. One function per directive group; the
 * transform and attribute directives act on the builder's graphics state
 * here, the rest go to the builder files. */
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/limits.h"
#include "base/log.h"
#include "base/mem.h"
#include "scene/filter.h"
#include "scene/parse.h"
#include "scene/token.h"

#define MAX_INCLUDE_DEPTH 64

/* A v4 `Attribute "target" params...` default, live until the
 * AttributeEnd that closes the scope it was set in. */
struct attr_default {
    char target[16];
    struct cv_param p;
    size_t depth;
};

struct parser {
    struct cv_builder *b;
    struct attr_default *attrs;
    size_t n_attrs, cap_attrs;
    struct cv_lexer *lx;       /* stack of open files */
    size_t n_lx, cap_lx;
    char **real;               /* canonical paths of open files, for recursion */
};

#define LOC_OF(tok) {(tok).file, (tok).line, (tok).col}

static struct cv_lexer *top(struct parser *p) { return &p->lx[p->n_lx - 1]; }

/* Next token across included files: EOF of an include pops back. */
static bool next(struct parser *p, struct cv_token *t, struct cv_error *err)
{
    return cv_lexer_next(top(p), t, err);
}

static bool peek(struct parser *p, struct cv_token *t, struct cv_error *err)
{
    return cv_lexer_peek(top(p), t, err);
}

static bool expect_string(struct parser *p, const struct cv_token *dir, char **out,
                          struct cv_error *err)
{
    struct cv_token t;
    if (!next(p, &t, err))
        return false;
    if (t.kind != CV_TOK_STRING)
        return cv_fail(err, "%s:%d:%d: %.*s expects a quoted string here", t.file, t.line,
                       t.col, (int)dir->len, dir->text);
    *out = cv_token_strdup(&t);
    return true;
}

static bool read_numbers(struct parser *p, const struct cv_token *dir, double *out, size_t n,
                         struct cv_error *err)
{
    struct cv_token t;
    bool bracket = false;
    if (!peek(p, &t, err))
        return false;
    if (t.kind == CV_TOK_LBRACKET) {
        bracket = true;
        next(p, &t, err);
    }
    for (size_t i = 0; i < n; i++) {
        if (!next(p, &t, err))
            return false;
        if (t.kind != CV_TOK_NUMBER)
            return cv_fail(err, "%s:%d:%d: %.*s expects %zu numbers", t.file, t.line, t.col,
                           (int)dir->len, dir->text, n);
        if (!cv_token_number(&t, &out[i], err))
            return false;
    }
    if (bracket) {
        if (!next(p, &t, err))
            return false;
        if (t.kind != CV_TOK_RBRACKET)
            return cv_fail(err, "%s:%d:%d: expected ']' after %zu numbers of %.*s", t.file,
                           t.line, t.col, n, (int)dir->len, dir->text);
    }
    return true;
}

/* One value of a parameter list: number, string or bare true/false. */
static bool add_value(struct cv_param *pa, const struct cv_token *t, size_t *cap_n,
                      size_t *cap_s, struct cv_error *err)
{
    if (t->kind == CV_TOK_NUMBER) {
        double v;
        if (!cv_token_number(t, &v, err))
            return false;
        if (pa->type == CV_PARAM_BOOL)
            return cv_fail(err, "%s:%d:%d: bool parameter \"%s\" expects true or false",
                           t->file, t->line, t->col, pa->name);
        if (pa->type == CV_PARAM_STRING || pa->type == CV_PARAM_TEXTURE)
            return cv_fail(err, "%s:%d:%d: %s parameter \"%s\" expects a quoted string",
                           t->file, t->line, t->col, cv_param_type_name(pa->type), pa->name);
        CV_PUSH(pa->nums, pa->n_nums, *cap_n, v);
        return true;
    }
    if (t->kind == CV_TOK_STRING || t->kind == CV_TOK_WORD) {
        if (pa->type == CV_PARAM_BOOL) {
            if (cv_token_is(t, "true")) {
                CV_PUSH(pa->nums, pa->n_nums, *cap_n, 1.0);
                return true;
            }
            if (cv_token_is(t, "false")) {
                CV_PUSH(pa->nums, pa->n_nums, *cap_n, 0.0);
                return true;
            }
            return cv_fail(err, "%s:%d:%d: bool parameter \"%s\" expects true or false, not \"%.*s\"",
                           t->file, t->line, t->col, pa->name, (int)t->len, t->text);
        }
        if (t->kind == CV_TOK_WORD)
            return cv_fail(err, "%s:%d:%d: unexpected \"%.*s\" in the values of \"%s\"",
                           t->file, t->line, t->col, (int)(t->len > 40 ? 40 : t->len), t->text,
                           pa->name);
        if (pa->type != CV_PARAM_STRING && pa->type != CV_PARAM_TEXTURE &&
            pa->type != CV_PARAM_SPECTRUM)
            return cv_fail(err, "%s:%d:%d: parameter \"%s\" of type %s expects numbers, not a string",
                           t->file, t->line, t->col, pa->name, cv_param_type_name(pa->type));
        CV_PUSH(pa->strs, pa->n_strs, *cap_s, cv_token_strdup(t));
        return true;
    }
    return cv_fail(err, "%s:%d:%d: unexpected '%.*s' in the values of \"%s\"", t->file, t->line,
                   t->col, (int)t->len, t->text, pa->name);
}

static bool check_count(struct cv_param *pa, struct cv_error *err)
{
    size_t per = 1;
    switch (pa->type) {
    case CV_PARAM_POINT2: case CV_PARAM_VECTOR2: per = 2; break;
    case CV_PARAM_POINT3: case CV_PARAM_VECTOR3: case CV_PARAM_NORMAL: case CV_PARAM_RGB:
        per = 3; break;
    case CV_PARAM_SPECTRUM: per = pa->n_strs ? 1 : 2; break;
    default: break;
    }
    size_t n = pa->n_nums + pa->n_strs;
    if (n == 0 || (pa->n_nums && pa->n_strs) || n % per != 0)
        return cv_fail(err, "%s:%d:%d: parameter \"%s %s\" has %zu values, expected a non-zero multiple of %zu",
                       pa->file, pa->line, pa->col, cv_param_type_name(pa->type), pa->name, n, per);
    return true;
}

/* Parameter list: ("type name" value-or-[values])* up to the next directive. */
static bool read_params(struct parser *p, struct cv_params *ps, struct cv_error *err)
{
    for (;;) {
        struct cv_token t;
        if (!peek(p, &t, err))
            return false;
        if (t.kind != CV_TOK_STRING)
            return true;
        next(p, &t, err);
        /* "type name": split on whitespace */
        char *decl = cv_token_strdup(&t);
        char *s = decl, *ty, *nm;
        while (*s == ' ' || *s == '\t')
            s++;
        ty = s;
        while (*s && *s != ' ' && *s != '\t')
            s++;
        if (*s)
            *s++ = 0;
        while (*s == ' ' || *s == '\t')
            s++;
        nm = s;
        while (*s && *s != ' ' && *s != '\t')
            s++;
        bool trailing = false;
        if (*s) {
            *s++ = 0;
            while (*s == ' ' || *s == '\t')
                s++;
            trailing = *s != 0;
        }
        enum cv_param_type type;
        if (!*nm || trailing) {
            free(decl);
            return cv_fail(err, "%s:%d:%d: expected \"type name\" in a parameter list, found \"%.*s\"",
                           t.file, t.line, t.col, (int)(t.len > 60 ? 60 : t.len), t.text);
        }
        if (!cv_param_type_from_word(ty, &type)) {
            /* unsupported type: warn, skip its values, go on */
            struct cv_loc l = {t.file, t.line, t.col};
            bool w = cv_b_warn(p->b, err, &l, "unknown parameter type \"%s\"; \"%s\" ignored", ty, nm);
            free(decl); /* ty and nm point into it: not used below */
            if (!w)
                return false;
            struct cv_token v;
            if (!next(p, &v, err))
                return false;
            if (v.kind == CV_TOK_LBRACKET) {
                do {
                    if (!next(p, &v, err))
                        return false;
                    if (v.kind == CV_TOK_EOF || v.kind == CV_TOK_LBRACKET)
                        return cv_fail(err, "%s:%d:%d: unbalanced '[' (opened at %d:%d)", v.file,
                                       v.line, v.col, t.line, t.col);
                } while (v.kind != CV_TOK_RBRACKET);
            } else if (v.kind != CV_TOK_NUMBER && v.kind != CV_TOK_STRING && v.kind != CV_TOK_WORD) {
                return cv_fail(err, "%s:%d:%d: expected a parameter value", v.file, v.line, v.col);
            }
            continue;
        }
        struct cv_param pa = {.type = type, .name = cv_xstrdup(nm), .file = t.file,
                              .line = t.line, .col = t.col};
        free(decl);
        size_t cap_n = 0, cap_s = 0;
        CV_PUSH(ps->v, ps->n, ps->cap, pa);
        struct cv_param *pp = &ps->v[ps->n - 1];
        struct cv_token v;
        if (!next(p, &v, err))
            return false;
        if (v.kind == CV_TOK_LBRACKET) {
            for (;;) {
                if (!next(p, &v, err))
                    return false;
                if (v.kind == CV_TOK_RBRACKET)
                    break;
                if (v.kind == CV_TOK_EOF || v.kind == CV_TOK_LBRACKET)
                    return cv_fail(err, "%s:%d:%d: unbalanced '[' (opened at %d:%d) for parameter \"%s\"",
                                   v.file, v.line, v.col, pp->line, pp->col, pp->name);
                if (!add_value(pp, &v, &cap_n, &cap_s, err))
                    return false;
            }
        } else if (v.kind == CV_TOK_EOF) {
            return cv_fail(err, "%s:%d:%d: file ends before the value of parameter \"%s\"",
                           v.file, v.line, v.col, pp->name);
        } else if (!add_value(pp, &v, &cap_n, &cap_s, err)) {
            return false;
        }
        if (!check_count(pp, err))
            return false;
    }
}

/* name: as written in the Include, for messages. */
static bool push_file(struct parser *p, const char *path, const char *name,
                      const struct cv_token *from, struct cv_error *err)
{
    if (p->n_lx >= MAX_INCLUDE_DEPTH)
        return cv_fail(err, "%s:%d:%d: includes nested deeper than %d", from->file, from->line,
                       from->col, MAX_INCLUDE_DEPTH);
    char *real = realpath(path, NULL);
    for (size_t i = 0; real && i < p->n_lx; i++)
        if (p->real[i] && strcmp(p->real[i], real) == 0) {
            free(real);
            return cv_fail(err, "%s:%d:%d: recursive include of \"%s\"", from->file, from->line,
                           from->col, name);
        }
    struct cv_lexer lx;
    if (!cv_lexer_open(&lx, path, err)) {
        free(real);
        if (from)
            cv_error_prefix(err, "%s:%d:%d: cannot include \"%s\"", from->file, from->line,
                            from->col, name);
        return false;
    }
    size_t cap = p->cap_lx;
    CV_PUSH(p->lx, p->n_lx, p->cap_lx, lx);
    p->real = cv_xrealloc(p->real, p->cap_lx * sizeof(char *));
    (void)cap;
    p->real[p->n_lx - 1] = real;
    return true;
}

static void pop_file(struct parser *p)
{
    p->n_lx--;
    /* Locations keep pointing at the path: the builder owns it from now on. */
    struct cv_builder *b = p->b;
    CV_PUSH(b->paths, b->n_paths, b->cap_paths, p->lx[p->n_lx].path);
    p->lx[p->n_lx].path = NULL;
    cv_lexer_close(&p->lx[p->n_lx]);
    free(p->real[p->n_lx]);
}

static void apply(struct cv_builder *b, struct cv_mat4 m)
{
    if (b->gs.active & CV_XFORM_START)
        b->gs.ctm = cv_mat4_mul(&b->gs.ctm, &m);
    if (b->gs.active & CV_XFORM_END)
        b->gs.ctm_end = cv_mat4_mul(&b->gs.ctm_end, &m);
}

static void set_ctm(struct cv_builder *b, struct cv_mat4 m)
{
    if (b->gs.active & CV_XFORM_START)
        b->gs.ctm = m;
    if (b->gs.active & CV_XFORM_END)
        b->gs.ctm_end = m;
}

/* A shape or instance whose start and end transforms differ moves
 * (builder.h, cv_b_can_move); one that cannot is placed at its start
 * transform, with a warning that says why. Lights never move (as in
 * pbrt-v4, which takes their start transform too). */
static bool warn_animated(struct cv_builder *b, const struct cv_loc *loc, const char *what,
                          struct cv_error *err)
{
    if (memcmp(&b->gs.ctm, &b->gs.ctm_end, sizeof(b->gs.ctm)) == 0)
        return true;
    return cv_b_warn(b, err, loc, "animated transform: %s motion blur is not rendered; the %s "
                     "is taken at its start time", what, what);
}

/* Shape `type` (NULL: an instance of object `index`) under the current
 * transforms: moving when they differ and it can move. */
static bool place(struct cv_builder *b, const char *type, struct cv_params *ps, int index,
                  const struct cv_loc *loc, const char *dir, struct cv_error *err)
{
    const char *why;
    bool moving = cv_b_can_move(b, type, &why);
    if (why && !cv_b_warn(b, err, loc, "animated transform: %s; taken at its start time", why))
        return false;
    if (moving)
        cv_b_motion_begin(b, type == NULL);
    bool ok = type ? cv_b_shape(b, type, ps, loc, dir, err) : cv_b_instance(b, index, loc, err);
    if (moving)
        cv_b_motion_end(b);
    return ok;
}

static bool attr_push(struct cv_builder *b, bool transform_only, const struct cv_loc *loc)
{
    struct cv_gstate g = b->gs;
    g.transform_only = transform_only;
    size_t cap = b->cap_stack;
    CV_PUSH(b->stack, b->n_stack, b->cap_stack, g);
    if (cap != b->cap_stack)
        b->stack_loc = cv_xrealloc(b->stack_loc, b->cap_stack * sizeof(*b->stack_loc));
    b->stack_loc[b->n_stack - 1] = *loc;
    return true;
}

static bool attr_pop(struct cv_builder *b, bool transform_only, const struct cv_token *t,
                     struct cv_error *err)
{
    const char *what = transform_only ? "TransformEnd" : "AttributeEnd";
    if (b->n_stack == 0)
        return cv_fail(err, "%s:%d:%d: %s without a matching %s", t->file, t->line, t->col, what,
                       transform_only ? "TransformBegin" : "AttributeBegin");
    struct cv_gstate *g = &b->stack[b->n_stack - 1];
    if (g->transform_only != transform_only) {
        struct cv_loc *l = &b->stack_loc[b->n_stack - 1];
        struct cv_loc here = {t->file, t->line, t->col};
        if (!cv_b_warn(b, err, &here, "%s closes the %s opened at %s:%d:%d", what,
                       g->transform_only ? "TransformBegin" : "AttributeBegin", l->file,
                       l->line, l->col))
            return false;
    }
    if (transform_only) {
        b->gs.ctm = g->ctm;
        b->gs.ctm_end = g->ctm_end;
        b->gs.active = g->active;
    } else
        b->gs = *g;
    b->n_stack--;
    return true;
}

static struct cv_param param_copy(const struct cv_param *a)
{
    struct cv_param c = *a;
    c.name = cv_xstrdup(a->name);
    c.nums = a->n_nums ? cv_xmalloc(a->n_nums * sizeof(double)) : NULL;
    if (a->n_nums)
        memcpy(c.nums, a->nums, a->n_nums * sizeof(double));
    c.strs = a->n_strs ? cv_xmalloc(a->n_strs * sizeof(char *)) : NULL;
    for (size_t i = 0; i < a->n_strs; i++)
        c.strs[i] = cv_xstrdup(a->strs[i]);
    return c;
}

static void param_free(struct cv_param *pa)
{
    free(pa->name);
    free(pa->nums);
    for (size_t i = 0; i < pa->n_strs; i++)
        free(pa->strs[i]);
    free(pa->strs);
}

static void attrs_drop_to(struct parser *p, size_t depth)
{
    while (p->n_attrs > 0 && p->attrs[p->n_attrs - 1].depth > depth)
        param_free(&p->attrs[--p->n_attrs].p);
}

/* Appends the Attribute defaults of target that ps does not set itself;
 * they count as used (an attribute may not apply to every type). */
static void attrs_apply(struct parser *p, const char *target, struct cv_params *ps)
{
    for (size_t i = p->n_attrs; i-- > 0;) {
        struct attr_default *a = &p->attrs[i];
        if (strcmp(a->target, target) != 0)
            continue;
        bool have = false;
        for (size_t j = 0; j < ps->n && !have; j++)
            have = strcmp(ps->v[j].name, a->p.name) == 0;
        if (have)
            continue;
        struct cv_param c = param_copy(&a->p);
        c.used = true;
        CV_PUSH(ps->v, ps->n, ps->cap, c);
    }
}

static bool do_directive(struct parser *p, const struct cv_token *d, struct cv_error *err);

/* Every directive do_directive takes, once: its dispatch and the test that
 * tells a scene file from any other file by its first token read this. */
#define CV_DIRECTIVES(X) \
    X(Accelerator) X(ActiveTransform) X(AreaLightSource) X(Attribute) X(AttributeBegin) \
    X(AttributeEnd) X(Camera) X(ColorSpace) X(ConcatTransform) X(CoordSysTransform) \
    X(CoordinateSystem) X(Film) X(Identity) X(Import) X(Include) X(Integrator) \
    X(LightSource) X(LookAt) X(MakeNamedMaterial) X(MakeNamedMedium) X(Material) \
    X(MediumInterface) X(NamedMaterial) X(ObjectBegin) X(ObjectEnd) X(ObjectInstance) \
    X(Option) X(PixelFilter) X(ReverseOrientation) X(Rotate) X(Sampler) X(Scale) X(Shape) \
    X(Texture) X(Transform) X(TransformBegin) X(TransformEnd) X(TransformTimes) X(Translate) \
    X(WorldBegin) X(WorldEnd)

enum directive {
#define X(name) DIR_##name,
    CV_DIRECTIVES(X)
#undef X
};

static const char *const directive_names[] = {
#define X(name) #name,
    CV_DIRECTIVES(X)
#undef X
};

/* The directive token t names, or -1. */
static int directive_of(const struct cv_token *t)
{
    if (t->kind != CV_TOK_WORD)
        return -1;
    for (size_t i = 0; i < CV_ARRAY_SIZE(directive_names); i++)
        if (cv_token_is(t, directive_names[i]))
            return (int)i;
    return -1;
}

static bool run(struct parser *p, size_t base, struct cv_error *err)
{
    while (p->n_lx > base) {
        struct cv_token t;
        if (!next(p, &t, err))
            return false;
        if (t.kind == CV_TOK_EOF) {
            pop_file(p);
            continue;
        }
        /* A file that does not start with a directive may be anything the
         * scene names (Include "/etc/shadow"): its text is not echoed. */
        if (top(p)->directives++ == 0 && directive_of(&t) < 0)
            return cv_fail(err, "%s:%d:%d: not a pbrt scene file (it does not start with a "
                                "directive)", t.file, t.line, t.col);
        if (t.kind != CV_TOK_WORD)
            return cv_fail(err, "%s:%d:%d: expected a directive, found %s\"%.*s\"", t.file,
                           t.line, t.col,
                           t.kind == CV_TOK_STRING ? "string " : t.kind == CV_TOK_NUMBER ? "number " : "",
                           (int)(t.len > 40 ? 40 : t.len), t.text);
        if (!do_directive(p, &t, err))
            return false;
    }
    return true;
}

/* Directives with "type" params: Shape, Material, LightSource, ... */
static bool typed(struct parser *p, const struct cv_token *d, char **type, struct cv_params *ps,
                  struct cv_error *err)
{
    if (!expect_string(p, d, type, err))
        return false;
    return read_params(p, ps, err);
}

static char *dir_of(struct parser *p, const struct cv_token *d)
{
    (void)p;
    return cv_path_dirname(d->file);
}

static bool do_directive(struct parser *p, const struct cv_token *d, struct cv_error *err)
{
    struct cv_builder *b = p->b;
    struct cv_loc loc = LOC_OF(*d);
    double v[16];
    char *type = NULL, *name = NULL, *dir = NULL;
    struct cv_params ps = {0};
    bool ok = true;

    int id = directive_of(d);
#define IS(name) (id == DIR_##name)
    if (IS(Translate)) {
        if (!read_numbers(p, d, v, 3, err))
            return false;
        apply(b, cv_mat4_translate(v[0], v[1], v[2]));
    } else if (IS(Scale)) {
        if (!read_numbers(p, d, v, 3, err))
            return false;
        apply(b, cv_mat4_scale(v[0], v[1], v[2]));
    } else if (IS(Rotate)) {
        if (!read_numbers(p, d, v, 4, err))
            return false;
        apply(b, cv_mat4_rotate(v[0], v[1], v[2], v[3]));
    } else if (IS(LookAt)) {
        if (!read_numbers(p, d, v, 9, err))
            return false;
        struct cv_mat4 m;
        if (!cv_mat4_look_at(v, v + 3, v + 6, &m)) {
            if (!cv_b_warn(b, err, &loc, "degenerate LookAt ignored"))
                return false;
        } else {
            apply(b, m);
        }
    } else if (IS(Transform) || IS(ConcatTransform)) {
        if (!read_numbers(p, d, v, 16, err))
            return false;
        struct cv_mat4 m;
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++)
                m.m[j][i] = v[i * 4 + j];
        if (IS(Transform))
            set_ctm(b, m);
        else
            apply(b, m);
    } else if (IS(Identity)) {
        set_ctm(b, cv_mat4_identity());
    } else if (IS(CoordinateSystem) || IS(CoordSysTransform)) {
        if (!expect_string(p, d, &name, err))
            return false;
        size_t i;
        for (i = 0; i < b->n_coordsys; i++)
            if (strcmp(b->coordsys[i].name, name) == 0)
                break;
        if (IS(CoordinateSystem)) {
            if (i == b->n_coordsys) {
                struct cv_coordsys c = {cv_xstrdup(name), b->gs.ctm, b->gs.ctm_end};
                CV_PUSH(b->coordsys, b->n_coordsys, b->cap_coordsys, c);
            } else {
                b->coordsys[i].m = b->gs.ctm;
                b->coordsys[i].m_end = b->gs.ctm_end;
            }
        } else if (i == b->n_coordsys) {
            ok = cv_b_warn(b, err, &loc, "unknown coordinate system \"%s\"", name);
        } else {
            /* pbrt-v4 sets both transforms, whichever are active */
            b->gs.ctm = b->coordsys[i].m;
            b->gs.ctm_end = b->coordsys[i].m_end;
        }
    } else if (IS(ActiveTransform)) {
        struct cv_token t;
        if (!next(p, &t, err))
            return false;
        if (t.kind != CV_TOK_WORD ||
            !(cv_token_is(&t, "StartTime") || cv_token_is(&t, "EndTime") || cv_token_is(&t, "All")))
            return cv_fail(err, "%s:%d:%d: ActiveTransform expects StartTime, EndTime or All",
                           t.file, t.line, t.col);
        b->gs.active = cv_token_is(&t, "StartTime") ? CV_XFORM_START
                       : cv_token_is(&t, "EndTime") ? CV_XFORM_END
                                                    : CV_XFORM_START | CV_XFORM_END;
    } else if (IS(TransformTimes)) {
        if (!read_numbers(p, d, v, 2, err))
            return false;
        if (!(v[0] <= v[1]))
            return cv_fail(err, "%s:%d:%d: TransformTimes: the start time is after the end time",
                           loc.file, loc.line, loc.col);
        b->transform_times[0] = v[0];
        b->transform_times[1] = v[1];
    } else if (IS(ReverseOrientation)) {
        b->gs.reverse = !b->gs.reverse;
    } else if (IS(AttributeBegin) || IS(TransformBegin)) {
        attr_push(b, IS(TransformBegin), &loc);
    } else if (IS(AttributeEnd) || IS(TransformEnd)) {
        if (!attr_pop(b, IS(TransformEnd), d, err))
            return false;
        attrs_drop_to(p, b->n_stack);
    } else if (IS(Attribute)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        if (strcmp(type, "shape") != 0 && strcmp(type, "light") != 0 && strcmp(type, "material") != 0 &&
            strcmp(type, "medium") != 0 && strcmp(type, "texture") != 0) {
            ok = cv_fail(err, "%s:%d:%d: Attribute target must be shape, light, material, medium or texture, not \"%s\"",
                         loc.file, loc.line, loc.col, type);
        } else {
            for (size_t i = 0; i < ps.n; i++) {
                struct attr_default a = {{0}, param_copy(&ps.v[i]), b->n_stack};
                snprintf(a.target, sizeof(a.target), "%s", type);
                CV_PUSH(p->attrs, p->n_attrs, p->cap_attrs, a);
                ps.v[i].used = true;
            }
        }
    } else if (IS(Option)) {
        if (!read_params(p, &ps, err))
            goto fail;
        for (size_t i = 0; i < ps.n; i++)
            ps.v[i].used = true;
        ok = ps.n == 0 || cv_b_warn(b, err, &loc, "Option \"%s\" noted and ignored", ps.v[0].name);
    } else if (IS(ColorSpace)) {
        if (!expect_string(p, d, &name, err))
            return false;
        if (strcmp(name, "srgb") != 0)
            ok = cv_b_warn(b, err, &loc, "ColorSpace \"%s\": colours are read as linear sRGB/Rec.709", name);
        free(b->color_space);
        b->color_space = name;
        name = NULL;
    } else if (IS(WorldBegin)) {
        if (b->world)
            ok = cv_b_warn(b, err, &loc, "WorldBegin repeated");
        b->world = true;
        /* pbrt: the camera's named coordinate system, then the world starts
         * with the identity transform. */
        b->gs.ctm = b->gs.ctm_end = cv_mat4_identity();
        b->gs.active = CV_XFORM_START | CV_XFORM_END;
        struct cv_coordsys c = {cv_xstrdup("world"), cv_mat4_identity(), cv_mat4_identity()};
        CV_PUSH(b->coordsys, b->n_coordsys, b->cap_coordsys, c);
    } else if (IS(WorldEnd)) {
        /* v3: end of scene; nothing to do. */
    } else if (IS(Camera)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        ok = cv_b_camera(b, type, &ps, &loc, err) && cv_b_check_unused(b, &ps, "Camera", err);
    } else if (IS(Film)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        ok = cv_b_film(b, type, &ps, &loc, err) && cv_b_check_unused(b, &ps, "Film", err);
    } else if (IS(Sampler)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        int spp = cv_params_int(&ps, "pixelsamples", (int)CV_DEFAULT_SPP);
        if ((unsigned)spp > CV_MAX_SPP && spp > 0) {
            if (!cv_b_warn(b, err, &loc, "pixelsamples %d is above the most Cavalry renders, %u",
                           spp, CV_MAX_SPP))
                goto fail;
            spp = (int)CV_MAX_SPP;
        }
        b->s->settings.spp = spp > 0 ? (uint32_t)spp : 1;
        free(b->s->settings.sampler);
        b->s->settings.sampler = type;
        type = NULL;
        for (size_t i = 0; i < ps.n; i++)
            ps.v[i].used = true; /* sampler tuning has no meaning here */
    } else if (IS(PixelFilter)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        struct cv_render_settings *st = &b->s->settings;
        const struct cv_filter_info *fi = cv_filter_by_name(type);
        if (!fi) {
            fi = cv_filter_info(CV_FILTER_DEFAULT);
            ok = cv_b_warn(b, err, &loc, "pixel filter \"%s\" is not supported; using a %s", type,
                           fi->name);
        }
        st->filter = fi->type;
        double def = fi->radius;
        /* v4 radius, v3 width (which pbrt-v3 also meant as a radius) */
        st->filter_radius[0] = (float)cv_params_float(&ps, "xradius", cv_params_float(&ps, "xwidth", def));
        st->filter_radius[1] = (float)cv_params_float(&ps, "yradius", cv_params_float(&ps, "ywidth", def));
        /* pbrt-v3's gaussian falls off as exp(-alpha x^2): v4's of sigma
         * 1 / sqrt(2 alpha) (v3's default alpha, 2, is v4's sigma) */
        double alpha = cv_params_float(&ps, "alpha", 0);
        bool v3_alpha = cv_params_find(&ps, "alpha") != NULL;
        st->filter_sigma = (float)cv_params_float(
            &ps, "sigma", v3_alpha && alpha > 0 ? 1 / sqrt(2 * alpha) : CV_FILTER_GAUSSIAN_SIGMA);
        st->filter_b = (float)cv_params_float(&ps, "B", CV_FILTER_MITCHELL_B);
        st->filter_c = (float)cv_params_float(&ps, "C", CV_FILTER_MITCHELL_C);
        st->filter_tau = (float)cv_params_float(&ps, "tau", CV_FILTER_SINC_TAU);
        if (ok && !(st->filter_radius[0] > 0 && st->filter_radius[1] > 0 && st->filter_sigma > 0 &&
              st->filter_tau > 0 && (!v3_alpha || alpha > 0)))
            ok = cv_fail(err, "%s:%d:%d: PixelFilter radii, sigma, alpha and tau must be positive",
                         loc.file, loc.line, loc.col);
        ok = ok && cv_b_check_unused(b, &ps, "PixelFilter", err);
    } else if (IS(Integrator)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        int md = cv_params_int(&ps, "maxdepth", (int)CV_DEFAULT_MAX_DEPTH);
        b->s->settings.max_depth = md > 0 ? (uint32_t)md : CV_DEFAULT_MAX_DEPTH;
        /* pbrt-v4's roughening of near-specular vertices changes the
         * image; the other tuning (lightsampler, ...) changes its noise */
        if (cv_params_bool(&ps, "regularize", false) &&
            !cv_b_warn(b, err, &loc, "Integrator \"regularize\" is not supported; rendered "
                       "without it"))
            goto fail;
        free(b->s->settings.integrator);
        b->s->settings.integrator = type;
        free(b->s->settings.integrator_at);
        b->s->settings.integrator_at = cv_xasprintf("%s:%d:%d", loc.file, loc.line, loc.col);
        type = NULL;
        for (size_t i = 0; i < ps.n; i++)
            ps.v[i].used = true;
    } else if (IS(Accelerator)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        for (size_t i = 0; i < ps.n; i++)
            ps.v[i].used = true;
        cv_info("%s:%d:%d: Accelerator \"%s\" ignored (Cavalry builds its own BVH)", loc.file,
                loc.line, loc.col, type);
    } else if (IS(Shape)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        attrs_apply(p, "shape", &ps);
        dir = dir_of(p, d);
        ok = place(b, type, &ps, -1, &loc, dir, err) && cv_b_check_unused(b, &ps, "Shape", err);
    } else if (IS(Material)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        attrs_apply(p, "material", &ps);
        dir = dir_of(p, d);
        int idx;
        ok = cv_b_material(b, type, NULL, &ps, &loc, dir, err, &idx) &&
             cv_b_check_unused(b, &ps, "Material", err);
        if (ok) {
            b->gs.material = idx;
            cv_b_material_at(b, idx, &loc);
        }
    } else if (IS(MakeNamedMaterial)) {
        if (!typed(p, d, &name, &ps, err))
            goto fail;
        attrs_apply(p, "material", &ps);
        dir = dir_of(p, d);
        const char *ty = cv_params_string(&ps, "type", NULL);
        int idx;
        if (!ty) {
            ok = cv_fail(err, "%s:%d:%d: MakeNamedMaterial \"%s\" has no \"string type\"",
                         loc.file, loc.line, loc.col, name);
        } else {
            ok = cv_b_material(b, ty, name, &ps, &loc, dir, err, &idx) &&
                 cv_b_check_unused(b, &ps, "MakeNamedMaterial", err);
            if (ok) {
                cv_b_material_at(b, idx, &loc);
                if (cv_b_lookup(b->materials_named, b->n_materials_named, name) >= 0)
                    ok = cv_b_warn(b, err, &loc, "named material \"%s\" redefined", name);
                cv_b_set_named(&b->materials_named, &b->n_materials_named,
                               &b->cap_materials_named, name, idx);
            }
        }
    } else if (IS(NamedMaterial)) {
        if (!expect_string(p, d, &name, err))
            return false;
        int idx = cv_b_lookup(b->materials_named, b->n_materials_named, name);
        if (idx < 0)
            ok = cv_fail(err, "%s:%d:%d: unknown named material \"%s\"", loc.file, loc.line,
                         loc.col, name);
        else
            b->gs.material = idx;
    } else if (IS(Texture)) {
        char *kind = NULL;
        if (!expect_string(p, d, &name, err) || !expect_string(p, d, &kind, err) ||
            !typed(p, d, &type, &ps, err)) {
            free(kind);
            goto fail;
        }
        attrs_apply(p, "texture", &ps);
        dir = dir_of(p, d);
        ok = cv_b_texture(b, name, kind, type, &ps, &loc, dir, err) &&
             cv_b_check_unused(b, &ps, "Texture", err);
        free(kind);
    } else if (IS(LightSource)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        attrs_apply(p, "light", &ps);
        dir = dir_of(p, d);
        ok = warn_animated(b, &loc, "light", err) && cv_b_light(b, type, &ps, &loc, dir, err) &&
             cv_b_check_unused(b, &ps, "LightSource", err);
    } else if (IS(AreaLightSource)) {
        if (!typed(p, d, &type, &ps, err))
            goto fail;
        attrs_apply(p, "light", &ps);
        dir = dir_of(p, d);
        ok = cv_b_area_light(b, type, &ps, &loc, dir, err) &&
             cv_b_check_unused(b, &ps, "AreaLightSource", err);
    } else if (IS(MakeNamedMedium)) {
        if (!typed(p, d, &name, &ps, err))
            goto fail;
        attrs_apply(p, "medium", &ps);
        dir = dir_of(p, d);
        ok = cv_b_medium(b, name, &ps, &loc, dir, err) &&
             cv_b_check_unused(b, &ps, "MakeNamedMedium", err);
    } else if (IS(MediumInterface)) {
        /* one or two names: inside [outside]; one name is both */
        if (!expect_string(p, d, &name, err))
            return false;
        struct cv_token t;
        if (!peek(p, &t, err))
            goto fail;
        char *outside = NULL;
        if (t.kind == CV_TOK_STRING && !expect_string(p, d, &outside, err))
            goto fail;
        ok = cv_b_medium_interface(b, name, outside ? outside : name, &loc, err);
        free(outside);
    } else if (IS(ObjectBegin)) {
        if (!expect_string(p, d, &name, err))
            return false;
        if (b->cur_object >= 0) {
            ok = cv_fail(err, "%s:%d:%d: ObjectBegin \"%s\" inside another ObjectBegin",
                         loc.file, loc.line, loc.col, name);
        } else {
            attr_push(b, false, &loc);
            struct cv_object o = {0};
            o.name = name;
            name = NULL;
            CV_PUSH(b->objects, b->n_objects, b->cap_objects, o);
            b->cur_object = (int)b->n_objects - 1;
        }
    } else if (IS(ObjectEnd)) {
        if (b->cur_object < 0)
            return cv_fail(err, "%s:%d:%d: ObjectEnd without ObjectBegin", loc.file, loc.line, loc.col);
        b->cur_object = -1;
        if (!attr_pop(b, false, d, err))
            return false;
    } else if (IS(ObjectInstance)) {
        if (!expect_string(p, d, &name, err))
            return false;
        int found = -1;
        for (size_t i = 0; i < b->n_objects; i++)
            if (strcmp(b->objects[i].name, name) == 0)
                found = (int)i;
        if (found < 0 || found == b->cur_object)
            ok = cv_fail(err, "%s:%d:%d: unknown object \"%s\"", loc.file, loc.line, loc.col, name);
        else
            ok = place(b, NULL, NULL, found, &loc, NULL, err);
    } else if (IS(Include) || IS(Import)) {
        if (!expect_string(p, d, &name, err))
            return false;
        dir = dir_of(p, d);
        char *path = cv_b_resolve(b, dir, name, err);
        if (path)
            ok = push_file(p, path, name, d, err);
        else {
            cv_error_prefix(err, "%s:%d:%d: cannot include \"%s\"", d->file, d->line, d->col,
                            name);
            ok = false;
        }
        free(path);
    } else {
        return cv_fail(err, "%s:%d:%d: unknown directive \"%.*s\"", d->file, d->line, d->col,
                       (int)(d->len > 40 ? 40 : d->len), d->text);
    }
#undef IS
    cv_params_free(&ps);
    free(type);
    free(name);
    free(dir);
    return ok;
fail:
    cv_params_free(&ps);
    free(type);
    free(name);
    free(dir);
    return false;
}

static bool parse_with(struct parser *p, struct cv_error *err)
{
    bool ok = run(p, 0, err);
    while (p->n_lx > 0)
        pop_file(p);
    free(p->lx);
    free(p->real);
    for (size_t i = 0; i < p->n_attrs; i++)
        param_free(&p->attrs[i].p);
    free(p->attrs);
    if (ok && p->b->n_stack > 0) {
        struct cv_loc *l = &p->b->stack_loc[p->b->n_stack - 1];
        return cv_fail(err, "%s:%d:%d: %s not closed at end of input", l->file, l->line, l->col,
                       p->b->stack[p->b->n_stack - 1].transform_only ? "TransformBegin"
                                                                     : "AttributeBegin");
    }
    return ok;
}

bool cv_parse_file(struct cv_builder *b, const char *path, struct cv_error *err)
{
    struct parser p = {.b = b};
    free(b->main_dir);
    b->main_dir = cv_path_dirname(path);
    if (!cv_b_check_root(b, path, err) || !push_file(&p, path, path, NULL, err)) {
        free(p.lx);
        free(p.real);
        return false;
    }
    return parse_with(&p, err);
}

bool cv_parse_string(struct cv_builder *b, const char *name, const char *text, size_t len,
                     struct cv_error *err)
{
    struct parser p = {.b = b};
    free(b->main_dir);
    b->main_dir = cv_path_dirname(name);
    struct cv_lexer lx;
    cv_lexer_open_string(&lx, name, text, len);
    CV_PUSH(p.lx, p.n_lx, p.cap_lx, lx);
    p.real = cv_xcalloc(p.cap_lx, sizeof(char *));
    return parse_with(&p, err);
}
