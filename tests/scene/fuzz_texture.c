/* fuzz_texture.c: a deterministic mutation fuzzer for the texture image
 * loader (scene/image.h: PNG and TGA through stb_image, PFM, Radiance HDR,
 * EXR through OpenEXR). Seeds are tiny images written here (TGA plain and
 * RLE, PFM colour and grey, flat HDR, EXR half/float, zip/none)
 * plus the .png files of the folders given; each iteration mutates one
 * seed (tests/fuzz_mutate.h) with a fixed-seed PRNG, writes it to a
 * temporary folder under its format's extension and loads it with
 * cv_image_load. It passes when no input crashes, hangs or (under ASan)
 * leaks.
 *   fuzz_texture ITERATIONS SEED [DIR...]  */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/log.h"
#include "output/exr_write.h"
#include "scene/image.h"
#include "tests/fuzz_mutate.h"

enum { K_PNG, K_TGA, K_PFM, K_HDR, K_EXR, K_COUNT };
static const char *const exts[K_COUNT] = {"png", "tga", "pfm", "hdr", "exr"};

/* Header words and magic numbers of the formats, and sizes that overflow. */
static const char *const dict[] = {
    "\x89PNG\r\n\x1a\n", "IHDR", "IDAT", "IEND", "PLTE", "tRNS", "PF\n", "Pf\n", "-1.0\n", "1.0\n",
    "65535 65535\n", "0 0\n", "#?RADIANCE\n", "FORMAT=32-bit_rle_rgbe\n", "-Y 65535 +X 65535\n",
    "\x02\x02", "\x80", "\xff", "", "\x76\x2f\x31\x01", "channels", "compression", "dataWindow",
    "displayWindow", "lineOrder", "tiles", "chlist", "half", "box2i", "\xff\xff\xff\x7f",
    "\x00\x00\x00\x80", "\x01\x00\x00\x00",
};

static void add_seed(struct cv_fuzz_seed *seeds, size_t *n, const void *data, size_t len, int kind)
{
    seeds[*n].data = malloc(len);
    memcpy(seeds[*n].data, data, len);
    seeds[*n].len = len;
    seeds[*n].kind = kind;
    (*n)++;
}

static void add_tga(struct cv_fuzz_seed *seeds, size_t *n)
{
    /* 2x2 RGB, plain (type 2) and run-length (type 10) */
    unsigned char plain[18 + 12] = {0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 24, 0};
    for (int i = 0; i < 12; i++)
        plain[18 + i] = (unsigned char)(i * 21);
    add_seed(seeds, n, plain, sizeof(plain), K_TGA);
    unsigned char rle[18 + 8] = {0, 0, 10, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0, 2, 0, 24, 0x20,
                                 0x83, 10, 20, 30, 0x00, 40, 50, 60};
    add_seed(seeds, n, rle, sizeof(rle), K_TGA);
}

static void add_pfm(struct cv_fuzz_seed *seeds, size_t *n)
{
    const char *heads[2] = {"PF\n2 2\n-1.0\n", "Pf\n2 2\n-1.0\n"};
    for (int g = 0; g < 2; g++) {
        unsigned char buf[64];
        size_t hl = strlen(heads[g]), nf = g ? 4 : 12;
        memcpy(buf, heads[g], hl);
        for (size_t i = 0; i < nf; i++) {
            float f = 0.25f * (float)i;
            memcpy(buf + hl + 4 * i, &f, 4); /* little-endian hosts, as "-1.0" says */
        }
        add_seed(seeds, n, buf, hl + 4 * nf, K_PFM);
    }
}

static void add_hdr(struct cv_fuzz_seed *seeds, size_t *n)
{
    /* 2x2 flat RGBE, and 8x2 run-length encoded (one run per channel on
     * the first scanline, literal bytes on the second): truncating it ends
     * a scanline early, which Debian's stb_image would decode forever were
     * it not checked first (src/scene/hdr_check.c). */
    unsigned char buf[128];
    const char *flat = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 2\n";
    size_t l = strlen(flat);
    memcpy(buf, flat, l);
    for (int i = 0; i < 4; i++) {
        unsigned char px[4] = {(unsigned char)(64 + i), 128, 200, 129};
        memcpy(buf + l + 4 * i, px, 4);
    }
    add_seed(seeds, n, buf, l + 16, K_HDR);
    const char *rle = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n";
    l = strlen(rle);
    memcpy(buf, rle, l);
    for (int k = 0; k < 4; k++) { /* scanline 0: a run of 8 per channel */
        if (k == 0)
            memcpy(buf + l, (unsigned char[4]){2, 2, 0, 8}, 4), l += 4;
        buf[l++] = 128 + 8;
        buf[l++] = (unsigned char)(k == 3 ? 129 : 100 + 20 * k);
    }
    memcpy(buf + l, (unsigned char[4]){2, 2, 0, 8}, 4), l += 4;
    for (int k = 0; k < 4; k++) { /* scanline 1: 8 literal bytes per channel */
        buf[l++] = 8;
        for (int i = 0; i < 8; i++)
            buf[l++] = (unsigned char)(k == 3 ? 128 : 16 * i + k);
    }
    add_seed(seeds, n, buf, l, K_HDR);
}

