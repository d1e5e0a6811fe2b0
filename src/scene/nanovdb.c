/* nanovdb.c: NanoVDB files (nanovdb.h). The file's framing (segment
 * header, metadata records, compressed buffers) is parsed here; the grid
 * buffer itself through PNanoVDB.h, libnanovdb's portable C port of
 * NanoVDB.h, compiled with its bounds checks. */
#include "scene/nanovdb.h"

#include <blosc.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "base/file.h"
#include "base/limits.h"
#include "base/mem.h"

#define PNANOVDB_C
#define PNANOVDB_BUF_BOUNDS_CHECK
#include <nanovdb/PNanoVDB.h>

#define NVDB_MAGIC 0x304244566f6e614eull      /* "NanoVDB0" */
#define NVDB_MAGIC_GRID 0x314244566f6e614eull /* "NanoVDB1": grids of later 32.x */
#define NVDB_MAJOR 32u
#define HEADER_BYTES 16u
#define META_BYTES 176u
#define BLOSC_CHUNK (1ull << 30) /* IO.h's MAX_SIZE: BLOSC streams go in chunks of this */

enum { CODEC_NONE, CODEC_ZIP, CODEC_BLOSC, CODECS };
static const char *const codec_names[CODECS] = {"none", "ZIP", "BLOSC"};

/* NanoVDB's GridType and GridClass names, for messages */
static const char *const type_names[] = {
    "unknown", "float", "double", "int16", "int32", "int64", "Vec3f", "Vec3d", "mask", "half",
    "uint32", "bool", "RGBA8", "Fp4", "Fp8", "Fp16", "FpN", "Vec4f", "Vec4d", "index"};
static const char *const class_names[] = {
    "unknown", "level set", "fog volume", "staggered", "point index", "point data",
    "topology", "voxel volume", "index grid"};
#define NAME_OF(t, v) ((v) < sizeof(t) / sizeof(t[0]) ? t[v] : "unknown")

#define GRID_TYPE_FLOAT 1u
#define GRID_CLASS_UNKNOWN 0u
#define GRID_CLASS_FOG 2u

static uint16_t rd16(const unsigned char *p) { return (uint16_t)(p[0] | p[1] << 8); }
static uint32_t rd32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}
static uint64_t rd64(const unsigned char *p) { return rd32(p) | (uint64_t)rd32(p + 4) << 32; }
static double rdf64(const unsigned char *p)
{
    uint64_t u = rd64(p);
    double d;
    memcpy(&d, &u, sizeof(d));
    return d;
}

/* One metadata record of a segment: the fields we use. */
struct meta {
    uint64_t grid_size, file_size;
    uint32_t type, cls;
    const char *name; /* NUL-terminated, inside the file */
};

/* The grid's buffer decoded from the file bytes at [at, at + m->file_size). */
static bool decode(const char *path, const unsigned char *at, const struct meta *m,
                   unsigned codec, unsigned char *dst, struct cv_error *err)
{
    uint64_t n = m->file_size;
    if (codec == CODEC_NONE) {
        if (n < m->grid_size)
            return cv_fail(err, "%s: grid \"%s\": %llu bytes stored for a grid of %llu", path,
                           m->name, (unsigned long long)n, (unsigned long long)m->grid_size);
        memcpy(dst, at, m->grid_size);
        return true;
    }
    uint64_t left = m->grid_size, done = 0;
    do {
        if (n < 8)
            return cv_fail(err, "%s: grid \"%s\": %s stream ends early", path, m->name,
                           codec_names[codec]);
        uint64_t size = rd64(at);
        at += 8;
        n -= 8;
        if (size > n)
            return cv_fail(err, "%s: grid \"%s\": %s block of %llu bytes past the end of the "
                                "grid's %llu stored bytes", path, m->name, codec_names[codec],
                           (unsigned long long)size, (unsigned long long)n);
        if (codec == CODEC_ZIP) {
            uLongf got = (uLongf)left;
            int z = uncompress(dst, &got, at, (uLong)size);
            if (z != Z_OK || got != left)
                return cv_fail(err, "%s: grid \"%s\": ZIP data does not inflate to the grid's "
                                    "%llu bytes (%s)", path, m->name,
                               (unsigned long long)left, z == Z_OK ? "size differs" : zError(z));
            return true;
        }
        uint64_t chunk = left < BLOSC_CHUNK ? left : BLOSC_CHUNK;
        size_t nbytes = 0;
        if (blosc_cbuffer_validate(at, (size_t)size, &nbytes) != 0 || nbytes != chunk ||
            blosc_decompress_ctx(at, dst + done, (size_t)chunk, 1) != (int)chunk)
            return cv_fail(err, "%s: grid \"%s\": BLOSC block does not decode to %llu bytes",
                           path, m->name, (unsigned long long)chunk);
        at += size;
        n -= size;
        done += chunk;
        left -= chunk;
    } while (left > 0);
    return true;
}

