/* cli.c: the command line of cavalry-batch (see cavalry-batch(1)). Parses
 * options, fills the batch options and maps the batch's outcome to the
 * documented exit status. */
#include "config.h"

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "batch/batch.h"
#include "batch/signals.h"
#include "batch/workers.h"
#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "cli/knobs.h"
#include "gpu/context.h"
#include "manifest/keys.h"
#include "manifest/shard.h"
#include "manifest/yaml_view.h"
#include "output/exr_merge.h"
#include "scene/dump.h"
#include "scene/scene.h"

static void usage(FILE *out)
{
    fputs("usage: cavalry-batch [OPTION]... MANIFEST.yaml   (- for standard input)\n"
          "       cavalry-batch --list-gpus\n"
          "       cavalry-batch --dump-scene SCENE.pbrt\n"
          "       cavalry-batch --merge OUT.exr TILE.exr...\n"
          "Render the jobs of a batch manifest on a headless GPU.\n"
          "\n"
          "  -h, --help              show this help and exit\n"
          "  -V, --version           show the version and exit\n"
          "      --check             validate the manifest and its scenes, render nothing\n"
          "      --dry-run           print what would be rendered\n"
          "      --json              with --dry-run: the resolved jobs as JSON\n"
          "      --only=PATTERN      render only jobs whose name matches PATTERN (a\n"
          "                          glob: *, ?, [...]); may be repeated\n"
          "      --spp=N             samples per pixel of every job\n"
          "      --resolution=WxH    film size of every job\n"
          "      --output-dir=DIR    write outputs under DIR, not the manifest's folder\n"
          "      --resume            skip jobs whose outputs exist and match their settings\n"
          "      --force             render every selected job, even when up to date\n"
          "      --fail-fast         stop at the first failed job\n"
          "      --shard-index=I     render shard I (0-based) of --shard-count\n"
          "      --shard-count=N     split the jobs into N shards (see ENVIRONMENT)\n"
          "      --time-limit=TIME   stop each job after TIME (90, 1.5m, 2h)\n"
          "      --progress=MODE     auto, bar, json, openjd or none\n"
          "      --strict            treat warnings about scenes and jobs as errors (a\n"
          "                          scene's integrator rendered with another, too)\n"
          "      --scene-root=DIR    refuse scene files outside DIR (untrusted scenes)\n"
          "      --dump-scene=FILE   print a summary of a pbrt scene and exit\n"
          "      --merge=OUT.exr     merge the crop tiles given as arguments into OUT.exr\n"
          "      --list-gpus         list the GPUs and which one would be used\n"
          "      --list-keys         list the manifest keys: name, type, default, meaning\n"
          "      --gpu=N             use EGL device N (see --list-gpus)\n"
          "      --gpu=all, --gpu=N,M...\n"
          "                          spread the jobs over every GPU, or those listed,\n"
          "                          one worker process each\n"
          "      --workers=N         N worker processes over the GPUs given (default\n"
          "                          one per GPU)\n"
          "      --backend=NAME      auto, egl or osmesa\n"
          "  -q, --quiet             only errors\n"
          "  -v, --verbose           debugging detail, OpenGL debug messages included\n"
          "\n"
          "Environment (man cavalry-batch for more):\n"
          "  OCIO                    OpenColorIO config for jobs that name none\n"
          "  SLURM_ARRAY_TASK_ID, _MIN, _MAX, _STEP, _COUNT, JOB_COMPLETION_INDEX\n"
          "                          shard in a Slurm array or Kubernetes indexed Job\n"
          "  CAVALRY_CACHE_DIR       disk cache of linked GPU programs\n"
          "  CAVALRY_DATA_DIR        read shaders and configs from a source tree\n"
          "  CAVALRY_BVH_ROUNDS      treelet restructuring rounds, 0 to 32 (default 3)\n"
          "  CAVALRY_BVH_SPLIT       triangle splitting budget, 0 to 4 (default 0.3)\n"
          "  CAVALRY_STAGE_TIMES     time every render stage (diagnostic; slower)\n"
          "  CAVALRY_PARALLEL_COMPILE  0: compile GPU programs one at a time (diagnostic)\n"
          "  CAVALRY_MISSES          auto, intersect or stage: where misses restart (diagnostic)\n"
          "\n"
          "Exit status: 0 all done, 1 some jobs failed, 2 usage error, 3 invalid manifest\n"
          "or scene, 4 no usable GPU, 70 out of memory, 128+N stopped by signal N (130\n"
          "SIGINT, 143 SIGTERM, 129 SIGHUP; partial images written).\n",
          out);
}

