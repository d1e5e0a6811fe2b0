/* rlpath_converge_test.c: the unbiasedness test of the rlpath integrator:
 * in a closed room split by a partition that stops short of the ceiling,
 * the lamp on one side and the camera looking at the other (light arrives
 * mostly after a bounce off the ceiling), `rlpath` and `path` converge to the same image.
 * Each integrator renders B independent batches (a fresh renderer and seed
 * each, several passes so the table learns across them); the batch means
 * give each pixel's mean and standard error. Checked: the image means agree
 * within 4 standard errors of their difference, and no more than 1 % of
 * pixels differ by more than 4.5 standard errors (Student t with B - 1
 * degrees of freedom puts about 0.05 % there). A table option sweep checks
 * that other layouts (one with rlpath.guide: indirect) stay unbiased in the
 * image mean too; the room with glossy panels and a black-backed lamp
 * (rlpath_room_glossy: lobes that do not guide, a glossy coat over a guided
 * base, emitted light in the guided distribution) checks the image mean
 * again. */
#include "config.h"

#include "tests/trace/rlpath_room.h"
#include "tests/trace/trace_test_util.h"

#define B 12

struct stats {
    double *sum, *sum2;   /* per pixel, channel mean */
    double img_sum, img_sum2;
    size_t n;
};

static bool batches(struct cv_gpu *gpu, const struct cv_scene *s, struct cv_render_params p,
                    struct stats *st, struct cv_error *err)
{
    const uint32_t passes[] = {8, 8, 16, 16, 0};
    for (int b = 0; b < B; b++) {
        p.seed = 1000 + 17 * (uint64_t)b + (uint64_t)p.integrator * 7919;
        struct test_image img = {0};
        if (!test_render(gpu, s, &p, passes, &img, err))
            return false;
        st->n = (size_t)img.w * img.h;
        if (!st->sum) {
            st->sum = calloc(st->n, sizeof(double));
            st->sum2 = calloc(st->n, sizeof(double));
        }
        double m = 0;
        for (size_t i = 0; i < st->n; i++) {
            const float *px = img.rgba + 4 * i;
            double v = (px[0] + px[1] + px[2]) / 3.0;
            st->sum[i] += v;
            st->sum2[i] += v * v;
            m += v;
        }
        m /= (double)st->n;
        st->img_sum += m;
        st->img_sum2 += m * m;
        free(img.rgba);
    }
    return true;
}