/* Checks the decoded buffer of grid m and fills *g from it. */
static bool check_grid(const char *path, const struct meta *m, struct cv_nvdb_grid *g,
                       struct cv_error *err)
{
    const unsigned char *b = (const unsigned char *)g->words;
    uint64_t size = g->size;
    if (size < PNANOVDB_GRID_SIZE + PNANOVDB_TREE_SIZE)
        return cv_fail(err, "%s: grid \"%s\": %llu bytes are too few for a grid", path, m->name,
                       (unsigned long long)size);
    uint64_t magic = rd64(b + PNANOVDB_GRID_OFF_MAGIC);
    if (magic != NVDB_MAGIC && magic != NVDB_MAGIC_GRID)
        return cv_fail(err, "%s: grid \"%s\": its buffer does not start with NanoVDB's magic "
                            "number", path, m->name);
    uint32_t major = rd32(b + PNANOVDB_GRID_OFF_VERSION) >> 21;
    if (major != NVDB_MAJOR)
        return cv_fail(err, "%s: grid \"%s\" is NanoVDB version %u; version %u is read", path,
                       m->name, major, NVDB_MAJOR);
    uint32_t type = rd32(b + PNANOVDB_GRID_OFF_GRID_TYPE);
    uint32_t cls = rd32(b + PNANOVDB_GRID_OFF_GRID_CLASS);
    if (type != GRID_TYPE_FLOAT)
        return cv_fail(err, "%s: grid \"%s\" holds %s values; only float grids are read", path,
                       m->name, NAME_OF(type_names, type));
    if (cls != GRID_CLASS_FOG && cls != GRID_CLASS_UNKNOWN)
        return cv_fail(err, "%s: grid \"%s\" is a %s; a medium reads fog volumes", path,
                       m->name, NAME_OF(class_names, cls));
    /* the root and its tiles lie inside the buffer, so that the accessor's
     * search of the tiles is bounded */
    uint64_t root = PNANOVDB_GRID_SIZE + rd64(b + PNANOVDB_GRID_SIZE +
                                              PNANOVDB_TREE_OFF_NODE_OFFSET_ROOT);
    if (root < PNANOVDB_GRID_SIZE || root > size - 64)
        return cv_fail(err, "%s: grid \"%s\": its root lies outside the grid", path, m->name);
    uint32_t tiles = rd32(b + root + PNANOVDB_ROOT_OFF_TABLE_SIZE);
    if (tiles > (size - root - 64) / 32)
        return cv_fail(err, "%s: grid \"%s\": its root's %u tiles run past the grid's end", path,
                       m->name, tiles);
    for (int a = 0; a < 3; a++) {
        g->index_lo[a] = (int32_t)rd32(b + root + PNANOVDB_ROOT_OFF_BBOX_MIN + 4 * a);
        g->index_hi[a] = (int32_t)rd32(b + root + PNANOVDB_ROOT_OFF_BBOX_MAX + 4 * a);
        g->world_lo[a] = rdf64(b + PNANOVDB_GRID_OFF_WORLD_BBOX + 8 * a);
        g->world_hi[a] = rdf64(b + PNANOVDB_GRID_OFF_WORLD_BBOX + 24 + 8 * a);
        for (int c = 0; c < 3; c++) {
            g->map[a][c] = rdf64(b + PNANOVDB_GRID_OFF_MAP + PNANOVDB_MAP_OFF_MATD + 24 * a + 8 * c);
            g->inv[a][c] = rdf64(b + PNANOVDB_GRID_OFF_MAP + PNANOVDB_MAP_OFF_INVMATD + 24 * a +
                                 8 * c);
        }
        g->map[a][3] = g->inv[a][3] = rdf64(b + PNANOVDB_GRID_OFF_MAP + PNANOVDB_MAP_OFF_VECD +
                                            8 * a);
    }
    if (rd64(b + PNANOVDB_GRID_SIZE + PNANOVDB_TREE_OFF_VOXEL_COUNT) == 0 && tiles == 0)
        return cv_fail(err, "%s: grid \"%s\" is empty", path, m->name);
    for (int a = 0; a < 3; a++) {
        if (g->index_lo[a] > g->index_hi[a])
            return cv_fail(err, "%s: grid \"%s\" has empty index bounds", path, m->name);
        for (int c = 0; c < 4; c++)
            if (!isfinite(g->map[a][c]) || !isfinite(g->inv[a][c]))
                return cv_fail(err, "%s: grid \"%s\": its transform is not finite", path,
                               m->name);
    }
    return true;
}

