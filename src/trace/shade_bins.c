/* shade_bins.c: see shade_bins.h. */
#include "trace/shade_bins.h"

#include "glsl/shared/rlpath.h"

/* A coated diffuse takes the closed form where the host allowed it and
 * its coat is smooth enough (bsdf.glsl: cv_bsdf_at); with a textured
 * roughness only the shader knows, so it may walk. */
static bool always_closed(const CvMaterial *m)
{
    return (m->flags & CV_MATF_COAT_CLOSED) && m->roughness_u_tex < 0 && m->roughness_v_tex < 0 &&
           m->roughness.x <= CV_COAT_CLOSED_ALPHA && m->roughness.y <= CV_COAT_CLOSED_ALPHA;
}

/* Mixes nest at most this deep (bsdf.glsl: cv_material_resolve). */
enum { MIX_DEPTH = 8 };

static uint32_t bin_of(const CvMaterial *ms, uint32_t n, int32_t i, int depth)
{
    if (i < 0 || (uint32_t)i >= n)
        return CV_SHADE_BIN_OTHER;
    const CvMaterial *m = &ms[i];
    switch (m->type) {
    case CV_MAT_DIFFUSE:
        return CV_SHADE_BIN_DIFFUSE;
    case CV_MAT_COATED_DIFFUSE:
        return always_closed(m) ? CV_SHADE_BIN_OTHER : CV_SHADE_BIN_WALK;
    case CV_MAT_COATED_CONDUCTOR:
        return CV_SHADE_BIN_WALK;
    case CV_MAT_MIX: {
        if (depth >= MIX_DEPTH)
            return CV_SHADE_BIN_OTHER;  /* the shader stops resolving there too */
        uint32_t a = bin_of(ms, n, m->mix_a, depth + 1), b = bin_of(ms, n, m->mix_b, depth + 1);
        uint32_t k = a > b ? a : b;
        return k > CV_SHADE_BIN_OTHER ? k : CV_SHADE_BIN_OTHER;
    }
    default:
        return CV_SHADE_BIN_OTHER;
    }
}

uint32_t cv_shade_bin(const CvMaterial *ms, uint32_t n, uint32_t i)
{
    return bin_of(ms, n, (int32_t)i, 0);
}

void cv_shade_bins_mark(CvMaterial *ms, uint32_t n)
{
    uint32_t keep = (1u << CV_MATF_SHADE_BIN_SHIFT) - 1u;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t bin = cv_shade_bin(ms, n, i);
        ms[i].flags = (ms[i].flags & keep) | bin << CV_MATF_SHADE_BIN_SHIFT;
    }
}

/* Whether material i reads a texture where it is shaded (see
 * cv_shade_bins_textured). */
static bool reads_texture(const CvMaterial *ms, uint32_t n, int32_t i, int depth)
{
    if (i < 0 || (uint32_t)i >= n)
        return false;
    const CvMaterial *m = &ms[i];
    if (m->reflectance_tex >= 0 || m->specular_tex >= 0 || m->roughness_u_tex >= 0 ||
        m->roughness_v_tex >= 0 || m->eta_tex >= 0 || m->normal_tex >= 0 || m->displacement_tex >= 0)
        return true;
    if (m->type != CV_MAT_MIX || depth >= MIX_DEPTH)
        return false;
    return m->amount_tex >= 0 || reads_texture(ms, n, m->mix_a, depth + 1) ||
           reads_texture(ms, n, m->mix_b, depth + 1);
}

/* A material's property, a mix's from its components (depth: the mix
 * nesting so far). */
typedef bool material_test(const CvMaterial *ms, uint32_t n, int32_t i, int depth);

/* The bins (bit b for bin b) of the materials that pass test. */
static uint32_t bins_where(const CvMaterial *ms, uint32_t n, material_test *test)
{
    uint32_t bins = 0;
    for (uint32_t i = 0; i < n; i++)
        if (test(ms, n, (int32_t)i, 0))
            bins |= 1u << cv_shade_bin(ms, n, i);
    return bins;
}

uint32_t cv_shade_bins_textured(const CvMaterial *ms, uint32_t n)
{
    return bins_where(ms, n, reads_texture);
}

/* Whether rlpath's guide may serve material i (see cv_shade_bins_guided). */
static bool may_guide(const CvMaterial *ms, uint32_t n, int32_t i, int depth)
{
    if (i < 0 || (uint32_t)i >= n)
        return false;
    const CvMaterial *m = &ms[i];
    if (CV_RL_DIFFUSE_LIKE(m->type))
        return true;
    if (CV_RL_GUIDED_WHERE_ROUGH(m->type))
        return m->roughness_u_tex >= 0 || m->roughness_v_tex >= 0 ||
               (m->roughness.x >= CV_RL_GLOSSY_ALPHA && m->roughness.y >= CV_RL_GLOSSY_ALPHA);
    if (m->type != CV_MAT_MIX || depth >= MIX_DEPTH)
        return false;
    return may_guide(ms, n, m->mix_a, depth + 1) || may_guide(ms, n, m->mix_b, depth + 1);
}

uint32_t cv_shade_bins_guided(const CvMaterial *ms, uint32_t n)
{
    return bins_where(ms, n, may_guide);
}

bool cv_shade_bins_walk_only(const CvMaterial *ms, uint32_t n)
{
    for (uint32_t i = 0; i < n; i++)
        if (ms[i].type == CV_MAT_MIX && cv_shade_bin(ms, n, i) == CV_SHADE_BIN_WALK)
            return false;
    return true;
}

void cv_shade_bins_features(const CvMaterial *ms, uint32_t n, uint32_t *bins, bool *walk_closed)
{
    *bins = 0;
    *walk_closed = false;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t bin = cv_shade_bin(ms, n, i);
        *bins |= 1u << bin;
        if (bin != CV_SHADE_BIN_WALK)
            continue;
        /* a mix may resolve to a closed-form coat */
        if ((ms[i].flags & CV_MATF_COAT_CLOSED) || ms[i].type == CV_MAT_MIX)
            *walk_closed = true;
    }
}
