/* radix_sort_test.c: the GPU radix sort equals a stable CPU sort of the same
 * keys with their indices, for random and adversarial key sets (all equal,
 * sorted, reversed, few distinct, full 32-bit, odd pass counts, a narrower
 * last digit, every digit value in every tile, all bits set in a partial
 * tile, 60- and 64-bit keys of two words, sizes around a tile, enough keys
 * for blocks of several tiles with a short last block, and the sizes either
 * side of the first such), and the GPU prefix sum equals a CPU one across
 * several scan levels. Sort scratch that the driver cannot address
 * (gpu/storage.h) is refused with the buffer named. */
#include "config.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bvh/radix_sort.h"
#include "bvh/scan.h"
#include "gpu/buffer.h"
#include "tests/gpu/gpu_test_util.h"

static uint32_t rng = 2463534242u;
static uint32_t next_rand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

static uint64_t *g_keys;
static int cmp_pair(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    if (g_keys[x] != g_keys[y])
        return g_keys[x] < g_keys[y] ? -1 : 1;
    return x < y ? -1 : (x > y);
}

static void check_sort(struct cv_radix_sort *rs, const char *name, uint64_t *keys, uint32_t n,
                       int bits)
{
    struct cv_error err = {{0}};
    size_t words = bits > 32 ? 2 : 1;
    uint32_t *vals = malloc(n * 4), *order = malloc(n * 4), *up = malloc(n * 4 * words);
    uint32_t *got_k = malloc(n * 4 * words), *got_v = malloc(n * 4);
    uint64_t mask = bits >= 64 ? ~0ull : (1ull << bits) - 1u;
    for (uint32_t i = 0; i < n; i++) {
        keys[i] &= mask;
        vals[i] = order[i] = i;
        up[words * i] = (uint32_t)keys[i];
        if (words == 2)
            up[2 * i + 1] = (uint32_t)(keys[i] >> 32);
    }
    GLuint bk = cv_buffer_create(n * 4 * words, up, "keys", &err);
    GLuint bv = cv_buffer_create(n * 4, vals, "vals", &err);
    bool ok = bk && bv && cv_radix_sort_run(rs, bk, bv, n, bits, &err) &&
              cv_buffer_read(bk, 0, n * 4 * words, got_k, &err) && cv_buffer_read(bv, 0, n * 4, got_v, &err);
    g_keys = keys;
    qsort(order, n, 4, cmp_pair);
    uint32_t bad = 0, first = 0;
    for (uint32_t i = 0; ok && i < n; i++) {
        uint64_t k = got_k[words * i];
        if (words == 2)
            k |= (uint64_t)got_k[2 * i + 1] << 32;
        if ((got_v[i] != order[i] || k != keys[order[i]]) && bad++ == 0)
            first = i;
    }
    tap_ok(ok && bad == 0, "%s (n=%u, %d bits): %s, %u misplaced (first at %u)", name, n, bits,
           ok ? "sorted" : err.msg, bad, first);
    cv_buffer_destroy(&bk);
    cv_buffer_destroy(&bv);
    free(vals);
    free(up);
    free(order);
    free(got_k);
    free(got_v);
}

static void check_scan(struct cv_gpu *gpu, uint32_t n)
{
    struct cv_error err = {{0}};
    uint32_t *data = malloc((size_t)n * 4), *got = malloc((size_t)n * 4);
    for (uint32_t i = 0; i < n; i++)
        data[i] = next_rand() % 5;
    struct cv_scan *scan = cv_scan_create(gpu, n, &err);
    GLuint b = cv_buffer_create((size_t)n * 4, data, "scan", &err);
    bool ok = scan && b && cv_scan_exclusive(scan, b, n, &err) &&
              cv_buffer_read(b, 0, (size_t)n * 4, got, &err);
    uint32_t run = 0, bad = 0;
    for (uint32_t i = 0; ok && i < n; i++) {
        bad += got[i] != run;
        run += data[i];
    }
    tap_ok(ok && bad == 0, "exclusive scan of %u elements: %s, %u wrong", n, ok ? "ran" : err.msg,
           bad);
    cv_buffer_destroy(&b);
    cv_scan_destroy(&scan);
    free(data);
    free(got);
}