/* Parses the segments of the file bytes f[0, len) up to grid `name`. */
static bool find_grid(const char *path, const unsigned char *f, size_t len, const char *name,
                      struct cv_nvdb_grid *g, bool *found, struct cv_error *err)
{
    size_t pos = 0;
    while (pos < len) {
        if (len - pos < HEADER_BYTES)
            return cv_fail(err, "%s: truncated: a segment header at byte %zu needs %u bytes, "
                                "%zu are left", path, pos, HEADER_BYTES, len - pos);
        uint64_t magic = rd64(f + pos);
        if (magic != NVDB_MAGIC) {
            if (magic == __builtin_bswap64(NVDB_MAGIC))
                return cv_fail(err, "%s: a NanoVDB file of the other byte order", path);
            return cv_fail(err, "%s: not a NanoVDB file (no magic number \"NanoVDB0\" at byte "
                                "%zu)", path, pos);
        }
        uint32_t version = rd32(f + pos + 8);
        if (version >> 21 != NVDB_MAJOR)
            return cv_fail(err, "%s: NanoVDB file version %u.%u; version %u is read", path,
                           version >> 21, (version >> 10) & 2047u, NVDB_MAJOR);
        unsigned count = rd16(f + pos + 12), codec = rd16(f + pos + 14);
        if (codec >= CODECS)
            return cv_fail(err, "%s: unknown compression codec %u", path, codec);
        pos += HEADER_BYTES;
        struct meta *metas = cv_xmalloc((count ? count : 1) * sizeof(*metas));
        bool ok = true;
        for (unsigned i = 0; i < count && ok; i++) {
            if (len - pos < META_BYTES) {
                ok = cv_fail(err, "%s: truncated: the metadata of grid %u at byte %zu", path, i,
                             pos);
                break;
            }
            const unsigned char *p = f + pos;
            uint32_t nsize = rd32(p + 136);
            metas[i] = (struct meta){rd64(p), rd64(p + 8), rd32(p + 32), rd32(p + 36),
                                     (const char *)p + META_BYTES};
            pos += META_BYTES;
            if (nsize == 0 || len - pos < nsize || p[META_BYTES + nsize - 1] != '\0')
                ok = cv_fail(err, "%s: truncated or damaged: the name of grid %u at byte %zu",
                             path, i, pos);
            pos += nsize;
        }
        for (unsigned i = 0; i < count && ok; i++) {
            const struct meta *m = &metas[i];
            if (m->file_size > len - pos) {
                ok = cv_fail(err, "%s: truncated: grid \"%s\" needs %llu bytes at byte %zu, %zu "
                                  "are left", path, m->name, (unsigned long long)m->file_size,
                             pos, len - pos);
                break;
            }
            if (strcmp(m->name, name) == 0) {
                if (m->type != GRID_TYPE_FLOAT)
                    ok = cv_fail(err, "%s: grid \"%s\" holds %s values; only float grids are "
                                      "read", path, name, NAME_OF(type_names, m->type));
                else if (m->grid_size < PNANOVDB_GRID_SIZE + PNANOVDB_TREE_SIZE ||
                         m->grid_size > CV_MAX_INPUT_BYTES || m->grid_size % 8 != 0)
                    ok = cv_fail(err, "%s: grid \"%s\": size %llu bytes is not a grid's", path,
                                 name, (unsigned long long)m->grid_size);
                if (ok) {
                    g->size = m->grid_size;
                    g->words = cv_xmalloc((size_t)g->size);
                    ok = decode(path, f + pos, m, codec, (unsigned char *)g->words, err) &&
                         check_grid(path, m, g, err);
                }
                free(metas);
                *found = ok;
                return ok;
            }
            pos += (size_t)m->file_size;
        }
        free(metas);
        if (!ok)
            return false;
    }
    return true;
}

