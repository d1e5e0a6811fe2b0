/* hdr_check.c: see hdr_check.h. It follows stb_image's reading order
 * (header lines up to an empty one, then "-Y H +X W", then scanlines that
 * are flat when W < 8, W >= 32768 or the first does not start 2 2, and
 * run-length encoded per channel otherwise). */
#include <stdlib.h>
#include <string.h>

#include "scene/hdr_check.h"

struct reader {
    const unsigned char *p, *end;
};

/* The next line without its '\n'; false at the end of the data. */
static bool next_line(struct reader *r, const char **line, size_t *n)
{
    if (r->p >= r->end)
        return false;
    const unsigned char *nl = memchr(r->p, '\n', (size_t)(r->end - r->p));
    if (!nl)
        return false;
    *line = (const char *)r->p;
    *n = (size_t)(nl - r->p);
    r->p = nl + 1;
    return true;
}

static bool parse_size(const char *s, size_t n, long *w, long *h)
{
    char buf[64];
    if (n >= sizeof(buf))
        return false;
    memcpy(buf, s, n);
    buf[n] = 0;
    char *e;
    if (strncmp(buf, "-Y ", 3) != 0)
        return false;
    *h = strtol(buf + 3, &e, 10);
    if (strncmp(e, " +X ", 4) != 0)
        return false;
    *w = strtol(e + 4, &e, 10);
    return *w > 0 && *h > 0;
}

/* One run-length encoded scanline of w pixels, its 4-byte marker read. */
static bool rle_scanline(struct reader *r, long w)
{
    for (int k = 0; k < 4; k++) {
        for (long i = 0; i < w;) {
            if (r->p >= r->end)
                return false;
            int count = *r->p++;
            size_t bytes = 1;
            if (count > 128)
                count -= 128;
            else
                bytes = (size_t)count;
            if (count == 0 || count > w - i || (size_t)(r->end - r->p) < bytes)
                return false;
            r->p += bytes;
            i += count;
        }
    }
    return true;
}

bool cv_hdr_check(const char *path, const unsigned char *data, size_t len, struct cv_error *err)
{
    struct reader r = {data, data + len};
    const char *line;
    size_t n;
    do {
        if (!next_line(&r, &line, &n))
            return cv_fail(err, "%s: Radiance HDR header has no end", path);
    } while (n > 0);
    long w, h;
    if (!next_line(&r, &line, &n) || !parse_size(line, n, &w, &h))
        return cv_fail(err, "%s: Radiance HDR size is not \"-Y height +X width\"", path);
    size_t flat = (size_t)w * (size_t)h * 4;
    if (w < 8 || w >= 32768)
        goto flat;
    for (long j = 0; j < h; j++) {
        if (r.end - r.p < 4)
            return cv_fail(err, "%s: Radiance HDR data ends at scanline %ld of %ld", path, j, h);
        const unsigned char *m = r.p;
        if (m[0] != 2 || m[1] != 2 || (m[2] & 0x80)) {
            if (j == 0)
                goto flat; /* stb reads the whole image flat */
            return cv_fail(err, "%s: Radiance HDR scanline %ld is not run-length encoded", path, j);
        }
        if (((long)m[2] << 8 | m[3]) != w)
            return cv_fail(err, "%s: Radiance HDR scanline %ld has the wrong length", path, j);
        r.p += 4;
        if (!rle_scanline(&r, w))
            return cv_fail(err, "%s: bad run-length data in Radiance HDR scanline %ld", path, j);
    }
    return true;
flat:
    if ((size_t)(r.end - r.p) < flat)
        return cv_fail(err, "%s: Radiance HDR data is shorter than %ld x %ld pixels", path, w, h);
    return true;
}