static void add_exr(struct cv_fuzz_seed *seeds, size_t *n, const char *dir)
{
    float rgba[4 * 4 * 4];
    for (int i = 0; i < 64; i++)
        rgba[i] = 0.125f * (float)(i % 9);
    const enum cv_exr_compression comp[2] = {CV_EXR_NONE, CV_EXR_ZIP};
    char path[128];
    snprintf(path, sizeof(path), "%s/seed.exr", dir);
    for (int f = 0; f < 2; f++)
        for (int c = 0; c < 2; c++) {
            struct cv_exr_params p = {.rgba = rgba, .width = 4, .height = 4, .use_float = f,
                                      .compression = comp[c]};
            struct cv_error err = {0};
            char *data;
            size_t len;
            if (!cv_exr_write(path, &p, &err) || !cv_read_file(path, &data, &len, &err)) {
                fprintf(stderr, "cannot write the EXR seed: %s\n", err.msg);
                abort();
            }
            seeds[*n].data = (unsigned char *)data;
            seeds[*n].len = len;
            seeds[*n].kind = K_EXR;
            (*n)++;
        }
    unlink(path);
}

int main(int argc, char **argv)
{
    if (argc < 3) {
        fprintf(stderr, "usage: fuzz_texture ITERATIONS SEED [DIR...]\n");
        return 2;
    }
    long iters = atol(argv[1]);
    cv_fuzz_seed_rng(strtoull(argv[2], NULL, 10));
    char dir[] = "/tmp/cv-fuzz-texture-XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 1;
    }
    struct cv_fuzz_seed seeds[80];
    size_t n_seeds = 0;
    static const char *const suffixes[] = {".png"};
    for (int i = 3; i < argc; i++)
        cv_fuzz_read_seeds(argv[i], suffixes, 1, seeds, &n_seeds, 64);
    add_tga(seeds, &n_seeds);
    add_pfm(seeds, &n_seeds);
    add_hdr(seeds, &n_seeds);
    add_exr(seeds, &n_seeds, dir);
    FILE *null = fopen("/dev/null", "w");
    cv_log_set_stream(null);
    long counts[K_COUNT] = {0}, loaded = 0;
    char path[K_COUNT][64];
    for (int k = 0; k < K_COUNT; k++)
        snprintf(path[k], sizeof(path[k]), "%s/fuzz.%s", dir, exts[k]);
    for (long it = 0; it < iters; it++) {
        struct cv_fuzz_seed *s = &seeds[cv_fuzz_rng() % n_seeds];
        size_t len;
        unsigned char *buf = cv_fuzz_mutant(s, dict, sizeof(dict) / sizeof(dict[0]), &len);
        cv_fuzz_write_file(path[s->kind], buf, len);
        struct cv_image img;
        struct cv_error err = {0};
        if (cv_image_load(path[s->kind], it & 1, &img, &err)) {
            loaded++;
            cv_image_free(&img);
        }
        counts[s->kind]++;
        free(buf);
    }
    cv_log_set_stream(NULL);
    fclose(null);
    for (int k = 0; k < K_COUNT; k++)
        unlink(path[k]);
    rmdir(dir);
    for (size_t i = 0; i < n_seeds; i++)
        free(seeds[i].data);
    for (int k = 0; k < K_COUNT; k++)
        printf("%s %d - %ld mutated %s files decoded without a crash\n", counts[k] || k != K_PNG ? "ok" : "not ok",
               k + 1, counts[k], exts[k]);
    printf("# %ld of %ld inputs still loaded after mutation\n", loaded, iters);
    printf("1..%d\n", K_COUNT);
    return counts[K_PNG] ? 0 : 1;
}
