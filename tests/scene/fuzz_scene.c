/* fuzz_scene.c: a small deterministic mutation fuzzer for the pbrt parser
 * and the PLY reader. Seeds are the .pbrt and .ply files of a folder; each
 * iteration mutates one seed (tests/fuzz_mutate.h) with a fixed-seed PRNG
 * and loads it. It passes when no input crashes, hangs or (under ASan) leaks.
 *   fuzz_scene DIR ITERATIONS [SEED]
 * Build with -DCV_LIBFUZZER and -fsanitize=fuzzer (clang) to get a libFuzzer
 * target instead: the first byte picks parser or PLY reader. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/file.h"
#include "base/log.h"
#include "scene/ply.h"
#include "scene/scene.h"

static char fuzz_dir[1024];
static long loaded;  /* inputs that loaded without error */

static void run_one(const unsigned char *data, size_t len, bool ply)
{
    struct cv_error err = {0};
    if (ply) {
        unsigned char *copy = malloc(len + 1);
        memcpy(copy, data, len);
        copy[len] = 0;
        struct cv_ply_mesh m;
        if (cv_ply_parse("fuzz.ply", copy, len, &m, &err)) {
            cv_ply_free(&m);
            loaded++;
        }
        free(copy);
    } else {
        char name[1100];
        snprintf(name, sizeof(name), "%s/fuzz-input.pbrt", fuzz_dir[0] ? fuzz_dir : ".");
        struct cv_scene *s = NULL;
        struct cv_scene_load_params p = {false};
        if (cv_scene_load_string(name, (const char *)data, len, &p, &s, &err)) {
            cv_scene_destroy(&s);
            loaded++;
        }
    }
}

#ifdef CV_LIBFUZZER
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static FILE *null;
    if (!null) {
        null = fopen("/dev/null", "w");
        cv_log_set_stream(null);
    }
    if (size == 0)
        return 0;
    run_one(data + 1, size - 1, data[0] & 1);
    return 0;
}
#else

#include "tests/fuzz_mutate.h"

static const char *const dict[] = {
    "[", "]", "\"", "#", "\n", " ", "0", "-1", "1e30", "-nan", "3.5", "AttributeBegin", "AttributeEnd",
    "TransformBegin", "TransformEnd", "WorldBegin", "ObjectBegin \"o\"", "ObjectEnd", "ObjectInstance \"o\"",
    "ReverseOrientation", "Scale -1 1 1", "\"float radius\" [ 2 ]", "\"integer indices\" [ 0 1 2 ]",
    "\"point3 P\" [ 0 0 0 1 0 0 0 1 0 ]", "Shape \"sphere\"", "Shape \"trianglemesh\"", "\"rgb L\" [ 1 1 1 ]",
    "AreaLightSource \"diffuse\"", "Include \"quad.ply\"", "\"string filename\" \"quad.ply\"",
    "\"spectrum eta\" [ 300 1 800 2 ]", "\"blackbody L\" 6500", "\"texture reflectance\" \"m\"",
    "Material \"mix\"", "MakeNamedMaterial \"x\"", "\"bool twosided\" true", "Attribute \"shape\" \"float radius\" 0.5", "Import \"errors.pbrt\"", "element vertex 3\n",
    "property float x\n", "property list uchar int vertex_indices\n", "end_header\n", "4294967295",
    "format binary_big_endian 1.0\n", "\xff\xff\xff\xff", "\0",
};

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: fuzz_scene DIR ITERATIONS [SEED]\n");
        return 2;
    }
    snprintf(fuzz_dir, sizeof(fuzz_dir), "%s", argv[1]);
    long iters = atol(argv[2]);
    cv_fuzz_seed_rng(argc > 3 ? strtoull(argv[3], NULL, 10) : 0x5eed5eedull);
    static const char *const suffixes[] = {".pbrt", ".ply"};
    struct cv_fuzz_seed seeds[64];
    size_t n_seeds = 0;
    cv_fuzz_read_seeds(argv[1], suffixes, 2, seeds, &n_seeds, 64);
    if (!n_seeds) {
        printf("1..0 # SKIP no seeds in %s\n", argv[1]);
        return 0;
    }
    FILE *null = fopen("/dev/null", "w");
    cv_log_set_stream(null);
    long counts[2] = {0, 0};
    for (long it = 0; it < iters; it++) {
        struct cv_fuzz_seed *s = &seeds[cv_fuzz_rng() % n_seeds];
        size_t len;
        unsigned char *buf = cv_fuzz_mutant(s, dict, sizeof(dict) / sizeof(dict[0]), &len);
        run_one(buf, len, s->kind == 1);
        counts[s->kind == 1]++;
        free(buf);
    }
    cv_log_set_stream(NULL);
    fclose(null);
    for (size_t i = 0; i < n_seeds; i++)
        free(seeds[i].data);
    printf("ok 1 - %ld mutated scene files parsed without a crash\n", counts[0]);
    printf("ok 2 - %ld mutated PLY files read without a crash\n", counts[1]);
    printf("# %ld of %ld inputs still loaded after mutation\n", loaded, iters);
    printf("1..2\n");
    return 0;
}
#endif
