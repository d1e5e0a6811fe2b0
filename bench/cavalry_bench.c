/* cavalry_bench.c: the benchmark driver. It links libcavalry and calls the
 * stages directly, so every number comes from the code under test and not
 * from a CLI that could change its output:
 *   --bench SCENE   one flat JSON object per repeat on stdout: scene load
 *                   (wall clock), BVH build phases and rendering (GL timer
 *                   queries), peak GPU memory, GPU name and driver;
 *   --summarize F.. medians and spreads of those records as one JSON
 *                   document, and a table on stderr;
 *   --converge      relMSE against a reference EXR at doubling spp, as CSV;
 *   --relmse A B    relMSE of EXR image A against reference B.
 * Measurements that this build cannot make are listed under "unavailable.*"
 * with the reason, never invented. */
#define _XOPEN_SOURCE 700   /* nftw */
#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "base/file.h"
#include "base/limits.h"
#include "base/log.h"
#include "base/mem.h"
#include "bench/bench.h"
#include "glsl/shared/guide_choice.h"
#include "gpu/context.h"
#include "gpu/program.h"
#include "output/exr_read.h"
#include "scene/scene.h"

/* The loader's implementation arrives with src/scene/parse.h; scene.h alone
 * (the interface) is on main before it, and linking would fail. */
#if defined(__has_include)
#if __has_include("scene/parse.h")
#define BENCH_HAVE_LOADER 1
#endif
#endif

static void usage(FILE *f)
{
    fputs("usage: cavalry_bench --bench SCENE.pbrt [--spp N] [--repeat K] [--width W]\n"
          "                     [--height H] [--integrator path|rlpath] [--json] [--gpu INDEX]\n"
          "                     [--rl-method qlearn|sdtree] [--rl-grid N] [--rl-directions N]\n"
          "                     [--rl-mix M] [--rl-guide all|indirect] [--rl-train N] [--seed S]\n"
          "                     [--rl-fallback true|false] [--paths-per-pixel N] [--pass-spp N]\n"
          "                     [--no-gpu] [-v]\n"
          "       cavalry_bench --summarize RECORDS.jsonl... [--out RESULT.json]\n"
          "       cavalry_bench --converge SCENE.pbrt [--reference REF.exr | --ref-spp N]\n"
          "                     [--spp N] [--width W --height H] [--integrator path|rlpath]\n"
          "                     [--rl-method qlearn|sdtree] [--rl-grid N] [--rl-directions N]\n"
          "                     [--rl-mix M] [--rl-guide all|indirect] [--rl-train N] [--seed S]\n"
          "                     [--rl-fallback true|false] [--csv OUT.csv]\n"
          "       cavalry_bench --relmse IMAGE.exr REFERENCE.exr\n", f);
}

#ifdef BENCH_HAVE_LOADER
static double scan_bytes;

static int add_size(const char *path, const struct stat *st, int type, struct FTW *ftw)
{
    (void)ftw;
    const char *dot = strrchr(path, '.');
    if (type == FTW_F && dot && (!strcmp(dot, ".ply") || !strcmp(dot, ".pbrt")))
        scan_bytes += (double)st->st_size;
    return 0;
}

/* Bytes of .pbrt and .ply files beside the scene: what the loader reads for
 * the generated scenes (an upper bound where a folder holds several). */
static double scene_input_bytes(const char *scene_path)
{
    char *dir = cv_path_dirname(scene_path);
    scan_bytes = 0;
    nftw(dir, add_size, 16, FTW_PHYS);
    free(dir);
    return scan_bytes;
}
#endif

static double relmse(const float *img, const float *ref, size_t n)
{
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        double d = (double)img[i] - ref[i];
        sum += d * d / ((double)ref[i] * ref[i] + CV_RELMSE_EPS);
    }
    return n ? sum / (double)n : 0;
}

static void record_gpu(struct bench_record *r, const struct cv_gpu *gpu)
{
    bench_str(r, "gpu.renderer", gpu->info.renderer);
    bench_str(r, "gpu.vendor", gpu->info.vendor);
    bench_str(r, "gpu.version", gpu->info.version);
    bench_str(r, "gpu.backend", gpu->info.backend);
    bench_str(r, "gpu.device", gpu->info.device);
}

struct opts {
    const char *scene, *reference, *csv, *out, *integrator, *rl_method;
    unsigned spp, repeat, width, height, ref_spp, rl_grid, rl_directions, seed;
    unsigned paths_per_pixel, pass_spp;
    float rl_mix;
    bool rl_guide_indirect;
    bool rl_no_fallback;    /* --rl-fallback false */
    unsigned rl_train;      /* render.h's rl_train: 0 the default, CV_RL_TRAIN_ALWAYS */
    int gpu_index;
    bool no_gpu;
    struct cv_knobs knobs;  /* CAVALRY_BVH_*, CAVALRY_STAGE_TIMES, as cavalry-batch reads them */
};

