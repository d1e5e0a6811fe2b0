/* exr_write_test.c: EXR files written by cv_exr_write read back through
 * OpenEXR's own C API with the channels, pixel types, attributes and pixel
 * values asked for (within half precision), for every compression; failures
 * mid-write leave nothing behind and keep an older file. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <openexr.h>

#include "base/error.h"
#include "base/mem.h"
#include "output/atomic_file.h"
#include "output/exr_read.h"
#include "output/exr_write.h"
#include "tests/output/output_helpers.h"
#include "tests/rng.h"
#include "tests/tap.h"

#define W 37 /* not a multiple of any chunk height */
#define H 23

static float rgba[W * H * 4], albedo[W * H * 3], normal[W * H * 3], depth[W * H];

static uint32_t rng = 12345;
static float rnd(void)
{
    return (float)cv_test_lcg32(&rng);
}

static void fill(void)
{
    for (int i = 0; i < W * H; i++) {
        for (int c = 0; c < 3; c++) {
            rgba[i * 4 + c] = rnd() * (c == 0 ? 1.0f : c == 1 ? 8.0f : 300.0f);
            albedo[i * 3 + c] = rnd();
            normal[i * 3 + c] = rnd() * 2.0f - 1.0f;
        }
        rgba[i * 4 + 3] = i % 5 == 0 ? 0.0f : 1.0f;
        depth[i] = 1.0f + rnd() * 1000.0f;
    }
}

static bool near_half(float got, float want)
{
    return fabsf(got - want) <= fabsf(want) * (1.0f / 2048.0f) + 6.0e-8f;
}

/* Worst mismatch of n interleaved values against want, as a count of
 * failures under the rule `half` (within half precision) or exact. */
static int mismatches(const float *got, const float *want, size_t n, bool half)
{
    int bad = 0;
    for (size_t i = 0; i < n; i++)
        if (half ? !near_half(got[i], want[i]) : got[i] != want[i])
            bad++;
    return bad;
}

static const struct cv_image_layer layers[] = {
    { .name = "albedo", .n_channels = 3, .channels = { "R", "G", "B" }, .data = albedo },
    { .name = "N", .n_channels = 3, .channels = { "X", "Y", "Z" }, .data = normal,
      .pixel = CV_EXR_PIXEL_HALF },
    { .name = NULL, .n_channels = 1, .channels = { "Z" }, .data = depth,
      .pixel = CV_EXR_PIXEL_FLOAT },
};

static struct cv_metadata *job_meta(void)
{
    struct cv_metadata *m = cv_metadata_new();
    cv_metadata_set_string(m, "scene", "scenes/cornell box.pbrt");
    cv_metadata_set_string(m, "integrator", "path");
    cv_metadata_set_int(m, "spp", 256);
    cv_metadata_set_int(m, "seed", -7);
    cv_metadata_set_float(m, "renderTime", 12.25);
    cv_metadata_set_string(m, "gpu", "Mesa llvmpipe");
    cv_metadata_set_string(m, "job", "shot_010");
    cv_metadata_set_string(m, "jobHash", "9f86d081884c7d65");
    cv_metadata_set_bool(m, "partial", false);
    cv_metadata_set_int(m, "bigCount", 5000000000LL);
    return m;
}

