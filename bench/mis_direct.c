/* mis_direct.c: an independent check of veach-mis renders. For the middle
 * pixel row of each of the four conductor plates it integrates the light
 * reflected straight from the three sphere lights (Monte Carlo over each
 * light's cone, 200 000 directions per light and pixel), in double
 * precision, with pbrt-v4's conductor BRDF written out here from the
 * formulas (Trowbridge-Reitz D, Smith G, complex Fresnel; green channel of
 * the scene's RGB eta and k; alpha = roughness, as remaproughness false
 * says), and prints it beside the green channel of two EXR renders at
 * 1280x720. Direct light is a lower bound: a render may exceed it by the
 * plate's reflection of the lit walls, never fall below it. Geometry, lights
 * and camera are veach-mis's own (scene-v3.pbrt and scene-v4.pbrt agree).
 *
 *   bench/mis_direct RENDER.exr TungstenRender.exr */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "output/exr_read.h"

typedef struct { double x, y, z; } v3;

static v3 V(double x, double y, double z) { return (v3){x, y, z}; }
static v3 add(v3 a, v3 b) { return V(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 sub(v3 a, v3 b) { return V(a.x - b.x, a.y - b.y, a.z - b.z); }
static v3 mul(v3 a, double s) { return V(a.x * s, a.y * s, a.z * s); }
static double dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 unit(v3 a) { return mul(a, 1 / sqrt(dot(a, a))); }
static v3 cross(v3 a, v3 b)
{
    return V(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

/* pbrt-v4 FrComplex: unpolarised reflectance of a conductor */
static double fresnel(double c, double complex eta)
{
    c = fmin(fmax(c, 0), 1);
    double complex ct = csqrt(1 - (1 - c * c) / (eta * eta));
    double complex rpa = (eta * c - ct) / (eta * c + ct), rpe = (c - eta * ct) / (c + eta * ct);
    return (creal(rpa * conj(rpa)) + creal(rpe * conj(rpe))) / 2;
}

static double lambda(double a2, double c)
{
    return (sqrt(1 + a2 * (1 - c * c) / (c * c)) - 1) / 2;
}

static double brdf(double alpha, v3 n, v3 wo, v3 wi)
{
    double co = dot(n, wo), ci = dot(n, wi);
    if (co <= 0 || ci <= 0)
        return 0;
    v3 wm = unit(add(wo, wi));
    double cm = dot(wm, n), c2 = cm * cm, t2 = (1 - c2) / c2, a2 = alpha * alpha;
    double d = 1 / (M_PI * a2 * c2 * c2 * (1 + t2 / a2) * (1 + t2 / a2));
    double g = 1 / (1 + lambda(a2, co) + lambda(a2, ci));
    double f = fresnel(fabs(dot(wo, wm)), 0.924033 + 2.452848 * I);
    return d * f * g / (4 * co * ci);
}

static const struct plate {
    const char *name;
    double alpha, n[3], p[3], x0, x1;   /* top face: normal, a vertex, x extent */
} plates[] = {
    {"Smooth", 0.01, {0.641183, 0.767388, 0}, {-0.445511, 4.88636, 4}, -0.445511, 1.166},
    {"Glossy", 0.05, {0.37809, 0.925769, 0}, {2.14629, 3.25288, 4}, 2.14629, 4.0904},
    {"Rough", 0.1, {0.184835, 0.98277, 0}, {6.09563, 2.1604, 4}, 6.09563, 8.15944},
    {"SuperRough", 0.25, {0.121887, 0.992544, 0}, {9.65301, 1.51062, 4}, 9.65301, 11.7374},
};

static const struct { v3 c; double r, L; } lights[] = {
    {{0, 6.5, -2.8}, 1, 7.599088}, {{0, 6.5, 0}, 0.5, 30.396353}, {{0, 6.5, 2.7}, 0.05, 3039.6353}};

/* The camera of the scene's Transform: at (28.2792, 3.5, 0) looking down -x,
 * right = -z; fov 20.114292 degrees on the short axis. */
static v3 camera_dir(int px, int py)
{
    double t = tan(20.114292 / 2 * M_PI / 180), asp = 1280.0 / 720;
    double sx = -asp + 2 * asp * (px + 0.5) / 1280, sy = 1 - 2 * (py + 0.5) / 720;
    return unit(V(-1, sy * t, -sx * t));
}

static bool hit_plate(const struct plate *pl, v3 d, v3 *p)
{
    v3 cam = V(28.2792, 3.5, 0), n = unit(V(pl->n[0], pl->n[1], pl->n[2]));
    double t = (dot(n, V(pl->p[0], pl->p[1], pl->p[2])) - dot(n, cam)) / dot(n, d);
    *p = add(cam, mul(d, t));
    return t > 0 && p->x > pl->x0 && p->x < pl->x1 && p->z > -4 && p->z < 4;
}

static double direct(const struct plate *pl, v3 p, v3 wo)
{
    v3 n = unit(V(pl->n[0], pl->n[1], pl->n[2]));
    double sum = 0;
    for (size_t k = 0; k < sizeof(lights) / sizeof(lights[0]); k++) {
        v3 to = sub(lights[k].c, p);
        double dist = sqrt(dot(to, to));
        double cmax = sqrt(1 - lights[k].r * lights[k].r / (dist * dist));
        v3 z = mul(to, 1 / dist), x = unit(cross(fabs(z.x) > 0.5 ? V(0, 1, 0) : V(1, 0, 0), z));
        v3 y = cross(z, x);
        const int n_dirs = 200000;
        double s = 0;
        for (int i = 0; i < n_dirs; i++) {
            double ct = 1 - drand48() * (1 - cmax), st = sqrt(1 - ct * ct), ph = 2 * M_PI * drand48();
            v3 wi = add(add(mul(x, st * cos(ph)), mul(y, st * sin(ph))), mul(z, ct));
            s += brdf(pl->alpha, n, wo, wi) * fmax(dot(n, wi), 0);
        }
        sum += lights[k].L * s / n_dirs * 2 * M_PI * (1 - cmax);
    }
    return sum;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: mis_direct RENDER.exr REFERENCE.exr (both 1280x720)\n");
        return 2;
    }
    float *img[2];
    uint32_t w[2], h[2];
    struct cv_error err = {{0}};
    for (int i = 0; i < 2; i++)
        if (!cv_exr_read_rgba(argv[1 + i], &img[i], &w[i], &h[i], &err)) {
            fprintf(stderr, "mis_direct: %s\n", err.msg);
            return 1;
        }
    for (int i = 0; i < 2; i++)
        if (w[i] != 1280 || h[i] != 720) {
            fprintf(stderr, "mis_direct: %s is %ux%u, not 1280x720\n", argv[1 + i], w[i], h[i]);
            return 1;
        }
    srand48(1);
    for (size_t k = 0; k < sizeof(plates) / sizeof(plates[0]); k++) {
        const struct plate *pl = &plates[k];
        int y0 = -1, y1 = -1;
        v3 p;
        for (int py = 0; py < 720; py++)
            if (hit_plate(pl, camera_dir(640, py), &p)) {
                if (y0 < 0)
                    y0 = py;
                y1 = py;
            }
        int py = (y0 + y1) / 2;
        printf("%s plate (alpha %g), pixel row %d; green channel\n"
               "    x    direct    render  reference\n", pl->name, pl->alpha, py);
        for (int px = 340; px <= 940; px += 40) {
            v3 d = camera_dir(px, py);
            if (!hit_plate(pl, d, &p))
                continue;
            size_t o = 4 * ((size_t)py * 1280 + px) + 1;
            printf("%5d %9.4f %9.4f %10.4f\n", px, direct(pl, p, mul(d, -1)), img[0][o], img[1][o]);
        }
    }
    free(img[0]);
    free(img[1]);
    return 0;
}
