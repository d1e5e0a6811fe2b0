/* bsdf_query_test.c: one BSDF query asked for several things answers each
 * as a query asked for it alone (glsl/trace/bsdf/bsdf.glsl, cv_bsdf_query,
 * through bsdf_probe.comp). The query runs its estimates in slots that line
 * a warp's invocations up (a sampling and a guided bounce share slots 2 and
 * 3); every estimate hashes its own directions and numbers, so the slot an
 * answer comes from must change none of its bits. Per material (coated
 * walks with a smooth and a rough coat and a medium, a coated conductor,
 * and lobes that do not walk) and per mix of questions as the shade stages
 * ask them (path's, a guided bounce's, a guided bounce that lets the BSDF
 * pick its delta lobe, with and without the gates), random wi0, wi1 and
 * numbers against three single queries:
 *  - f and pdf at wi0 and at wi1 equal those asked alone, bit for bit (a
 *    gated pdf is 0 where its f is 0);
 *  - the sample equals the one asked alone; under CV_BQ_DELTA_ONLY a delta
 *    lobe's sample in full, another's direction and flags (its pdf stays
 *    the walk's proportional one). */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glsl/shared/bsdf_query.h"
#include "tests/rng.h"
#include "tests/trace/bsdf_probe.h"

#define N 2048

static uint64_t rs = 0x2545F4914F6CDD1Dull;
static float rnd(void)
{
    return (float)((cv_test_xorshift64_next(&rs) >> 40) * (1.0 / 16777216.0));
}

/* A direction with z above -0.5: a third of them below the surface, where
 * f is 0 and the gates act. */
static void sphere_dir(float w[4])
{
    float z = 1 - 2 * rnd() * 0.75f, phi = 6.2831853f * rnd(), r = sqrtf(fmaxf(0, 1 - z * z));
    w[0] = r * cosf(phi);
    w[1] = r * sinf(phi);
    w[2] = z;
    w[3] = 0;
}

static CvMaterial coated(bool conductor, float coat_alpha, float thick, float albedo)
{
    CvMaterial m = probe_material(conductor ? CV_MAT_COATED_CONDUCTOR : CV_MAT_COATED_DIFFUSE);
    m.reflectance = (cv_vec4){0.8f, 0.6f, 0.4f, 0};
    m.roughness = (cv_vec4){coat_alpha, coat_alpha, thick, 0.3f};
    m.roughness2 = (cv_vec4){0.3f, 0.3f, 10, 1};
    m.specular = (cv_vec4){albedo, albedo, albedo, 0};
    if (conductor)
        m.flags |= CV_MATF_CONDUCTOR_REFLECTANCE;
    m.eta.w = 1.5f;
    return m;
}

