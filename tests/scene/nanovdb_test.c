/* nanovdb_test.c: the NanoVDB reader (src/scene/nanovdb.c) and pbrt-v4's
 * "nanovdb" medium (media_grid.c) on the oracle's vol_nanovdb.nvdb
 * (make_nanovdb.py): its voxels against the generator's formula, the
 * same grids uncompressed, ZIP and BLOSC, what the medium becomes, and
 * broken files (truncated, wrong magic, missing grid, other value types
 * and classes, unknown codec) failing with the statement's location. */
#include <blosc.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "base/file.h"
#include "base/mem.h"
#include "scene/nanovdb.h"
#include "scene/scene.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

#define META 176

/* make_nanovdb.py's density at voxel (i, j, k); 0 at its holes and
 * outside its box */
static double density_of(int i, int j, int k)
{
    if (i < 3 || i > 14 || j < 5 || j > 14 || k < 2 || k > 9 || (i * 7 + j * 3 + k) % 23 == 0)
        return 0;
    double u = (i - 8.5) / 6, v = (j - 9.5) / 5, w = (k - 5.5) / 4;
    return 1.4 * exp(-1.2 * (u * u + v * v + w * w)) + 0.35 * (1 + sin(1.3 * i + 0.7 * j - 0.9 * k));
}

static uint64_t rd64(const unsigned char *p)
{
    uint64_t v;
    memcpy(&v, p, 8);
    return v;
}

static void wr64(unsigned char *p, uint64_t v) { memcpy(p, &v, 8); }

/* The two grids of the committed file, decompressed, and its framing. */
struct grids {
    unsigned char head[16];
    unsigned char meta[2][META + 16];
    size_t meta_len[2];
    unsigned char *buf[2];
    uint64_t size[2];
};

static bool unpack(const unsigned char *f, size_t len, struct grids *g)
{
    memcpy(g->head, f, 16);
    size_t pos = 16;
    for (int i = 0; i < 2; i++) {
        uint32_t nsize;
        memcpy(&nsize, f + pos + 136, 4);
        g->meta_len[i] = META + nsize;
        memcpy(g->meta[i], f + pos, g->meta_len[i]);
        g->size[i] = rd64(f + pos);
        pos += g->meta_len[i];
    }
    for (int i = 0; i < 2; i++) {
        uint64_t file_size = rd64(g->meta[i] + 8), zsize = rd64(f + pos);
        g->buf[i] = cv_xmalloc(g->size[i]);
        uLongf n = (uLongf)g->size[i];
        if (uncompress(g->buf[i], &n, f + pos + 8, (uLong)zsize) != Z_OK || n != g->size[i])
            return false;
        pos += file_size;
    }
    return pos == len;
}

/* The grids written again with codec 0 (none) or 2 (BLOSC); *len bytes. */
static unsigned char *repack(const struct grids *g, unsigned codec, size_t *len)
{
    unsigned char *blob[2];
    size_t blen[2];
    for (int i = 0; i < 2; i++) {
        if (codec == 0) {
            blen[i] = g->size[i];
            blob[i] = cv_xmalloc(blen[i]);
            memcpy(blob[i], g->buf[i], blen[i]);
        } else {
            blob[i] = cv_xmalloc(g->size[i] + BLOSC_MAX_OVERHEAD + 8);
            int n = blosc_compress_ctx(9, 1, sizeof(float), g->size[i], g->buf[i], blob[i] + 8,
                                       g->size[i] + BLOSC_MAX_OVERHEAD, "lz4", 1 << 18, 1);
            wr64(blob[i], (uint64_t)(n > 0 ? n : 0));
            blen[i] = 8 + (size_t)(n > 0 ? n : 0);
        }
    }
    size_t total = 16 + g->meta_len[0] + g->meta_len[1] + blen[0] + blen[1], pos = 0;
    unsigned char *out = cv_xmalloc(total);
    memcpy(out, g->head, 16);
    uint16_t c16 = (uint16_t)codec;
    memcpy(out + 14, &c16, 2);
    pos = 16;
    for (int i = 0; i < 2; i++) {
        memcpy(out + pos, g->meta[i], g->meta_len[i]);
        wr64(out + pos + 8, blen[i]);
        memcpy(out + pos + 168, &c16, 2);
        pos += g->meta_len[i];
    }
    for (int i = 0; i < 2; i++) {
        memcpy(out + pos, blob[i], blen[i]);
        pos += blen[i];
        free(blob[i]);
    }
    *len = total;
    return out;
}