/* What --bench and --converge render: the same options for both. */
static struct bench_run_params run_params(const struct opts *o)
{
    return (struct bench_run_params){.spp = o->spp, .width = o->width, .height = o->height,
                                     .integrator = o->integrator, .rl_grid = o->rl_grid,
                                     .rl_directions = o->rl_directions, .rl_mix = o->rl_mix,
                                     .rl_guide_indirect = o->rl_guide_indirect,
                                     .rl_method = o->rl_method,
                                     .rl_train = o->rl_train,
                                     .rl_no_fallback = o->rl_no_fallback, .seed = o->seed,
                                     .paths_per_pixel = o->paths_per_pixel,
                                     .pass_spp = o->pass_spp, .knobs = o->knobs};
}

#ifdef BENCH_HAVE_LOADER
static bool load_scene(const char *path, struct bench_record *r, struct cv_scene **scene,
                       struct cv_error *err)
{
    double t0 = bench_now_ms();
    struct cv_scene_load_params lp = {.strict = false};
    if (!cv_scene_load(path, &lp, scene, err))
        return false;
    double ms = bench_now_ms() - t0;
    double bytes = scene_input_bytes(path);
    bench_num(r, "load.wall_ms", ms);
    bench_num(r, "load.from_start_ms", bench_now_ms());
    bench_num(r, "load.input_mb", bytes / 1e6);
    if (ms > 0)
        bench_num(r, "load.mb_per_s", bytes / 1e6 / (ms * 1e-3));
    struct cv_scene *s = *scene;
    bench_num(r, "scene.triangles", s->n_triangles);
    bench_num(r, "scene.vertices", s->n_vertices);
    bench_num(r, "scene.materials", s->n_materials);
    bench_num(r, "scene.lights", s->n_lights);
    bench_num(r, "scene.warnings", s->warnings);
    if (ms > 0)
        bench_num(r, "load.triangles_per_s", s->n_triangles / (ms * 1e-3));
    return true;
}
#endif

/* One repeat: everything from a clean start except the GPU context, which a
 * --repeat K run shares (run.sh starts one process per repeat instead). */
static bool bench_once(const struct opts *o, unsigned rep, struct cv_gpu **gpu,
                       struct cv_error *err)
{
    struct bench_record r = {0};
    bench_str(&r, "scene", o->scene);
    bench_num(&r, "repeat", rep);
    bool ok = true;
    if (!*gpu && !o->no_gpu) {
        double t0 = bench_now_ms();
        struct cv_gpu_params gp = {.gpu_index = o->gpu_index, .backend = CV_BACKEND_AUTO};
        if (!cv_gpu_create(&gp, gpu, err)) {
            bench_record_free(&r);
            return false;
        }
        bench_num(&r, "gpu.create_ms", bench_now_ms() - t0);
        cv_program_set_serial(*gpu, o->knobs.serial_compile);
    }
    if (*gpu) {
        record_gpu(&r, *gpu);
        bench_gpu_memory_sample(*gpu);
        if (!(*gpu)->info.has_nvx_memory_info)
            bench_unavailable(&r, "gpu_memory", "the driver lacks GL_NVX_gpu_memory_info");
    } else {
        bench_unavailable(&r, "gpu", "--no-gpu");
    }
#ifdef BENCH_HAVE_LOADER
    struct cv_scene *scene = NULL;
    ok = load_scene(o->scene, &r, &scene, err);
    if (ok && *gpu) {
        struct bench_run_params p = run_params(o);
        ok = bench_gpu_stages(*gpu, scene, &p, &r, err);
    }
    cv_scene_destroy(&scene);
#else
    bench_unavailable(&r, "load", "the scene loader (src/scene) is not in this build");
    bench_unavailable(&r, "bvh", "needs the scene loader");
    bench_unavailable(&r, "render", "needs the scene loader");
#endif
    double used, total;
    if (*gpu && bench_gpu_memory_peak(&used, &total)) {
        bench_num(&r, "gpu.peak_used_mib", used);
        bench_num(&r, "gpu.total_mib", total);
    }
    if (ok)
        bench_record_print(&r, stdout);
    bench_record_free(&r);
    return ok;
}

/* An option of two values, no and yes: whether v is yes, or -1 (said on
 * stderr) for anything else. */
