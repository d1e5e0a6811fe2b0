/* env_plane_test.c: a diffuse plane of reflectance 0.5 under a constant
 * environment of radiance 1 reflects exactly 0.5 towards the camera
 * (rho / pi * pi); a distant light of radiance pi arriving along the normal
 * adds 0.5 more. Checked:
 * - light order: the environment counts whatever lights are declared
 *   before it (a distant light, a small area light), and several infinite
 *   lights (constant, or an image map) add up;
 * - scale: planes of half-size 1, 1000 and 100000, and a tilted plane far
 *   from the origin, reflect the same (rays leaving the surface must not
 *   hit it again: their origin offset follows the hit point's rounding
 *   error, which grows with the vertices' magnitude);
 * - no leak: inside a closed box the environment is black (far from the
 *   origin, within what float coordinates there can resolve).
 * Image means of 16x16 pixels at 256 spp, within 0.6 % (the noise is a
 * few times smaller; a 1 % darkening fails). */
#include "config.h"

#include <stdio.h>

#include "tests/scene/scene_helpers.h"
#include "tests/trace/trace_test_util.h"

/* An orthonormal frame (u, v, n = u x v) around centre c. */
struct frame {
    double c[3], u[3], v[3], n[3];
};

static double max3d(double a, double b, double c) { return fmax(a, fmax(b, c)); }

static const struct frame axis_frame = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};

