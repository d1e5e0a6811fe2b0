/* shade_bins_test.c: the shade bin of each kind of material
 * (src/trace/shade_bins.h): diffuse in bin 0; what may take the coated
 * walk in bin 2 (a mix by its components); a coated diffuse that always
 * takes the closed form in bin 1 with the other materials; the
 * features that decide whether the bin-2 program is built; which
 * bins' kernels read textures (the others are built without them); and
 * whether bin 2 holds a mix (else its kernel carries only the coated
 * materials' code); and which bins hold a material rlpath's guide may
 * serve (the others are built without the guide). */
#include <string.h>

#include "base/mem.h"
#include "tests/tap.h"
#include "glsl/shared/rlpath.h"
#include "trace/shade_bins.h"

static CvMaterial mat(uint32_t type)
{
    CvMaterial m;
    memset(&m, 0, sizeof(m));
    m.type = type;
    m.displacement_tex = m.normal_tex = m.reflectance_tex = m.specular_tex = -1;
    m.roughness_u_tex = m.roughness_v_tex = m.alpha_tex = m.amount_tex = m.eta_tex = -1;
    m.mix_a = m.mix_b = -1;
    m.alpha = 1;
    return m;
}

int main(void)
{
    enum { DIFF, COND, GLASS, CLOSED, CLOSED_ROUGH, CLOSED_TEX, WALK_DIFF, COAT_COND, MIX_DD, MIX_DW,
           MIX_NEST, HAIR, N };
    CvMaterial ms[N];
    ms[DIFF] = mat(CV_MAT_DIFFUSE);
    ms[COND] = mat(CV_MAT_CONDUCTOR);
    ms[GLASS] = mat(CV_MAT_DIELECTRIC);
    ms[CLOSED] = mat(CV_MAT_COATED_DIFFUSE);
    ms[CLOSED].flags = CV_MATF_COAT_CLOSED;
    ms[CLOSED].roughness.x = ms[CLOSED].roughness.y = CV_COAT_CLOSED_ALPHA;
    ms[CLOSED_ROUGH] = ms[CLOSED];
    ms[CLOSED_ROUGH].roughness.x = 0.01f;
    ms[CLOSED_TEX] = ms[CLOSED];
    ms[CLOSED_TEX].roughness_v_tex = 0;
    ms[WALK_DIFF] = mat(CV_MAT_COATED_DIFFUSE);
    ms[COAT_COND] = mat(CV_MAT_COATED_CONDUCTOR);
    ms[MIX_DD] = mat(CV_MAT_MIX);
    ms[MIX_DD].mix_a = DIFF;
    ms[MIX_DD].mix_b = DIFF;
    ms[MIX_DW] = mat(CV_MAT_MIX);
    ms[MIX_DW].mix_a = DIFF;
    ms[MIX_DW].mix_b = COAT_COND;
    ms[MIX_NEST] = mat(CV_MAT_MIX);
    ms[MIX_NEST].mix_a = MIX_DD;
    ms[MIX_NEST].mix_b = MIX_DW;
    ms[HAIR] = mat(CV_MAT_HAIR);
    static const uint32_t want[N] = {0, 1, 1, 1, 2, 2, 2, 2, 1, 2, 2, 1};
    static const char *const names[N] = {
        "diffuse", "conductor", "dielectric", "closed-form coated diffuse",
        "closed-form allowed, rough coat", "closed-form allowed, textured roughness",
        "coated diffuse with a medium", "coated conductor", "mix of diffuse",
        "mix of diffuse and coated conductor", "mix of those mixes", "hair"};
    for (uint32_t i = 0; i < N; i++) {
        uint32_t b = cv_shade_bin(ms, N, i);
        tap_ok(b == want[i], "%s: bin %u (want %u)", names[i], b, want[i]);
    }
    cv_shade_bins_mark(ms, N);
    bool marked = true;
    for (uint32_t i = 0; i < N; i++)
        marked = marked && ms[i].flags >> CV_MATF_SHADE_BIN_SHIFT == want[i];
    tap_ok(marked && (ms[CLOSED].flags & CV_MATF_COAT_CLOSED), "marked in the flags, others kept");

    uint32_t bins;
    bool walk_closed;
    cv_shade_bins_features(ms, N, &bins, &walk_closed);
    tap_ok(bins == 7u && walk_closed, "every bin; the walk's may also take the closed form");
    cv_shade_bins_features(ms, CLOSED + 1, &bins, &walk_closed);
    tap_ok(bins == 3u && !walk_closed, "no walk among diffuse, conductor, dielectric, closed form");
    cv_shade_bins_features(ms + WALK_DIFF, 2, &bins, &walk_closed);
    tap_ok(bins == 4u && !walk_closed, "walks alone, without the closed form");

    /* textured bins */
    tap_ok(cv_shade_bins_textured(ms, N) == 4u, "only the textured roughness's bin reads textures");
    enum { T_DIFF, T_COAT, T_MIX, T_ALPHA, T_NORMAL, TN };
    CvMaterial ts[TN];
    ts[T_DIFF] = mat(CV_MAT_DIFFUSE);
    ts[T_DIFF].reflectance_tex = 0;
    ts[T_COAT] = mat(CV_MAT_COATED_CONDUCTOR);
    tap_ok(cv_shade_bins_textured(ts, 2) == 1u,
           "a textured diffuse beside an untextured coated conductor: bin 0 alone");
    ts[T_MIX] = mat(CV_MAT_MIX);
    ts[T_MIX].mix_a = T_DIFF;
    ts[T_MIX].mix_b = T_COAT;
    tap_ok(cv_shade_bins_textured(ts, 3) == 5u, "a walking mix with a textured component: bins 0 and 2");
    ts[T_ALPHA] = mat(CV_MAT_CONDUCTOR);
    ts[T_ALPHA].alpha_tex = 1;
    tap_ok(cv_shade_bins_textured(ts + T_COAT, 1) == 0u &&
               cv_shade_bins_textured(ts + T_ALPHA, 1) == 0u,
           "untextured, or a cut-out's alpha alone: no bin");
    ts[T_NORMAL] = mat(CV_MAT_CONDUCTOR);
    ts[T_NORMAL].normal_tex = 2;
    tap_ok(cv_shade_bins_textured(ts + T_NORMAL, 1) == 2u, "a normal map: its material's bin");
    /* a mix of two untextured coated conductors, its amount textured */
    CvMaterial am[2] = {mat(CV_MAT_COATED_CONDUCTOR), mat(CV_MAT_MIX)};
    am[1].mix_a = am[1].mix_b = 0;
    am[1].amount_tex = 1;
    tap_ok(cv_shade_bins_textured(am, 2) == 4u, "a mix's amount texture: the mix's bin");

    /* walk-only: no mix in bin 2 */
    tap_ok(!cv_shade_bins_walk_only(ms, N), "a mix in bin 2: not walk-only");
    tap_ok(cv_shade_bins_walk_only(ms, MIX_DD + 1),
           "every type, a mix of diffuse (bin 1) but none in bin 2: walk-only");
    tap_ok(!cv_shade_bins_walk_only(am, 2), "a mix of two coated conductors: not walk-only");
    tap_ok(cv_shade_bins_walk_only(ms, 0), "no material: walk-only (bin 2 unused)");

    /* guided: diffuse-like types, conductors and dielectrics where rough */
    enum { G_SMOOTH, G_GLASS, G_ROUGH, G_HALF, G_TEX, G_DIFF, G_MIX, G_CLOSED, G_HAIR, G_N };
    CvMaterial gs[G_N];
    gs[G_SMOOTH] = mat(CV_MAT_CONDUCTOR);
    gs[G_SMOOTH].roughness.x = gs[G_SMOOTH].roughness.y = 0.1f;
    gs[G_GLASS] = mat(CV_MAT_DIELECTRIC);
    gs[G_ROUGH] = mat(CV_MAT_CONDUCTOR);
    gs[G_ROUGH].roughness.x = gs[G_ROUGH].roughness.y = CV_RL_GLOSSY_ALPHA;
    gs[G_HALF] = gs[G_ROUGH];
    gs[G_HALF].roughness.y = 0.1f;   /* rough along one axis only */
    gs[G_TEX] = gs[G_SMOOTH];
    gs[G_TEX].roughness_u_tex = 0;
    gs[G_DIFF] = mat(CV_MAT_DIFFUSE);
    gs[G_MIX] = mat(CV_MAT_MIX);
    gs[G_MIX].mix_a = 0;   /* (in gx below) */
    gs[G_MIX].mix_b = 1;
    gs[G_CLOSED] = ms[CLOSED];
    gs[G_HAIR] = mat(CV_MAT_HAIR);
    tap_ok(cv_shade_bins_guided(gs, 2) == 0u,
           "a glossy conductor and smooth glass: no bin the guide serves");
    tap_ok(cv_shade_bins_guided(gs + G_HAIR, 1) == 0u, "hair: none");
    tap_ok(cv_shade_bins_guided(gs + G_ROUGH, 1) == 2u, "a rough conductor: bin 1");
    tap_ok(cv_shade_bins_guided(gs + G_HALF, 1) == 0u, "rough along one axis only: none");
    tap_ok(cv_shade_bins_guided(gs + G_TEX, 1) == 2u, "a textured roughness may be rough: bin 1");
    tap_ok(cv_shade_bins_guided(gs + G_DIFF, 1) == 1u, "diffuse: bin 0");
    CvMaterial gx[3] = {gs[G_GLASS], gs[G_DIFF], gs[G_MIX]};
    tap_ok(cv_shade_bins_guided(gx, 2) == 1u && cv_shade_bins_guided(gx, 3) == 3u,
           "glass and diffuse: bin 0; with a mix of the two: bin 1 too (the mix's)");
    tap_ok(cv_shade_bins_guided(gs + G_CLOSED, 1) == 2u,
           "a closed-form coated diffuse (diffuse-like): bin 1");
    tap_ok(cv_shade_bins_guided(ms + WALK_DIFF, 2) == 4u,
           "coated diffuse that walks: bin 2 by type (its kernel never guides: guides.glsl)");
    return tap_done();
}
