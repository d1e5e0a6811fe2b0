/* bvh_bench.c: benchmark of the GPU BVH build (not a test). Generates N
 * triangles (half uniform with varied sizes, half in dense clusters; fixed
 * seed), builds the BVH several times and prints the median time of each
 * phase, bytes per triangle and the SAH cost, as text and as one JSON line.
 *   bvh_bench N [--reps R] [--rounds R] [--treelet S] [--no-collapse] [--split F] [--check]
 *             [--ref] [--rays R]
 *             [--all] [--gl-debug] [--fresh] [--idle S]
 *   bvh_bench --scene FILE.pbrt [same options]
 * --scene builds the triangles of a pbrt scene instead of generated ones
 * (the shared scenes: the same warm repeats as the generated ones, where
 * cavalry_bench times the one build that follows a scene load).
 * --split F sets the triangle splitting budget (extra references per
 * triangle, 0 = off; default: CAVALRY_BVH_SPLIT or the built-in default).
 * --ref also builds a CPU binned-SAH tree over the same triangles and prints
 * its SAH cost for comparison.
 * --rays R traces R rays (closest hit + any hit, glsl/bvh/rays_test.comp)
 * through the default tree and a plain LBVH and prints rays per second and
 * nodes visited per ray.
 * --check keeps the binary tree, reads both trees of the last build back
 * and verifies their invariants (as the tests do) and prints their depths;
 * the exit status is 1 when they fail.
 * --all prints every rep's phases and the wall time of the build and of
 * its destruction; --gl-debug logs the driver's notifications (buffer
 * placement and the like). --fresh frees the context's pooled scratch
 * before each build, so that every build pays for fresh memory as the
 * first build of a process (or of a scene too large to keep it) does.
 * --idle S waits S seconds before each timed build, long enough for an idle
 * GPU to lower its clocks, as it has when a batch job's scene has just been
 * parsed on the CPU (an idle GPU runs at a fraction of its clock:
 * bench/RESULTS.md, "BVH build: wall time").
 * Run from the build tree with CAVALRY_DATA_DIR unset (embedded shaders). */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "base/log.h"
#include "bvh/bvh.h"
#include "cli/knobs.h"
#include "glsl/shared/bindings.h"
#include "gpu/program.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/context.h"
#include "scene/scene.h"
#include "tests/bvh/bvh_test_util.h"

