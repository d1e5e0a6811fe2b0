/* medium_nanovdb_test.c: the shipped grid-medium code (glsl/trace/medium/
 * grid.glsl through glsl/trace/test/grid_probe.comp) on pbrt-v4's
 * "nanovdb" medium of the oracle's vol_nanovdb.nvdb under a rotation,
 * against NanoVDB's own semantics computed here in double from the file's
 * voxels (src/scene/nanovdb.c's reader, not the medium's lattice): the
 * point taken to index space by the inverse CTM and the grid's inverse
 * map, trilinear interpolation between voxels at integer index points
 * (NanoVDB's SampleFromVoxels of order 1), vacuum outside the world box
 * of the active voxels' bounds [lo, hi + 1] of both grids, emission
 * Lescale times the blackbody of the interpolated temperature; and every
 * majorant bounds sigma_t at the points of its cell. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "scene/builder.h"
#include "scene/nanovdb.h"
#include "scene/scene.h"
#include "scene/transform.h"
#include "tests/gpu/gpu_test_util.h"
#include "tests/rng.h"
#include "tests/trace/grid_probe.h"
#include "trace/scene_upload.h"

#define N_POINTS 20000
#define SA 0.5
#define SS 1.6
#define LESCALE 0.3
#define T_OFF 100.0
#define T_SCALE 1.2

static uint32_t lcg = 4242;
static double rnd(void)
{
    return cv_test_lcg32(&lcg);
}

/* NanoVDB's trilinear sample of grid g at index point x. */
static double sample(const struct cv_nvdb_grid *g, const double x[3])
{
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; a++) {
        i0[a] = (int)floor(x[a]);
        f[a] = x[a] - i0[a];
    }
    double v = 0;
    for (int c = 0; c < 8; c++) {
        double w = 1;
        for (int a = 0; a < 3; a++)
            w *= (c >> a) & 1 ? f[a] : 1 - f[a];
        v += w * cv_nvdb_value(g, i0[0] + (c & 1), i0[1] + (c >> 1 & 1), i0[2] + (c >> 2 & 1));
    }
    return v;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    const char *dir = getenv("CV_TEST_DATA");
    char *path = cv_xasprintf("%s/trace/oracle/vol_nanovdb.nvdb", dir ? dir : "tests/data");
    struct cv_nvdb_grid dg, tg;
    bool found_d = false, found_t = false;
    if (!tap_ok(cv_nvdb_read(path, "density", &dg, &found_d, &err) && found_d &&
                    cv_nvdb_read(path, "temperature", &tg, &found_t, &err) && found_t,
                "the oracle's NanoVDB file reads: %s", err.msg))
        return tap_done();
    char *text = cv_xasprintf(
        "WorldBegin\nTranslate 0.1 0 0.2\nRotate 25 0 1 0\n"
        "MakeNamedMedium \"cloud\" \"string type\" \"nanovdb\" \"string filename\" \"%s\"\n"
        "  \"rgb sigma_a\" [%g %g %g] \"rgb sigma_s\" [%g %g %g] \"float Lescale\" %g\n"
        "  \"float temperatureoffset\" %g \"float temperaturescale\" %g\n",
        path, SA, SA, SA, SS, SS, SS, LESCALE, T_OFF, T_SCALE);
    struct cv_mat4 t = cv_mat4_translate(0.1, 0, 0.2), r = cv_mat4_rotate(25, 0, 1, 0);
    struct cv_mat4 ctm = cv_mat4_mul(&t, &r);
    /* the world box of both grids' active voxels: [lo, hi + 1] */
    double wlo[3], whi[3];
    for (int a = 0; a < 3; a++) {
        int lo = dg.index_lo[a] < tg.index_lo[a] ? dg.index_lo[a] : tg.index_lo[a];
        int hi = dg.index_hi[a] > tg.index_hi[a] ? dg.index_hi[a] : tg.index_hi[a];
        wlo[a] = dg.map[a][a] * lo + dg.map[a][3];
        whi[a] = dg.map[a][a] * (hi + 1) + dg.map[a][3];
    }

    struct cv_scene_load_params lp = {.strict = true};
    struct cv_scene *s = NULL;
    struct cv_scene_gpu g = {0};
    bool loaded = cv_scene_load_string("nanovdb.pbrt", text, strlen(text), &lp, &s, &err);
    if (tap_ok(loaded && s->n_media == 2 && s->media[1].type == CV_MEDIUM_NANOVDB,
               "the nanovdb medium loads: %s", err.msg) &&
        tap_ok(cv_scene_upload(gpu, s, NULL, &g, &err), "the scene uploads: %s", err.msg)) {
        cv_scene_bind(&g);
        struct cv_program *prog = cv_program_get(gpu, "trace/test/grid_probe.comp", NULL, &err);
        if (tap_ok(prog != NULL, "grid_probe.comp compiles: %s", prog ? "" : err.msg)) {
            /* medium-space points over the box and a tenth beyond it */
            double *pm = cv_xmalloc(N_POINTS * 3 * sizeof(double));
            float *in = cv_xmalloc(N_POINTS * 16), *out = cv_xmalloc(N_POINTS * 64);
            for (size_t i = 0; i < N_POINTS; i++) {
                double p[3];
                for (int a = 0; a < 3; a++) {
                    double u = -0.1 + 1.2 * rnd();
                    pm[3 * i + a] = wlo[a] + u * (whi[a] - wlo[a]);
                }
                cv_mat4_point(&ctm, pm + 3 * i, p);
                memcpy(in + 4 * i, (float[4]){(float)p[0], (float)p[1], (float)p[2], 0}, 16);
            }
            bool ran = grid_probe_run(prog, 0, 1, 1, in, N_POINTS, N_POINTS, out, 4 * N_POINTS,
                                      &err);
            if (tap_ok(ran, "the probe runs: %s", err.msg)) {
                double worst = 0, worst_le = 0, worst_maj = 0;
                size_t inside = 0, hot = 0, skipped = 0;
                for (size_t i = 0; i < N_POINTS; i++) {
                    const float *o = out + 16 * i;
                    const double *q = pm + 3 * i;
                    /* points within float rounding of a face: either side is right */
                    bool in_box = true, near_face = false;
                    for (int a = 0; a < 3; a++) {
                        in_box &= q[a] >= wlo[a] && q[a] <= whi[a];
                        near_face |= fabs(q[a] - wlo[a]) < 1e-5 || fabs(q[a] - whi[a]) < 1e-5;
                    }
                    if (near_face) {
                        skipped++;
                        continue;
                    }
                    double d = 0, T = 0, x[3];
                    for (int a = 0; a < 3; a++)
                        x[a] = dg.inv[a][a] * (q[a] - dg.inv[a][3]);
                    if (in_box) {
                        inside++;
                        d = sample(&dg, x);
                        T = (sample(&tg, x) - T_OFF) * T_SCALE;
                    }
                    double le[3] = {0, 0, 0};
                    if (in_box && T > 100) {
                        cv_blackbody_sensor_rgb(T, le);
                        hot++;
                    }
                    for (int c = 0; c < 3; c++) {
                        worst = fmax(worst, fabs(o[c] - SA * d) / (SA + SS) / 2.5);
                        worst = fmax(worst, fabs(o[4 + c] - SS * d) / (SA + SS) / 2.5);
                        worst_le = fmax(worst_le, fabs(o[8 + c] - LESCALE * le[c]) / LESCALE);
                    }
                    /* the majorant of the point's cell */
                    worst_maj = fmax(worst_maj, ((double)o[0] + o[4]) / fmax(o[3], 1e-30));
                }
                tap_ok(worst < 2e-5 && inside > N_POINTS / 2,
                       "sigma_a and sigma_s are NanoVDB's trilinear density inside the world "
                       "box, 0 outside (worst %.2g of the largest sigma_t; %zu inside, %zu "
                       "within rounding of a face skipped)", worst, inside, skipped);
                tap_ok(worst_le < 2e-3 && hot > 100,
                       "emission is Lescale times the blackbody of the interpolated "
                       "temperature (worst %.2g of Lescale, the blackbody table's "
                       "interpolation; %zu points above 100 K)", worst_le, hot);
                tap_ok(worst_maj <= 1, "every majorant bounds sigma_t in its cell (closest "
                                       "%.6f of it)", worst_maj);
            }
            free(pm);
            free(in);
            free(out);
        }
        cv_scene_gpu_release(&g);
    }
    cv_scene_destroy(&s);
    cv_nvdb_free(&dg);
    cv_nvdb_free(&tg);
    free(text);
    free(path);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
