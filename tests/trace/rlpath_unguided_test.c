/* rlpath_unguided_test.c: neither rlpath method guides in the coated
 * walk's shade bin (trace/shade_bins.h; glsl/trace/rlpath/guides.glsl:
 * cv_rl_guides), nor in a bin built with CV_RL_UNGUIDED (where the host
 * finds none of its materials served: cv_shade_bins_guided), on the GLSL
 * that ships: those programs read none of the guide's tables, which the
 * diffuse bin's and the other materials' bin's read. A guide's lookups cost
 * a kernel its registers whether they run or not, and the coated walk's
 * kernel is the largest (bench/RESULTS.md, "sdtree without guiding the
 * coated walk"). sdtree's builds are those of the passes after training
 * (CV_FROZEN): while training, every bin reads the tree to splat the
 * records of the paths that end there. */
#include "config.h"

#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

/* Whether program `file` built with `defines` reads the uniform `name`
 * (-1: it did not build). */
static int reads(struct cv_gpu *gpu, const char *file, const char *const *defines,
                 const char *name)
{
    return test_uniforms_read(gpu, file, defines, &name, 1);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    /* a scene of diffuse and coated diffuse materials, no mix */
#define WALK "CV_NO_ENV", "CV_NO_TEXTURES", "CV_NO_HAIR", "CV_NO_MEASURED", "CV_BSDF_WALK_ONLY"
    static const struct {
        const char *method, *file, *table, *extra;
    } methods[] = {
        {"qlearn", "trace/rlpath/shade.comp", "rl_guide", NULL},
        {"sdtree", "trace/rlpath/sd_shade.comp", "sd_tree", "CV_FROZEN"},
    };
    for (int m = 0; m < 2; m++) {
        const char *bin0[] = {WALK, "CV_SHADE_BIN=0", methods[m].extra, NULL};
        const char *bin1[] = {WALK, "CV_SHADE_BIN=1", methods[m].extra, NULL};
        const char *bin1_unguided[] = {WALK, "CV_SHADE_BIN=1", "CV_RL_UNGUIDED",
                                       methods[m].extra, NULL};
        const char *bin2[] = {WALK, "CV_SHADE_BIN=2", methods[m].extra, NULL};
        int n = reads(gpu, methods[m].file, bin0, methods[m].table);
        tap_ok(n == 1, "%s: the diffuse bin reads the guide's %s (%d)", methods[m].method,
               methods[m].table, n);
        n = reads(gpu, methods[m].file, bin1, methods[m].table);
        tap_ok(n == 1, "%s: so does bin 1 (%d)", methods[m].method, n);
        n = reads(gpu, methods[m].file, bin1_unguided, methods[m].table);
        tap_ok(n == 0, "%s: bin 1 with CV_RL_UNGUIDED does not (%d)", methods[m].method, n);
        n = reads(gpu, methods[m].file, bin2, methods[m].table);
        tap_ok(n == 0, "%s: the coated walk's bin does not (%d)", methods[m].method, n);
    }
    cv_gpu_destroy(&gpu);
    return tap_done();
}