/* mean and squared standard error of the mean of B values */
static void mean_se2(double sum, double sum2, double *mean, double *se2)
{
    *mean = sum / B;
    double var = (sum2 - B * *mean * *mean) / (B - 1);
    *se2 = (var > 0 ? var : 0) / B;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    struct cv_scene *s = NULL;
    struct cv_scene_load_params lp = {0};
    if (!tap_ok(cv_scene_load_string("room.pbrt", rlpath_room, sizeof(rlpath_room) - 1, &lp, &s, &err),
                "load the room: %s", err.msg))
        return tap_done();

    struct stats sp = {0}, sr = {0};
    struct cv_render_params pp = {.sampler = CV_SAMPLER_INDEPENDENT,
                                  .integrator = CV_INTEGRATOR_PATH};
    struct cv_render_params pr = pp;
    pr.integrator = CV_INTEGRATOR_RLPATH;
    pr.rl_grid = 4;
    pr.rl_mix = -1;   /* the default */
    if (!tap_ok(batches(gpu, s, pp, &sp, &err), "path: %d batches of 48 spp: %s", B, err.msg) ||
        !tap_ok(batches(gpu, s, pr, &sr, &err), "rlpath: %d batches of 48 spp: %s", B, err.msg))
        return tap_done();

    double mp, sep, mr, ser;
    mean_se2(sp.img_sum, sp.img_sum2, &mp, &sep);
    mean_se2(sr.img_sum, sr.img_sum2, &mr, &ser);
    double z = (mr - mp) / sqrt(sep + ser);
    tap_ok(mp > 0.05, "the room is lit (path mean %.4f)", mp);
    tap_ok(fabs(z) < 4, "image means agree: path %.5f +- %.5f, rlpath %.5f +- %.5f (z = %.2f)", mp,
           sqrt(sep), mr, sqrt(ser), z);
    size_t far = 0;
    double worst = 0;
    for (size_t i = 0; i < sp.n; i++) {
        double a, sa, b, sb;
        mean_se2(sp.sum[i], sp.sum2[i], &a, &sa);
        mean_se2(sr.sum[i], sr.sum2[i], &b, &sb);
        double t = sa + sb > 0 ? fabs(b - a) / sqrt(sa + sb) : (a == b ? 0 : INFINITY);
        if (t > 4.5)
            far++;
        if (t > worst)
            worst = t;
    }
    tap_ok(far <= sp.n / 100, "pixels agree: %zu of %zu beyond 4.5 standard errors (largest %.2f)",
           far, sp.n, worst);
    tap_diag("per-batch image variance: path %.3g, rlpath %.3g", sep * B, ser * B);
    free(sp.sum), free(sp.sum2), free(sr.sum), free(sr.sum2);

    /* other layouts: unbiased in the image mean as well */
    const struct { uint32_t grid, dirs; float mix; bool indirect; } opt[] = {
        {1, 32, 0.7f, false}, {8, 200, 0.2f, true}};
    for (size_t k = 0; k < sizeof(opt) / sizeof(opt[0]); k++) {
        struct cv_render_params po = pr;
        po.rl_grid = opt[k].grid;
        po.rl_directions = opt[k].dirs;
        po.rl_mix = opt[k].mix;
        po.rl_guide_indirect = opt[k].indirect;
        struct stats so = {0};
        if (!tap_ok(batches(gpu, s, po, &so, &err),
                    "rlpath grid %u, %u directions, mix %.1f, guide %s: %s", opt[k].grid,
                    opt[k].dirs, opt[k].mix, opt[k].indirect ? "indirect" : "all", err.msg))
            continue;
        double mo, seo;
        mean_se2(so.img_sum, so.img_sum2, &mo, &seo);
        double zo = (mo - mp) / sqrt(sep + seo);
        tap_ok(fabs(zo) < 4, "grid %u: image mean %.5f +- %.5f agrees with path (z = %.2f)",
               opt[k].grid, mo, sqrt(seo), zo);
        free(so.sum), free(so.sum2);
    }

    /* glossy panels: path and rlpath agree in the image mean */
    struct cv_scene *sg = NULL;
    if (tap_ok(cv_scene_load_string("glossy.pbrt", rlpath_room_glossy,
                                    sizeof(rlpath_room_glossy) - 1, &lp, &sg, &err),
               "load the glossy room: %s", err.msg)) {
        struct stats gp = {0}, gr = {0};
        if (tap_ok(batches(gpu, sg, pp, &gp, &err), "glossy room, path: %s", err.msg) &&
            tap_ok(batches(gpu, sg, pr, &gr, &err), "glossy room, rlpath: %s", err.msg)) {
            double a, sa, b, sb;
            mean_se2(gp.img_sum, gp.img_sum2, &a, &sa);
            mean_se2(gr.img_sum, gr.img_sum2, &b, &sb);
            double zg = (b - a) / sqrt(sa + sb);
            tap_ok(a > 0.03 && fabs(zg) < 4, "glossy room: image means agree: path %.5f +- %.5f, "
                   "rlpath %.5f +- %.5f (z = %.2f)", a, sqrt(sa), b, sqrt(sb), zg);
        }
        free(gp.sum), free(gp.sum2), free(gr.sum), free(gr.sum2);
        cv_scene_destroy(&sg);
    }

    struct cv_render_params bad = pr;
    bad.rl_mix = 2;
    struct cv_renderer *r = NULL;
    tap_ok(!cv_renderer_create(gpu, s, &bad, &r, &err) && strstr(err.msg, "mix"),
           "a mix above 1 is refused: %s", err.msg);
    cv_scene_destroy(&s);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
