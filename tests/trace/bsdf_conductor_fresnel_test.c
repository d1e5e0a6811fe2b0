/* bsdf_conductor_fresnel_test.c: conductors given by spectra in the
 * shipped GLSL (CV_CONDUCTOR_TABLES): a rough copper conductor with
 * pbrt-v4's spectra (CV_MATF_CONDUCTOR_FRESNEL, its table from
 * src/scene/conductor_fresnel.c in the buffer texture) against the same
 * conductor by RGB eta and k, evaluated in the mirror direction (the half
 * vector is the normal, so D and G are equal and the ratio of the two is
 * the ratio of the Fresnel terms at cos theta, which the host computes);
 * and the albedo (Fresnel at normal incidence) of both and of coated
 * conductors over a coat of index 1.5, whose table holds the ratio of
 * indices already. */
#include "config.h"

#include <math.h>
#include <stdio.h>

#include "glsl/shared/bindings.h"
#include "glsl/shared/conductor_fresnel.h"
#include "scene/conductor_fresnel.h"
#include "scene/fresnel.h"
#include "scene/spectrum.h"
#include "tests/trace/bsdf_probe.h"

enum { FLOATS = 4 * CV_CONDUCTOR_FRESNEL_N };

static const double cu_eta[3] = {0.200438, 0.924033, 1.10221}, cu_k[3] = {3.91295, 2.45285, 2.14219};

static double lookup(const float *table, double cos_i, int c)
{
    double x = cos_i * (CV_CONDUCTOR_FRESNEL_N - 1);
    int i = (int)x < CV_CONDUCTOR_FRESNEL_N - 2 ? (int)x : CV_CONDUCTOR_FRESNEL_N - 2;
    double t = x - i;
    return table[4 * i + c] * (1 - t) + table[4 * (i + 1) + c] * t;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    size_t n_eta, n_k;
    const double *eta = cv_metal_spectrum("metal-Cu-eta", &n_eta), *k = cv_metal_spectrum("metal-Cu-k", &n_k);
    static float tables[2 * FLOATS];
    cv_conductor_fresnel_table(eta, n_eta, k, n_k, 1, tables);
    cv_conductor_fresnel_table(eta, n_eta, k, n_k, 1.5, tables + FLOATS);

    CvMaterial m[4];
    for (int i = 0; i < 4; i++) {
        m[i] = probe_material(i < 2 ? CV_MAT_CONDUCTOR : CV_MAT_COATED_CONDUCTOR);
        m[i].eta = (cv_vec4){(float)cu_eta[0], (float)cu_eta[1], (float)cu_eta[2], 1.5f};
        m[i].k = (cv_vec4){(float)cu_k[0], (float)cu_k[1], (float)cu_k[2], 0};
        m[i].roughness = (cv_vec4){0.3f, 0.3f, 0.01f, 0};
        m[i].roughness2 = (cv_vec4){0.3f, 0.3f, 10, 1};
    }
    m[0].flags = m[2].flags = CV_MATF_CONDUCTOR_FRESNEL;
    m[2].k.w = 1; /* the table over the coat */

    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, m, 4, &err), "probe: %s", err.msg))
        return tap_done();
    static const char *const defines[] = {"CV_CONDUCTOR_TABLES", NULL};
    p.prog = cv_program_get(gpu, "trace/test/bsdf_probe.comp", defines, &err);
    GLuint buf = cv_buffer_create(sizeof(tables), tables, "conductor Fresnel tables", &err), tex = 0;
    if (buf)
        tex = cv_buffer_texture(buf, GL_RGBA32F, 2 * CV_CONDUCTOR_FRESNEL_N, &err);
    if (!tap_ok(p.prog && tex, "probe with CV_CONDUCTOR_TABLES, tables bound: %s", err.msg))
        return tap_done();
    glBindTextureUnit(CV_TEXUNIT_CONDUCTOR_FRESNEL, tex);

    /* mirror directions: wm = n, Fresnel at cos theta of wo */
    static const double thetas[] = {0, 20, 45, 60, 75, 85};
    double worst = 0, worst_theta = 0;
    bool ran = true;
    for (size_t j = 0; j < sizeof(thetas) / sizeof(thetas[0]); j++) {
        float wo[3], wi[4], f_tab[4], f_rgb[4];
        probe_dir(thetas[j], 30, wo);
        wi[0] = -wo[0];
        wi[1] = -wo[1];
        wi[2] = wo[2];
        wi[3] = 0;
        ran = ran && probe_run(&p, 1, 0, wo, 1, wi, 1, f_tab, &err) && probe_run(&p, 1, 1, wo, 1, wi, 1, f_rgb, &err);
        if (!ran)
            break;
        for (int c = 0; c < 3; c++) {
            double want = lookup(tables, wo[2], c) / cv_fresnel_complex(wo[2], cu_eta[c], cu_k[c]);
            double got = f_tab[c] / f_rgb[c], d = fabs(got / want - 1);
            if (!(d <= worst)) {
                worst = d;
                worst_theta = thetas[j];
            }
        }
    }
    tap_ok(ran && worst < 1e-4,
           "rough copper: f by the table over f by RGB eta and k is the Fresnel ratio within 0.01 %% "
           "(worst %.2g at %g degrees; %s)", worst, worst_theta, err.msg);

    /* albedo: Fresnel at normal incidence */
    float q[4] = {0.5f, 0.5f, 0.5f, 0.5f}, out[4][8], up[3] = {0, 0, 1};
    for (unsigned i = 0; i < 4; i++)
        ran = ran && probe_run(&p, 2, i, up, 0, q, 1, out[i], &err);
    double d_tab = 0, d_rgb = 0, d_coat = 0, d_coat_rgb = 0;
    for (int c = 0; c < 3; c++) {
        d_tab = fmax(d_tab, fabs(out[0][c] - tables[4 * (CV_CONDUCTOR_FRESNEL_N - 1) + c]));
        d_rgb = fmax(d_rgb, fabs(out[1][c] - cv_fresnel_complex(1, cu_eta[c], cu_k[c])));
        d_coat = fmax(d_coat, fabs(out[2][c] - tables[FLOATS + 4 * (CV_CONDUCTOR_FRESNEL_N - 1) + c]));
        d_coat_rgb = fmax(d_coat_rgb, fabs(out[3][c] - cv_fresnel_complex(1, cu_eta[c] / 1.5, cu_k[c] / 1.5)));
    }
    tap_ok(ran && d_tab < 1e-5 && d_rgb < 1e-4,
           "albedo: copper's table at normal incidence (%.4f %.4f %.4f, off by %.2g); by RGB (off by %.2g)",
           out[0][0], out[0][1], out[0][2], d_tab, d_rgb);
    tap_ok(ran && d_coat < 1e-5 && d_coat_rgb < 1e-4,
           "albedo of coated copper: its table over index 1.5 (off by %.2g), not divided again; by RGB (off by %.2g)",
           d_coat, d_coat_rgb);
    glDeleteTextures(1, &tex);
    cv_buffer_destroy(&buf);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