/* The batch's outcomes and their exit statuses (cavalry-batch(1)), both
 * ways: a multi-GPU batch reads its workers' exit statuses. */
static const struct {
    enum cv_batch_status status;
    int code;
} exit_codes[] = {
    {CV_BATCH_OK, CV_EXIT_OK},
    {CV_BATCH_JOBS_FAILED, CV_EXIT_JOBS_FAILED},
    {CV_BATCH_INVALID, CV_EXIT_INVALID},
    {CV_BATCH_NO_GPU, CV_EXIT_NO_GPU},
};

static int exit_code(enum cv_batch_status status)
{
    if (status == CV_BATCH_INTERRUPTED)
        return CV_EXIT_SIGNAL_BASE + cv_signals_which();
    for (size_t i = 0; i < CV_ARRAY_SIZE(exit_codes); i++)
        if (exit_codes[i].status == status)
            return exit_codes[i].code;
    return CV_EXIT_JOBS_FAILED;
}

static bool status_of_exit(int code, enum cv_batch_status *status)
{
    if (code > CV_EXIT_SIGNAL_BASE && code < CV_EXIT_SIGNAL_BASE + 64) {
        *status = CV_BATCH_INTERRUPTED;
        return true;
    }
    for (size_t i = 0; i < CV_ARRAY_SIZE(exit_codes); i++) {
        if (exit_codes[i].code == code) {
            *status = exit_codes[i].status;
            return true;
        }
    }
    return false;
}

/* --gpu: "all", one index or a comma-separated list (an index may repeat:
 * two workers on one device). */
struct gpu_choice {
    bool all;
    int list[CV_MAX_WORKERS];
    size_t n;
};

static bool parse_gpus(const char *s, struct gpu_choice *g)
{
    *g = (struct gpu_choice){0};
    if (strcmp(s, "all") == 0) {
        g->all = true;
        return true;
    }
    const char *p = s;
    do {
        char *end;
        if (*p < '0' || *p > '9' || g->n == CV_MAX_WORKERS)
            return false;
        unsigned long v = strtoul(p, &end, 10);
        if (v > 1000 || (*end && *end != ','))
            return false;
        g->list[g->n++] = (int)v;
        p = *end ? end + 1 : end;
    } while (*p || p[-1] == ',');
    return g->n > 0;
}

/* Runs the batch on the devices of --gpu and --workers: in this process
 * when that is one worker on one device, as without them. */
static int run_batch(const char *manifest, struct cv_batch_options *o, const struct gpu_choice *g,
                     unsigned workers, char **argv, int n_options)
{
    int gpus[CV_MAX_WORKERS];
    size_t n = 0;
    if (g->all)
        n = (size_t)cv_gpu_all_devices(&o->gpu, gpus, CV_MAX_WORKERS);
    for (size_t i = 0; i < g->n; i++)
        gpus[n++] = g->list[i];
    if (n == 0)
        gpus[n++] = o->gpu.gpu_index;  /* the default choice, or the one --gpu named */
    if (!workers)
        workers = (unsigned)n;
    if (workers == 1 || o->check_only || o->dry_run) {
        o->gpu.gpu_index = gpus[0];
        return exit_code(cv_batch_run(manifest, o));
    }
    struct cv_workers_params wp = {
        .gpus = gpus,
        .n_gpus = n,
        .n_workers = workers,
        .argv = argv,
        .n_options = n_options,
        .status_of_exit = status_of_exit,
    };
    return exit_code(cv_workers_run(manifest, o, &wp));
}

