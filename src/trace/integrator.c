/* integrator.c: see integrator.h. The table of integrators, and the path
 * integrator's entry, which is data alone. */
#include <stddef.h>

#include "glsl/shared/trace.h"
#include "trace/bdpt.h"
#include "trace/integrator.h"
#include "trace/rlpath.h"
#include "trace/rlpath_sd.h"

/* The path integrator shades each bin of the hit queue with its own build
 * of trace/shade.comp (CV_SHADE_BIN: diffuse hits with the BSDF code cut
 * down to diffuse, the others but the coated walk's, then those:
 * trace/shade_bins.h). */
static const struct cv_integrator_ops path_ops = {
    .n_shade = 3,
    .file = {"trace/shade.comp", "trace/shade.comp", "trace/shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1", "CV_SHADE_BIN=2"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B, CV_ARGS_HITS_C},
    .bins = {1u, 2u, 4u},
};

/* volpath: the path integrator's stages with participating media
 * (glsl/trace/medium): pbrt-v4's VolPathIntegrator. */
static const struct cv_integrator_ops volpath_ops = {
    .media = true,
    .n_shade = 3,
    .file = {"trace/shade.comp", "trace/shade.comp", "trace/shade.comp"},
    .define = {"CV_SHADE_BIN=0", "CV_SHADE_BIN=1", "CV_SHADE_BIN=2"},
    .args = {CV_ARGS_HITS, CV_ARGS_HITS_B, CV_ARGS_HITS_C},
    .bins = {1u, 2u, 4u},
};

/* One entry for each of manifest/enums.h's integrators. */
static const struct cv_integrator_ops *const integrators[CV_INTEGRATOR_COUNT] = {
    [CV_INTEGRATOR_PATH] = &path_ops,
    [CV_INTEGRATOR_RLPATH] = &cv_rlpath_ops,
    [CV_INTEGRATOR_VOLPATH] = &volpath_ops,
    [CV_INTEGRATOR_BDPT] = &cv_bdpt_ops,
};

const struct cv_integrator_ops *cv_integrator_find(enum cv_integrator id)
{
    if ((unsigned)id >= CV_INTEGRATOR_COUNT)
        return NULL;
    return integrators[id];
}

const struct cv_integrator_ops *cv_integrator_for(const struct cv_render_params *p)
{
    if (p->integrator == CV_INTEGRATOR_RLPATH && p->rl_sdtree)
        return &cv_rlpath_sd_ops;
    return cv_integrator_find(p->integrator);
}
