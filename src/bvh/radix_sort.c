/* radix_sort.c: see radix_sort.h. Each pass counts digits per block of
 * tiles (radix_count.comp), scans each digit's row of the digit-major
 * counts in a workgroup of its own (radix_spine.comp) and scatters
 * (radix_scatter.comp): three dispatches. Passes ping-pong between the
 * caller's buffers and ours; after an odd count the result is copied
 * back. */
#include <stdio.h>
#include <stdlib.h>

#include "base/mem.h"
#include "bvh/radix_sort.h"
#include "bvh/scratch.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

#define RADIX_TILE 1024u
/* Bits per digit (the shaders take 4..8). 8 makes the fewest passes over
 * 30-bit Morton codes (4), whose dispatches and passes over the keys cost
 * more than the wider tiles do: it sorted fastest of 4 to 8
 * (bench/RESULTS.md, "Figures behind the code"). */
#define RADIX_BITS 8
#define RADIX_BINS (1u << RADIX_BITS)
/* Blocks per pass, at most: more give more workgroups to small sorts, fewer
 * a shorter scan of each digit's row (radix_spine.comp takes up to 8 per
 * invocation, 2048 in all). */
#define RADIX_MAX_BLOCKS 2048u
/* Tiles per block, at most: bounds the sort at 2048 * 63 tiles. */
#define RADIX_MAX_BLOCK_TILES 63u

struct cv_radix_sort {
    struct cv_gpu *gpu;
    uint32_t max_n;
    int max_bits;
    GLuint keys, vals, counts;
    uint64_t bytes;
};

/* Tiles per block for n keys: one, until there would be more than
 * RADIX_MAX_BLOCKS blocks. */
static uint32_t block_tiles(uint32_t n)
{
    uint32_t tiles = (n + RADIX_TILE - 1) / RADIX_TILE;
    uint32_t t = (tiles + RADIX_MAX_BLOCKS - 1) / RADIX_MAX_BLOCKS;
    if (t < 1)
        t = 1;
    return t > RADIX_MAX_BLOCK_TILES ? RADIX_MAX_BLOCK_TILES : t;
}

static uint32_t n_blocks(uint32_t n)
{
    uint32_t keys_per_block = block_tiles(n) * RADIX_TILE;
    return (uint32_t)(((uint64_t)n + keys_per_block - 1) / keys_per_block);
}

struct cv_radix_sort *cv_radix_sort_create(struct cv_gpu *gpu, uint32_t max_n, int max_bits,
                                           struct cv_error *err)
{
    if (max_bits < 1 || max_bits > 64) {
        cv_fail(err, "radix sort keys of %d bits", max_bits);
        return NULL;
    }
    size_t words = max_bits > 32 ? 2 : 1;
    struct cv_radix_sort *rs = cv_xcalloc(1, sizeof(*rs));
    rs->gpu = gpu;
    rs->max_n = max_n < 1 ? 1 : max_n;
    rs->max_bits = max_bits;
    uint32_t blocks = n_blocks(rs->max_n);
    if (blocks > RADIX_MAX_BLOCKS) {
        cv_fail(err, "radix sort of %u keys: at most %u fit", max_n,
                RADIX_MAX_BLOCKS * RADIX_MAX_BLOCK_TILES * RADIX_TILE);
        free(rs);
        return NULL;
    }
    /* Pooled scratch (bvh/scratch.h): every pass writes them before
     * reading them. */
    uint64_t n4 = (uint64_t)rs->max_n * 4;
    rs->keys = cv_bvh_scratch(gpu, n4 * words, "radix keys", &rs->bytes, err);
    rs->vals = rs->keys ? cv_bvh_scratch(gpu, n4, "radix vals", &rs->bytes, err) : 0;
    /* A row of block counts per digit, then the digits' totals. Fewer keys
     * can make more blocks (2048 tiles make 2048 blocks, 2049 make 1025),
     * but never more than tiles or RADIX_MAX_BLOCKS. */
    uint32_t most_tiles = (rs->max_n + RADIX_TILE - 1) / RADIX_TILE;
    uint32_t most_blocks = most_tiles < RADIX_MAX_BLOCKS ? most_tiles : RADIX_MAX_BLOCKS;
    size_t counts = ((size_t)most_blocks + 1) * RADIX_BINS;
    rs->counts = rs->vals ? cv_bvh_scratch(gpu, counts * 4, "radix counts", &rs->bytes, err) : 0;
    if (!rs->counts) {
        cv_radix_sort_destroy(&rs);
        return NULL;
    }
    return rs;
}

