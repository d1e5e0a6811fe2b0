/* bsdf_material_test.c: material resolution in the shipped GLSL:
 * bilinear image lookups (v = 0 at the image's bottom), constant, scale,
 * checkerboard and nested mix textures, mix materials picked with their
 * amount, alpha cut-outs (stochastic for 0 < alpha < 1), interface
 * materials passed through, normal maps and bump maps tilting the shading
 * normal as expected. */
#include "config.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tests/trace/bsdf_probe.h"

static uint16_t half_of(float f)
{
    union { float f; uint32_t u; } v = {f};
    uint32_t sign = (v.u >> 16) & 0x8000u;
    int32_t e = (int32_t)((v.u >> 23) & 0xff) - 127 + 15;
    uint32_t m = v.u & 0x7fffffu;
    if (e <= 0)
        return (uint16_t)sign;
    return (uint16_t)(sign | ((uint32_t)e << 10) | ((m + 0x1000u) >> 13));
}

static void texel(uint32_t *t, float r, float g, float b)
{
    t[0] = half_of(r) | ((uint32_t)half_of(g) << 16);
    t[1] = half_of(b) | ((uint32_t)half_of(1) << 16);
}

static CvTexture tex_init(unsigned type)
{
    CvTexture t;
    memset(&t, 0, sizeof(t));
    t.type = type;
    t.tex_a = t.tex_b = t.amount_tex = -1;
    t.scale = 1;
    t.uv_map = (cv_vec4){1, 1, 0, 0};
    t.levels = 1;
    return t;
}