/* The density grid of file rel in th_dir matches the formula. */
static void check_density(const char *rel, const char *desc)
{
    struct cv_nvdb_grid g;
    struct cv_error err = {{0}};
    bool found = false;
    if (!tap_ok(cv_nvdb_read(th_path(rel), "density", &g, &found, &err) && found,
                "%s: density read: %s", desc, err.msg))
        return;
    bool box = g.index_lo[0] == 3 && g.index_lo[1] == 5 && g.index_lo[2] == 2 &&
               g.index_hi[0] == 14 && g.index_hi[1] == 14 && g.index_hi[2] == 9;
    tap_ok(box, "%s: index bounds (3 5 2)-(14 14 9): (%d %d %d)-(%d %d %d)", desc, g.index_lo[0],
           g.index_lo[1], g.index_lo[2], g.index_hi[0], g.index_hi[1], g.index_hi[2]);
    tap_ok(fabs(g.map[0][0] - 0.15) < 1e-12 && fabs(g.map[1][3] + 0.5) < 1e-12 &&
               fabs(g.world_lo[0] - (-1.3 + 0.45)) < 1e-9 &&
               fabs(g.world_hi[1] - (-0.5 + 0.15 * 15)) < 1e-9,
           "%s: map (voxel 0.15, origin -1.3 -0.5 -0.8) and world bounds", desc);
    /* every voxel of the box and a shell around it */
    const int32_t lo[3] = {1, 3, 0};
    const uint32_t n[3] = {16, 14, 12};
    float *v = cv_xmalloc(16 * 14 * 12 * sizeof(float));
    cv_nvdb_fill(&g, lo, n, v);
    double worst = 0;
    int holes = 0;
    for (uint32_t z = 0; z < n[2]; z++)
        for (uint32_t y = 0; y < n[1]; y++)
            for (uint32_t x = 0; x < n[0]; x++) {
                int i = lo[0] + (int)x, j = lo[1] + (int)y, k = lo[2] + (int)z;
                double want = density_of(i, j, k);
                float got = v[(z * n[1] + y) * n[0] + x];
                worst = fmax(worst, fabs(got - want));
                holes += want == 0 && i >= 3 && i <= 14 && j >= 5 && j <= 14 && k >= 2 && k <= 9;
            }
    tap_ok(worst < 6e-5 && holes > 0,
           "%s: all voxels in and around the box are the generator's (worst %g, %d holes read 0)",
           desc, worst, holes);
    tap_ok(cv_nvdb_value(&g, 8, 9, 5) == v[((5 - 0) * 14 + (9 - 3)) * 16 + (8 - 1)] &&
               cv_nvdb_value(&g, -4000, 9, 5) == 0 && cv_nvdb_value(&g, 8, 9, 100000) == 0,
           "%s: single lookups, far outside the tree the background 0", desc);
    free(v);
    cv_nvdb_free(&g);
}

static void write_scene_with(const char *nvdb, const char *extra, char *text, size_t cap)
{
    snprintf(text, cap,
             "WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"nanovdb\"\n"
             "  \"string filename\" \"%s\"%s\n", nvdb, extra);
}

