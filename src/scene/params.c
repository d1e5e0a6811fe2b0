/* params.c: typed parameter lists of the pbrt directives. */
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "scene/params.h"

static const struct {
    const char *word;
    enum cv_param_type type;
} type_words[] = {
    {"integer", CV_PARAM_INTEGER}, {"float", CV_PARAM_FLOAT},
    {"point2", CV_PARAM_POINT2},   {"vector2", CV_PARAM_VECTOR2},
    {"point3", CV_PARAM_POINT3},   {"point", CV_PARAM_POINT3},
    {"vector3", CV_PARAM_VECTOR3}, {"vector", CV_PARAM_VECTOR3},
    {"normal", CV_PARAM_NORMAL},   {"normal3", CV_PARAM_NORMAL},
    {"rgb", CV_PARAM_RGB},         {"color", CV_PARAM_RGB},
    {"spectrum", CV_PARAM_SPECTRUM}, {"blackbody", CV_PARAM_BLACKBODY},
    {"bool", CV_PARAM_BOOL},       {"string", CV_PARAM_STRING},
    {"texture", CV_PARAM_TEXTURE},
};

bool cv_param_type_from_word(const char *word, enum cv_param_type *out)
{
    for (size_t i = 0; i < CV_ARRAY_SIZE(type_words); i++)
        if (strcmp(word, type_words[i].word) == 0) {
            *out = type_words[i].type;
            return true;
        }
    return false;
}

const char *cv_param_type_name(enum cv_param_type t)
{
    for (size_t i = 0; i < CV_ARRAY_SIZE(type_words); i++)
        if (type_words[i].type == t)
            return type_words[i].word;
    return "?";
}

void cv_params_free(struct cv_params *ps)
{
    for (size_t i = 0; i < ps->n; i++) {
        struct cv_param *p = &ps->v[i];
        free(p->name);
        free(p->nums);
        for (size_t j = 0; j < p->n_strs; j++)
            free(p->strs[j]);
        free(p->strs);
    }
    free(ps->v);
    memset(ps, 0, sizeof(*ps));
}

struct cv_param *cv_params_find(struct cv_params *ps, const char *name)
{
    for (size_t i = ps->n; i-- > 0;)
        if (strcmp(ps->v[i].name, name) == 0) {
            ps->v[i].used = true;
            return &ps->v[i];
        }
    return NULL;
}

static struct cv_param *find_numeric(struct cv_params *ps, const char *name)
{
    for (size_t i = ps->n; i-- > 0;) {
        struct cv_param *p = &ps->v[i];
        if (strcmp(p->name, name) == 0 && p->n_nums > 0 && p->type != CV_PARAM_SPECTRUM &&
            p->type != CV_PARAM_BLACKBODY && p->type != CV_PARAM_RGB) {
            p->used = true;
            return p;
        }
    }
    return NULL;
}

double cv_params_float(struct cv_params *ps, const char *name, double def)
{
    struct cv_param *p = find_numeric(ps, name);
    return p ? p->nums[0] : def;
}

int cv_params_int(struct cv_params *ps, const char *name, int def)
{
    struct cv_param *p = find_numeric(ps, name);
    if (!p)
        return def;
    double v = p->nums[0];
    if (v > 2147483647.0)
        return 2147483647;
    if (v < -2147483647.0)
        return -2147483647;
    return (int)v;
}

bool cv_params_bool(struct cv_params *ps, const char *name, bool def)
{
    struct cv_param *p = find_numeric(ps, name);
    return p ? p->nums[0] != 0 : def;
}

const char *cv_params_string(struct cv_params *ps, const char *name, const char *def)
{
    for (size_t i = ps->n; i-- > 0;) {
        struct cv_param *p = &ps->v[i];
        if (strcmp(p->name, name) == 0 && p->n_strs > 0 &&
            (p->type == CV_PARAM_STRING || p->type == CV_PARAM_TEXTURE)) {
            p->used = true;
            return p->strs[0];
        }
    }
    return def;
}

bool cv_params_floats(struct cv_params *ps, const char *name, double *out, size_t n)
{
    struct cv_param *p = find_numeric(ps, name);
    if (!p || p->n_nums != n)
        return false;
    memcpy(out, p->nums, n * sizeof(double));
    return true;
}

struct cv_param *cv_params_array(struct cv_params *ps, const char *name)
{
    return find_numeric(ps, name);
}
