/* integrator.c: see integrator.h. The table of integrators, and the path
 * integrator's entry, which is data alone. */
#include <stddef.h>

#include "glsl/shared/trace.h"
#include "trace/integrator.h"
#include "trace/rlpath.h"

/* The path integrator shades each bin of the hit queue with its own build
 * of trace/shade.comp (CV_SHADE_BIN: diffuse hits with the BSDF code cut
 * down to diffuse, then the others). */
static const struct cv_integrator_ops path_ops = {
    .n_shade = 2,
    .file = {"trace/shade.comp", "trace/shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B},
};

static const struct cv_integrator_ops *const integrators[] = {
    [CV_RENDER_PATH] = &path_ops,
    [CV_RENDER_RLPATH] = &cv_rlpath_ops,
};

const struct cv_integrator_ops *cv_integrator_find(int id)
{
    if (id < 0 || (size_t)id >= sizeof(integrators) / sizeof(integrators[0]))
        return NULL;
    return integrators[id];
}
