/* guide_choice.c: see guide_choice.h. */
#include <stdlib.h>

#include <epoxy/gl.h>

#include "base/log.h"
#include "base/mem.h"
#include "glsl/shared/guide_choice.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"
#include "gpu/timer.h"
#include "trace/guide_choice.h"

static const char FILE_[] = "trace/guide_choice.comp";
static const char *const REDUCE[] = {"CV_CHOICE_REDUCE", NULL};

/* The blocks of the median of means: each strategy's error is the median
 * of the mean errors of this many blocks of groups of pixels, block b
 * holding every group g with g % BLOCKS == b, so each spans the image. A
 * render's error over many samples takes in its rare bright samples
 * (fireflies) at their rate; a few sub-passes catch them by chance, and
 * one that did would decide the choice alone in a plain mean. A firefly
 * lifts one block; the median moves only where they are in half the
 * blocks, and otherwise stays near the mean (Nemirovsky and Yudin's median
 * of means). Dropping the largest 1 % of the groups instead was measured
 * to drop more of guiding's error than of path's on a scene with no
 * fireflies (bench/RESULTS.md, "The guide's choice after training").
 * A block holds at least BLOCK_GROUPS groups, fewer blocks on a smaller
 * film, down to one (the plain mean): the median of blocks of a few
 * groups is the median of the image's regions, not their mean, and on a
 * small film the regions' errors differ by orders of magnitude (near a
 * lamp, in a shadow). */
#define BLOCKS 16
#define BLOCK_GROUPS 64

/* The sub-passes in order: two guided, then two unguided. */
enum { STEP_GUIDED_A, STEP_GUIDED_B, STEP_UNGUIDED_A, STEP_UNGUIDED_B, STEPS };

enum { GUIDED, UNGUIDED };
static const char *const row_names[2] = {"guided", "unguided"};

struct cv_guide_choice {
    struct cv_gpu *gpu;
    uint32_t n_pixels, groups;
    GLuint pixels, sums;
    struct cv_gpu_timer *timer;   /* rows: the strategies' second sub-passes */
    int step;
    uint32_t spp_a;               /* the strategy's first sub-pass's samples */
    uint32_t spp_b[2];            /* ... and its second's, timed */
    float *group[2];              /* each strategy's groups' sums */
    double raw[2];                /* relative squared error a sample: the mean */
    double err[2];                /* ... the median of means (BLOCKS) */
    double ms[2];                 /* GPU milliseconds a sample */
    bool unguided;
};

bool cv_guide_choice_create(struct cv_gpu *gpu, uint32_t n_pixels,
                            struct cv_guide_choice **out, struct cv_error *err)
{
    struct cv_guide_choice *c = cv_xcalloc(1, sizeof(*c));
    c->gpu = gpu;
    c->n_pixels = n_pixels;
    c->groups = (n_pixels + CV_CHOICE_GROUP - 1) / CV_CHOICE_GROUP;
    c->timer = cv_gpu_timer_create(gpu, &(struct cv_gpu_timer_params){.names = row_names,
                                                                      .n_names = 2});
    c->group[0] = cv_xmalloc((size_t)c->groups * sizeof(float));
    c->group[1] = cv_xmalloc((size_t)c->groups * sizeof(float));
    /* both written by the sub-passes' dispatches before any read */
    if (!(c->pixels = cv_buffer_create_uninit((size_t)n_pixels * 3 * 16, "guide choice pixels",
                                              err)) ||
        !(c->sums = cv_buffer_create_uninit((size_t)c->groups * 4, "guide choice sums", err))) {
        cv_guide_choice_destroy(&c);
        return false;
    }
    *out = c;
    return true;
}

void cv_guide_choice_request(struct cv_gpu *gpu)
{
    cv_program_request(gpu, FILE_, NULL);
    cv_program_request(gpu, FILE_, REDUCE);
}

bool cv_guide_choice_pending(const struct cv_guide_choice *c) { return c->step < STEPS; }

bool cv_guide_choice_next_unguided(const struct cv_guide_choice *c)
{
    return c->step >= STEP_UNGUIDED_A;
}

bool cv_guide_choice_unguided(const struct cv_guide_choice *c) { return c->unguided; }

static void bind(const struct cv_guide_choice *c)
{
    cv_buffer_bind(c->pixels, CV_BIND_CHOICE_PIXELS);
    cv_buffer_bind(c->sums, CV_BIND_CHOICE_SUMS);
}

/* The film's pixel sums into third h of c->pixels. */
static bool snapshot(struct cv_guide_choice *c, uint32_t h, struct cv_error *err)
{
    struct cv_program *p = cv_program_get(c->gpu, FILE_, NULL, err);
    if (!p)
        return false;
    bind(c);
    cv_program_set_uint(p, "u_third", h);
    cv_program_dispatch_1d(p, c->n_pixels);
    return true;
}

/* The strategy's relative squared error a sample from its two sub-passes
 * (reads back from the GPU: twice a render). */