static void test_full(const char *dir)
{
    char *path = cv_xasprintf("%s/full.exr", dir);
    struct cv_metadata *meta = job_meta();
    struct cv_error err = { { 0 } };
    struct cv_exr_params p = {
        .rgba = rgba, .width = W, .height = H, .compression = CV_EXR_ZIP,
        .layers = layers, .n_layers = 3, .meta = meta,
    };
    if (!tap_ok(cv_exr_write(path, &p, &err), "write half RGBA with AOVs and metadata"))
        tap_diag("%s", err.msg);
    TAP_EQ_INT(count_entries(dir), 1, "one file, no temporary");

    exr_context_t ctxt = NULL;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    tap_ok(exr_start_read(&ctxt, path, &init) == EXR_ERR_SUCCESS, "OpenEXR opens it");

    const exr_attr_chlist_t *chl = NULL;
    exr_get_channels(ctxt, 0, &chl);
    static const struct { const char *name; exr_pixel_type_t type; } want[] = {
        { "A", EXR_PIXEL_HALF },   { "B", EXR_PIXEL_HALF },   { "G", EXR_PIXEL_HALF },
        { "N.X", EXR_PIXEL_HALF }, { "N.Y", EXR_PIXEL_HALF }, { "N.Z", EXR_PIXEL_HALF },
        { "R", EXR_PIXEL_HALF },   { "Z", EXR_PIXEL_FLOAT },  { "albedo.B", EXR_PIXEL_HALF },
        { "albedo.G", EXR_PIXEL_HALF }, { "albedo.R", EXR_PIXEL_HALF },
    };
    TAP_EQ_INT(chl ? chl->num_channels : -1, 11, "channel count");
    bool names_ok = chl && chl->num_channels == 11;
    for (int i = 0; names_ok && i < 11; i++) {
        if (strcmp(chl->entries[i].name.str, want[i].name) != 0
            || chl->entries[i].pixel_type != want[i].type) {
            tap_diag("channel %d: %s type %d", i, chl->entries[i].name.str,
                     (int)chl->entries[i].pixel_type);
            names_ok = false;
        }
    }
    tap_ok(names_ok, "channel names and pixel types (RGBA/AOVs half, Z float)");

    exr_compression_t comp;
    tap_ok(exr_get_compression(ctxt, 0, &comp) == EXR_ERR_SUCCESS && comp == EXR_COMPRESSION_ZIP,
           "compression zip");
    exr_attr_box2i_t dw;
    exr_get_data_window(ctxt, 0, &dw);
    tap_ok(dw.min.x == 0 && dw.min.y == 0 && dw.max.x == W - 1 && dw.max.y == H - 1,
           "data window %dx%d", W, H);
    exr_attr_chromaticities_t chroma;
    tap_ok(exr_attr_get_chromaticities(ctxt, 0, "chromaticities", &chroma) == EXR_ERR_SUCCESS
               && chroma.red_x == 0.64f && chroma.red_y == 0.33f && chroma.green_x == 0.30f
               && chroma.green_y == 0.60f && chroma.blue_x == 0.15f && chroma.blue_y == 0.06f
               && chroma.white_x == 0.3127f && chroma.white_y == 0.3290f,
           "chromaticities Rec.709 / D65");
    int32_t len;
    const char *s = NULL;
    tap_ok(exr_attr_get_string(ctxt, 0, "software", &len, &s) == EXR_ERR_SUCCESS
               && len > 8 && strncmp(s, "cavalry ", 8) == 0,
           "software names cavalry and its version");
    tap_ok(exr_attr_get_string(ctxt, 0, "scene", &len, &s) == EXR_ERR_SUCCESS
               && len == (int32_t)strlen("scenes/cornell box.pbrt")
               && memcmp(s, "scenes/cornell box.pbrt", (size_t)len) == 0,
           "scene string");
    int32_t iv = 0;
    tap_ok(exr_attr_get_int(ctxt, 0, "spp", &iv) == EXR_ERR_SUCCESS && iv == 256, "spp int");
    tap_ok(exr_attr_get_int(ctxt, 0, "seed", &iv) == EXR_ERR_SUCCESS && iv == -7, "seed int");
    tap_ok(exr_attr_get_int(ctxt, 0, "partial", &iv) == EXR_ERR_SUCCESS && iv == 0,
           "partial flag as int 0");
    float fv = 0;
    tap_ok(exr_attr_get_float(ctxt, 0, "renderTime", &fv) == EXR_ERR_SUCCESS && fv == 12.25f,
           "renderTime float");
    double dv = 0;
    tap_ok(exr_attr_get_double(ctxt, 0, "bigCount", &dv) == EXR_ERR_SUCCESS
               && dv == 5000000000.0,
           "integer beyond 32 bits stored as double");
    exr_finish(&ctxt);

    char *hash = NULL;
    tap_ok(cv_exr_read_attribute_string(path, "jobHash", &hash, &err)
               && strcmp(hash, "9f86d081884c7d65") == 0,
           "cv_exr_read_attribute_string reads the job hash");
    free(hash);
    tap_ok(!cv_exr_read_attribute_string(path, "nope", &hash, &err) && strstr(err.msg, path)
               && strstr(err.msg, "nope"),
           "missing attribute: %s", err.msg);
    tap_ok(!cv_exr_read_attribute_string(path, "spp", &hash, &err)
               && strstr(err.msg, "not a string"),
           "non-string attribute: %s", err.msg);

    float *px = NULL, *ch = NULL;
    uint32_t w = 0, h = 0;
    tap_ok(cv_exr_read_rgba(path, &px, &w, &h, &err) && w == W && h == H, "read RGBA back");
    TAP_EQ_INT(px ? mismatches(px, rgba, W * H * 4, true) : -1, 0,
               "RGBA equal within half precision");
    free(px);
    tap_ok(cv_exr_read_channel(path, "albedo.G", &ch, &w, &h, &err), "read albedo.G");
    int bad = 0;
    for (int i = 0; ch && i < W * H; i++)
        bad += !near_half(ch[i], albedo[i * 3 + 1]);
    TAP_EQ_INT(bad, 0, "albedo.G within half precision");
    free(ch);
    tap_ok(cv_exr_read_channel(path, "N.Z", &ch, &w, &h, &err), "read N.Z");
    bad = 0;
    for (int i = 0; ch && i < W * H; i++)
        bad += !near_half(ch[i], normal[i * 3 + 2]);
    TAP_EQ_INT(bad, 0, "N.Z within half precision");
    free(ch);
    tap_ok(cv_exr_read_channel(path, "Z", &ch, &w, &h, &err), "read Z");
    TAP_EQ_INT(ch ? mismatches(ch, depth, W * H, false) : -1, 0, "Z exact (float)");
    free(ch);
    tap_ok(!cv_exr_read_channel(path, "Q", &ch, &w, &h, &err) && strstr(err.msg, "\"Q\""),
           "missing channel is an error: %s", err.msg);

    cv_metadata_destroy(&meta);
    unlink(path);
    free(path);
}

