/* nanovdb.h: reads float grids from NanoVDB files (.nvdb, the format of
 * nanovdb/util/IO.h, major version 32: segments of a header, one metadata
 * record per grid and the grids' buffers, uncompressed, ZIP (zlib) or
 * BLOSC). A grid's buffer is checked (magic, version, type, node offsets
 * inside it) and then read through libnanovdb's portable C accessor
 * (PNanoVDB.h) with bounds checks, so a damaged buffer reads zeros rather
 * than memory outside it. All numbers are little-endian, as the format. */
#ifndef CV_SCENE_NANOVDB_H
#define CV_SCENE_NANOVDB_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "base/error.h"

struct cv_nvdb_grid {
    uint32_t *words;      /* the grid's buffer (owned) */
    uint64_t size;        /* its size [bytes] */
    double map[3][4];     /* index to world: 3x3 matrix | translation */
    double inv[3][4];     /* world to index: the file's inverse | its translation */
    double world_lo[3], world_hi[3]; /* the world bounds the grid stores */
    int32_t index_lo[3], index_hi[3]; /* bounds of the active voxels, inclusive */
};

/* Reads the first grid called name from the file path. *found is false
 * (and true returned, *out zeroed) when no grid has that name. A grid that
 * holds other values than float, or whose class is neither fog volume nor
 * unknown (pbrt-v4's test), is an error. Errors name the file and what is
 * wrong ("cloud.nvdb: grid \"density\" holds Vec3f values; ..."). Reads the
 * whole file: memory of the order of the file and the grid. */
bool cv_nvdb_read(const char *path, const char *name, struct cv_nvdb_grid *out, bool *found,
                  struct cv_error *err);
/* The values of the voxels lo + (x, y, z), 0 <= x < n[0] ... into out,
 * x fastest; the value NanoVDB's accessor gives (the stored value of an
 * active or inactive voxel, a tile's value, or the background). */
void cv_nvdb_fill(const struct cv_nvdb_grid *g, const int32_t lo[3], const uint32_t n[3],
                  float *out);
/* Value of voxel (i, j, k). */
float cv_nvdb_value(const struct cv_nvdb_grid *g, int32_t i, int32_t j, int32_t k);
/* Accepts a zeroed struct; zeroes it. */
void cv_nvdb_free(struct cv_nvdb_grid *g);

#endif
