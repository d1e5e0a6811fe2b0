/* ply_test.c: the PLY reader on every variant it claims (ascii, binary
 * little and big endian, float and double, index types, quads and
 * polygons, normals, uvs, gzip) and on broken files. The files are written
 * by the test itself. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <zlib.h>

#include "scene/ply.h"
#include "tests/scene/scene_helpers.h"
#include "tests/tap.h"

struct buf {
    unsigned char *d;
    size_t n, cap;
};

static void put(struct buf *b, const void *p, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2;
        b->d = realloc(b->d, b->cap);
    }
    memcpy(b->d + b->n, p, n);
    b->n += n;
}

static void puts_(struct buf *b, const char *s) { put(b, s, strlen(s)); }

/* Writes value v as `type` in the given byte order. */
static void put_val(struct buf *b, const char *type, double v, bool big)
{
    unsigned char tmp[8];
    size_t n = 0;
    if (!strcmp(type, "uchar")) { uint8_t x = (uint8_t)v; memcpy(tmp, &x, n = 1); }
    else if (!strcmp(type, "char")) { int8_t x = (int8_t)v; memcpy(tmp, &x, n = 1); }
    else if (!strcmp(type, "ushort")) { uint16_t x = (uint16_t)v; memcpy(tmp, &x, n = 2); }
    else if (!strcmp(type, "short")) { int16_t x = (int16_t)v; memcpy(tmp, &x, n = 2); }
    else if (!strcmp(type, "int")) { int32_t x = (int32_t)v; memcpy(tmp, &x, n = 4); }
    else if (!strcmp(type, "uint")) { uint32_t x = (uint32_t)v; memcpy(tmp, &x, n = 4); }
    else if (!strcmp(type, "float")) { float x = (float)v; memcpy(tmp, &x, n = 4); }
    else if (!strcmp(type, "double")) { memcpy(tmp, &v, n = 8); }
    if (big)
        for (size_t i = 0; i < n / 2; i++) {
            unsigned char t = tmp[i];
            tmp[i] = tmp[n - 1 - i];
            tmp[n - 1 - i] = t;
        }
    put(b, tmp, n);
}

/* A unit square as one quad (or two triangles), with normals and uvs. */
static void make_square(struct buf *b, const char *format, const char *vt, const char *ct,
                        const char *it, bool quads, bool extra)
{
    bool ascii = !strcmp(format, "ascii"), big = !strcmp(format, "binary_big_endian");
    char hdr[1024];
    snprintf(hdr, sizeof(hdr),
             "ply\nformat %s 1.0\ncomment test\nelement vertex 4\nproperty %s x\nproperty %s y\n"
             "property %s z\nproperty %s nx\nproperty %s ny\nproperty %s nz\nproperty %s u\nproperty %s v\n"
             "%selement face %d\nproperty list %s %s vertex_indices\n%send_header\n",
             format, vt, vt, vt, vt, vt, vt, vt, vt, extra ? "property uchar red\n" : "", quads ? 1 : 2, ct, it,
             extra ? "element material 1\nproperty list uchar float params\n" : "");
    puts_(b, hdr);
    double v[4][8] = {{0, 0, 0, 0, 0, 1, 0, 0}, {1, 0, 0, 0, 0, 1, 1, 0}, {1, 1, 0, 0, 0, 1, 1, 1},
                      {0, 1, 0, 0, 0, 1, 0, 1}};
    for (int i = 0; i < 4; i++) {
        for (int k = 0; k < 8; k++) {
            if (ascii) {
                char s[32];
                snprintf(s, sizeof(s), "%g ", v[i][k]);
                puts_(b, s);
            } else {
                put_val(b, vt, v[i][k], big);
            }
        }
        if (extra) {
            if (ascii)
                puts_(b, "7");
            else
                put_val(b, "uchar", 7, big);
        }
        if (ascii)
            puts_(b, "\n");
    }
    int faces[2][4] = {{0, 1, 2, -1}, {0, 2, 3, -1}}, quad[4] = {0, 1, 2, 3};
    for (int f = 0; f < (quads ? 1 : 2); f++) {
        const int *ix = quads ? quad : faces[f];
        int n = quads ? 4 : 3;
        if (ascii) {
            char s[64];
            snprintf(s, sizeof(s), "%d %d %d %d%s%d\n", n, ix[0], ix[1], ix[2], n == 4 ? " " : "", n == 4 ? ix[3] : 0);
            if (n == 3)
                snprintf(s, sizeof(s), "3 %d %d %d\n", ix[0], ix[1], ix[2]);
            puts_(b, s);
        } else {
            put_val(b, ct, n, big);
            for (int k = 0; k < n; k++)
                put_val(b, it, ix[k], big);
        }
    }
    if (extra) {
        if (ascii)
            puts_(b, "2 0.5 0.25\n");
        else {
            put_val(b, "uchar", 2, big);
            put_val(b, "float", 0.5, big);
            put_val(b, "float", 0.25, big);
        }
    }
}

static bool check_square(const struct cv_ply_mesh *m)
{
    if (m->n_verts != 4 || m->n_tris != 2 || !m->N || !m->uv)
        return false;
    if (m->P[3 * 2] != 1 || m->P[3 * 2 + 1] != 1 || m->N[3 * 3 + 2] != 1 || m->uv[2 * 3 + 1] != 1)
        return false;
    /* triangles cover 0..3 and are (0 1 2), (0 2 3) */
    uint32_t want[6] = {0, 1, 2, 0, 2, 3};
    return memcmp(m->idx, want, sizeof(want)) == 0;
}