static struct frame far_frame(void)
{
    /* tilted about an oblique axis, every coordinate of order 1e5 */
    struct frame f = {{1.0e5, -7.0e4, 3.0e4}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    double u[3] = {0.8, 0.36, -0.48}, n0[3] = {0.3, -0.4, 0.5};
    double d = n0[0] * u[0] + n0[1] * u[1] + n0[2] * u[2], l = 0;
    for (int i = 0; i < 3; i++)
        f.n[i] = n0[i] - d * u[i], l += f.n[i] * f.n[i];
    for (int i = 0; i < 3; i++)
        f.n[i] /= sqrt(l), f.u[i] = u[i];
    f.v[0] = f.n[1] * f.u[2] - f.n[2] * f.u[1];
    f.v[1] = f.n[2] * f.u[0] - f.n[0] * f.u[2];
    f.v[2] = f.n[0] * f.u[1] - f.n[1] * f.u[0];
    return f;
}

/* The point c + a u + b v + h n, printed. */
static char *pt(const struct frame *f, double a, double b, double h)
{
    static char buf[8][96];
    static int k;
    char *s = buf[k++ & 7];
    snprintf(s, 96, "%.17g %.17g %.17g", f->c[0] + a * f->u[0] + b * f->v[0] + h * f->n[0],
             f->c[1] + a * f->u[1] + b * f->v[1] + h * f->n[1],
             f->c[2] + a * f->u[2] + b * f->v[2] + h * f->n[2]);
    return s;
}

/* A quad of half-size a at height h, facing +n. */
static char *quad(const struct frame *f, double a, double h)
{
    return cv_xasprintf("Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3]\n"
                        "  \"point3 P\" [%s  %s  %s  %s]\n",
                        pt(f, -a, -a, h), pt(f, a, -a, h), pt(f, a, a, h), pt(f, -a, a, h));
}

static const char *const view_fmt =
    "LookAt %s  %s  %.17g %.17g %.17g\n"
    "Camera \"perspective\" \"float fov\" [20]\n"
    "Film \"rgb\" \"integer xresolution\" [16] \"integer yresolution\" [16] \"string filename\" \"p.exr\"\n"
    "PixelFilter \"box\"\n"
    "WorldBegin\n";

/* The plane of half-size `half` in frame f seen from height 1, with `lights`
 * (LightSource lines, or area-light blocks) before it. */
static char *plane_scene(const struct frame *f, double half, const char *lights)
{
    char *sq = quad(f, half, 0);
    char *s = cv_xasprintf("%s%s" "Material \"diffuse\" \"rgb reflectance\" [0.5 0.5 0.5]\n%s",
                           "", lights, sq);
    char *view = cv_xasprintf(view_fmt, pt(f, 0, 0, 1), pt(f, 0, 0, 0), f->u[0], f->u[1], f->u[2]);
    char *all = cv_xasprintf("%s%s", view, s);
    free(sq), free(s), free(view);
    return all;
}

/* A distant light of radiance pi arriving along -n (straight down). */
static char *distant(const struct frame *f)
{
    return cv_xasprintf("LightSource \"distant\" \"rgb L\" [3.14159265 3.14159265 3.14159265]\n"
                        "  \"point3 from\" [0 0 0] \"point3 to\" [%.17g %.17g %.17g]\n",
                        -f->n[0], -f->n[1], -f->n[2]);
}

/* A small one-sided area light above the camera, facing away from the
 * plane: a light that adds nothing here. */
static char *small_lamp(const struct frame *f)
{
    char *q = quad(f, 0.01, 3);
    char *s = cv_xasprintf("AttributeBegin\nAreaLightSource \"diffuse\" \"rgb L\" [50 50 50]\n%sAttributeEnd\n", q);
    free(q);
    return s;
}

static double render_mean(struct cv_gpu *gpu, const char *text, uint64_t seed, bool *ok)
{
    struct cv_scene *s = NULL;
    struct cv_error err = {{0}};
    struct cv_scene_load_params lp = {0};
    *ok = false;
    if (!cv_scene_load_string(th_path("plane.pbrt"), text, strlen(text), &lp, &s, &err)) {
        tap_diag("load: %s", err.msg);
        return NAN;
    }
    struct cv_render_params p = {.seed = seed, .sampler = CV_SAMPLER_INDEPENDENT};
    struct test_image img = {0};
    const uint32_t passes[] = {64, 64, 128, 0};
    double m = NAN;
    if (test_render(gpu, s, &p, passes, &img, &err)) {
        m = test_mean(&img, 0, NULL);
        *ok = true;
    } else {
        tap_diag("render: %s", err.msg);
    }
    free(img.rgba);
    cv_scene_destroy(&s);
    return m;
}

#define TOL 0.006

static void check_plane(struct cv_gpu *gpu, const struct frame *f, double half, const char *lights,
                        double expect, const char *what)
{
    char *text = plane_scene(f, half, lights);
    bool ok;
    double m = render_mean(gpu, text, 11, &ok);
    tap_ok(ok && fabs(m / expect - 1) < TOL, "%s: mean %.5f is %.2f within %.1f %%", what, m, expect,
           100 * TOL);
    free(text);
}

static void light_order(struct cv_gpu *gpu)
{
    const struct frame *f = &axis_frame;
    char *d = distant(f), *a = small_lamp(f);
    const char *env = "LightSource \"infinite\" \"rgb L\" [1 1 1]\n";
    const char *env_q = "LightSource \"infinite\" \"rgb L\" [0.25 0.25 0.25]\n";
    const char *env_3q = "LightSource \"infinite\" \"rgb L\" [0.75 0.75 0.75]\n";
    char *l;
    check_plane(gpu, f, 10, env, 0.5, "environment alone");
    l = cv_xasprintf("%s%s", env, d);
    check_plane(gpu, f, 10, l, 1.0, "environment, then a distant light");
    free(l);
    l = cv_xasprintf("%s%s", d, env);
    check_plane(gpu, f, 10, l, 1.0, "a distant light, then the environment");
    free(l);
    l = cv_xasprintf("%s%s", a, env);
    check_plane(gpu, f, 10, l, 0.5, "a small area light, then the environment");
    free(l);
    l = cv_xasprintf("%s%s%s%s", a, env_q, d, env_3q);
    check_plane(gpu, f, 10, l, 1.0, "area light, environment 0.25, distant light, environment 0.75");
    free(l);
    /* an image map of 0.6 (lat-long, 8x4) with a constant 0.4 */
    float px[8 * 4 * 3];
    for (int i = 0; i < 8 * 4 * 3; i++)
        px[i] = 0.6f;
    char hdr[32];
    int n = snprintf(hdr, sizeof(hdr), "PF\n8 4\n-1.0\n");
    char *pfm = cv_xmalloc((size_t)n + sizeof(px));
    memcpy(pfm, hdr, (size_t)n);
    memcpy(pfm + n, px, sizeof(px));
    th_write("sky.pfm", pfm, (size_t)n + sizeof(px));
    free(pfm);
    l = cv_xasprintf("%sLightSource \"infinite\" \"string mapname\" \"sky.pfm\"\n%s"
                     "LightSource \"infinite\" \"rgb L\" [0.4 0.4 0.4]\n", d, a);
    check_plane(gpu, f, 10, l, 1.0, "distant light, image environment 0.6, area light, environment 0.4");
    free(l);
    free(d), free(a);
}

static void scale(struct cv_gpu *gpu)
{
    const char *env = "LightSource \"infinite\" \"rgb L\" [1 1 1]\n";
    const double halves[] = {1, 1000, 100000};
    struct frame far = far_frame();
    for (int k = 0; k < 3; k++) {
        char what[96];
        snprintf(what, sizeof(what), "plane of half-size %g", halves[k]);
        check_plane(gpu, &axis_frame, halves[k], env, 0.5, what);
        snprintf(what, sizeof(what), "tilted plane of half-size %g about (1e5, -7e4, 3e4)", halves[k]);
        check_plane(gpu, &far, halves[k], env, 0.5, what);
    }
}

/* Inside a closed box (two-sided diffuse walls) nothing of the environment
 * may arrive, at any scale: an offset past a wall would let it in. */
static void closed_box(struct cv_gpu *gpu, const struct frame *f, double half, const char *what)
{
    char *walls = cv_xasprintf(
        "Material \"diffuse\" \"rgb reflectance\" [0.9 0.9 0.9]\n"
        "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3  4 6 5 4 7 6  0 3 7 0 7 4\n"
        "    1 5 6 1 6 2  0 4 5 0 5 1  3 2 6 3 6 7]\n"
        "  \"point3 P\" [%s  %s  %s  %s  %s  %s  %s  %s]\n",
        pt(f, -half, -half, -half), pt(f, half, -half, -half), pt(f, half, half, -half),
        pt(f, -half, half, -half), pt(f, -half, -half, half), pt(f, half, -half, half),
        pt(f, half, half, half), pt(f, -half, half, half));
    char *view = cv_xasprintf(view_fmt, pt(f, -0.3 * half, -0.2 * half, -0.1 * half),
                              pt(f, half, half, half), f->n[0], f->n[1], f->n[2]);
    char *text = cv_xasprintf("%sLightSource \"infinite\" \"rgb L\" [1 1 1]\n%s", view, walls);
    bool ok;
    double m = render_mean(gpu, text, 5, &ok);
    /* Far from the origin a hit point is good only to the float spacing
     * of its coordinates (2^-7 at 1e5), so one close to an edge may land
     * just outside the next wall and its ray see the outside: allow the
     * share of wall within a few spacings of an edge. Near the origin,
     * nothing. */
    double c = max3d(fabs(f->c[0]), fabs(f->c[1]), fabs(f->c[2]));
    double allow = c > 0 ? 4 * ldexp(1, ilogb(c) - 23) / half : 0;
    tap_ok(ok && m <= allow, "%s: no light leaks in (mean %.3g, at most %.3g)", what, m, allow);
    free(walls), free(view), free(text);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    th_init();
    light_order(gpu);
    scale(gpu);
    struct frame far = far_frame();
    closed_box(gpu, &axis_frame, 1, "closed box of half-size 1");
    closed_box(gpu, &axis_frame, 1000, "closed box of half-size 1000");
    closed_box(gpu, &far, 1, "tilted closed box of half-size 1 about (1e5, -7e4, 3e4)");
    closed_box(gpu, &far, 10, "tilted closed box of half-size 10 about (1e5, -7e4, 3e4)");
    closed_box(gpu, &far, 100, "tilted closed box of half-size 100 about (1e5, -7e4, 3e4)");
    th_cleanup();
    cv_gpu_destroy(&gpu);
    return tap_done();
}