static void random_keys(uint64_t *keys, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        keys[i] = next_rand();
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    const uint32_t n = 60001;
    struct cv_radix_sort *rs = cv_radix_sort_create(gpu, n, 64, &err);
    if (!tap_ok(rs != NULL, "sort scratch created: %s", rs ? "yes" : err.msg))
        return tap_done();
    uint64_t *keys = malloc(n * 8);

    random_keys(keys, n);
    check_sort(rs, "random 30-bit", keys, n, 30);
    random_keys(keys, n);
    check_sort(rs, "random 32-bit", keys, n, 32);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = 0x2aaaaaaa;
    check_sort(rs, "all equal", keys, n, 30);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = i * 7u;
    check_sort(rs, "already sorted", keys, n, 30);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (n - i) * 13u;
    check_sort(rs, "reversed", keys, n, 30);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (next_rand() % 3u) << 27;
    check_sort(rs, "three distinct keys", keys, n, 30);
    random_keys(keys, n);
    check_sort(rs, "12 bits (odd pass count)", keys, n, 12);
    random_keys(keys, n);
    check_sort(rs, "20 bits (5 passes)", keys, n, 20);
    random_keys(keys, n);
    check_sort(rs, "5 bits (one narrow digit)", keys, n, 5);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (uint64_t)((i * 37u) & 255u) << 8 | (255u - (i & 255u));
    check_sort(rs, "every digit value in every tile", keys, n, 16);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = ~0ull;
    check_sort(rs, "all bits set (64-bit, partial last tile)", keys, n, 64);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (uint64_t)(next_rand() % 7u) << 32 | 0xffffffffu;
    check_sort(rs, "60-bit, equal low words", keys, n, 60);
    for (uint32_t i = 0; i < 1000; i++)
        keys[i] = next_rand();
    check_sort(rs, "one partial tile", keys, 1000, 30);
    /* A tile is 1024 keys (src/bvh/radix_sort.c); few distinct keys make
     * runs that cross the invocations' shares of it. */
    const uint32_t around_tile[] = {1023, 1024, 1025, 2047, 3073};
    for (size_t t = 0; t < sizeof(around_tile) / sizeof(around_tile[0]); t++) {
        for (uint32_t i = 0; i < around_tile[t]; i++)
            keys[i] = (next_rand() % 3u) * 0x01010101u;
        check_sort(rs, "sizes around a tile, few distinct keys", keys, around_tile[t], 32);
    }
    keys[0] = 5;
    keys[1] = 3;
    check_sort(rs, "two keys", keys, 2, 30);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (uint64_t)next_rand() << 32 | next_rand();
    check_sort(rs, "random 60-bit", keys, n, 60);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (uint64_t)(next_rand() % 4u) << 40 | (next_rand() % 2u);
    check_sort(rs, "64-bit, few distinct in both words", keys, n, 64);
    for (uint32_t i = 0; i < n; i++)
        keys[i] = (uint64_t)(n - i) << 33;
    check_sort(rs, "64-bit reversed (high word only)", keys, n, 64);
    cv_radix_sort_destroy(&rs);
    tap_ok(rs == NULL, "destroy clears the pointer");

    /* Past 2048 tiles a block walks several (src/bvh/radix_sort.c); 2149
     * tiles make blocks of two and a last block of one. */
    const uint32_t big = 2200001;
    rs = cv_radix_sort_create(gpu, big, 64, &err);
    uint64_t *big_keys = malloc(big * 8);
    if (tap_ok(rs != NULL && big_keys, "large sort scratch created: %s", rs ? "yes" : err.msg)) {
        random_keys(big_keys, big);
        for (uint32_t i = 0; i < big; i++)
            big_keys[i] %= 5000u;
        check_sort(rs, "blocks of several tiles, many equal keys", big_keys, big, 30);
        random_keys(big_keys, big);
        check_sort(rs, "blocks of several tiles, random 64-bit", big_keys, big, 64);
        /* 2048 tiles are the most blocks of one tile; one key more makes
         * blocks of two tiles and a last block of one key. */
        random_keys(big_keys, big);
        check_sort(rs, "the most blocks of one tile", big_keys, 2048u * 1024u, 30);
        random_keys(big_keys, big);
        check_sort(rs, "blocks of two tiles, last of one key", big_keys, 2048u * 1024u + 1u, 30);
    }
    free(big_keys);
    cv_radix_sort_destroy(&rs);

    /* As after a failed probe just past the advertised size: keys one
     * word past it must not be allocated and bound. Where the driver
     * advertises more than 256 MiB (NVIDIA: 2 GiB), that many keys are
     * past what one sort takes anyway (132 M), which fails first. */
    uint64_t limit = gpu->info.max_ssbo_bytes > 0 ? (uint64_t)gpu->info.max_ssbo_bytes : 0;
    if (limit > 0 && limit <= 256ull << 20) {
        struct cv_gpu_storage kept = gpu->storage;
        gpu->storage.fails = limit + 4;
        err = (struct cv_error){{0}};
        rs = cv_radix_sort_create(gpu, (uint32_t)(limit / 4) + 1u, 32, &err);
        tap_ok(rs == NULL && strstr(err.msg, "radix keys"),
               "sort scratch past what the driver addresses is refused: %s",
               rs ? "created" : err.msg);
        cv_radix_sort_destroy(&rs);
        gpu->storage = kept;
    } else {
        tap_ok(true, "# SKIP the driver advertises %llu MiB per storage block",
               (unsigned long long)(limit >> 20));
    }

    check_scan(gpu, 1);
    check_scan(gpu, 1025);
    check_scan(gpu, 65536);
    check_scan(gpu, 65537);
    check_scan(gpu, 1100000);
    free(keys);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