static void variant(const char *desc, const char *format, const char *vt, const char *ct, const char *it,
                    bool quads, bool extra)
{
    struct buf b = {0};
    make_square(&b, format, vt, ct, it, quads, extra);
    th_write("v.ply", b.d, b.n);
    struct cv_ply_mesh m;
    struct cv_error err = {0};
    bool ok = cv_ply_read(th_path("v.ply"), &m, &err);
    tap_ok(ok && check_square(&m) && m.n_quads == (quads ? 1u : 0u) &&
           (!quads || (m.quad_first && m.quad_first[0] == 0)), "%s%s%s", desc, ok ? "" : ": ", ok ? "" : err.msg);
    if (ok)
        cv_ply_free(&m);
    free(b.d);
}

static void broken(const char *desc, const char *text, size_t len, const char *expect)
{
    struct cv_ply_mesh m;
    struct cv_error err = {0};
    char *copy = malloc(len + 1);
    memcpy(copy, text, len);
    copy[len] = 0;
    bool ok = cv_ply_parse("b.ply", (const unsigned char *)copy, len, &m, &err);
    tap_ok(!ok && strstr(err.msg, expect) != NULL, "%s: %s", desc, err.msg);
    if (ok)
        cv_ply_free(&m);
    free(copy);
}

int main(void)
{
    th_init();
    variant("ascii triangles", "ascii", "float", "uchar", "int", false, false);
    variant("ascii quad", "ascii", "float", "uchar", "int", true, false);
    variant("binary LE float, uchar/int", "binary_little_endian", "float", "uchar", "int", false, false);
    variant("binary LE quad", "binary_little_endian", "float", "uchar", "uint", true, false);
    variant("binary BE float, uchar/int", "binary_big_endian", "float", "uchar", "int", false, false);
    variant("binary BE double, ushort/ushort", "binary_big_endian", "double", "ushort", "ushort", true, false);
    variant("binary LE double, int/char", "binary_little_endian", "double", "int", "char", false, false);
    variant("binary LE short index", "binary_little_endian", "float", "uchar", "short", false, false);
    variant("extra properties and elements skipped (LE)", "binary_little_endian", "float", "uchar", "int", true, true);
    variant("extra properties and elements skipped (BE)", "binary_big_endian", "float", "uchar", "int", true, true);
    variant("extra properties and elements skipped (ascii)", "ascii", "float", "uchar", "int", true, true);

    /* gzip */
    struct buf b = {0};
    make_square(&b, "binary_little_endian", "float", "uchar", "int", true, false);
    gzFile gz = gzopen(th_path("v.ply.gz"), "wb");
    gzwrite(gz, b.d, (unsigned)b.n);
    gzclose(gz);
    struct cv_ply_mesh m;
    struct cv_error err = {0};
    bool ok = cv_ply_read(th_path("v.ply.gz"), &m, &err);
    tap_ok(ok && check_square(&m), "gzip-compressed .ply.gz%s%s", ok ? "" : ": ", ok ? "" : err.msg);
    if (ok)
        cv_ply_free(&m);

    /* a pentagon is fan-split; CRLF header lines */
    const char *pent = "ply\r\nformat ascii 1.0\r\nelement vertex 5\r\nproperty float x\r\nproperty float y\r\n"
                       "property float z\r\nelement face 1\r\nproperty list uchar int vertex_index\r\nend_header\r\n"
                       "0 0 0\n1 0 0\n1 1 0\n0.5 2 0\n0 1 0\n5 0 1 2 3 4\n";
    ok = cv_ply_parse("p.ply", (const unsigned char *)pent, strlen(pent), &m, &err);
    tap_ok(ok && m.n_tris == 3 && !m.N && !m.uv && m.n_polys == 1, "polygon fan split, CRLF, no normals/uvs");
    if (ok)
        cv_ply_free(&m);

    /* truncated binary data */
    b.n -= 5;
    broken("truncated binary", (const char *)b.d, b.n, "data ends");
    free(b.d);
    broken("no magic", "plx\nformat ascii 1.0\nend_header\n", 31, "not a PLY file");
    broken("no end_header", "ply\nformat ascii 1.0\nelement vertex 1\n", 38, "no end_header");
    broken("unknown format", "ply\nformat foo 1.0\nend_header\n", 30, "b.ply:2: unknown PLY format");
    broken("bad property", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quux x\nend_header\n", 65,
           "b.ply:4: bad property line");
    const char *huge = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
                       "property float y\nproperty float z\nend_header\n\1\2\3";
    broken("count larger than the file", huge, strlen(huge), "more than the file holds");
    const char *badidx = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0 1 0 0 0 1 0\n3 0 1 7\n";
    broken("index out of range", badidx, strlen(badidx), "face index 7 out of range");
    const char *badnum = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                         "end_header\n0 zz 0\n";
    broken("bad ascii number", badnum, strlen(badnum), "malformed");
    const char *noxyz = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float q\nend_header\n1\n";
    broken("vertex without x/y/z", noxyz, strlen(noxyz), "no x/y/z");
    th_cleanup();
    return tap_done();
}