static double bench_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The split's parts follow the total, so that the indices above stay. */

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: %s N [--reps R] [--rounds R] [--treelet S] [--no-collapse]\n",
                argv[0]);
        return 2;
    }
    const char *scene_path = NULL;
    uint32_t n = 0;
    if (strcmp(argv[1], "--scene") == 0 && argc >= 3)
        scene_path = argv[2];
    else
        n = (uint32_t)strtoul(argv[1], NULL, 10);
    int reps = 3;
    /* as cavalry-batch: the defaults with CAVALRY_BVH_* (cli/knobs.h) */
    struct cv_bvh_params params = cv_knobs_from_environment().bvh;
    bool check = false, ref = false;
    uint32_t n_rays = 0;
    bool all = false, gl_debug = false, fresh = false;
    double idle_s = 0.0;
    for (int i = scene_path ? 3 : 2; i < argc; i++) {
        if (strcmp(argv[i], "--reps") == 0 && i + 1 < argc)
            reps = atoi(argv[++i]);
        else if (strcmp(argv[i], "--rounds") == 0 && i + 1 < argc)
            params.treelet_rounds = atoi(argv[++i]);
        else if (strcmp(argv[i], "--split") == 0 && i + 1 < argc)
            params.split_budget = (float)atof(argv[++i]);
        else if (strcmp(argv[i], "--treelet") == 0 && i + 1 < argc)
            params.treelet_size = atoi(argv[++i]);
        else if (strcmp(argv[i], "--rays") == 0 && i + 1 < argc)
            n_rays = (uint32_t)strtoul(argv[++i], NULL, 10);
        else if (strcmp(argv[i], "--ref") == 0)
            ref = true;
        else if (strcmp(argv[i], "--check") == 0)
            check = params.keep_binary = true;
        else if (strcmp(argv[i], "--no-collapse") == 0)
            params.collapse_leaves = false;
        else if (strcmp(argv[i], "--all") == 0)
            all = true;
        else if (strcmp(argv[i], "--gl-debug") == 0)
            gl_debug = true;
        else if (strcmp(argv[i], "--fresh") == 0)
            fresh = true;
        else if (strcmp(argv[i], "--idle") == 0 && i + 1 < argc)
            idle_s = atof(argv[++i]);
        else {
            fprintf(stderr, "unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    if (reps < 1 || reps > 101)
        reps = 3;
    struct cv_error err = {{0}};
    int status = 0;
    struct cv_gpu *gpu = NULL;
    if (gl_debug)
        cv_log_set_level(CV_LOG_DEBUG);
    if (!cv_gpu_create(&(struct cv_gpu_params){.gpu_index = -1}, &gpu, &err)) {
        fprintf(stderr, "bvh_bench: %s\n", err.msg);
        return 1;
    }
    fprintf(stderr, "GPU: %s | %s\n", gpu->info.renderer, gpu->info.version);
    struct mesh m;
    if (scene_path) {
        struct cv_scene *sc = NULL;
        if (!cv_scene_load(scene_path, &(struct cv_scene_load_params){0}, &sc, &err)) {
            fprintf(stderr, "bvh_bench: %s\n", err.msg);
            return 1;
        }
        /* The scene's arrays become the mesh's. */
        m = (struct mesh){.v = sc->vertices, .t = sc->triangles, .nv = sc->n_vertices,
                          .nt = sc->n_triangles};
        sc->vertices = NULL;
        sc->triangles = NULL;
        cv_scene_destroy(&sc);
        n = m.nt;
        if (n == 0) {
            fprintf(stderr, "bvh_bench: %s has no triangles\n", scene_path);
            return 1;
        }
    } else {
        mesh_soup(&m, n);
    }
    GLuint vb = 0, tb = 0;
    if (!mesh_upload(&m, &vb, &tb, &err)) {
        fprintf(stderr, "bvh_bench: %s\n", err.msg);
        return 1;
    }
    double ref_cost = ref ? ref_sah(&m) : 0.0;
    float *rays = NULL;
    if (n_rays) {
        rays = malloc((size_t)n_rays * 32);
        make_rays(&m, rays, n_rays);
    }
    if (!check)
        mesh_free(&m);

    /* One untimed build compiles the shaders. */
    struct cv_bvh *bvh = NULL;
    if (!cv_bvh_build(gpu, vb, tb, n, &params, &bvh, &err)) {
        fprintf(stderr, "bvh_bench: %s\n", err.msg);
        return 1;
    }
    cv_bvh_destroy(&bvh);
    double *t[CV_BVH_N_PHASES];
    for (int p = 0; p < CV_BVH_N_PHASES; p++)
        t[p] = calloc((size_t)reps, sizeof(double));
    struct cv_bvh_stats last = {0};
    double *walls = calloc((size_t)reps, sizeof(double));
    for (int r = 0; r < reps; r++) {
        if (fresh) {
            cv_buffer_pool_trim(gpu->scratch);
            glFinish();
        }
        if (idle_s > 0) {
            glFinish();
            usleep((useconds_t)(idle_s * 1e6));
        }
        double w0 = bench_ms();
        if (!cv_bvh_build(gpu, vb, tb, n, &params, &bvh, &err)) {
            fprintf(stderr, "bvh_bench: %s\n", err.msg);
            return 1;
        }
        double wall = bench_ms() - w0;
        last = *cv_bvh_stats(bvh);
        if (check && r == reps - 1) {
            struct tree_info ti = check_tree(&m, bvh);
            fprintf(stderr, "check: %s (binary depth %d, wide depth %d, stack need %d, read-back "
                    "SAH %.4f) %s\n", ti.ok ? "tree invariants hold" : "TREE INVALID", ti.depth,
                    ti.wide_depth, ti.stack_need, ti.sah, ti.why);
            if (ti.ok && (ti.stack_need != (int)last.stack_need || ti.wide_depth != (int)last.depth)) {
                fprintf(stderr, "check: the build counted depth %u and stack need %u\n",
                        last.depth, last.stack_need);
                status = 1;
            }
            if (!ti.ok)
                status = 1;
        }
        double v[CV_BVH_N_PHASES];
        for (int p = 0; p < CV_BVH_N_PHASES; p++)
            v[p] = cv_bvh_phase_ms(&last, &cv_bvh_phases[p]);
        for (int p = 0; p < CV_BVH_N_PHASES; p++)
            t[p][r] = v[p];
        walls[r] = wall;
        w0 = bench_ms();
        cv_bvh_destroy(&bvh);
        if (all) {
            glFinish();
            printf("  rep %d:", r);
            for (int p = 0; p < CV_BVH_N_PHASES; p++)
                printf(" %.3f", v[p]);
            printf(" | wall: build %.1f ms, destroy %.1f ms\n", wall, bench_ms() - w0);
        }
    }
    double med[CV_BVH_N_PHASES];
    for (int p = 0; p < CV_BVH_N_PHASES; p++) {
        qsort(t[p], (size_t)reps, sizeof(double), cmp_double);
        med[p] = t[p][reps / 2];
    }
    /* The LBVH proper: bounds through refit. */
    double lbvh = 0, total = 0;
    for (int p = 0; p < CV_BVH_N_PHASES; p++) {
        const char *name = cv_bvh_phases[p].name;
        if (!strcmp(name, "bounds") || !strcmp(name, "morton") || !strcmp(name, "sort") ||
            !strcmp(name, "hierarchy") || !strcmp(name, "refit"))
            lbvh += med[p];
        if (!strcmp(name, "total"))
            total = med[p];
    }
    qsort(walls, (size_t)reps, sizeof(double), cmp_double);
    double wall_med = walls[reps / 2];
    free(walls);
    if (scene_path)
        printf("%s: ", scene_path);
    printf("BVH build of %u triangles on %s (median of %d; rounds %d, treelet %d, collapse %s, "
           "split %g%s%s)\n",
           n, gpu->info.renderer, reps, params.treelet_rounds, params.treelet_size,
           params.collapse_leaves ? "on" : "off", params.split_budget,
           fresh ? ", fresh scratch" : "", idle_s > 0 ? ", idle before each" : "");
    for (int p = 0; p < CV_BVH_N_PHASES; p++)
        printf("  %-11s %10.3f ms\n", cv_bvh_phases[p].name, med[p]);
    printf("  LBVH part   %10.3f ms (bounds..refit)\n", lbvh);
    printf("  wall        %10.3f ms (the cv_bvh_build call, host clock)\n", wall_med);
    printf("  ms per million triangles: %.3f\n", total * 1e6 / (n ? n : 1));
    printf("  references %u (%.3f per triangle)\n", last.n_refs, (double)last.n_refs / (n ? n : 1));
    printf("  nodes %u (4-wide, %u levels, stack need %u; %u binary), %.2f bytes/triangle (+ %.2f "
           "bytes/triangle scratch while building)\n",
           last.n_nodes, last.depth, last.stack_need, last.n_binary_nodes,
           (double)last.bytes / (n ? n : 1),
           (double)last.scratch_bytes / (n ? n : 1));
    printf("  SAH cost %.4f", last.sah_cost);
    if (ref)
        printf(" (CPU binned SAH %.4f: %+.1f%%)", ref_cost, 100.0 * (last.sah_cost / ref_cost - 1));
    printf("\n");
    printf("{");
    if (scene_path)
        printf("\"scene\": \"%s\", ", scene_path);
    printf("\"triangles\": %u, \"renderer\": \"%s\", \"reps\": %d, \"treelet_rounds\": %d, "
           "\"treelet_size\": %d, \"collapse_leaves\": %s, \"split_budget\": %g, \"fresh\": %s, "
           "\"idle_s\": %g, \"refs\": %u",
           n, gpu->info.renderer, reps, params.treelet_rounds, params.treelet_size,
           params.collapse_leaves ? "true" : "false", params.split_budget,
           fresh ? "true" : "false", idle_s, last.n_refs);
    for (int p = 0; p < CV_BVH_N_PHASES; p++)
        printf(", \"ms_%s\": %.4f", cv_bvh_phases[p].name, med[p]);
    printf(", \"ms_lbvh\": %.4f, \"ms_wall\": %.4f", lbvh, wall_med);
    printf(", \"nodes\": %u, \"bytes\": %llu, \"bytes_per_triangle\": %.3f, "
           "\"scratch_bytes\": %llu, \"sah_cost\": %.5f, \"ref_sah_cost\": %.5f, "
           "\"binary_nodes\": %u, \"depth\": %u, \"stack_need\": %u}\n",
           last.n_nodes, (unsigned long long)last.bytes, (double)last.bytes / (n ? n : 1),
           (unsigned long long)last.scratch_bytes, last.sah_cost, ref_cost, last.n_binary_nodes,
           last.depth, last.stack_need);
    double mrays[2] = {0, 0}, steps[2] = {0, 0};
    if (n_rays) {
        GLuint rb = cv_buffer_create((size_t)n_rays * 32, rays, "rays", &err);
        GLuint res = rb ? cv_buffer_create((size_t)n_rays * 16, NULL, "ray results", &err) : 0;
        struct cv_program *prog = res ? cv_program_get(gpu, "bvh/rays_test.comp", NULL, &err) : NULL;
        for (int v = 0; prog && v < 2; v++) {
            struct cv_bvh_params rp = params;
            if (v == 1)
                rp.treelet_rounds = 0;
            if (!cv_bvh_build(gpu, vb, tb, n, &rp, &bvh, &err))
                break;
            /* the stack the renderer would trace this tree with */
            const char *stack_defs[2] = {cv_bvh_stack_define(bvh), NULL};
            if (!(prog = cv_program_get(gpu, "bvh/rays_test.comp", stack_defs, &err))) {
                cv_bvh_destroy(&bvh);
                break;
            }
            cv_buffer_bind(vb, CV_BIND_VERTICES);
            cv_buffer_bind(tb, CV_BIND_TRIANGLES);
            cv_bvh_bind(bvh);
            cv_buffer_bind(rb, CV_BIND_PROBE_IN);
            cv_buffer_bind(res, CV_BIND_PROBE_OUT);
            cv_program_set_uint(prog, "u_n_rays", n_rays);
            cv_program_set_uint(prog, "u_n_tris", n);
            cv_program_dispatch_1d(prog, n_rays); /* warm-up */
            glFinish();
            double t0 = bench_ms();
            cv_program_dispatch_1d(prog, n_rays);
            glFinish();
            mrays[v] = n_rays / ((bench_ms() - t0) * 1e3);
            /* Nodes visited per ray by both queries, so that rates of
             * different trees compare per node as well as per ray. Staged,
             * so that the next variant writes its results to video memory
             * (gpu/buffer.h). */
            uint32_t *got = malloc((size_t)n_rays * 16);
            if (got && cv_buffer_read_staged(res, 0, (size_t)n_rays * 16, 0, got, &err)) {
                for (uint32_t i = 0; i < n_rays; i++)
                    steps[v] += got[4 * i + 3];
                steps[v] /= n_rays;
            }
            free(got);
            cv_bvh_destroy(&bvh);
        }
        if (!prog || mrays[1] == 0)
            fprintf(stderr, "bvh_bench: rays: %s\n", err.msg);
        printf("  rays (closest + any hit, %u): %.3f Mrays/s restructured, %.3f Mrays/s plain LBVH\n",
               n_rays, mrays[0], mrays[1]);
        printf("  nodes visited per ray (both queries): %.1f restructured, %.1f plain LBVH\n",
               steps[0], steps[1]);
        printf("{\"rays\": %u, \"mrays_per_s\": %.4f, \"mrays_per_s_lbvh\": %.4f, "
               "\"steps_per_ray\": %.2f, \"steps_per_ray_lbvh\": %.2f}\n",
               n_rays, mrays[0], mrays[1], steps[0], steps[1]);
        cv_buffer_destroy(&rb);
        cv_buffer_destroy(&res);
    }
    free(rays);
    for (int p = 0; p < CV_BVH_N_PHASES; p++)
        free(t[p]);
    cv_buffer_destroy(&vb);
    cv_buffer_destroy(&tb);
    mesh_free(&m);
    cv_gpu_destroy(&gpu);
    return status;
}