static bool reduce(struct cv_guide_choice *c, int strategy, uint32_t spp_b, uint32_t spp_total,
                   struct cv_error *err)
{
    struct cv_program *p = cv_program_get(c->gpu, FILE_, REDUCE, err);
    if (!p)
        return false;
    bind(c);
    cv_program_set_uint(p, "u_spp_a", c->spp_a);
    cv_program_set_uint(p, "u_spp_b", spp_b);
    cv_program_set_uint(p, "u_spp_total", spp_total);
    cv_program_set_uint(p, "u_before", strategy == GUIDED ? 0 : 2);
    cv_program_dispatch_1d(p, c->n_pixels);
    float *s = c->group[strategy];
    bool ok = cv_buffer_read(c->sums, 0, (size_t)c->groups * sizeof(*s), s, err);
    double sum = 0;
    for (uint32_t g = 0; ok && g < c->groups; g++)
        sum += s[g];
    c->raw[strategy] = sum / (3.0 * c->n_pixels);
    return ok && cv_gl_check(err, "measuring the %s sub-passes", row_names[strategy]);
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A strategy's error: the median of its blocks' mean errors. */
static double median_of_means(const struct cv_guide_choice *c, const float *group)
{
    uint32_t nb = c->groups / BLOCK_GROUPS;
    nb = nb < 1 ? 1 : nb > BLOCKS ? BLOCKS : nb;
    double sum[BLOCKS] = {0}, pixels[BLOCKS] = {0}, mean[BLOCKS];
    for (uint32_t g = 0; g < c->groups; g++) {
        uint32_t first = g * CV_CHOICE_GROUP, n = c->n_pixels - first;
        sum[g % nb] += group[g];
        pixels[g % nb] += n < CV_CHOICE_GROUP ? n : CV_CHOICE_GROUP;
    }
    for (uint32_t b = 0; b < nb; b++)
        mean[b] = sum[b] / (3.0 * pixels[b]);
    qsort(mean, nb, sizeof(*mean), by_value);
    return nb % 2 ? mean[nb / 2] : 0.5 * (mean[nb / 2 - 1] + mean[nb / 2]);
}

bool cv_guide_choice_begin(struct cv_guide_choice *c, struct cv_error *err)
{
    /* third 0: the film after training, the guided sub-passes' start and
     * both strategies' weights; third 2: the unguided ones' start */
    if (c->step == STEP_GUIDED_A || c->step == STEP_UNGUIDED_A)
        return snapshot(c, c->step == STEP_GUIDED_A ? 0 : 2, err);
    cv_gpu_timer_begin(c->timer, c->step == STEP_GUIDED_B ? GUIDED : UNGUIDED, 0);
    return true;
}

bool cv_guide_choice_decide(double err_guided, double ms_guided, double err_unguided,
                            double ms_unguided)
{
    /* equal error takes time in proportion to error a sample times time
     * a sample; a strategy measured as no error (a black film) ties */
    return err_unguided * ms_unguided < err_guided * ms_guided;
}

bool cv_guide_choice_end(struct cv_guide_choice *c, uint32_t spp, uint32_t spp_total,
                         struct cv_error *err)
{
    int step = c->step++;
    if (step == STEP_GUIDED_A || step == STEP_UNGUIDED_A) {
        c->spp_a = spp;
        return snapshot(c, 1, err);
    }
    int strategy = step == STEP_GUIDED_B ? GUIDED : UNGUIDED;
    cv_gpu_timer_end(c->timer);
    c->spp_b[strategy] = spp;
    if (!reduce(c, strategy, spp, spp_total, err))
        return false;
    if (c->step < STEPS)
        return true;
    cv_gpu_timer_collect(c->timer);
    double *ms = c->ms;
    for (int k = 0; k < 2; k++)
        ms[k] = cv_gpu_timer_ms(c->timer, (unsigned)k) / c->spp_b[k];
    for (int k = 0; k < 2; k++)
        c->err[k] = median_of_means(c, c->group[k]);
    c->unguided = cv_guide_choice_decide(c->err[GUIDED], ms[GUIDED], c->err[UNGUIDED],
                                         ms[UNGUIDED]);
    cv_info("after training: %s (relative squared error a sample, median of means and mean, "
            "and GPU time a sample: guided %.4g, %.4g, %.3f ms; path's %.4g, %.4g, %.3f ms)",
            c->unguided ? "path's programs render on" : "guided", c->err[GUIDED],
            c->raw[GUIDED], ms[GUIDED], c->err[UNGUIDED], c->raw[UNGUIDED], ms[UNGUIDED]);
    return true;
}

void cv_guide_choice_measures(const struct cv_guide_choice *c, double g[3], double u[3])
{
    g[0] = c->err[GUIDED];
    g[1] = c->ms[GUIDED];
    g[2] = c->raw[GUIDED];
    u[0] = c->err[UNGUIDED];
    u[1] = c->ms[UNGUIDED];
    u[2] = c->raw[UNGUIDED];
}

void cv_guide_choice_destroy(struct cv_guide_choice **cp)
{
    if (!cp || !*cp)
        return;
    struct cv_guide_choice *c = *cp;
    cv_buffer_destroy(&c->pixels);
    cv_buffer_destroy(&c->sums);
    cv_gpu_timer_destroy(&c->timer);
    free(c->group[0]);
    free(c->group[1]);
    free(c);
    *cp = NULL;
}
