/* plot.c: draws convergence curves (error against time) as a log-log line
 * plot in a PNG, so that integrators can be compared without gnuplot. Each
 * input CSV is one series; the first line is a header naming the columns and
 * --x/--y pick two of them by name. Text uses a built-in 5x7 pixel font. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <png.h>

/* ---- 5x7 font: 7 rows per glyph, bit 4 is the leftmost pixel ---- */

struct glyph {
    char c;
    unsigned char rows[7];
};

static const struct glyph font[] = {
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}},
    {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}},
    {'3', {0x1f, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}},
    {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x06, 0x08, 0x10, 0x1e, 0x11, 0x11, 0x0e}},
    {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}},
    {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x02, 0x0c}},
    {'A', {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'B', {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}},
    {'C', {0x0e, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0e}},
    {'D', {0x1c, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1c}},
    {'E', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}},
    {'F', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}},
    {'G', {0x0e, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0f}},
    {'H', {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'I', {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}},
    {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}},
    {'Q', {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}},
    {'R', {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}},
    {'S', {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}},
    {'T', {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0a}},
    {'X', {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0a, 0x04, 0x04, 0x04}},
    {'Z', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}},
    {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}},
    {',', {0x00, 0x00, 0x00, 0x00, 0x0c, 0x04, 0x08}},
    {':', {0x00, 0x0c, 0x0c, 0x00, 0x0c, 0x0c, 0x00}},
    {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}},
    {'+', {0x00, 0x04, 0x04, 0x1f, 0x04, 0x04, 0x00}},
    {'_', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1f}},
    {'/', {0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'[', {0x0e, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0e}},
    {']', {0x0e, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0e}},
    {'=', {0x00, 0x00, 0x1f, 0x00, 0x1f, 0x00, 0x00}},
    {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'^', {0x04, 0x0a, 0x11, 0x00, 0x00, 0x00, 0x00}},
    {'#', {0x0a, 0x0a, 0x1f, 0x0a, 0x1f, 0x0a, 0x0a}},
};

static const unsigned char *glyph_rows(char c)
{
    c = (char)toupper((unsigned char)c);
    for (size_t i = 0; i < sizeof font / sizeof font[0]; i++)
        if (font[i].c == c)
            return font[i].rows;
    return NULL;   /* space and anything unknown draw nothing */
}

/* ---- canvas ---- */

struct canvas {
    int w, h;
    unsigned char *rgb;
};

static void px(struct canvas *cv, int x, int y, const unsigned char col[3])
{
    if (x < 0 || y < 0 || x >= cv->w || y >= cv->h)
        return;
    memcpy(cv->rgb + 3 * ((size_t)y * cv->w + x), col, 3);
}

static void rect(struct canvas *cv, int x0, int y0, int x1, int y1, const unsigned char col[3])
{
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++)
            px(cv, x, y, col);
}

/* Line of the given thickness (Bresenham with a square brush). */
static void line(struct canvas *cv, int x0, int y0, int x1, int y1, int thick,
                 const unsigned char col[3])
{
    int dx = abs(x1 - x0), dy = -abs(y1 - y0);
    int sx = x0 < x1 ? 1 : -1, sy = y0 < y1 ? 1 : -1, e = dx + dy;
    int r = thick / 2;
    for (;;) {
        rect(cv, x0 - r, y0 - r, x0 - r + thick - 1, y0 - r + thick - 1, col);
        if (x0 == x1 && y0 == y1)
            break;
        int e2 = 2 * e;
        if (e2 >= dy)
            e += dy, x0 += sx;
        if (e2 <= dx)
            e += dx, y0 += sy;
    }
}

static int text_width(const char *s, int scale)
{
    return (int)strlen(s) * 6 * scale;
}