bool cv_nvdb_read(const char *path, const char *name, struct cv_nvdb_grid *out, bool *found,
                  struct cv_error *err)
{
    memset(out, 0, sizeof(*out));
    *found = false;
    char *bytes;
    size_t len;
    if (!cv_read_file(path, &bytes, &len, err))
        return false;
    bool ok = find_grid(path, (const unsigned char *)bytes, len, name, out, found, err);
    free(bytes);
    if (!ok || !*found)
        cv_nvdb_free(out);
    return ok;
}

static pnanovdb_buf_t buf_of(const struct cv_nvdb_grid *g)
{
    return pnanovdb_make_buf(g->words, g->size / 4);
}

void cv_nvdb_fill(const struct cv_nvdb_grid *g, const int32_t lo[3], const uint32_t n[3],
                  float *out)
{
    pnanovdb_buf_t buf = buf_of(g);
    pnanovdb_grid_handle_t grid = {pnanovdb_address_null()};
    pnanovdb_root_handle_t root = pnanovdb_tree_get_root(buf, pnanovdb_grid_get_tree(buf, grid));
    pnanovdb_readaccessor_t acc;
    pnanovdb_readaccessor_init(&acc, root);
    size_t k = 0;
    for (uint32_t z = 0; z < n[2]; z++)
        for (uint32_t y = 0; y < n[1]; y++)
            for (uint32_t x = 0; x < n[0]; x++) {
                pnanovdb_coord_t ijk = {lo[0] + (int32_t)x, lo[1] + (int32_t)y,
                                        lo[2] + (int32_t)z};
                pnanovdb_address_t at = pnanovdb_readaccessor_get_value_address(
                    PNANOVDB_GRID_TYPE_FLOAT, buf, &acc, &ijk);
                out[k++] = pnanovdb_read_float(buf, at);
            }
}

float cv_nvdb_value(const struct cv_nvdb_grid *g, int32_t i, int32_t j, int32_t k)
{
    float v;
    const int32_t lo[3] = {i, j, k};
    const uint32_t one[3] = {1, 1, 1};
    cv_nvdb_fill(g, lo, one, &v);
    return v;
}

void cv_nvdb_free(struct cv_nvdb_grid *g)
{
    free(g->words);
    memset(g, 0, sizeof(*g));
}
