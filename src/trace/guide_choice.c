/* guide_choice.c: see guide_choice.h. */
#include <math.h>
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

/* The blocks of the test that makes the choice: block b holds every group
 * g with g % BLOCKS == b, so that each spans the image, and both
 * strategies' blocks hold the same pixels. Each block gives the difference
 * of the two costs (error a sample times time a sample) over its pixels;
 * their mean is the difference of the plain means, their spread its
 * standard error. A render's error over many samples takes in its rare
 * bright samples (fireflies) at their rate, and a few sub-passes catch
 * them by chance: where they decide, the difference is within a few
 * standard errors of nothing, and path's programs, the cheaper a sample,
 * go on. Guiding goes on where it is the cheaper by more than Z standard
 * errors. The median of means, and the plain means alone, were measured
 * to choose wrongly on a scene each (bench/RESULTS.md, "The guide's
 * choice by a paired test"). A film of fewer groups has a block a group;
 * with one block there is no test, and path's programs go on. */
#define BLOCKS 16
#define Z 2.0

/* The most groups of pixels measured: a million pixels, so the films up to
 * 1024 x 1024 the choice was measured on are measured whole. The measure
 * holds three vec4 a pixel until it decides; a larger film is measured on
 * every stride-th group (each block still spans the image), so that its
 * memory stops growing with the film: 48 MiB at most, where a film of
 * 2^24 pixels took 768 MiB. */
#define MAX_GROUPS 16384

/* The sub-passes in order: two guided, then two unguided. */
enum { STEP_GUIDED_A, STEP_GUIDED_B, STEP_UNGUIDED_A, STEP_UNGUIDED_B, STEPS };

enum { GUIDED, UNGUIDED };
static const char *const row_names[2] = {"guided", "unguided"};

struct cv_guide_choice {
    struct cv_gpu *gpu;
    uint32_t film_pixels;
    uint32_t stride;              /* group q measured is the film's q * stride */
    uint32_t groups, slots;       /* groups measured, and their places */
    uint32_t n_pixels;            /* the film's pixels among them */
    GLuint pixels, sums;
    struct cv_gpu_timer *timer;   /* rows: the strategies' second sub-passes */
    int step;
    uint32_t spp_a;               /* the strategy's first sub-pass's samples */
    uint32_t spp_b[2];            /* ... and its second's, timed */
    float *group[2];              /* each strategy's groups' sums */
    double err[2];                /* relative squared error a sample: the mean */
    double ms[2];                 /* GPU milliseconds a sample */
    double z;                     /* the test's figure (cv_guide_choice_decide) */
    bool unguided;
};

/* The film's pixels in measured group q. */
static uint32_t group_pixels(const struct cv_guide_choice *c, uint32_t q)
{
    uint64_t first = (uint64_t)q * c->stride * CV_CHOICE_GROUP;
    uint64_t n = first < c->film_pixels ? c->film_pixels - first : 0;
    return n < CV_CHOICE_GROUP ? (uint32_t)n : CV_CHOICE_GROUP;
}