static void text(struct canvas *cv, int x, int y, const char *s, int scale,
                 const unsigned char col[3])
{
    for (; *s; s++, x += 6 * scale) {
        const unsigned char *g = glyph_rows(*s);
        if (!g)
            continue;
        for (int r = 0; r < 7; r++)
            for (int c = 0; c < 5; c++)
                if (g[r] & (0x10 >> c))
                    rect(cv, x + c * scale, y + r * scale, x + c * scale + scale - 1,
                         y + r * scale + scale - 1, col);
    }
}

/* Text rotated a quarter turn counter-clockwise, for the y axis label. */
static void text_up(struct canvas *cv, int x, int y, const char *s, int scale,
                    const unsigned char col[3])
{
    for (; *s; s++, y -= 6 * scale) {
        const unsigned char *g = glyph_rows(*s);
        if (!g)
            continue;
        for (int r = 0; r < 7; r++)
            for (int c = 0; c < 5; c++)
                if (g[r] & (0x10 >> c))
                    rect(cv, x + r * scale, y - c * scale - scale + 1, x + r * scale + scale - 1,
                         y - c * scale, col);
    }
}

static bool write_png(const struct canvas *cv, const char *path)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "plot: %s: %s\n", path, strerror(errno));
        return false;
    }
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!info) {
        fclose(f);
        fprintf(stderr, "plot: libpng initialisation failed\n");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        fclose(f);
        fprintf(stderr, "plot: %s: libpng write failed\n", path);
        return false;
    }
    png_init_io(png, f);
    png_set_IHDR(png, info, (png_uint_32)cv->w, (png_uint_32)cv->h, 8, PNG_COLOR_TYPE_RGB,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    for (int y = 0; y < cv->h; y++)
        png_write_row(png, cv->rgb + 3 * (size_t)y * cv->w);
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    if (fclose(f) != 0) {
        fprintf(stderr, "plot: %s: %s\n", path, strerror(errno));
        return false;
    }
    return true;
}

/* ---- data ---- */

struct series {
    char label[128];
    double *x, *y;
    int n;
};

/* Splits a CSV line in place; returns the number of fields. */
static int split_csv(char *line, char **fields, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        while (*p == ' ')
            p++;
        fields[n++] = p;
        char *c = strchr(p, ',');
        if (!c)
            break;
        *c = '\0';
        p = c + 1;
    }
    char *last = fields[n - 1];
    last[strcspn(last, "\r\n")] = '\0';
    return n;
}

static bool read_series(const char *path, const char *xcol, const char *ycol, struct series *s)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "plot: %s: %s\n", path, strerror(errno));
        return false;
    }
    char line[4096];
    char *fields[64];
    int xi = -1, yi = -1, lineno = 1;
    if (!fgets(line, sizeof line, f)) {
        fprintf(stderr, "plot: %s: empty file\n", path);
        fclose(f);
        return false;
    }
    int nf = split_csv(line, fields, 64);
    for (int i = 0; i < nf; i++) {
        if (!strcmp(fields[i], xcol))
            xi = i;
        if (!strcmp(fields[i], ycol))
            yi = i;
    }
    if (xi < 0 || yi < 0) {
        fprintf(stderr, "plot: %s:1: no column \"%s\"\n", path, xi < 0 ? xcol : ycol);
        fclose(f);
        return false;
    }
    int cap = 0;
    while (fgets(line, sizeof line, f)) {
        lineno++;
        if (line[0] == '#' || line[0] == '\n')
            continue;
        nf = split_csv(line, fields, 64);
        if (nf <= xi || nf <= yi) {
            fprintf(stderr, "plot: %s:%d: too few fields\n", path, lineno);
            fclose(f);
            return false;
        }
        char *e1, *e2;
        double x = strtod(fields[xi], &e1), y = strtod(fields[yi], &e2);
        if (e1 == fields[xi] || e2 == fields[yi]) {
            fprintf(stderr, "plot: %s:%d: not a number\n", path, lineno);
            fclose(f);
            return false;
        }
        if (!(x > 0) || !(y > 0))   /* cannot be drawn on log axes */
            continue;
        if (s->n == cap) {
            cap = cap ? 2 * cap : 16;
            s->x = realloc(s->x, sizeof(double) * (size_t)cap);
            s->y = realloc(s->y, sizeof(double) * (size_t)cap);
            if (!s->x || !s->y) {
                fprintf(stderr, "plot: out of memory\n");
                exit(1);
            }
        }
        s->x[s->n] = x, s->y[s->n] = y, s->n++;
    }
    fclose(f);
    return true;
}

