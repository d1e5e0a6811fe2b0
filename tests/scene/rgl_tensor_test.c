/* rgl_tensor_test.c: the RGL tensor reader (src/scene/rgl_tensor.c) and
 * the measured BRDF tables built from it (src/scene/measured.c), on
 * tests/data/trace/oracle/measured_ggx.bsdf (make_measured.py) and on
 * broken copies of it:
 * - the file reads, with the fields and shapes make_measured.py wrote,
 *   and its tables lay out as glsl/shared/measured.h says;
 * - every truncation of it (each length from 0 to its size less one) is
 *   an error naming the file, never a read past the end (run under ASan
 *   or valgrind to see it), as the texture loaders' fuzz tests;
 * - a fixed-seed mutation run over its header and field table: no crash,
 *   and each failure names the file;
 * - wrong header, version, type, a missing field and a shape that does not
 *   fit give errors that say so;
 * - in a scene: Material "measured" loads the file once for two
 *   materials, warns about nothing, and a truncated or missing file is an
 *   error at the directive's file:line:col. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "base/file.h"
#include "base/mem.h"
#include "glsl/shared/measured.h"
#include "scene/measured.h"
#include "scene/rgl_tensor.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

#define MUTATIONS 3000

static bool starts_with(const char *s, const char *prefix) { return strncmp(s, prefix, strlen(prefix)) == 0; }

/* parse (and, when that succeeds, build the tables of) bytes as "t.bsdf" */
static bool try_bytes(const unsigned char *b, size_t len, struct cv_error *err)
{
    struct cv_tensor_file t;
    if (!cv_tensor_parse("t.bsdf", b, len, &t, err))
        return false;
    uint32_t *block = NULL;
    size_t n = 0;
    bool ok = cv_measured_tables("t.bsdf", &t, &block, &n, err);
    free(block);
    cv_tensor_free(&t);
    return ok;
}

/* the first place in b where the n bytes of what appear, or NULL */
static unsigned char *find_bytes(unsigned char *b, size_t len, const char *what, size_t n)
{
    for (size_t i = 0; i + n <= len; i++)
        if (memcmp(b + i, what, n) == 0)
            return b + i;
    return NULL;
}

static uint64_t rng_state = 20261126;
static uint32_t rng(void)
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(rng_state >> 33);
}