static int parse_two(const char *opt, const char *v, const char *no, const char *yes)
{
    if (!strcmp(v, no) || !strcmp(v, yes))
        return !strcmp(v, yes);
    fprintf(stderr, "cavalry_bench: %s takes %s or %s, not %s\n", opt, no, yes, v);
    return -1;
}

static bool parse_uint(const char *s, unsigned *v)
{
    char *end;
    unsigned long x = strtoul(s, &end, 10);
    if (end == s || *end || x > 1u << 20)
        return false;
    *v = (unsigned)x;
    return true;
}

int main(int argc, char **argv)
{
    bench_now_ms();
    struct opts o = {.spp = 16, .repeat = 1, .ref_spp = 4096, .gpu_index = -1, .csv = NULL,
                     .rl_mix = -1, .knobs = cv_knobs_from_environment()};
    enum { M_NONE, M_BENCH, M_SUMMARIZE, M_CONVERGE, M_RELMSE } mode = M_NONE;
    char **files = cv_xcalloc((size_t)argc, sizeof(char *));
    int n_files = 0;
    int quit = -1;   /* an exit code that ends the parsing: --help, a refused option */
    for (int i = 1; i < argc && quit < 0; i++) {
        const char *a = argv[i];
        bool has = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            quit = 0;
        } else if (!strcmp(a, "--bench") && has) {
            mode = M_BENCH, o.scene = argv[++i];
        } else if (!strcmp(a, "--converge") && has) {
            mode = M_CONVERGE, o.scene = argv[++i];
        } else if (!strcmp(a, "-v") || !strcmp(a, "--verbose")) {
            cv_log_set_level(CV_LOG_DEBUG);
        } else if (!strcmp(a, "--summarize")) {
            mode = M_SUMMARIZE;
        } else if (!strcmp(a, "--relmse")) {
            mode = M_RELMSE;
        } else if (!strcmp(a, "--reference") && has) {
            o.reference = argv[++i];
        } else if (!strcmp(a, "--integrator") && has) {
            o.integrator = argv[++i];
        } else if (!strcmp(a, "--rl-method") && has) {
            o.rl_method = argv[++i];
        } else if (!strcmp(a, "--rl-grid") && has) {
            o.rl_grid = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--rl-directions") && has) {
            o.rl_directions = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--seed") && has) {
            o.seed = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--paths-per-pixel") && has) {
            o.paths_per_pixel = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--pass-spp") && has) {
            o.pass_spp = (unsigned)strtoul(argv[++i], NULL, 10);
        } else if (!strcmp(a, "--rl-train") && has) {
            /* as the manifest's rlpath.train: 0 learns in every pass */
            unsigned long t = strtoul(argv[++i], NULL, 10);
            o.rl_train = t == 0 ? CV_RL_TRAIN_ALWAYS : (unsigned)t;
        } else if (!strcmp(a, "--rl-mix") && has) {
            o.rl_mix = strtof(argv[++i], NULL);
        } else if (!strcmp(a, "--rl-guide") && has) {
            int v = parse_two(a, argv[++i], "all", "indirect");
            if (v < 0)
                quit = 2;
            o.rl_guide_indirect = v;
        } else if (!strcmp(a, "--rl-fallback") && has) {
            /* as the manifest's rlpath.fallback */
            int v = parse_two(a, argv[++i], "true", "false");
            if (v < 0)
                quit = 2;
            o.rl_no_fallback = v;
        } else if (!strcmp(a, "--csv") && has) {
            o.csv = argv[++i];
        } else if (!strcmp(a, "--out") && has) {
            o.out = argv[++i];
        } else if (!strcmp(a, "--json")) {
            /* records are always JSON; accepted for the documented interface */
        } else if (!strcmp(a, "--no-gpu")) {
            o.no_gpu = true;
        } else if ((!strcmp(a, "--spp") || !strcmp(a, "--repeat") || !strcmp(a, "--width") ||
                    !strcmp(a, "--height") || !strcmp(a, "--gpu") || !strcmp(a, "--ref-spp")) && has) {
            unsigned v;
            if (!parse_uint(argv[++i], &v)) {
                fprintf(stderr, "cavalry_bench: %s: bad number \"%s\"\n", a, argv[i]);
                quit = 2;
                continue;
            }
            if (!strcmp(a, "--spp")) o.spp = v;
            else if (!strcmp(a, "--repeat")) o.repeat = v;
            else if (!strcmp(a, "--width")) o.width = v;
            else if (!strcmp(a, "--height")) o.height = v;
            else if (!strcmp(a, "--ref-spp")) o.ref_spp = v;
            else o.gpu_index = (int)v;
        } else if (a[0] != '-') {
            files[n_files++] = argv[i];
        } else {
            fprintf(stderr, "cavalry_bench: unknown or incomplete option %s\n", a);
            usage(stderr);
            quit = 2;
        }
    }
    if (quit >= 0) {
        free(files);
        return quit;
    }
    struct cv_error err = {{0}};
    int rc = 0;
    struct cv_gpu *gpu = NULL;
    switch (mode) {
    case M_NONE:
        usage(stderr);
        rc = 2;
        break;
    case M_BENCH:
        if (o.repeat < 1 || o.spp < 1) {
            fprintf(stderr, "cavalry_bench: --repeat and --spp must be at least 1\n");
            rc = 2;
            break;
        }
        for (unsigned k = 0; k < o.repeat && rc == 0; k++) {
            if (k)
                bench_reset_epoch();
            if (!bench_once(&o, k, &gpu, &err)) {
                fprintf(stderr, "cavalry_bench: %s: %s\n", o.scene, err.msg);
                rc = 1;
            }
        }
        break;
    case M_SUMMARIZE: {
        FILE *out = stdout;
        if (o.out && !(out = fopen(o.out, "w"))) {
            fprintf(stderr, "cavalry_bench: cannot write %s\n", o.out);
            rc = 1;
            break;
        }
        if (!bench_summarize(files, n_files, out, stderr, &err)) {
            fprintf(stderr, "cavalry_bench: %s\n", err.msg);
            rc = 1;
        }
        if (out != stdout && fclose(out) != 0)
            rc = 1;
        break;
    }
    case M_RELMSE: {
        float *a = NULL, *b = NULL;
        uint32_t aw, ah, bw, bh;
        if (n_files != 2) {
            usage(stderr);
            rc = 2;
        } else if (!cv_exr_read_rgb_any(files[0], &a, &aw, &ah, &err) ||
                   !cv_exr_read_rgb_any(files[1], &b, &bw, &bh, &err)) {
            fprintf(stderr, "cavalry_bench: %s\n", err.msg);
            rc = 1;
        } else if (aw != bw || ah != bh) {
            fprintf(stderr, "cavalry_bench: sizes differ: %ux%u vs %ux%u\n", aw, ah, bw, bh);
            rc = 1;
        } else {
            /* relMSE, then the mean-brightness ratio of each channel: the two
             * figures quoted when comparing with a reference renderer. */
            double sa[3] = {0}, sb[3] = {0};
            for (size_t i = 0; i < (size_t)aw * ah; i++)
                for (int c = 0; c < 3; c++) {
                    sa[c] += a[i * 3 + c];
                    sb[c] += b[i * 3 + c];
                }
            printf("%.6g mean-ratio %.4f %.4f %.4f\n", relmse(a, b, (size_t)aw * ah * 3),
                   sb[0] > 0 ? sa[0] / sb[0] : 0, sb[1] > 0 ? sa[1] / sb[1] : 0,
                   sb[2] > 0 ? sa[2] / sb[2] : 0);
        }
        free(a);
        free(b);
        break;
    }
    case M_CONVERGE: {
        float *ref = NULL;
        uint32_t rw = 0, rh = 0;
        FILE *csv = stdout;
        if (o.reference && !cv_exr_read_rgb_any(o.reference, &ref, &rw, &rh, &err)) {
            fprintf(stderr, "cavalry_bench: %s\n", err.msg);
            rc = 1;
            break;
        }
#ifdef BENCH_HAVE_LOADER
        struct cv_scene *scene = NULL;
        struct cv_gpu_params gp = {.gpu_index = o.gpu_index, .backend = CV_BACKEND_AUTO};
        struct bench_run_params rp = run_params(&o);
        if (o.csv && !(csv = fopen(o.csv, "w"))) {
            fprintf(stderr, "cavalry_bench: cannot write %s\n", o.csv);
            rc = 1;
        } else if (!cv_scene_load(o.scene, &(struct cv_scene_load_params){0}, &scene, &err) ||
                   !cv_gpu_create(&gp, &gpu, &err) ||
                   !bench_converge(gpu, scene, &rp, ref, rw, rh, o.ref_spp, csv, &err)) {
            fprintf(stderr, "cavalry_bench: %s: %s\n", o.scene, err.msg);
            rc = 1;
        }
        if (csv && csv != stdout)
            fclose(csv);
        cv_scene_destroy(&scene);
#else
        (void)csv;
        fprintf(stderr, "cavalry_bench: convergence needs the scene loader, which is not in "
                "this build\n");
        rc = 1;
#endif
        free(ref);
        break;
    }
    }
    cv_gpu_destroy(&gpu);
    free(files);
    return rc;
}