/* Every diagnostic, this one too, carries the log's prefix ("error: "). */
static void out_of_memory(size_t size)
{
    cv_error_log("out of memory (asked for %zu bytes)", size);
    exit(CV_EXIT_NO_MEMORY);
}

static bool parse_backend(const char *s, enum cv_gpu_backend *b)
{
    if (strcmp(s, "auto") == 0)
        *b = CV_BACKEND_AUTO;
    else if (strcmp(s, "egl") == 0)
        *b = CV_BACKEND_EGL;
    else if (strcmp(s, "osmesa") == 0)
        *b = CV_BACKEND_OSMESA;
    else
        return false;
    return true;
}

/* The rest of a usage error, as GNU tools say it. */
static int usage_error(void)
{
    fputs("Try 'cavalry-batch --help' for more information.\n", stderr);
    return CV_EXIT_USAGE;
}

static bool parse_uint(const char *s, unsigned max, unsigned *out)
{
    char *end;
    if (!s || !*s || *s == '-')
        return false;
    unsigned long v = strtoul(s, &end, 10);
    if (*end || v > max)
        return false;
    *out = (unsigned)v;
    return true;
}

/* Reads an optional unsigned variable; false when set but not a number. */
static bool env_uint(const char *name, unsigned *out)
{
    const char *s = getenv(name);
    if (!s || !*s)
        return true;
    if (!parse_uint(s, 1u << 30, out)) {
        cv_error_log("%s is not a number: \"%s\"", name, s);
        return false;
    }
    return true;
}

/* Farm schedulers say which task this is: Slurm job arrays (with their
 * offset and step), and Kubernetes indexed Jobs (which give no count:
 * --shard-count must be set). */
static bool shard_from_environment(struct cv_batch_options *o, bool *have_index, bool have_count)
{
    if (*have_index)
        return true;
    const char *id = getenv("SLURM_ARRAY_TASK_ID");
    if (id && *id) {
        unsigned v = 0, min = 0, step = 0, count = 0, max = 0, index, n;
        if (!env_uint("SLURM_ARRAY_TASK_ID", &v) || !env_uint("SLURM_ARRAY_TASK_MIN", &min) ||
            !env_uint("SLURM_ARRAY_TASK_MAX", &max) || !env_uint("SLURM_ARRAY_TASK_STEP", &step) ||
            !env_uint("SLURM_ARRAY_TASK_COUNT", &count))
            return false;
        if (!getenv("SLURM_ARRAY_TASK_MAX")) {
            if (!count) {
                cv_error_log("SLURM_ARRAY_TASK_ID is set without "
                             "SLURM_ARRAY_TASK_MAX or SLURM_ARRAY_TASK_COUNT");
                return false;
            }
            max = min + (count - 1) * (step ? step : 1);
        }
        const char *why;
        if (!cv_shard_from_array(v, min, max, step, count, &index, &n, &why)) {
            cv_error_log("Slurm array task %u (min %u, max %u, step %u, "
                         "count %u): %s", v, min, max, step ? step : 1, count, why);
            return false;
        }
        o->shard_index = index;
        *have_index = true;
        if (!have_count)
            o->shard_count = n;
        return true;
    }
    const char *k8s = getenv("JOB_COMPLETION_INDEX");
    if (k8s) {
        unsigned v;
        if (!parse_uint(k8s, 1u << 30, &v)) {
            cv_error_log("JOB_COMPLETION_INDEX is not a number: \"%s\"", k8s);
            return false;
        }
        o->shard_index = v;
        *have_index = true;
    }
    return true;
}