/* Writes 10^k as text: "0.001", "100", "1e+06". */
static void decade_label(int k, char *buf, size_t n)
{
    if (k >= 0 && k <= 5)
        snprintf(buf, n, "%.0f", pow(10, k));
    else if (k < 0 && k >= -3)
        snprintf(buf, n, "%.*f", -k, pow(10, k));
    else
        snprintf(buf, n, "1E%d", k);
}

static void usage(FILE *f)
{
    fputs("usage: plot --out PLOT.png [--title T] [--x COL] [--y COL] [--xlabel L] [--ylabel L]\n"
          "            [--width W] [--height H] FILE.csv[=LABEL]...\n"
          "Draws each CSV as one series on log-log axes. Defaults: --x seconds --y relmse.\n", f);
}

int main(int argc, char **argv)
{
    const char *out = NULL, *title = "", *xcol = "seconds", *ycol = "relmse";
    const char *xlabel = NULL, *ylabel = NULL;
    int W = 900, H = 600;
    struct series ser[16];
    int ns = 0;
    memset(ser, 0, sizeof ser);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (a[0] == '-' && a[1] == '-' && i + 1 < argc) {
            const char *v = argv[++i];
            if (!strcmp(a, "--out")) out = v;
            else if (!strcmp(a, "--title")) title = v;
            else if (!strcmp(a, "--x")) xcol = v;
            else if (!strcmp(a, "--y")) ycol = v;
            else if (!strcmp(a, "--xlabel")) xlabel = v;
            else if (!strcmp(a, "--ylabel")) ylabel = v;
            else if (!strcmp(a, "--width")) W = atoi(v);
            else if (!strcmp(a, "--height")) H = atoi(v);
            else {
                fprintf(stderr, "plot: unknown option %s\n", a);
                return 2;
            }
        } else if (a[0] == '-') {
            fprintf(stderr, "plot: %s needs a value\n", a);
            return 2;
        } else {
            if (ns == 16) {
                fprintf(stderr, "plot: at most 16 series\n");
                return 2;
            }
            char path[4096];
            snprintf(path, sizeof path, "%s", a);
            char *eq = strchr(path, '=');
            const char *label = a;
            if (eq) {
                *eq = '\0';
                label = eq + 1;
            } else {
                const char *slash = strrchr(a, '/');
                label = slash ? slash + 1 : a;
            }
            snprintf(ser[ns].label, sizeof ser[ns].label, "%s", label);
            char *dot = strstr(ser[ns].label, ".csv");
            if (dot && !eq)
                *dot = '\0';
            if (!read_series(path, xcol, ycol, &ser[ns]))
                return 1;
            ns++;
        }
    }
    if (!out || ns == 0 || W < 200 || H < 150 || W > 8000 || H > 8000) {
        usage(stderr);
        return 2;
    }
    if (!xlabel)
        xlabel = xcol;
    if (!ylabel)
        ylabel = ycol;

    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    for (int s = 0; s < ns; s++)
        for (int i = 0; i < ser[s].n; i++) {
            xmin = fmin(xmin, ser[s].x[i]), xmax = fmax(xmax, ser[s].x[i]);
            ymin = fmin(ymin, ser[s].y[i]), ymax = fmax(ymax, ser[s].y[i]);
        }
    if (!(xmin <= xmax) || !(ymin <= ymax)) {
        fprintf(stderr, "plot: no positive data points to draw\n");
        return 1;
    }
    /* Whole decades on both axes, at least one. */
    int dx0 = (int)floor(log10(xmin)), dx1 = (int)ceil(log10(xmax));
    int dy0 = (int)floor(log10(ymin)), dy1 = (int)ceil(log10(ymax));
    if (dx1 == dx0) dx1++;
    if (dy1 == dy0) dy1++;

    struct canvas cv = {W, H, malloc((size_t)W * H * 3)};
    if (!cv.rgb) {
        fprintf(stderr, "plot: out of memory\n");
        return 1;
    }
    memset(cv.rgb, 255, (size_t)W * H * 3);
    static const unsigned char black[3] = {0, 0, 0}, grid[3] = {225, 225, 225},
        minor[3] = {242, 242, 242};
    static const unsigned char colors[8][3] = {
        {31, 119, 180}, {214, 39, 40}, {44, 160, 44}, {255, 127, 14},
        {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {23, 190, 207}};
    int L = 90, R = W - 30, T = 50, B = H - 70;
#define MAPX(v) (L + (int)lround((log10(v) - dx0) / (dx1 - dx0) * (R - L)))
#define MAPY(v) (B - (int)lround((log10(v) - dy0) / (dy1 - dy0) * (B - T)))
    char buf[64];
    for (int k = dx0; k <= dx1; k++) {
        for (int m = 2; m < 10 && k < dx1; m++) {
            int x = MAPX(m * pow(10, k));
            line(&cv, x, T, x, B, 1, minor);
        }
        int x = MAPX(pow(10, k));
        line(&cv, x, T, x, B, 1, grid);
        line(&cv, x, B, x, B + 6, 1, black);
        decade_label(k, buf, sizeof buf);
        text(&cv, x - text_width(buf, 2) / 2, B + 12, buf, 2, black);
    }
    for (int k = dy0; k <= dy1; k++) {
        for (int m = 2; m < 10 && k < dy1; m++) {
            int y = MAPY(m * pow(10, k));
            line(&cv, L, y, R, y, 1, minor);
        }
        int y = MAPY(pow(10, k));
        line(&cv, L, y, R, y, 1, grid);
        line(&cv, L - 6, y, L, y, 1, black);
        decade_label(k, buf, sizeof buf);
        text(&cv, L - 10 - text_width(buf, 2), y - 7, buf, 2, black);
    }
    line(&cv, L, T, L, B, 2, black);
    line(&cv, L, B, R, B, 2, black);
    text(&cv, (L + R) / 2 - text_width(xlabel, 2) / 2, H - 28, xlabel, 2, black);
    text_up(&cv, 8, (T + B) / 2 + text_width(ylabel, 2) / 2, ylabel, 2, black);
    text(&cv, (L + R) / 2 - text_width(title, 2) / 2, 16, title, 2, black);

    for (int s = 0; s < ns; s++) {
        const unsigned char *col = colors[s % 8];
        for (int i = 0; i < ser[s].n; i++) {
            int x = MAPX(ser[s].x[i]), y = MAPY(ser[s].y[i]);
            if (i > 0)
                line(&cv, MAPX(ser[s].x[i - 1]), MAPY(ser[s].y[i - 1]), x, y, 3, col);
            rect(&cv, x - 4, y - 4, x + 4, y + 4, col);
        }
        /* Legend, top right. */
        int ly = T + 12 + s * 22;
        int lx = R - 20 - text_width(ser[s].label, 2) - 40;
        line(&cv, lx, ly + 6, lx + 30, ly + 6, 3, col);
        text(&cv, lx + 38, ly, ser[s].label, 2, black);
    }
#undef MAPX
#undef MAPY
    bool ok = write_png(&cv, out);
    free(cv.rgb);
    for (int s = 0; s < ns; s++)
        free(ser[s].x), free(ser[s].y);
    return ok ? 0 : 1;
}