static void fails(const char *nvdb, const char *extra, const char *expect, const char *desc)
{
    char text[1024];
    write_scene_with(nvdb, extra, text, sizeof(text));
    struct cv_error err = {{0}};
    struct cv_scene *s = th_load(text, false, &err);
    tap_ok(!s && strstr(err.msg, expect) != NULL && strstr(err.msg, "main.pbrt:2:1: medium \"g\""),
           "%s fails at the statement with \"%s\": %s", desc, expect, err.msg);
    cv_scene_destroy(&s);
}

int main(void)
{
    th_init();
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/oracle/vol_nanovdb.nvdb", dir ? dir : "tests/data");
    struct cv_error err = {{0}};
    char *bytes = NULL;
    size_t len = 0;
    if (!tap_ok(cv_read_file(path, &bytes, &len, &err), "read %s: %s", path, err.msg))
        return tap_done();
    const unsigned char *file = (const unsigned char *)bytes;
    struct grids g;
    memset(&g, 0, sizeof(g));
    if (!tap_ok(unpack(file, len, &g), "the committed file is two ZIP-compressed grids"))
        return tap_done();

    /* ---- the same grids in three codecs ---- */
    th_write("zip.nvdb", file, len);
    size_t raw_len, blosc_len;
    unsigned char *raw = repack(&g, 0, &raw_len), *blosc = repack(&g, 2, &blosc_len);
    th_write("raw.nvdb", raw, raw_len);
    th_write("blosc.nvdb", blosc, blosc_len);
    check_density("zip.nvdb", "ZIP");
    check_density("raw.nvdb", "uncompressed");
    check_density("blosc.nvdb", "BLOSC");
    {
        struct cv_nvdb_grid t;
        bool found = false;
        bool ok = cv_nvdb_read(th_path("raw.nvdb"), "temperature", &t, &found, &err) && found;
        tap_ok(ok && t.index_lo[1] == 9 && t.index_hi[1] == 16 &&
                   fabs(cv_nvdb_value(&t, 6, 9, 4) - (2600 + 260 * ((6 + 18 + 4) % 5))) < 1e-3,
               "the second grid, temperature, is found after the first: %s", err.msg);
        cv_nvdb_free(&t);
        ok = cv_nvdb_read(th_path("raw.nvdb"), "smoke", &t, &found, &err);
        tap_ok(ok && !found && t.words == NULL, "a name the file lacks is not found, no error");
    }

    /* ---- the medium ---- */
    {
        char text[1024];
        write_scene_with("raw.nvdb", " \"rgb sigma_s\" [2 2 2] \"float scale\" 0.5 "
                                     "\"float Lescale\" 0.3", text, sizeof(text));
        struct cv_scene *s = th_load(text, false, &err);
        if (tap_ok(s && s->n_media == 2, "the oracle's file makes a nanovdb medium: %s",
                   err.msg)) {
            const CvMedium *m = &s->media[1];
            tap_ok(m->type == CV_MEDIUM_NANOVDB && m->res.x == 13 && m->res.y == 13 &&
                       m->res.z == 9 && m->grids.x == m->grids.y && m->grids.z == CV_NO_GRID &&
                       m->temperature_grids.x != CV_NO_GRID && m->emissive &&
                       fabs(m->Le.x - 0.3) < 1e-6 && fabs(m->sigma_s.x - 1) < 1e-6 &&
                       fabs(m->sigma_a.x - 0.5) < 1e-6,
                   "its lattice spans the union of both grids' voxels lo .. hi + 1 (13x13x9); "
                   "sigma times scale; Lescale emits through the temperature grid");
            /* lattice sample (x, y, z) is voxel lo + (x, y, z); the voxel's
             * world point maps to (x, y, z) / (res - 1) */
            int x = 5, y = 4, z = 3;
            float got = s->medium_grids[m->grids.x + (z * 13 + y) * 13 + x];
            double wx = 0.15 * (3 + x) - 1.3, wy = 0.15 * (5 + y) - 0.5, wz = 0.15 * (2 + z) - 0.8;
            const cv_vec4 *r = m->to_grid;
            double gx = r[0].x * wx + r[0].y * wy + r[0].z * wz + r[0].w;
            double gy = r[1].x * wx + r[1].y * wy + r[1].z * wz + r[1].w;
            double gz = r[2].x * wx + r[2].y * wy + r[2].z * wz + r[2].w;
            tap_ok(fabs(got - density_of(3 + x, 5 + y, 2 + z)) < 6e-5 &&
                       fabs(gx - x / 12.0) < 1e-5 && fabs(gy - y / 12.0) < 1e-5 &&
                       fabs(gz - z / 8.0) < 1e-5,
                   "a voxel's value and place in the lattice (%g; g %g %g %g)", got, gx, gy, gz);
        }
        cv_scene_destroy(&s);
        write_scene_with("raw.nvdb", " \"string temperaturename\" \"none\"", text, sizeof(text));
        s = th_load(text, false, &err);
        tap_ok(s && s->media[1].res.y == 11 && !s->media[1].emissive &&
                   s->media[1].temperature_grids.x == CV_NO_GRID,
               "without a temperature grid: the density's bounds alone, no emission: %s",
               err.msg);
        cv_scene_destroy(&s);
    }

    /* ---- broken files ---- */
    size_t cuts[] = {10, 16 + 100, 16 + 176 + 3, raw_len / 2, raw_len - 1};
    for (size_t i = 0; i < sizeof(cuts) / sizeof(cuts[0]); i++) {
        th_write("cut.nvdb", raw, cuts[i]);
        char what[64];
        snprintf(what, sizeof(what), "a file cut at byte %zu", cuts[i]);
        fails("cut.nvdb", "", "truncated", what);
    }
    {
        unsigned char *bad = cv_xmalloc(raw_len);
        memcpy(bad, raw, raw_len);
        bad[3] = 'X';
        th_write("magic.nvdb", bad, raw_len);
        fails("magic.nvdb", "", "not a NanoVDB file", "a wrong magic number");
        /* metadata type Vec3f (6) */
        memcpy(bad, raw, raw_len);
        bad[16 + 32] = 6;
        th_write("vec3.nvdb", bad, raw_len);
        fails("vec3.nvdb", "", "grid \"density\" holds Vec3f values; only float grids are read",
              "a Vec3f density grid");
        /* the buffer's own type double (2): caught after decoding */
        memcpy(bad, raw, raw_len);
        size_t grid0 = 16 + g.meta_len[0] + g.meta_len[1];
        bad[grid0 + 636] = 2;
        th_write("double.nvdb", bad, raw_len);
        fails("double.nvdb", "", "holds double values", "a grid buffer of doubles");
        /* a level set */
        memcpy(bad, raw, raw_len);
        bad[grid0 + 632] = 1;
        th_write("ls.nvdb", bad, raw_len);
        fails("ls.nvdb", "", "is a level set; a medium reads fog volumes", "a level set");
        /* root bounds damaged to span more than 2^32 voxels */
        memcpy(bad, raw, raw_len);
        int32_t far = -2000000000;
        memcpy(bad + grid0 + 672 + 64, &far, 4);
        th_write("huge.nvdb", bad, raw_len);
        fails("huge.nvdb", "", "and a scene's grid media address at most 4294967295 floats",
              "bounds over 2^32 voxels");
        /* bounds damaged to span more than 2^26 samples (the old limit
         * of a nanovdb medium): the lattice is copied whole, its voxels
         * in place; the GPU's limit is checked at upload
         * (tests/trace/medium_grid_store_test.c) */
        memcpy(bad, raw, raw_len);
        int32_t wide = -680000;
        memcpy(bad + grid0 + 672 + 64, &wide, 4);
        th_write("wide.nvdb", bad, raw_len);
        {
            char text[1024];
            write_scene_with("wide.nvdb", " \"string temperaturename\" \"none\"", text,
                             sizeof(text));
            struct cv_scene *s = th_load(text, false, &err);
            const CvMedium *m = s ? &s->media[1] : NULL;
            size_t nx = 14 + 1 - (size_t)wide + 1;
            int x = 5 - wide, y = 4, z = 3;
            tap_ok(m && m->res.x == nx && m->res.y == 11 && m->res.z == 9 &&
                       (double)nx * 11 * 9 > (1u << 26) &&
                       fabs(s->medium_grids[m->grids.x + ((size_t)z * 11 + y) * nx + x] -
                            density_of(5, 5 + y, 2 + z)) < 6e-5 &&
                       s->medium_grids[m->grids.x + ((size_t)z * 11 + y) * nx + 7] == 0,
                   "bounds of %zu x 11 x 9 samples, over 2^26, are copied whole, the voxels in "
                   "place: %s", nx, err.msg);
            cv_scene_destroy(&s);
        }
        /* codec 7 */
        memcpy(bad, raw, raw_len);
        bad[14] = 7;
        th_write("codec.nvdb", bad, raw_len);
        fails("codec.nvdb", "", "unknown compression codec 7", "an unknown codec");
        free(bad);
        /* damaged ZIP data */
        bad = cv_xmalloc(len);
        memcpy(bad, file, len);
        bad[16 + g.meta_len[0] + g.meta_len[1] + 8 + 40] ^= 0x5a;
        th_write("zipbad.nvdb", bad, len);
        fails("zipbad.nvdb", "", "ZIP data does not inflate", "damaged ZIP data");
        free(bad);
    }
    {
        /* random damage to the framing, the grid's header, tree and root
         * and anywhere: a clean error or a grid whose lookups stay inside
         * its buffer (run under valgrind to see the latter) */
        uint32_t seed = 99;
        unsigned char *bad = cv_xmalloc(raw_len);
        size_t grid0 = 16 + g.meta_len[0] + g.meta_len[1];
        int errors = 0, read = 0;
        for (int it = 0; it < 300; it++) {
            memcpy(bad, raw, raw_len);
            for (int k = 0; k < 1 + it % 4; k++) {
                seed = seed * 1664525u + 1013904223u;
                size_t where = (seed >> 8) % 3 == 0   ? (seed >> 12) % grid0
                               : (seed >> 8) % 3 == 1 ? grid0 + (seed >> 12) % 2048
                                                      : (seed >> 12) % raw_len;
                seed = seed * 1664525u + 1013904223u;
                bad[where] = (unsigned char)(seed >> 24);
            }
            th_write("fuzz.nvdb", bad, raw_len);
            struct cv_nvdb_grid fg;
            bool found = false;
            struct cv_error e2 = {{0}};
            if (cv_nvdb_read(th_path("fuzz.nvdb"), "density", &fg, &found, &e2) && found) {
                float v[64];
                const uint32_t n4[3] = {4, 4, 4};
                cv_nvdb_fill(&fg, fg.index_lo, n4, v);
                read++;
            } else {
                errors += e2.msg[0] != '\0';
            }
            cv_nvdb_free(&fg);
        }
        tap_ok(errors > 0 && read > 0,
               "300 randomly damaged files: %d clean errors, %d grids read and sampled", errors,
               read);
        free(bad);
    }
    fails("raw.nvdb", " \"string gridname\" \"smoke\"", "raw.nvdb has no grid \"smoke\"",
          "a missing density grid");
    fails("nothere.nvdb", "", "nothere.nvdb", "a missing file");
    {
        struct cv_error e2 = {{0}};
        struct cv_scene *s =
            th_load("WorldBegin\nMakeNamedMedium \"g\" \"string type\" \"nanovdb\"\n", false, &e2);
        tap_ok(!s && strstr(e2.msg, "main.pbrt:2:1: medium \"g\": a nanovdb medium needs "
                                    "\"string filename\""),
               "no filename: %s", e2.msg);
        cv_scene_destroy(&s);
    }

    free(raw);
    free(blosc);
    free(g.buf[0]);
    free(g.buf[1]);
    free(bytes);
    free(path);
    th_cleanup();
    return tap_done();
}