static void test_compressions(const char *dir)
{
    static const char *const names[] = { "none", "zip", "zips", "piz", "rle", "dwaa", "dwab" };
    for (size_t i = 0; i < CV_ARRAY_SIZE(names); i++) {
        enum cv_exr_compression c;
        struct cv_error err = { { 0 } };
        bool lossy = strncmp(names[i], "dwa", 3) == 0;
        if (!cv_exr_compression_parse(names[i], &c, &err)) {
            /* Only DWA may be missing, and only with a clear reason. */
            tap_ok(lossy && strstr(err.msg, names[i]) && strstr(err.msg, "3.2"),
                   "%s refused: %s", names[i], err.msg);
            struct cv_exr_params p = { .rgba = rgba, .width = W, .height = H,
                                       .compression = lossy ? (i == 5 ? CV_EXR_DWAA : CV_EXR_DWAB)
                                                            : CV_EXR_ZIP };
            char *path = cv_xasprintf("%s/%s.exr", dir, names[i]);
            tap_ok(!cv_exr_write(path, &p, &err) && count_entries(dir) == 0,
                   "writing %s refused too, nothing written: %s", names[i], err.msg);
            free(path);
            continue;
        }
        tap_ok(strcmp(cv_exr_compression_name(c), names[i]) == 0, "parse %s", names[i]);
        for (int use_float = 0; use_float < 2; use_float++) {
            char *path = cv_xasprintf("%s/%s-%d.exr", dir, names[i], use_float);
            struct cv_exr_params p = {
                .rgba = rgba, .width = W, .height = H, .compression = c,
                .use_float = use_float,
            };
            bool ok = cv_exr_write(path, &p, &err);
            if (!tap_ok(ok, "write %s %s", names[i], use_float ? "float" : "half"))
                tap_diag("%s", err.msg);
            float *px = NULL;
            uint32_t w = 0, h = 0;
            ok = ok && cv_exr_read_rgba(path, &px, &w, &h, &err) && w == W && h == H;
            if (!ok) {
                tap_ok(false, "read back %s: %s", names[i], err.msg);
            } else if (lossy) {
                double sum = 0;
                for (int k = 0; k < W * H * 4; k++)
                    sum += fabs(px[k] - rgba[k]) / (fabs(rgba[k]) + 1.0);
                tap_ok(sum / (W * H * 4) < 0.05, "%s %s: mean relative error %.4f", names[i],
                       use_float ? "float" : "half", sum / (W * H * 4));
            } else {
                TAP_EQ_INT(mismatches(px, rgba, W * H * 4, !use_float), 0,
                           use_float ? "lossless float exact" : "lossless half within precision");
            }
            free(px);
            unlink(path);
            free(path);
        }
    }
    enum cv_exr_compression c;
    struct cv_error err = { { 0 } };
    tap_ok(!cv_exr_compression_parse("jpeg", &c, &err) && strstr(err.msg, "jpeg"),
           "unknown compression: %s", err.msg);
}

