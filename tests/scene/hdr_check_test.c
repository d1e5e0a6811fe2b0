/* hdr_check_test.c: Radiance .hdr files through cv_image_load. A good
 * run-length encoded file decodes to its RGBE values; every truncation of
 * it, and runs of length 0 or longer than the scanline, are refused with a
 * message instead of decoding forever (Debian's stb_image never returns
 * from a run count of 0: alarm() turns such a hang into a failure). */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "scene/image.h"
#include "tests/tap.h"

#define W 8
#define H 2

static const char *head = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n";

/* Scanline 0: one run per channel (R 100, G 120, B 140, E 129); scanline 1:
 * literal bytes (R 16i, G 16i+1, B 16i+2, E 128). */
static size_t good_file(unsigned char *b)
{
    size_t l = strlen(head);
    memcpy(b, head, l);
    for (int j = 0; j < H; j++) {
        memcpy(b + l, (unsigned char[4]){2, 2, 0, W}, 4);
        l += 4;
        for (int k = 0; k < 4; k++) {
            if (j == 0) {
                b[l++] = 128 + W;
                b[l++] = (unsigned char)(k == 3 ? 129 : 100 + 20 * k);
            } else {
                b[l++] = W;
                for (int i = 0; i < W; i++)
                    b[l++] = (unsigned char)(k == 3 ? 128 : 16 * i + k);
            }
        }
    }
    return l;
}

static const char *path(void)
{
    static char p[64];
    if (!p[0])
        snprintf(p, sizeof(p), "hdr_check_test.%ld.hdr", (long)getpid());
    return p;
}

static bool load(const unsigned char *b, size_t n, struct cv_image *img, struct cv_error *err)
{
    FILE *f = fopen(path(), "wb");
    if (!f || fwrite(b, 1, n, f) != n || fclose(f) != 0)
        return false;
    return cv_image_load(path(), false, img, err);
}

static void on_alarm(int sig)
{
    (void)sig;
    static const char msg[] = "not ok - cv_image_load did not return (hang)\n";
    write(1, msg, sizeof(msg) - 1);
    _exit(1);
}

int main(void)
{
    signal(SIGALRM, on_alarm);
    alarm(60);
    unsigned char b[256];
    size_t n = good_file(b);
    struct cv_image img;
    struct cv_error err = {0};
    bool ok = load(b, n, &img, &err);
    tap_ok(ok, "run-length encoded 8x2 file loads%s%s", ok ? "" : ": ", ok ? "" : err.msg);
    if (ok) {
        /* RGBE as stb_image reads it: byte * 2^(E - 136); E 129: 2^-7, E 128: 2^-8 */
        bool same = img.width == W && img.height == H;
        for (int i = 0; same && i < W; i++) {
            same = fabsf(img.rgba[4 * i] - 100.0f / 128) < 1e-3f &&
                   fabsf(img.rgba[4 * i + 2] - 140.0f / 128) < 1e-3f &&
                   fabsf(img.rgba[4 * (W + i) + 1] - (16 * i + 1.0f) / 256) < 1e-3f;
        }
        tap_ok(same, "decoded RGBE values of both scanlines");
        cv_image_free(&img);
    }
    size_t head_len = strlen(head), refused = 0, cases = 0;
    for (size_t cut = head_len; cut < n; cut++, cases++) {
        cv_error_clear(&err);
        if (!load(b, cut, &img, &err) && err.msg[0])
            refused++;
        else if (err.msg[0] == 0)
            cv_image_free(&img);
    }
    tap_ok(refused == cases, "every truncation of the pixel data is refused (%zu of %zu)", refused, cases);
    unsigned char z[256];
    memcpy(z, b, n);
    z[head_len + 4] = 0; /* scanline 0, red: a run count of 0 */
    cv_error_clear(&err);
    ok = load(z, n, &img, &err);
    tap_ok(!ok && strstr(err.msg, "run-length"), "a run of length 0 is refused: %s", err.msg);
    memcpy(z, b, n);
    z[head_len + 4] = 128 + W + 1; /* a run past the scanline's end */
    cv_error_clear(&err);
    ok = load(z, n, &img, &err);
    tap_ok(!ok && strstr(err.msg, "run-length"), "a run past the scanline is refused: %s", err.msg);
    unlink(path());
    return tap_done();
}
