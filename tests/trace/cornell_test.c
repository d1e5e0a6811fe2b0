/* cornell_test.c: ../shared/scenes/cornell-box at 64x64, 64 spp against its
 * TungstenRender.exr box-downsampled to 64x64: the mean-brightness ratio
 * must lie within 3 % of 1 (pbrt-v4 lands within 2 %) and the mean relative
 * pixel error |ours - ref| / (ref + 0.01) below 0.15 (64 spp noise is most of
 * it); the v3 and v4 files must render the same image (identical scenes,
 * same seed: mean relative difference below 1e-3). Skips when the shared
 * scenes are absent. Prints the figures. */
#include "config.h"

#include <stdio.h>

#include "tests/trace/exr_ref.h"
#include "tests/trace/trace_test_util.h"

#define RES 64

static bool render(struct cv_gpu *gpu, const char *path, float **rgba, struct cv_error *err,
                   struct cv_render_counters *counters)
{
    struct cv_scene *s = NULL;
    struct cv_scene_load_params lp = {0};
    if (!cv_scene_load(path, &lp, &s, err))
        return false;
    CvCamera cam = test_camera(s, RES, RES);
    struct cv_render_params p = {.seed = 2024, .camera = &cam};
    struct test_image img = {0};
    const uint32_t passes[] = {32, 32, 0};
    bool ok = test_render(gpu, s, &p, passes, &img, err);
    cv_scene_destroy(&s);
    *rgba = img.rgba;
    *counters = img.counters;
    return ok && img.w == RES && img.h == RES;
}

int main(void)
{
    const char *shared = getenv("CV_SHARED_SCENES");
    char dir[4096];
    snprintf(dir, sizeof(dir), "%s/cornell-box", shared ? shared : "");
    if (!shared || !cv_path_exists(dir))
        return tap_skip_all("no shared scenes (CV_SHARED_SCENES/cornell-box)");
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    char path[4200], why[4400] = "";
    float *ref_full = NULL;
    uint32_t rw = 0, rh = 0;
    snprintf(path, sizeof(path), "%s/TungstenRender.exr", dir);
    bool read = exr_ref_read_rgb(path, &ref_full, &rw, &rh, why, sizeof(why));
    if (!tap_ok(read && rw % RES == 0 && rh % RES == 0 && rw == rh, "reference %ux%u read %s", rw,
                rh, why))
        return tap_done();
    float *ref = exr_ref_downsample(ref_full, rw, rh, rw / RES);
    free(ref_full);

    float *v4 = NULL, *v3 = NULL;
    struct cv_render_counters c4, c3;
    snprintf(path, sizeof(path), "%s/scene-v4.pbrt", dir);
    bool ok4 = tap_ok(render(gpu, path, &v4, &err, &c4), "scene-v4 renders: %s", err.msg);
    snprintf(path, sizeof(path), "%s/scene-v3.pbrt", dir);
    bool ok3 = tap_ok(render(gpu, path, &v3, &err, &c3), "scene-v3 renders: %s", err.msg);
    if (ok4) {
        double sum = 0, sum_ref = 0, rel = 0;
        for (int i = 0; i < RES * RES; i++) {
            double a = (v4[4 * i] + v4[4 * i + 1] + v4[4 * i + 2]) / 3;
            double b = (ref[3 * i] + ref[3 * i + 1] + ref[3 * i + 2]) / 3;
            sum += a;
            sum_ref += b;
            rel += fabs(a - b) / (b + 0.01);
        }
        double ratio = sum / sum_ref;
        rel /= RES * RES;
        tap_diag("cornell-box %dx%d 64 spp: mean %.5f, reference %.5f, ratio %.4f, mean relative error %.4f",
                 RES, RES, sum / (RES * RES), sum_ref / (RES * RES), ratio, rel);
        for (int ch = 0; ch < 3; ch++) {
            double a = 0, b = 0;
            for (int i = 0; i < RES * RES; i++) {
                a += v4[4 * i + ch];
                b += ref[3 * i + ch];
            }
            tap_diag("channel %d ratio %.4f", ch, a / b);
        }
        tap_diag("rays: primary %llu secondary %llu shadow %llu, GPU %.1f ms",
                 (unsigned long long)c4.primary_rays, (unsigned long long)c4.secondary_rays,
                 (unsigned long long)c4.shadow_rays, c4.gpu_ms);
        tap_ok(fabs(ratio - 1) < 0.03, "mean-brightness ratio %.4f within 3%% of 1", ratio);
        tap_ok(rel < 0.15, "mean relative pixel error %.4f below 0.15", rel);
    }
    if (ok4 && ok3) {
        double d = 0;
        for (int i = 0; i < RES * RES * 4; i++)
            d += fabs(v4[i] - v3[i]) / (fabs(v4[i]) + 0.01);
        d /= RES * RES * 4;
        tap_ok(d < 1e-3, "v3 and v4 files render the same image (mean relative difference %.2g)", d);
    }
    free(v4);
    free(v3);
    free(ref);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
