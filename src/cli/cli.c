/* cli.c: the command line of cavalry-batch (see cavalry-batch(1)). */
#include "config.h"

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "cli/cli.h"
#include "cli/exit_codes.h"
#include "gpu/context.h"

static void usage(FILE *out)
{
    fputs("usage: cavalry-batch [OPTION]... MANIFEST.yaml\n"
          "Render the jobs of a batch manifest on a headless GPU.\n"
          "\n"
          "  -h, --help            show this help and exit\n"
          "  -V, --version         show the version and exit\n"
          "      --list-gpus       list the GPUs and which one would be used\n"
          "      --gpu=N           use EGL device N (see --list-gpus)\n"
          "      --backend=NAME    auto, egl or osmesa\n"
          "  -q, --quiet           only errors\n"
          "  -v, --verbose         more detail (twice: debug)\n",
          out);
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

int cv_cli_main(int argc, char **argv)
{
    enum { OPT_LIST_GPUS = 256, OPT_GPU, OPT_BACKEND };
    static const struct option longopts[] = {
        {"help", no_argument, NULL, 'h'},
        {"version", no_argument, NULL, 'V'},
        {"list-gpus", no_argument, NULL, OPT_LIST_GPUS},
        {"gpu", required_argument, NULL, OPT_GPU},
        {"backend", required_argument, NULL, OPT_BACKEND},
        {"quiet", no_argument, NULL, 'q'},
        {"verbose", no_argument, NULL, 'v'},
        {NULL, 0, NULL, 0},
    };
    struct cv_gpu_params gpu_params = {.gpu_index = -1, .backend = CV_BACKEND_AUTO};
    bool list_gpus = false;
    int verbosity = 0, c;
    while ((c = getopt_long(argc, argv, "hVqv", longopts, NULL)) != -1) {
        switch (c) {
        case 'h':
            usage(stdout);
            return CV_EXIT_OK;
        case 'V':
            printf("cavalry-batch %s\n", PACKAGE_VERSION);
            return CV_EXIT_OK;
        case OPT_LIST_GPUS:
            list_gpus = true;
            break;
        case OPT_GPU: {
            char *end;
            long v = strtol(optarg, &end, 10);
            if (*end || v < 0 || v > 1000) {
                fprintf(stderr, "cavalry-batch: --gpu wants a device index, not \"%s\"\n", optarg);
                return CV_EXIT_USAGE;
            }
            gpu_params.gpu_index = (int)v;
            break;
        }
        case OPT_BACKEND:
            if (!parse_backend(optarg, &gpu_params.backend)) {
                fprintf(stderr, "cavalry-batch: unknown backend \"%s\" (auto, egl, osmesa)\n",
                        optarg);
                return CV_EXIT_USAGE;
            }
            break;
        case 'q':
            verbosity--;
            break;
        case 'v':
            verbosity++;
            break;
        default:
            usage(stderr);
            return CV_EXIT_USAGE;
        }
    }
    cv_log_set_level(verbosity < 0 ? CV_LOG_ERROR
                     : verbosity == 0 ? CV_LOG_INFO
                                      : CV_LOG_DEBUG);
    if (list_gpus) {
        struct cv_error err = {{0}};
        if (!cv_gpu_list(&gpu_params, stdout, &err)) {
            cv_error_log("%s", err.msg);
            return CV_EXIT_NO_GPU;
        }
        return CV_EXIT_OK;
    }
    if (optind >= argc) {
        usage(stderr);
        return CV_EXIT_USAGE;
    }
    cv_error_log("rendering manifests is not built yet");
    return CV_EXIT_USAGE;
}