bool cv_guide_choice_create(struct cv_gpu *gpu, uint32_t n_pixels, uint32_t max_groups,
                            struct cv_guide_choice **out, struct cv_error *err)
{
    struct cv_guide_choice *c = cv_xcalloc(1, sizeof(*c));
    c->gpu = gpu;
    c->film_pixels = n_pixels;
    uint32_t film_groups = (n_pixels + CV_CHOICE_GROUP - 1) / CV_CHOICE_GROUP;
    uint32_t cap = max_groups ? max_groups : MAX_GROUPS;
    c->stride = film_groups > cap ? (film_groups + cap - 1) / cap : 1;
    c->groups = (film_groups + c->stride - 1) / c->stride;
    c->slots = c->groups * CV_CHOICE_GROUP;
    for (uint32_t q = 0; q < c->groups; q++)
        c->n_pixels += group_pixels(c, q);
    c->timer = cv_gpu_timer_create(gpu, &(struct cv_gpu_timer_params){.names = row_names,
                                                                      .n_names = 2});
    c->group[0] = cv_xmalloc((size_t)c->groups * sizeof(float));
    c->group[1] = cv_xmalloc((size_t)c->groups * sizeof(float));
    /* both written by the sub-passes' dispatches before any read */
    if (!(c->pixels = cv_buffer_create_uninit((size_t)c->slots * 3 * 16, "guide choice pixels",
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

static void bind(const struct cv_guide_choice *c, struct cv_program *p)
{
    cv_buffer_bind(c->pixels, CV_BIND_CHOICE_PIXELS);
    cv_buffer_bind(c->sums, CV_BIND_CHOICE_SUMS);
    cv_program_set_uint(p, "u_stride", c->stride);
    cv_program_set_uint(p, "u_measured", c->slots);
}

/* The film's pixel sums into third h of c->pixels. */
static bool snapshot(struct cv_guide_choice *c, uint32_t h, struct cv_error *err)
{
    struct cv_program *p = cv_program_get(c->gpu, FILE_, NULL, err);
    if (!p)
        return false;
    bind(c, p);
    cv_program_set_uint(p, "u_third", h);
    cv_program_dispatch_1d(p, c->slots);
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
    bind(c, p);
    cv_program_set_uint(p, "u_spp_a", c->spp_a);
    cv_program_set_uint(p, "u_spp_b", spp_b);
    cv_program_set_uint(p, "u_spp_total", spp_total);
    cv_program_set_uint(p, "u_before", strategy == GUIDED ? 0 : 2);
    cv_program_dispatch_1d(p, c->slots);
    float *s = c->group[strategy];
    bool ok = cv_buffer_read(c->sums, 0, (size_t)c->groups * sizeof(*s), s, err);
    double sum = 0;
    for (uint32_t g = 0; ok && g < c->groups; g++)
        sum += s[g];
    c->err[strategy] = sum / (3.0 * c->n_pixels);
    return ok && cv_gl_check(err, "measuring the %s sub-passes", row_names[strategy]);
}

/* Each block's mean relative squared error a sample, of a strategy's
 * groups' sums; returns the blocks' count. */
static uint32_t block_means(const struct cv_guide_choice *c, const float *group,
                            double mean[BLOCKS])
{
    uint32_t nb = c->groups < BLOCKS ? c->groups : BLOCKS;
    double sum[BLOCKS] = {0}, pixels[BLOCKS] = {0};
    for (uint32_t g = 0; g < c->groups; g++) {
        sum[g % nb] += group[g];
        pixels[g % nb] += group_pixels(c, g);
    }
    for (uint32_t b = 0; b < nb; b++)
        mean[b] = sum[b] / (3.0 * pixels[b]);
    return nb;
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

bool cv_guide_choice_decide(const double *g, const double *u, uint32_t nb, double ms_g,
                            double ms_u, double *z)
{
    /* equal error takes time in proportion to error a sample times time
     * a sample: the cost compared, block by block over the same pixels */
    double mean = 0, var = 0;
    for (uint32_t b = 0; b < nb; b++)
        mean += g[b] * ms_g - u[b] * ms_u;
    mean /= nb;
    for (uint32_t b = 0; nb > 1 && b < nb; b++) {
        double d = g[b] * ms_g - u[b] * ms_u - mean;
        var += d * d / ((double)nb * (nb - 1));
    }
    double se = sqrt(var);
    *z = se > 0 ? mean / se : mean < 0 ? -INFINITY : mean > 0 ? INFINITY : 0;
    /* (one block has no spread: no test, path's programs) */
    return !(nb > 1 && mean < -Z * se);
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
    double bg[BLOCKS], bu[BLOCKS];
    uint32_t nb = block_means(c, c->group[GUIDED], bg);
    block_means(c, c->group[UNGUIDED], bu);
    c->unguided = cv_guide_choice_decide(bg, bu, nb, ms[GUIDED], ms[UNGUIDED], &c->z);
    cv_info("after training: %s (relative squared error a sample and GPU time a sample: "
            "guided %.4g, %.3f ms; path's %.4g, %.3f ms; guiding's cost less path's, over "
            "its standard error in %u blocks: %+.2f)",
            c->unguided ? "path's programs render on" : "guided", c->err[GUIDED], ms[GUIDED],
            c->err[UNGUIDED], ms[UNGUIDED], nb, c->z);
    return true;
}

void cv_guide_choice_measures(const struct cv_guide_choice *c, double err[2], double ms[2],
                              double *z)
{
    for (int k = GUIDED; k <= UNGUIDED; k++)
        err[k] = c->err[k], ms[k] = c->ms[k];
    *z = c->z;
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