static bool same(const float *a, const float *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof(float)) == 0;
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    CvMaterial conductor = probe_material(CV_MAT_CONDUCTOR);
    conductor.eta = (cv_vec4){0.2f, 0.92f, 1.1f, 0};
    conductor.k = (cv_vec4){3.9f, 2.45f, 2.14f, 0};
    conductor.roughness = (cv_vec4){0.3f, 0.3f, 0, 0};
    CvMaterial diffuse = probe_material(CV_MAT_DIFFUSE);
    diffuse.reflectance = (cv_vec4){0.5f, 0.5f, 0.5f, 0};
    struct {
        const char *name;
        CvMaterial m;
    } mats[] = {
        {"coated diffuse, smooth coat, medium (walks, delta lobe)", coated(false, 0, 0.1f, 0.5f)},
        {"coated diffuse, coat alpha 0.2 (walks)", coated(false, 0.2f, 0.01f, 0)},
        {"coated conductor, smooth coat (walks, delta lobe)", coated(true, 0, 0.01f, 0)},
        {"rough conductor", conductor},
        {"diffuse", diffuse},
    };
    const unsigned E0 = CV_BQ_F0 | CV_BQ_PDF0, E1 = CV_BQ_F1 | CV_BQ_PDF1;
    struct {
        const char *name;
        unsigned ask;
    } asks[] = {
        {"path's (light sample, bounce)", E0 | CV_BQ_GATE0 | CV_BQ_SAMPLE},
        {"a guided bounce's", E0 | CV_BQ_GATE0 | E1},
        {"a guided bounce's, gated", E0 | CV_BQ_GATE0 | E1 | CV_BQ_GATE1},
        {"a guided bounce's with the BSDF's delta pick", E0 | CV_BQ_GATE0 | CV_BQ_SAMPLE | CV_BQ_DELTA_ONLY | E1 | CV_BQ_GATE1},
        {"everything, ungated", E0 | CV_BQ_SAMPLE | E1},
        {"a bounce without a light sample, guided", E1},
    };
    size_t n_mats = CV_ARRAY_SIZE(mats);
    CvMaterial table[CV_ARRAY_SIZE(mats)];
    for (size_t i = 0; i < n_mats; i++)
        table[i] = mats[i].m;
    struct probe p;
    if (!tap_ok(probe_open(gpu, &p, table, n_mats, &err), "probe shader and buffers: %s", err.msg)) {
        cv_gpu_destroy(&gpu);
        return tap_done();
    }
    float *in = malloc(N * 12 * sizeof(float)), *in1 = malloc(N * 12 * sizeof(float));
    float *out = malloc(N * 16 * sizeof(float)), *r0 = malloc(N * 16 * sizeof(float));
    float *r1 = malloc(N * 16 * sizeof(float)), *rs_ = malloc(N * 16 * sizeof(float));
    float wo[3];
    probe_dir(40, 25, wo);
    for (size_t m = 0; m < n_mats; m++) {
        for (size_t i = 0; i < N; i++) {
            sphere_dir(in + 12 * i);
            sphere_dir(in + 12 * i + 4);
            float *u = in + 12 * i + 8;
            u[0] = rnd(), u[1] = rnd(), u[2] = rnd(), u[3] = 0;
            /* wi1 asked as wi0 alone */
            memcpy(in1 + 12 * i, in + 12 * i + 4, 4 * sizeof(float));
            memcpy(in1 + 12 * i + 4, in + 12 * i + 4, 4 * sizeof(float));
            memcpy(in1 + 12 * i + 8, u, 4 * sizeof(float));
        }
        unsigned seed = 7 + (unsigned)m;
        if (!probe_query(&p, (unsigned)m, wo, seed, E0, in, N, r0, &err) ||
            !probe_query(&p, (unsigned)m, wo, seed, E0, in1, N, r1, &err) ||
            !probe_query(&p, (unsigned)m, wo, seed, CV_BQ_SAMPLE, in, N, rs_, &err)) {
            tap_ok(false, "%s: single queries: %s", mats[m].name, err.msg);
            continue;
        }
        size_t deltas = 0, zeros = 0;
        for (size_t i = 0; i < N; i++) {
            deltas += rs_[16 * i + 15] >= 0 && ((unsigned)rs_[16 * i + 15] & 4u);
            zeros += !(r1[16 * i] > 0 || r1[16 * i + 1] > 0 || r1[16 * i + 2] > 0);
        }
        tap_diag("%s: %zu of %d samples take a delta lobe, f is 0 at %zu of the wi1", mats[m].name, deltas, N,
                 zeros);
        for (size_t a = 0; a < CV_ARRAY_SIZE(asks); a++) {
            unsigned ask = asks[a].ask;
            if (!probe_query(&p, (unsigned)m, wo, seed, ask, in, N, out, &err)) {
                tap_ok(false, "%s, %s: %s", mats[m].name, asks[a].name, err.msg);
                continue;
            }
            size_t bad0 = 0, bad1 = 0, bads = 0;
            for (size_t i = 0; i < N; i++) {
                const float *o = out + 16 * i, *a0 = r0 + 16 * i, *a1 = r1 + 16 * i, *s = rs_ + 16 * i;
                float want[4];
                if (ask & CV_BQ_F0) {
                    memcpy(want, a0, sizeof(want));
                    if ((ask & CV_BQ_GATE0) && !(want[0] > 0 || want[1] > 0 || want[2] > 0))
                        want[3] = 0;
                    bad0 += !same(o, want, 4);
                }
                if (ask & CV_BQ_F1) {
                    memcpy(want, a1, sizeof(want));  /* r1 holds wi1's answer in its wi0 place */
                    if ((ask & CV_BQ_GATE1) && !(want[0] > 0 || want[1] > 0 || want[2] > 0))
                        want[3] = 0;
                    bad1 += !same(o + 4, want, 4);
                }
                if (ask & CV_BQ_SAMPLE) {
                    bool delta = s[15] >= 0 && ((unsigned)s[15] & 4u);
                    if (!(ask & CV_BQ_DELTA_ONLY) || delta)
                        bads += !same(o + 8, s + 8, 8);
                    else if (s[15] >= 0)  /* direction and flags; the pdf may stay proportional */
                        bads += !same(o + 8, s + 8, 3) || o[15] != s[15];
                }
            }
            tap_ok(bad0 == 0 && bad1 == 0 && bads == 0,
                   "%s, %s: every answer equals the one asked alone (differ: wi0 %zu, wi1 %zu, sample %zu of %d)",
                   mats[m].name, asks[a].name, bad0, bad1, bads, N);
        }
    }
    free(in);
    free(in1);
    free(out);
    free(r0);
    free(r1);
    free(rs_);
    probe_close(&p);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
