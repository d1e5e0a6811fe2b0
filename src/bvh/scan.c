/* scan.c: see scan.h. Tiles of 1024 are scanned in one dispatch, their
 * totals scanned recursively (one level per factor of 1024), then added
 * back. */
#include <stdlib.h>

#include "base/mem.h"
#include "bvh/scan.h"
#include "bvh/scratch.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/buffer_pool.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

#define SCAN_TILE 1024u
#define SCAN_MAX_LEVELS 6

struct cv_scan {
    struct cv_gpu *gpu;
    GLuint sums[SCAN_MAX_LEVELS];
    uint32_t sums_n[SCAN_MAX_LEVELS];
    int n_levels;
    uint64_t bytes;
};

struct cv_scan *cv_scan_create(struct cv_gpu *gpu, uint32_t max_n, struct cv_error *err)
{
    struct cv_scan *scan = cv_xcalloc(1, sizeof(*scan));
    scan->gpu = gpu;
    uint32_t n = max_n < 1 ? 1 : max_n;
    do {
        n = (n + SCAN_TILE - 1) / SCAN_TILE;
        if (scan->n_levels == SCAN_MAX_LEVELS) {
            cv_scan_destroy(&scan);
            cv_fail(err, "scan of %u elements is too large", max_n);
            return NULL;
        }
        scan->sums_n[scan->n_levels] = n;
        /* Pooled scratch: scan_block.comp writes them. */
        scan->sums[scan->n_levels] =
            cv_bvh_scratch(gpu, (uint64_t)n * 4, "bvh scan sums", &scan->bytes, err);
        if (!scan->sums[scan->n_levels++]) {
            cv_scan_destroy(&scan);
            return NULL;
        }
    } while (n > 1);
    return scan;
}

static const char *const scan_files[2] = {"bvh/scan_block.comp", "bvh/scan_add.comp"};

void cv_scan_prefetch(struct cv_gpu *gpu)
{
    for (int i = 0; i < 2; i++)
        cv_program_request(gpu, scan_files[i], NULL);
}

static bool scan_level(struct cv_scan *scan, GLuint buf, uint32_t n, int level,
                       struct cv_error *err)
{
    struct cv_program *block, *add;
    if (!(block = cv_program_get(scan->gpu, scan_files[0], NULL, err)) ||
        !(add = cv_program_get(scan->gpu, scan_files[1], NULL, err)))
        return false;
    if (level >= scan->n_levels)
        return cv_fail(err, "scan: more elements than the scratch was made for");
    uint32_t tiles = (n + SCAN_TILE - 1) / SCAN_TILE;
    cv_buffer_bind(buf, CV_BIND_SCAN_DATA);
    cv_buffer_bind(scan->sums[level], CV_BIND_SCAN_SUMS);
    cv_program_set_uint(block, "u_n", n);
    cv_program_dispatch_1d(block, (uint64_t)tiles * block->local_size[0]);
    if (tiles > 1) {
        if (!scan_level(scan, scan->sums[level], tiles, level + 1, err))
            return false;
        cv_buffer_bind(buf, CV_BIND_SCAN_DATA);
        cv_buffer_bind(scan->sums[level], CV_BIND_SCAN_SUMS);
        cv_program_set_uint(add, "u_n", n);
        cv_program_dispatch_1d(add, n);
    }
    return true;
}

bool cv_scan_exclusive(struct cv_scan *scan, GLuint buf, uint32_t n, struct cv_error *err)
{
    if (n == 0)
        return true;
    if (!scan_level(scan, buf, n, 0, err))
        return false;
    return cv_gl_check(err, "prefix sum of %u elements", n);
}

uint64_t cv_scan_bytes(const struct cv_scan *scan)
{
    return scan->bytes;
}

void cv_scan_destroy(struct cv_scan **scan)
{
    if (!scan || !*scan)
        return;
    for (int i = 0; i < SCAN_MAX_LEVELS; i++)
        cv_buffer_pool_put((*scan)->gpu->scratch, &(*scan)->sums[i]);
    free(*scan);
    *scan = NULL;
}