int main(void)
{
    th_init();
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/oracle/measured_ggx.bsdf", dir ? dir : "tests/data");
    struct cv_error err = {{0}};
    char *bytes = NULL;
    size_t len = 0;
    if (!tap_ok(cv_read_file(path, &bytes, &len, &err), "read %s: %s", path, err.msg))
        return tap_done();
    const unsigned char *file = (const unsigned char *)bytes;

    /* ---- the good file ---- */
    struct cv_tensor_file t;
    bool ok = cv_tensor_load(path, &t, &err);
    tap_ok(ok, "loads: %s", err.msg);
    if (ok) {
        static const struct {
            const char *name;
            enum cv_tensor_type type;
            uint32_t ndim;
            uint64_t shape[5];
        } want[] = {
            {"description", CV_TENSOR_U8, 1, {0}},
            {"jacobian", CV_TENSOR_U8, 1, {1}},
            {"theta_i", CV_TENSOR_F32, 1, {6}},
            {"phi_i", CV_TENSOR_F32, 1, {1}},
            {"wavelengths", CV_TENSOR_F32, 1, {8}},
            {"ndf", CV_TENSOR_F32, 2, {16, 16}},
            {"sigma", CV_TENSOR_F32, 2, {16, 16}},
            {"vndf", CV_TENSOR_F32, 4, {1, 6, 16, 16}},
            {"luminance", CV_TENSOR_F32, 4, {1, 6, 12, 12}},
            {"spectra", CV_TENSOR_F32, 5, {1, 6, 8, 12, 12}},
        };
        int good = 0;
        for (size_t i = 0; i < CV_ARRAY_SIZE(want); i++) {
            const struct cv_tensor_field *f = cv_tensor_field(&t, want[i].name);
            bool same = f && f->type == want[i].type && f->ndim == want[i].ndim;
            for (uint32_t d = 0; same && d < f->ndim; d++)
                same = want[i].shape[d] == 0 || f->shape[d] == want[i].shape[d];
            good += same;
        }
        const struct cv_tensor_field *th = cv_tensor_field(&t, "theta_i");
        tap_ok(t.n_fields == 11 && good == (int)CV_ARRAY_SIZE(want) && th && cv_tensor_f32(th, 0) == 0 &&
                   fabsf(cv_tensor_f32(th, 5) - 1.5707964f) < 1e-6f,
               "fields, types and shapes as make_measured.py wrote them (%zu fields, %d of %zu match)", t.n_fields,
               good, CV_ARRAY_SIZE(want));
        uint32_t *block = NULL;
        size_t n = 0;
        ok = cv_measured_tables(path, &t, &block, &n, &err);
        tap_ok(ok, "tables: %s", err.msg);
        if (ok) {
            /* six VNDF and LUM slices, 18 colour slices: the arrays fit the
             * block and the VNDF's marginal CDFs end at 1 */
            bool fits = block[CV_MEAS_H_ISOTROPIC] == 1 && block[CV_MEAS_H_NPHI] == 1 && block[CV_MEAS_H_NTHETA] == 6;
            float last = 0;
            for (unsigned k = 0; k < CV_MEAS_TABLES; k++) {
                const uint32_t *h = block + CV_MEAS_H_WARPS + k * CV_MEAS_W_WORDS;
                size_t slices = k == CV_MEAS_RGB ? 18 : (k >= CV_MEAS_VNDF ? 6 : 1);
                fits = fits && h[CV_MEAS_W_DATA] + slices * h[CV_MEAS_W_NX] * h[CV_MEAS_W_NY] <= n;
                if (k == CV_MEAS_VNDF)
                    memcpy(&last, block + h[CV_MEAS_W_MARGINAL] + 6 * h[CV_MEAS_W_NY] - 1, 4);
            }
            tap_ok(fits && fabsf(last - 1) < 1e-6f, "table layout (%zu words, last marginal %.7f)", n, last);
        }
        free(block);
        cv_tensor_free(&t);
    }

    /* ---- every truncation ---- */
    size_t failed = 0, named = 0;
    char first_msg[256] = "";
    for (size_t l = 0; l < len; l++) {
        struct cv_error e = {{0}};
        if (!try_bytes(file, l, &e)) {
            failed++;
            named += starts_with(e.msg, "t.bsdf: ");
            if (l == len / 2)
                snprintf(first_msg, sizeof(first_msg), "%.200s", e.msg);
        }
    }
    tap_ok(failed == len && named == len, "all %zu truncations fail (%zu), naming the file (%zu); at half: %s", len,
           failed, named, first_msg);

    /* ---- mutations of the header and the field table ---- */
    {
        unsigned char *m = malloc(len);
        size_t table_end = 0;
        struct cv_tensor_file tt;
        if (cv_tensor_parse("t.bsdf", file, len, &tt, &err)) {
            table_end = len;
            for (size_t i = 0; i < tt.n_fields; i++)
                table_end = tt.fields[i].offset < table_end ? tt.fields[i].offset : table_end;
            cv_tensor_free(&tt);
        }
        size_t fails = 0, unnamed = 0;
        for (int it = 0; it < MUTATIONS; it++) {
            memcpy(m, file, len);
            int flips = 1 + (int)(rng() % 4);
            for (int f = 0; f < flips; f++) {
                size_t at = rng() % (table_end ? table_end : len);
                uint32_t what = rng() % 4;
                m[at] = what == 0 ? 0 : what == 1 ? 0xff : (unsigned char)rng();
            }
            struct cv_error e = {{0}};
            if (!try_bytes(m, len, &e)) {
                fails++;
                unnamed += !starts_with(e.msg, "t.bsdf: ");
            }
        }
        free(m);
        tap_ok(unnamed == 0 && fails > 0, "%d mutations of the header and field table: %zu rejected, none crashed, "
               "%zu errors without the file's name", MUTATIONS, fails, unnamed);
    }

    /* ---- particular damage ---- */
    {
        unsigned char *m = malloc(len);
        struct {
            const char *what;
            size_t at;
            const char *find;  /* replace this name's bytes ... */
            const char *with;  /* ... by these */
            size_t n;          /* bytes of find and with */
            unsigned char byte;
            const char *expect;
        } cases[] = {
            {"header", 0, NULL, NULL, 0, 'x', "not a tensor file"},
            {"version", 12, NULL, NULL, 0, 2, "version 2.0"},
            {"missing field", 0, "\x04\x00vndf", "\x04\x00vndX", 6, 0, "no field \"vndf\""},
            /* name length, name, ndim 1, type code */
            {"wrong type", 0, "\x07\x00theta_i\x01\x00\x0a", "\x07\x00theta_i\x01\x00\x0b", 12, 0,
             "\"theta_i\" is float64"},
            {"unknown type", 0, "\x07\x00theta_i\x01\x00\x0a", "\x07\x00theta_i\x01\x00\x0e", 12, 0,
             "unknown type code 14"},
        };
        for (size_t c = 0; c < CV_ARRAY_SIZE(cases); c++) {
            memcpy(m, file, len);
            if (cases[c].find) {
                unsigned char *at = find_bytes(m, len, cases[c].find, cases[c].n);
                if (at)
                    memcpy(at, cases[c].with, cases[c].n);
            } else {
                m[cases[c].at] = cases[c].byte;
            }
            struct cv_error e = {{0}};
            bool res = try_bytes(m, len, &e);
            tap_ok(!res && strstr(e.msg, cases[c].expect) != NULL, "%s: \"%s\"", cases[c].what, e.msg);
        }
        free(m);
    }

    /* ---- in a scene ---- */
    {
        th_write("good.bsdf", file, len);
        th_write("cut.bsdf", file, len - 100);
        struct cv_error e = {{0}};
        struct cv_scene *s = th_load("WorldBegin\n"
                                     "Material \"measured\" \"string filename\" \"good.bsdf\"\n"
                                     "Shape \"sphere\"\n"
                                     "MakeNamedMaterial \"again\" \"string type\" \"measured\" \"string filename\" \"good.bsdf\"\n"
                                     "NamedMaterial \"again\"\n"
                                     "Shape \"sphere\"\n",
                                     true, &e);
        int measured = 0, at = -2;
        bool shared = true;
        for (uint32_t i = 0; s && i < s->n_materials; i++)
            if (s->materials[i].type == CV_MAT_MEASURED) {
                measured++;
                shared = shared && (at == -2 || s->materials[i].mix_a == at);
                at = s->materials[i].mix_a;
            }
        tap_ok(s && measured == 2 && shared && at == 0 && s->n_measured > CV_MEAS_HEADER_WORDS && s->warnings == 0,
               "scene with two measured materials (strict): %d measured, one block of %zu words, %u warnings %s",
               measured, s ? s->n_measured : 0, s ? s->warnings : 0, e.msg);
        cv_scene_destroy(&s);
        s = th_load("WorldBegin\n\nMaterial \"measured\" \"string filename\" \"cut.bsdf\"\n", false, &e);
        tap_ok(!s && starts_with(e.msg, th_path("main.pbrt")) && strstr(e.msg, ":3:1: measured") &&
                   strstr(e.msg, "cut.bsdf") && strstr(e.msg, "truncated"),
               "truncated file in a scene: %s", e.msg);
        cv_scene_destroy(&s);
        s = th_load("WorldBegin\nMaterial \"measured\" \"string filename\" \"none.bsdf\"\n", false, &e);
        tap_ok(!s && strstr(e.msg, ":2:1: measured \"none.bsdf\""), "missing file: %s", e.msg);
        cv_scene_destroy(&s);
        s = th_load("WorldBegin\nMaterial \"measured\"\n", false, &e);
        tap_ok(!s && strstr(e.msg, ":2:1: measured: \"string filename\""), "no filename: %s", e.msg);
        cv_scene_destroy(&s);
    }

    free(bytes);
    free(path);
    th_cleanup();
    return tap_done();
}
