/* bench.h: what the parts of cavalry_bench share. A measurement is a flat
 * record of named numbers and strings, printed as one JSON object per line;
 * flat keys ("bvh.phase.sort_ms") keep the summariser a small parser. Keys
 * of quantities carry their unit as a suffix (_ms, _mb, _per_s). */
#ifndef CV_BENCH_BENCH_H
#define CV_BENCH_BENCH_H

#include <stdbool.h>
#include <stdio.h>

#include "base/error.h"
#include "cli/knobs.h"
#include "gpu/context.h"
#include "scene/scene.h"

struct bench_field {
    char key[96];
    bool is_num;
    double num;
    char str[320];
};

struct bench_record {
    struct bench_field *f;
    int n, cap;
};

void bench_num(struct bench_record *r, const char *key, double v);
void bench_str(struct bench_record *r, const char *key, const char *v);
/* Appends a measurement that this build cannot make, with the reason. */
void bench_unavailable(struct bench_record *r, const char *what, const char *why);
void bench_record_print(const struct bench_record *r, FILE *out);
/* Writes s as a JSON string, quoted and escaped. */
void bench_json_string(FILE *out, const char *s);
void bench_record_free(struct bench_record *r);
/* Parses one line printed by bench_record_print; false when it is not one. */
bool bench_record_parse(const char *line, struct bench_record *r);
const struct bench_field *bench_get(const struct bench_record *r, const char *key);

/* Milliseconds on the monotonic clock since the process started main(). */
double bench_now_ms(void);
/* Restarts that clock: later in-process repeats measure from their start. */
void bench_reset_epoch(void);

/* Peak of (total - available) video memory seen so far, in MiB, from
 * GL_NVX_gpu_memory_info; false when the driver does not report it. */
void bench_gpu_memory_sample(const struct cv_gpu *gpu);
bool bench_gpu_memory_peak(double *used_mib, double *total_mib);

/* GPU time of the work between begin and end, from a GL_TIME_ELAPSED query
 * (nesting is not allowed by GL, so callers time one stage at a time). */
struct bench_timer {
    unsigned query;
};
void bench_timer_begin(struct bench_timer *t);
/* Waits for the result; returns milliseconds of GPU time, < 0 on failure. */
double bench_timer_end(struct bench_timer *t);

struct bench_run_params {
    unsigned spp;               /* passes of one sample per pixel */
    unsigned width, height;     /* 0: as the scene file says */
    const char *integrator;     /* "path" (NULL) or "rlpath" */
    unsigned rl_grid, rl_directions;   /* rlpath options; 0: defaults */
    float rl_mix;                      /* rlpath guiding weight; negative: default */
    bool rl_guide_indirect;            /* --rl-guide indirect */
    const char *rl_method;             /* --rl-method: rlpath.method's name; NULL: qlearn */
    uint32_t rl_train;                 /* --rl-train (render.h's rl_train) */
    bool rl_no_fallback;               /* --rl-fallback false: rlpath.fallback false */
    unsigned seed;                     /* sampler seed; 0: 1 */
    unsigned paths_per_pixel;          /* trace/render.h; 0: the renderer's choice */
    unsigned pass_spp;                 /* passes of this many spp; 0: as cavalry-batch sizes them */
    struct cv_knobs knobs;             /* cavalry-batch's, from the environment (cli/knobs.h) */
};

/* BVH build and rendering through the bvh and trace stages; each records
 * what it measured or, when the stage is not in this build, why not. */
bool bench_gpu_stages(struct cv_gpu *gpu, struct cv_scene *scene,
                      const struct bench_run_params *p, struct bench_record *r,
                      struct cv_error *err);

/* Convergence: relMSE against reference RGB (ref_w x ref_h) at 1, 2, 4, ...
 * up to p->spp, as CSV rows "spp,seconds,wall_seconds,gpu_seconds,relmse";
 * times are render time only (passes, not read-back); "seconds" is the GPU
 * time, or the wall time on a software renderer. ref_rgb NULL: the reference is
 * rendered first with ref_spp samples at p's size. relMSE is the mean over
 * pixels and channels of (x - ref)^2 / (ref^2 + 0.01). */
bool bench_converge(struct cv_gpu *gpu, struct cv_scene *scene,
                    const struct bench_run_params *p, const float *ref_rgb,
                    unsigned ref_w, unsigned ref_h, unsigned ref_spp, FILE *csv,
                    struct cv_error *err);

/* Reads the per-repeat lines in `files` and prints the summary document
 * (median, min, max, spread per numeric key and scene) and a table. */
bool bench_summarize(char **files, int n_files, FILE *json, FILE *table,
                     struct cv_error *err);

#endif