static bool near3(const float *a, double x, double y, double z, double tol)
{
    return fabs(a[0] - x) < tol && fabs(a[1] - y) < tol && fabs(a[2] - z) < tol;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    uint32_t texels[2 * 8];
    /* tex 0: 2x2 image, rows top first: red green / blue white */
    texel(texels + 0, 1, 0, 0);
    texel(texels + 2, 0, 1, 0);
    texel(texels + 4, 0, 0, 1);
    texel(texels + 6, 1, 1, 1);
    /* tex 6: 1x1 normal map texel; tex 7: 2x1 displacement ramp 0 -> 1 */
    texel(texels + 8, 0.85f, 0.5f, 0.85f);
    texel(texels + 10, 0, 0, 0);
    texel(texels + 12, 1, 1, 1);
    CvTexture tex[8];
    tex[0] = tex_init(CV_TEX_IMAGE);
    tex[0].flags = CV_TEXF_WRAP_CLAMP;
    tex[0].width = tex[0].height = 2;
    tex[1] = tex_init(CV_TEX_CONSTANT);
    tex[1].value_a = (cv_vec4){0.2f, 0.4f, 0.6f, 0};
    tex[2] = tex_init(CV_TEX_SCALE);
    tex[2].tex_a = 0;
    tex[2].tex_b = 1;
    tex[3] = tex_init(CV_TEX_CHECKERBOARD);
    tex[3].value_a = (cv_vec4){1, 1, 1, 0};
    tex[3].uv_map = (cv_vec4){4, 4, 0, 0};
    tex[4] = tex_init(CV_TEX_MIX);
    tex[4].tex_a = 3;
    tex[4].tex_b = 1;
    tex[4].amount = 0.5f;
    tex[5] = tex_init(CV_TEX_CONSTANT);
    tex[6] = tex_init(CV_TEX_IMAGE);
    tex[6].offset = 4;
    tex[6].width = tex[6].height = 1;
    tex[7] = tex_init(CV_TEX_IMAGE);
    tex[7].flags = CV_TEXF_WRAP_CLAMP | CV_TEXF_FLOAT;
    tex[7].offset = 5;
    tex[7].width = 2;
    tex[7].height = 1;

    CvMaterial m[10];
    for (int i = 0; i < 10; i++) {
        m[i] = probe_material(CV_MAT_DIFFUSE);
        m[i].reflectance = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
    }
    m[0].reflectance_tex = 0;
    m[1].reflectance_tex = 2;
    m[2].reflectance_tex = 4;
    m[3].type = CV_MAT_MIX;
    m[3].mix_a = 5;
    m[3].mix_b = 6;
    m[3].amount = 0.3f;
    m[4].alpha = 0.3f;
    m[5].reflectance = (cv_vec4){0.1f, 0.1f, 0.1f, 0};
    m[6].type = CV_MAT_CONDUCTOR;
    m[6].k = (cv_vec4){3, 3, 3, 0};
    m[7].type = CV_MAT_INTERFACE;
    m[8].normal_tex = 6;
    m[9].displacement_tex = 7;
    struct probe p;
    if (!tap_ok(probe_open_tex(gpu, &p, m, 10, tex, 8, texels, 8, &err), "probe: %s", err.msg))
        return tap_done();

    float wo[3] = {0, 0, 1};
    float q[4 * 8] = {0.25f, 0.75f, 0, 0, 0.5f, 0.5f, 0, 0, 0.75f, 0.25f, 0, 0, 0.5f, 0.75f, 0, 0,
                      0.1f, 0.1f, 0, 0, 0.3f, 0.1f, 0, 0};
    float out[8 * 8];
    tap_ok(probe_run(&p, 2, 0, wo, 0, q, 4, out, &err), "image texture run: %s", err.msg);
    tap_ok(near3(out + 0, 1, 0, 0, 1e-3), "texel centre (top-left at v = 0.75): %.3f %.3f %.3f", out[0],
           out[1], out[2]);
    tap_ok(near3(out + 8, 0.5, 0.5, 0.5, 1e-3), "bilinear centre: %.3f %.3f %.3f", out[8], out[9], out[10]);
    tap_ok(near3(out + 16, 1, 1, 1, 1e-3), "bottom-right texel: %.3f %.3f %.3f", out[16], out[17], out[18]);
    tap_ok(near3(out + 24, 0.5, 0.5, 0, 1e-3), "bilinear between top texels: %.3f %.3f %.3f", out[24],
           out[25], out[26]);
    bool ran = probe_run(&p, 2, 1, wo, 0, q, 1, out, &err);
    tap_ok(ran && near3(out, 0.2, 0, 0, 1e-3),
           "scale texture (image x constant): %.3f %.3f %.3f", out[0], out[1], out[2]);
    ran = probe_run(&p, 2, 2, wo, 0, q + 16, 2, out, &err);
    tap_ok(ran && near3(out, 0.6, 0.7, 0.8, 1e-3) &&
               near3(out + 8, 0.1, 0.2, 0.3, 1e-3),
           "mix of checkerboard and constant (nested): %.3f %.3f %.3f / %.3f %.3f %.3f", out[0], out[1], out[2],
           out[8], out[9], out[10]);

    /* stochastic choices */
    enum { NS = 20000 };
    float *qs = malloc(NS * 4 * sizeof(float)), *os = malloc(NS * 8 * sizeof(float));
    for (int i = 0; i < NS; i++) {
        qs[4 * i] = qs[4 * i + 1] = 0.5f;
        qs[4 * i + 2] = qs[4 * i + 3] = (i + 0.5f) / NS;
    }
    int cond = 0, pass = 0;
    tap_ok(probe_run(&p, 2, 3, wo, 0, qs, NS, os, &err), "mix run");
    for (int i = 0; i < NS; i++)
        cond += os[8 * i + 7] == (float)CV_MAT_CONDUCTOR;
    tap_ok(abs(cond - NS * 3 / 10) <= 2, "mix picks mix_b with probability amount (%d of %d)", cond, NS);
    tap_ok(probe_run(&p, 2, 4, wo, 0, qs, NS, os, &err), "alpha run");
    for (int i = 0; i < NS; i++)
        pass += os[8 * i + 3] > 0.5f;
    tap_ok(abs(pass - NS * 7 / 10) <= 2, "alpha 0.3 passes 70 %% of rays (%d of %d)", pass, NS);
    pass = 0;
    tap_ok(probe_run(&p, 2, 7, wo, 0, qs, 100, os, &err), "interface run");
    for (int i = 0; i < 100; i++)
        pass += os[8 * i + 3] > 0.5f;
    tap_ok(pass == 100, "interface material always passes (%d of 100)", pass);
    ran = probe_run(&p, 2, 5, wo, 0, qs, 100, os, &err);
    tap_ok(ran && os[3] == 0 && os[8 * 99 + 3] == 0,
           "opaque material never passes");
    free(qs);
    free(os);

    ran = probe_run(&p, 2, 8, wo, 0, q + 4, 1, out, &err);
    tap_ok(ran && near3(out + 4, M_SQRT1_2, 0, M_SQRT1_2, 2e-3),
           "normal map (0.85, 0.5, 0.85) tilts n towards dpdu: %.3f %.3f %.3f", out[4], out[5], out[6]);
    ran = probe_run(&p, 2, 9, wo, 0, q + 4, 1, out, &err);
    tap_ok(ran &&
               near3(out + 4, -2 / sqrt(5), 0, 1 / sqrt(5), 2e-3),
           "bump map with slope 2 along u: %.3f %.3f %.3f", out[4], out[5], out[6]);
    probe_close(&p);

    /* a textured roughness is remapped per lookup as its material's pbrt
     * version remaps a constant: pbrt-v3's polynomial for a v3 metal (and
     * glass, substrate), pbrt-v4's square root for a conductor. Each
     * textured material must match the one given the remapped constant. */
    {
        const double r = 0.1, x = log(r);
        const double v3 = 1.62142 + 0.819955 * x + 0.1734 * x * x + 0.0171201 * x * x * x +
                          0.000640711 * x * x * x * x;
        CvTexture rt = tex_init(CV_TEX_CONSTANT);
        rt.value_a = (cv_vec4){(float)r, (float)r, (float)r, 0};
        CvMaterial c[4];
        for (int i = 0; i < 4; i++) {
            c[i] = probe_material(CV_MAT_CONDUCTOR);
            c[i].eta = (cv_vec4){0.2f, 0.9f, 1.1f, 0};
            c[i].k = (cv_vec4){3.9f, 2.4f, 2.1f, 0};
        }
        c[0].roughness_u_tex = c[0].roughness_v_tex = 0;
        c[0].flags = CV_MATF_REMAP_ROUGHNESS | CV_MATF_ROUGHNESS_V3;
        c[1].roughness = (cv_vec4){(float)v3, (float)v3, 0, 0};
        c[2].roughness_u_tex = c[2].roughness_v_tex = 0;
        c[2].flags = CV_MATF_REMAP_ROUGHNESS;
        c[3].roughness = (cv_vec4){(float)sqrt(r), (float)sqrt(r), 0, 0};
        uint32_t none[2] = {0, 0};
        struct probe pr;
        if (tap_ok(probe_open_tex(gpu, &pr, c, 4, &rt, 1, none, 1, &err), "roughness probe: %s", err.msg)) {
            enum { ND = 6 };
            float dirs[ND * 4], f[4][ND * 4], wo2[3];
            probe_dir(30, 0, wo2);
            for (int i = 0; i < ND; i++) {
                probe_dir(20 + 8 * i, 180 + 10 * i, dirs + 4 * i);
                dirs[4 * i + 3] = 0;
            }
            bool ran2 = true;
            for (unsigned k = 0; k < 4; k++)
                ran2 = ran2 && probe_run(&pr, 1, k, wo2, 0, dirs, ND, f[k], &err);
            double worst[2] = {0, 0}, apart = 0;
            for (int i = 0; i < ND * 4; i++)
                for (int k = 0; k < 2; k++) {
                    double a = f[2 * k][i], e = f[2 * k + 1][i];
                    worst[k] = fmax(worst[k], fabs(a - e) / fmax(fabs(e), 1e-6));
                    if (k == 0)
                        apart = fmax(apart, fabs(a - f[3][i]) / fmax(fabs(f[3][i]), 1e-6));
                }
            tap_ok(ran2 && worst[0] < 1e-4, "textured roughness %g of a pbrt-v3 metal: alpha %.4f "
                   "(worst relative difference in f and pdf %.2g)", r, v3, worst[0]);
            tap_ok(ran2 && worst[1] < 1e-4, "textured roughness %g of a pbrt-v4 conductor: alpha %.4f "
                   "(worst relative difference %.2g)", r, sqrt(r), worst[1]);
            tap_ok(ran2 && apart > 0.05, "the two remaps differ there (%.2g)", apart);
            probe_close(&pr);
        }
    }
    cv_gpu_destroy(&gpu);
    return tap_done();
}