/* Cuts the disk off at several points of a write, the last one inside the
 * chunk offset table OpenEXR writes on finish. */
static void test_failures(const char *dir)
{
    char *path = cv_xasprintf("%s/shot.exr", dir);
    struct cv_metadata *meta = job_meta();
    struct cv_exr_params p = {
        .rgba = rgba, .width = W, .height = H, .compression = CV_EXR_NONE,
        .layers = layers, .n_layers = 3, .meta = meta,
    };
    struct cv_error err = { { 0 } };
    tap_ok(cv_exr_write(path, &p, &err), "reference write");
    struct stat st;
    stat(path, &st);
    long long size = (long long)st.st_size;
    put_file(path, "old image");
    char *v = NULL;
    tap_ok(!cv_exr_read_attribute_string(path, "jobHash", &v, &err) && strstr(err.msg, path),
           "a file that is not EXR: %s", err.msg);

    long long cuts[] = { 0, 10, 300, size / 2, size - 4 };
    for (size_t i = 0; i < CV_ARRAY_SIZE(cuts); i++) {
        p.write_limit = &(struct cv_write_limit){cuts[i], ENOSPC};
        bool ok = cv_exr_write(path, &p, &err);
        p.write_limit = NULL;
        tap_ok(!ok && strstr(err.msg, path) && strstr(err.msg, strerror(ENOSPC)),
               "disk full after %lld of %lld bytes fails: %s", cuts[i], size, err.msg);
        tap_ok(file_is(path, "old image") && count_entries(dir) == 1,
               "old file untouched, no temporary");
    }

    cv_metadata_set_string(meta, "compression", "zip");
    tap_ok(!cv_exr_write(path, &p, &err) && strstr(err.msg, "compression"),
           "metadata clashing with a standard attribute: %s", err.msg);
    cv_metadata_destroy(&meta);
    struct cv_image_layer bad = { .name = "x", .n_channels = 0 };
    p.meta = NULL;
    p.layers = &bad;
    p.n_layers = 1;
    tap_ok(!cv_exr_write(path, &p, &err), "a layer without channels fails: %s", err.msg);
    tap_ok(file_is(path, "old image") && count_entries(dir) == 1,
           "old file untouched, no temporary");

    char *missing = cv_xasprintf("%s/nowhere/shot.exr", dir);
    p.n_layers = 0;
    tap_ok(!cv_exr_write(missing, &p, &err) && strstr(err.msg, missing)
               && strstr(err.msg, strerror(ENOENT)),
           "missing folder: %s", err.msg);
    tap_ok(!cv_exr_read_attribute_string(missing, "x", &(char *){ NULL }, &err)
               && strstr(err.msg, missing),
           "reading a missing file: %s", err.msg);
    free(missing);
    unlink(path);
    free(path);
}

int main(void)
{
    fill();
    char *dir = scratch_dir("exr");
    test_full(dir);
    test_compressions(dir);
    test_failures(dir);
    remove_scratch(dir);
    return tap_done();
}