static int dump_scene(const char *path, bool strict, const char *root)
{
    struct cv_scene *scene = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {.strict = strict, .root = root};
    if (!cv_scene_load(path, &lp, &scene, &err)) {
        cv_error_log("%s", err.msg);
        return CV_EXIT_INVALID;
    }
    cv_scene_dump(scene, stdout);
    cv_scene_destroy(&scene);
    return CV_EXIT_OK;
}

int cv_cli_main(int argc, char **argv)
{
    enum {
        OPT_LIST_GPUS = 256, OPT_GPU, OPT_BACKEND, OPT_CHECK, OPT_DRY_RUN, OPT_ONLY, OPT_RESUME,
        OPT_FORCE, OPT_FAIL_FAST, OPT_SHARD_INDEX, OPT_SHARD_COUNT, OPT_TIME_LIMIT, OPT_PROGRESS,
        OPT_STRICT, OPT_DUMP_SCENE, OPT_LIST_KEYS, OPT_SCENE_ROOT, OPT_MERGE, OPT_JSON, OPT_SPP,
        OPT_RESOLUTION, OPT_OUTPUT_DIR, OPT_WORKERS, OPT_WORKER,
    };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {"check", no_argument, NULL, OPT_CHECK},
        {"dry-run", no_argument, NULL, OPT_DRY_RUN},
        {"only", required_argument, NULL, OPT_ONLY},
        {"json", no_argument, NULL, OPT_JSON},
        {"spp", required_argument, NULL, OPT_SPP},
        {"resolution", required_argument, NULL, OPT_RESOLUTION},
        {"output-dir", required_argument, NULL, OPT_OUTPUT_DIR},
        {"resume", no_argument, NULL, OPT_RESUME},
        {"force", no_argument, NULL, OPT_FORCE},
        {"fail-fast", no_argument, NULL, OPT_FAIL_FAST},
        {"shard-index", required_argument, NULL, OPT_SHARD_INDEX},
        {"shard-count", required_argument, NULL, OPT_SHARD_COUNT},
        {"time-limit", required_argument, NULL, OPT_TIME_LIMIT},
        {"progress", required_argument, NULL, OPT_PROGRESS},
        {"strict", no_argument, NULL, OPT_STRICT},
        {"scene-root", required_argument, NULL, OPT_SCENE_ROOT},
        {"dump-scene", required_argument, NULL, OPT_DUMP_SCENE},
        {"merge", required_argument, NULL, OPT_MERGE},
        {"list-gpus", no_argument, NULL, OPT_LIST_GPUS},
        {"list-keys", no_argument, NULL, OPT_LIST_KEYS},
        {"gpu", required_argument, NULL, OPT_GPU},
        {"workers", required_argument, NULL, OPT_WORKERS},
        {"worker", required_argument, NULL, OPT_WORKER},
        {"backend", required_argument, NULL, OPT_BACKEND},
        {"quiet", no_argument, NULL, 'q'},
        {"verbose", no_argument, NULL, 'v'},
        {NULL, 0, NULL, 0},
    };
    struct cv_batch_options o = {.gpu = {.gpu_index = -1, .backend = CV_BACKEND_AUTO}};
    bool list_gpus = false, have_index = false, have_count = false, worker = false;
    struct gpu_choice gpus = {0};
    unsigned workers = 0;
    int worker_gpu = -1;
    const char *dump = NULL, *merge = NULL;
    int verbosity = 0, c;
    unsigned u;
    /* --only patterns point into argv, at most one per argument; static,
     * so that a usage error's early return leaves nothing unreachable. */
    static const char **only;
    only = cv_xcalloc((size_t)argc + 1, sizeof(char *));
    o.only = only;
    cv_mem_set_out_of_memory(out_of_memory);
    opterr = 0;  /* getopt's messages would carry another prefix than the log's */
    while ((c = getopt_long(argc, argv, ":hVqv", longopts, NULL)) != -1) {
        switch (c) {
        case 'h':
            usage(stdout);
            return CV_EXIT_OK;
        case 'V':
            printf("cavalry-batch %s\n", PACKAGE_VERSION);
            return CV_EXIT_OK;
        case OPT_CHECK: o.check_only = true; break;
        case OPT_DRY_RUN: o.dry_run = true; break;
        case OPT_ONLY: only[o.n_only++] = optarg; break;
        case OPT_JSON: o.json = true; break;
        case OPT_OUTPUT_DIR:
            if (!*optarg) {
                cv_error_log("--output-dir wants a folder");
                return usage_error();
            }
            o.overrides.output_dir = optarg;
            break;
        case OPT_SPP:
            if (!parse_uint(optarg, UINT32_MAX, &o.overrides.spp) || !o.overrides.spp) {
                cv_error_log("--spp wants a number of samples >= 1, not \"%s\"", optarg);
                return usage_error();
            }
            break;
        case OPT_RESOLUTION: {
            unsigned w, h;
            int n = 0;
            if (sscanf(optarg, "%ux%u%n", &w, &h, &n) != 2 || optarg[n] || optarg[0] == '-' ||
                !w || !h) {
                cv_error_log("--resolution wants WIDTHxHEIGHT (\"640x480\"), not \"%s\"",
                             optarg);
                return usage_error();
            }
            o.overrides.width = w;
            o.overrides.height = h;
            break;
        }
        case OPT_RESUME: o.resume = true; break;
        case OPT_FORCE: o.force = true; break;
        case OPT_FAIL_FAST: o.fail_fast = true; break;
        case OPT_STRICT: o.strict = true; break;
        case OPT_SCENE_ROOT: o.scene_root = optarg; break;
        case OPT_DUMP_SCENE: dump = optarg; break;
        case OPT_MERGE: merge = optarg; break;
        case OPT_LIST_GPUS: list_gpus = true; break;
        case OPT_LIST_KEYS:
            cv_keys_print(stdout);
            return CV_EXIT_OK;
        case OPT_SHARD_INDEX:
        case OPT_SHARD_COUNT:
            if (!parse_uint(optarg, 1u << 30, &u)) {
                cv_error_log("--%s wants a number, not \"%s\"",
                        c == OPT_SHARD_INDEX ? "shard-index" : "shard-count", optarg);
                return usage_error();
            }
            if (c == OPT_SHARD_INDEX) {
                o.shard_index = u;
                have_index = true;
            } else {
                o.shard_count = u;
                have_count = true;
            }
            break;
        case OPT_TIME_LIMIT:
            if (!cv_duration_parse(optarg, &o.time_limit)) {
                cv_error_log("--time-limit wants %s, not \"%s\"", CV_DURATION_EXPECTED, optarg);
                return usage_error();
            }
            break;
        case OPT_PROGRESS:
            if (!cv_progress_mode_parse(optarg, &o.progress)) {
                cv_error_log("unknown progress mode \"%s\" (%s)", optarg,
                             cv_progress_mode_names);
                return usage_error();
            }
            break;
        case OPT_GPU:
            if (!parse_gpus(optarg, &gpus)) {
                cv_error_log("--gpu wants a device index, a list (0,1) or all, not \"%s\"",
                             optarg);
                return usage_error();
            }
            /* one device: as before, in this process */
            o.gpu.gpu_index = gpus.n == 1 ? gpus.list[0] : -1;
            if (gpus.n == 1)
                gpus.n = 0;
            break;
        case OPT_WORKERS:
            if (!parse_uint(optarg, CV_MAX_WORKERS, &workers) || !workers) {
                cv_error_log("--workers wants a number from 1 to %d, not \"%s\"",
                             CV_MAX_WORKERS, optarg);
                return usage_error();
            }
            break;
        case OPT_WORKER:  /* internal: a worker of a multi-GPU batch (workers.h) */
            worker = true;
            if (strcmp(optarg, "default") == 0)
                worker_gpu = -1;
            else if (parse_uint(optarg, 1000, &u))
                worker_gpu = (int)u;
            else {
                cv_error_log("--worker wants a GPU index or \"default\", not \"%s\"", optarg);
                return usage_error();
            }
            break;
        case OPT_BACKEND:
            if (!parse_backend(optarg, &o.gpu.backend)) {
                cv_error_log("unknown backend \"%s\" (auto, egl, osmesa)",
                        optarg);
                return usage_error();
            }
            break;
        case 'q': verbosity--; break;
        case 'v': verbosity++; break;
        case ':':
            cv_error_log("%s wants a value", argv[optind - 1]);
            return usage_error();
        default:
            if (optopt > 0 && optopt < 128)  /* a short option, maybe in a group */
                cv_error_log("unknown option -%c", optopt);
            else
                cv_error_log("unknown option %s", argv[optind - 1]);
            return usage_error();
        }
    }
    cv_log_set_level(verbosity < 0 ? CV_LOG_ERROR : verbosity == 0 ? CV_LOG_INFO : CV_LOG_DEBUG);
    struct cv_knobs knobs = cv_knobs_from_environment();
    o.bvh = &knobs.bvh;
    o.stage_times = knobs.stage_times;
    o.serial_compile = knobs.serial_compile;
    o.bdpt_slots = knobs.bdpt_slots;
    o.misses = knobs.misses;
    if (list_gpus) {
        struct cv_error err = {{0}};
        if (!cv_gpu_list(&o.gpu, stdout, &err)) {
            cv_error_log("%s", err.msg);
            return CV_EXIT_NO_GPU;
        }
        return CV_EXIT_OK;
    }
    if (dump)
        return dump_scene(dump, o.strict, o.scene_root);
    if (merge) {
        struct cv_error err = {{0}};
        if (!cv_exr_merge(merge, (const char *const *)argv + optind, (size_t)(argc - optind),
                          &err)) {
            cv_error_log("%s", err.msg);
            return CV_EXIT_INVALID;
        }
        return CV_EXIT_OK;
    }
    if (optind != argc - 1) {
        cv_error_log("%s",
                optind >= argc ? "no manifest given" : "one manifest at a time");
        return usage_error();
    }
    if (o.json && !o.dry_run) {
        cv_error_log("--json goes with --dry-run (--progress=json for a render)");
        return usage_error();
    }
    struct cv_error err = {{0}};
    if (!cv_plan_overrides_check(&o.overrides, &err)) {
        cv_error_log("%s", err.msg);
        return usage_error();
    }
    if (!shard_from_environment(&o, &have_index, have_count))
        return usage_error();
    /* a count given as 0, before the checks that read 0 as "none given" */
    if (have_count && !o.shard_count) {
        cv_error_log("--shard-count must be at least 1");
        return usage_error();
    }
    if (have_index && !o.shard_count) {
        cv_error_log("a shard index needs --shard-count");
        return usage_error();
    }
    /* Without an index every worker would render shard 0: the same jobs. */
    /* A submitter may list every shard's jobs at once, each with its shard. */
    if (have_count && !have_index && o.dry_run && o.json) {
        o.all_shards = true;
        have_index = true;
    }
    if (have_count && !have_index) {
        cv_error_log("--shard-count needs --shard-index, "
                     "SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX");
        return usage_error();
    }
    if (o.shard_count && o.shard_index >= o.shard_count) {
        cv_error_log("shard index %u is not below shard count %u",
                o.shard_index, o.shard_count);
        return usage_error();
    }
    if (worker) {
        /* the parent chose the device and shows the progress */
        o.gpu.gpu_index = worker_gpu;
        o.progress = CV_PROGRESS_WIRE;
        o.worker = cv_worker_attach();
        return exit_code(cv_batch_run(argv[optind], &o));
    }
    return run_batch(argv[optind], &o, &gpus, workers, argv, optind - 1);
}