/* The sort's three programs and their defines for keys of `bits` (rdef:
 * 32 bytes, defs: 3 entries), shared by the run and the prefetch. */
static const char *const radix_files[3] = {"bvh/radix_count.comp", "bvh/radix_spine.comp",
                                           "bvh/radix_scatter.comp"};
static void radix_defines(int bits, char *rdef, const char **defs)
{
    snprintf(rdef, 32, "RADIX_BITS=%d", RADIX_BITS);
    defs[0] = rdef;
    defs[1] = bits > 32 ? "KEY64" : NULL;
    defs[2] = NULL;
}

void cv_radix_sort_prefetch(struct cv_gpu *gpu, int bits)
{
    char rdef[32];
    const char *defs[3];
    radix_defines(bits, rdef, defs);
    for (int i = 0; i < 3; i++)
        cv_program_request(gpu, radix_files[i], defs);
}

bool cv_radix_sort_run(struct cv_radix_sort *rs, GLuint keys, GLuint vals, uint32_t n,
                       int bits, struct cv_error *err)
{
    if (n > rs->max_n)
        return cv_fail(err, "radix sort of %u keys, scratch holds %u", n, rs->max_n);
    if (bits < 1 || bits > rs->max_bits)
        return cv_fail(err, "radix sort of %d-bit keys, scratch made for %d", bits, rs->max_bits);
    char rdef[32];
    const char *defs[3];
    radix_defines(bits, rdef, defs);
    size_t words = bits > 32 ? 2 : 1;
    if (n < 2)
        return true;
    struct cv_program *count, *spine, *scatter;
    if (!(count = cv_program_get(rs->gpu, radix_files[0], defs, err)) ||
        !(spine = cv_program_get(rs->gpu, radix_files[1], defs, err)) ||
        !(scatter = cv_program_get(rs->gpu, radix_files[2], defs, err)))
        return false;
    int passes = (bits + RADIX_BITS - 1) / RADIX_BITS;
    uint32_t tiles = block_tiles(n), blocks = n_blocks(n);
    cv_program_set_uint(count, "u_n", n);
    cv_program_set_uint(count, "u_block_tiles", tiles);
    cv_program_set_uint(spine, "u_blocks", blocks);
    cv_program_set_uint(scatter, "u_n", n);
    cv_program_set_uint(scatter, "u_block_tiles", tiles);
    cv_buffer_bind(rs->counts, CV_BIND_SORT_COUNTS);
    GLuint src_k = keys, src_v = vals, dst_k = rs->keys, dst_v = rs->vals;
    for (int pass = 0; pass < passes; pass++) {
        uint32_t shift = (uint32_t)(pass * RADIX_BITS);
        cv_buffer_bind(src_k, CV_BIND_SORT_KEYS);
        cv_program_set_uint(count, "u_shift", shift);
        cv_program_dispatch_1d(count, (uint64_t)blocks * count->local_size[0]);
        cv_program_dispatch_1d(spine, (uint64_t)RADIX_BINS * spine->local_size[0]);
        cv_buffer_bind(src_v, CV_BIND_SORT_VALS);
        cv_buffer_bind(dst_k, CV_BIND_SORT_KEYS_OUT);
        cv_buffer_bind(dst_v, CV_BIND_SORT_VALS_OUT);
        cv_program_set_uint(scatter, "u_shift", shift);
        cv_program_dispatch_1d(scatter, (uint64_t)blocks * scatter->local_size[0]);
        GLuint tk = src_k, tv = src_v;
        src_k = dst_k;
        src_v = dst_v;
        dst_k = tk;
        dst_v = tv;
    }
    if (src_k != keys) {
        glCopyNamedBufferSubData(src_k, keys, 0, 0, (GLsizeiptr)(n * 4 * words));
        glCopyNamedBufferSubData(src_v, vals, 0, 0, (GLsizeiptr)n * 4);
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    return cv_gl_check(err, "radix sort of %u keys", n);
}

uint64_t cv_radix_sort_bytes(const struct cv_radix_sort *rs)
{
    return rs->bytes;
}

void cv_radix_sort_destroy(struct cv_radix_sort **rs)
{
    if (!rs || !*rs)
        return;
    struct cv_buffer_pool *pool = (*rs)->gpu->scratch;
    cv_buffer_pool_put(pool, &(*rs)->keys);
    cv_buffer_pool_put(pool, &(*rs)->vals);
    cv_buffer_pool_put(pool, &(*rs)->counts);
    free(*rs);
    *rs = NULL;
}
