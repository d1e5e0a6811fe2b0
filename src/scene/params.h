/* params.h: a directive's typed parameter list ("float fov" [ 45 ]). Each
 * lookup marks the parameter used, so that what a directive ignored can be
 * reported with its location afterwards. */
#ifndef CV_SCENE_PARAMS_H
#define CV_SCENE_PARAMS_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"
#include "scene/token.h"

enum cv_param_type {
    CV_PARAM_INTEGER,
    CV_PARAM_FLOAT,
    CV_PARAM_POINT2,
    CV_PARAM_VECTOR2,
    CV_PARAM_POINT3,
    CV_PARAM_VECTOR3,
    CV_PARAM_NORMAL,
    CV_PARAM_RGB,
    CV_PARAM_SPECTRUM,
    CV_PARAM_BLACKBODY,
    CV_PARAM_BOOL,
    CV_PARAM_STRING,
    CV_PARAM_TEXTURE,
};

struct cv_param {
    enum cv_param_type type;
    char *name;
    double *nums;       /* numeric values (bools as 0/1) */
    size_t n_nums;
    char **strs;        /* string values */
    size_t n_strs;
    const char *file;   /* borrowed from the lexer; valid during the directive */
    int line, col;
    bool used;
};

struct cv_params {
    struct cv_param *v;
    size_t n, cap;
};

/* Maps a type word ("point", "color", "normal3", ...) to a type; false if unknown. */
bool cv_param_type_from_word(const char *word, enum cv_param_type *out);
const char *cv_param_type_name(enum cv_param_type t);

void cv_params_free(struct cv_params *ps);
/* The last parameter of that name (any type), marked used; NULL if absent. */
struct cv_param *cv_params_find(struct cv_params *ps, const char *name);
/* Typed getters: the first value, or def when absent. Wrong types are
 * ignored (they stay unused and get reported). */
double cv_params_float(struct cv_params *ps, const char *name, double def);
int cv_params_int(struct cv_params *ps, const char *name, int def);
bool cv_params_bool(struct cv_params *ps, const char *name, bool def);
const char *cv_params_string(struct cv_params *ps, const char *name, const char *def);
/* n numbers of a point/vector/normal/float list into out; false if absent
 * or of another length. */
bool cv_params_floats(struct cv_params *ps, const char *name, double *out, size_t n);
/* The whole numeric array of a parameter of one of the accepted types. */
struct cv_param *cv_params_array(struct cv_params *ps, const char *name);

#endif
