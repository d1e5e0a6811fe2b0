/* fuzz_scene.c: a small deterministic mutation fuzzer for the pbrt parser
 * and the PLY reader. Seeds are the .pbrt and .ply files of a folder; each
 * iteration mutates one seed (byte flips, inserted tokens, deleted or
 * duplicated ranges, truncation) with a fixed-seed PRNG and loads it. It
 * passes when no input crashes, hangs or (under ASan) leaks.
 *   fuzz_scene DIR ITERATIONS [SEED]
 * Build with -DCV_LIBFUZZER and -fsanitize=fuzzer (clang) to get a libFuzzer
 * target instead: the first byte picks parser or PLY reader. */
#include <dirent.h>
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

static uint64_t rng_state;
static uint64_t rng(void)
{
    /* xorshift64* */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return rng_state * 0x2545F4914F6CDD1Dull;
}

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

struct seed {
    unsigned char *data;
    size_t len;
    bool ply;
};

static void mutate(unsigned char **buf, size_t *len, size_t *cap)
{
    int kind = (int)(rng() % 5);
    size_t n = *len;
    size_t pos = n ? (size_t)(rng() % (n + 1)) : 0;
    switch (kind) {
    case 0: /* flip */
        if (n)
            (*buf)[rng() % n] = (unsigned char)rng();
        break;
    case 1: { /* insert token */
        const char *t = dict[rng() % (sizeof(dict) / sizeof(dict[0]))];
        size_t tl = strlen(t) ? strlen(t) : 1;
        if (n + tl > *cap) {
            *cap = (n + tl) * 2;
            *buf = realloc(*buf, *cap + 1);
        }
        memmove(*buf + pos + tl, *buf + pos, n - pos);
        memcpy(*buf + pos, t, tl);
        *len = n + tl;
        break;
    }
    case 2: { /* delete range */
        size_t dl = (size_t)(rng() % 16) + 1;
        if (pos + dl > n)
            dl = n - pos;
        memmove(*buf + pos, *buf + pos + dl, n - pos - dl);
        *len = n - dl;
        break;
    }
    case 3: { /* duplicate range */
        size_t dl = (size_t)(rng() % 64) + 1;
        if (pos + dl > n)
            dl = n - pos;
        if (n + dl > 1 << 20)
            break;
        if (n + dl > *cap) {
            *cap = (n + dl) * 2;
            *buf = realloc(*buf, *cap + 1);
        }
        memmove(*buf + pos + dl, *buf + pos, n - pos);
        memcpy(*buf + pos + dl, *buf + pos, dl);
        *len = n + dl;
        break;
    }
    default: /* truncate */
        *len = pos;
        break;
    }
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: fuzz_scene DIR ITERATIONS [SEED]\n");
        return 2;
    }
    snprintf(fuzz_dir, sizeof(fuzz_dir), "%s", argv[1]);
    long iters = atol(argv[2]);
    rng_state = argc > 3 ? strtoull(argv[3], NULL, 10) : 0x5eed5eedull;
    if (!rng_state)
        rng_state = 1;
    DIR *d = opendir(argv[1]);
    if (!d) {
        printf("1..0 # SKIP no seed folder %s\n", argv[1]);
        return 0;
    }
    struct seed seeds[64];
    size_t n_seeds = 0;
    struct dirent *e;
    char *names[64];
    size_t n_names = 0;
    while ((e = readdir(d)) && n_names < 64) {
        size_t l = strlen(e->d_name);
        if ((l > 5 && strcmp(e->d_name + l - 5, ".pbrt") == 0) || (l > 4 && strcmp(e->d_name + l - 4, ".ply") == 0))
            names[n_names++] = strdup(e->d_name);
    }
    closedir(d);
    /* readdir order is not fixed: sort for determinism */
    for (size_t i = 0; i < n_names; i++)
        for (size_t j = i + 1; j < n_names; j++)
            if (strcmp(names[j], names[i]) < 0) {
                char *t = names[i];
                names[i] = names[j];
                names[j] = t;
            }
    for (size_t i = 0; i < n_names; i++) {
        char path[2200];
        snprintf(path, sizeof(path), "%s/%s", argv[1], names[i]);
        char *data;
        size_t len;
        struct cv_error err;
        if (cv_read_file(path, &data, &len, &err)) {
            seeds[n_seeds].data = (unsigned char *)data;
            seeds[n_seeds].len = len;
            seeds[n_seeds].ply = strstr(names[i], ".ply") != NULL;
            n_seeds++;
        }
        free(names[i]);
    }
    if (!n_seeds) {
        printf("1..0 # SKIP no seeds in %s\n", argv[1]);
        return 0;
    }
    FILE *null = fopen("/dev/null", "w");
    cv_log_set_stream(null);
    long counts[2] = {0, 0};
    for (long it = 0; it < iters; it++) {
        struct seed *s = &seeds[rng() % n_seeds];
        size_t cap = s->len * 2 + 64, len = s->len;
        unsigned char *buf = malloc(cap + 1);
        memcpy(buf, s->data, len);
        int muts = 1 + (int)(rng() % 4);
        for (int m = 0; m < muts; m++)
            mutate(&buf, &len, &cap);
        run_one(buf, len, s->ply);
        counts[s->ply]++;
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
