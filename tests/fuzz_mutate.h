/* fuzz_mutate.h: the mutation engine shared by the deterministic fuzzers
 * (tests/scene/fuzz_scene.c, tests/scene/fuzz_texture.c,
 * tests/manifest/fuzz_manifest.c): a fixed-seed PRNG, seed files read from
 * a folder in sorted order, and mutations (byte flips, inserted dictionary
 * tokens, deleted or duplicated ranges, truncation). Header-only: each
 * fuzzer is one program. */
#ifndef CV_TESTS_FUZZ_MUTATE_H
#define CV_TESTS_FUZZ_MUTATE_H

#include <dirent.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/file.h"

/* One seed input; kind is the index of the suffix it matched. */
struct cv_fuzz_seed {
    unsigned char *data;
    size_t len;
    int kind;
};

static uint64_t cv_fuzz_rng_state = 1;

static inline void cv_fuzz_seed_rng(uint64_t seed)
{
    cv_fuzz_rng_state = seed ? seed : 1;
}

static inline uint64_t cv_fuzz_rng(void)
{
    /* xorshift64* */
    cv_fuzz_rng_state ^= cv_fuzz_rng_state >> 12;
    cv_fuzz_rng_state ^= cv_fuzz_rng_state << 25;
    cv_fuzz_rng_state ^= cv_fuzz_rng_state >> 27;
    return cv_fuzz_rng_state * 0x2545F4914F6CDD1Dull;
}

/* Grows *buf (capacity *cap, one spare byte for a terminating NUL) to hold
 * need bytes. */
static inline void cv_fuzz_reserve(unsigned char **buf, size_t *cap, size_t need)
{
    if (need > *cap) {
        *cap = need * 2;
        *buf = realloc(*buf, *cap + 1);
        if (!*buf)
            abort();
    }
}

/* One mutation of buf[0..*len). An empty dictionary token inserts a NUL. */
static inline void cv_fuzz_mutate(unsigned char **buf, size_t *len, size_t *cap,
                                  const char *const *dict, size_t n_dict)
{
    int kind = (int)(cv_fuzz_rng() % 5);
    size_t n = *len;
    size_t pos = n ? (size_t)(cv_fuzz_rng() % (n + 1)) : 0;
    switch (kind) {
    case 0: /* flip */
        if (n)
            (*buf)[cv_fuzz_rng() % n] = (unsigned char)cv_fuzz_rng();
        break;
    case 1: { /* insert token */
        if (!n_dict)
            break;
        const char *t = dict[cv_fuzz_rng() % n_dict];
        size_t tl = strlen(t) ? strlen(t) : 1;
        cv_fuzz_reserve(buf, cap, n + tl);
        memmove(*buf + pos + tl, *buf + pos, n - pos);
        memcpy(*buf + pos, t, tl);
        *len = n + tl;
        break;
    }
    case 2: { /* delete range */
        size_t dl = (size_t)(cv_fuzz_rng() % 16) + 1;
        if (pos + dl > n)
            dl = n - pos;
        memmove(*buf + pos, *buf + pos + dl, n - pos - dl);
        *len = n - dl;
        break;
    }
    case 3: { /* duplicate range */
        size_t dl = (size_t)(cv_fuzz_rng() % 64) + 1;
        if (pos + dl > n)
            dl = n - pos;
        if (n + dl > 1 << 20)
            break;
        cv_fuzz_reserve(buf, cap, n + dl);
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

/* A mutant of seed: a copy with one to four mutations, NUL-terminated
 * (the NUL is not counted in *len). Free it with free(). */
static inline unsigned char *cv_fuzz_mutant(const struct cv_fuzz_seed *seed, const char *const *dict,
                                            size_t n_dict, size_t *len)
{
    size_t cap = seed->len * 2 + 64, n = seed->len;
    unsigned char *buf = malloc(cap + 1);
    if (!buf)
        abort();
    memcpy(buf, seed->data, n);
    int muts = 1 + (int)(cv_fuzz_rng() % 4);
    for (int m = 0; m < muts; m++)
        cv_fuzz_mutate(&buf, &n, &cap, dict, n_dict);
    buf[n] = 0;
    *len = n;
    return buf;
}

static inline int cv_fuzz_suffix(const char *name, const char *const *suffixes, size_t n_suffixes)
{
    size_t l = strlen(name);
    for (size_t i = 0; i < n_suffixes; i++) {
        size_t sl = strlen(suffixes[i]);
        if (l > sl && strcmp(name + l - sl, suffixes[i]) == 0)
            return (int)i;
    }
    return -1;
}

static inline int cv_fuzz_cmp_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* Appends the files of dir whose names end in one of suffixes to seeds
 * (*n_seeds of max used), in name order (readdir's order is not fixed).
 * A missing folder adds nothing. */
static inline void cv_fuzz_read_seeds(const char *dir, const char *const *suffixes, size_t n_suffixes,
                                      struct cv_fuzz_seed *seeds, size_t *n_seeds, size_t max)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    char *names[64];
    size_t n_names = 0;
    struct dirent *e;
    while ((e = readdir(d)) && n_names < 64)
        if (cv_fuzz_suffix(e->d_name, suffixes, n_suffixes) >= 0)
            names[n_names++] = strdup(e->d_name);
    closedir(d);
    qsort(names, n_names, sizeof(names[0]), cv_fuzz_cmp_names);
    for (size_t i = 0; i < n_names; i++) {
        char path[2200];
        snprintf(path, sizeof(path), "%s/%s", dir, names[i]);
        char *data;
        size_t len;
        struct cv_error err = {0};
        if (*n_seeds < max && cv_read_file(path, &data, &len, &err)) {
            seeds[*n_seeds].data = (unsigned char *)data;
            seeds[*n_seeds].len = len;
            seeds[*n_seeds].kind = cv_fuzz_suffix(names[i], suffixes, n_suffixes);
            (*n_seeds)++;
        }
        free(names[i]);
    }
}

/* Writes len bytes of data to path; aborts on failure (a fuzzer that
 * cannot write its input must not pass). */
static inline void cv_fuzz_write_file(const char *path, const void *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f || (len && fwrite(data, 1, len, f) != len) || fclose(f) != 0) {
        fprintf(stderr, "cannot write %s\n", path);
        abort();
    }
}

#endif
