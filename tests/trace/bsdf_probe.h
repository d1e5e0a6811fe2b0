/* bsdf_probe.h: runs glsl/trace/test/bsdf_probe.comp (the shipped BSDF
 * GLSL) from the BSDF tests: material setup, sampling and pdf evaluation at
 * a fixed shading point. */
#ifndef CV_TESTS_TRACE_BSDF_PROBE_H
#define CV_TESTS_TRACE_BSDF_PROBE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/scene.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "tests/gpu/gpu_test_util.h"

struct probe {
    struct cv_program *prog;
    GLuint materials, textures, texels, in, out;
    size_t cap_in, cap_out;
    float ng[3], ns[3], dpdu[3];
    float uv[2];  /* the shading point's uv (hair: v gives h); 0.5, 0.5 from probe_open */
};

static CvMaterial probe_material(unsigned type)
{
    CvMaterial m;
    memset(&m, 0, sizeof(m));
    m.type = type;
    m.displacement_tex = m.normal_tex = -1;
    m.reflectance_tex = m.specular_tex = m.roughness_u_tex = m.roughness_v_tex = -1;
    m.alpha_tex = m.amount_tex = m.eta_tex = -1;
    m.mix_a = m.mix_b = -1;
    m.alpha = 1;
    m.eta = (cv_vec4){1.5f, 1.5f, 1.5f, 1.5f};
    return m;
}

static void probe_frame(struct probe *p, const float ng[3], const float ns[3], const float dpdu[3])
{
    memcpy(p->ng, ng, sizeof(p->ng));
    memcpy(p->ns, ns, sizeof(p->ns));
    memcpy(p->dpdu, dpdu, sizeof(p->dpdu));
    p->uv[0] = p->uv[1] = 0.5f;
}

/* Like probe_open with the given texture table and texels (uvec2 each). */
static inline bool probe_open_tex(struct cv_gpu *gpu, struct probe *p, const CvMaterial *mats, size_t n_mats,
                           const CvTexture *tex, size_t n_tex, const uint32_t *texels, size_t n_texels,
                           struct cv_error *err)
{
    memset(p, 0, sizeof(*p));
    p->prog = cv_program_get(gpu, "trace/test/bsdf_probe.comp", NULL, err);
    if (!p->prog)
        return false;
    p->materials = cv_buffer_create(n_mats * sizeof(*mats), mats, "probe materials", err);
    p->textures = cv_buffer_create(n_tex * sizeof(*tex), tex, "probe textures", err);
    p->texels = cv_buffer_create(n_texels * 8, texels, "probe texels", err);
    float z[3] = {0, 0, 1}, x[3] = {1, 0, 0};
    probe_frame(p, z, z, x);
    return p->materials && p->textures && p->texels;
}

static inline bool probe_open(struct cv_gpu *gpu, struct probe *p, const CvMaterial *mats, size_t n_mats,
                       struct cv_error *err)
{
    memset(p, 0, sizeof(*p));
    p->prog = cv_program_get(gpu, "trace/test/bsdf_probe.comp", NULL, err);
    if (!p->prog)
        return false;
    CvTexture tex;
    memset(&tex, 0, sizeof(tex));
    tex.type = CV_TEX_CONSTANT;
    tex.tex_a = tex.tex_b = tex.amount_tex = -1;
    tex.scale = 1;
    uint32_t texel[2] = {0, 0};
    p->materials = cv_buffer_create(n_mats * sizeof(*mats), mats, "probe materials", err);
    p->textures = cv_buffer_create(sizeof(tex), &tex, "probe textures", err);
    p->texels = cv_buffer_create(sizeof(texel), texel, "probe texels", err);
    float z[3] = {0, 0, 1}, x[3] = {1, 0, 0};
    probe_frame(p, z, z, x);
    return p->materials && p->textures && p->texels;
}

static bool probe_reserve(GLuint *buf, size_t *cap, size_t bytes, struct cv_error *err)
{
    if (*cap >= bytes)
        return true;
    cv_buffer_destroy(buf);
    *buf = cv_buffer_create(bytes, NULL, "probe io", err);
    *cap = bytes;
    return *buf != 0;
}

/* mode 0: n samples, out gets 12 floats each (wi, pdf | f, flags |
 * f_eval, pdf_eval; pdf < 0: sampling failed). mode 1: `dirs` (4 floats
 * each) evaluated, out gets 4 floats each (f, pdf). mode 2: `dirs` holds
 * (u, v, u_mix, u_alpha), out gets 8 floats each (albedo, alpha pass |
 * shading normal, resolved type). mode 3: probe_query. */
static bool probe_run(struct probe *p, unsigned mode, unsigned material, const float wo[3], unsigned seed,
                      const float *dirs, size_t n, float *out, struct cv_error *err)
{
    size_t out_bytes = n * (mode == 0 ? 12 : (mode == 1 ? 4 : (mode == 2 ? 8 : 16))) * sizeof(float);
    size_t in_bytes = mode == 1 || mode == 2 ? n * 4 * sizeof(float) : 16;
    if (!probe_reserve(&p->out, &p->cap_out, out_bytes, err) ||
        (mode != 3 && !probe_reserve(&p->in, &p->cap_in, in_bytes, err)))
        return false;
    if ((mode == 1 || mode == 2) && !cv_buffer_upload(p->in, 0, n * 4 * sizeof(float), dirs, err))
        return false;
    cv_buffer_bind(p->materials, CV_BIND_MATERIALS);
    cv_buffer_bind(p->textures, CV_BIND_TEXTURES);
    cv_buffer_bind(p->texels, CV_BIND_TEXELS);
    cv_buffer_bind(p->in, CV_BIND_PROBE_IN);
    cv_buffer_bind(p->out, CV_BIND_PROBE_OUT);
    GLuint id = p->prog->id;
    glUseProgram(id);
    glUniform1ui(glGetUniformLocation(id, "u_mode"), mode);
    glUniform1ui(glGetUniformLocation(id, "u_count"), (GLuint)n);
    glUniform1ui(glGetUniformLocation(id, "u_material"), material);
    glUniform1ui(glGetUniformLocation(id, "u_seed"), seed);
    glUniform3f(glGetUniformLocation(id, "u_wo"), wo[0], wo[1], wo[2]);
    glUniform3f(glGetUniformLocation(id, "u_ng"), p->ng[0], p->ng[1], p->ng[2]);
    glUniform3f(glGetUniformLocation(id, "u_ns"), p->ns[0], p->ns[1], p->ns[2]);
    glUniform3f(glGetUniformLocation(id, "u_dpdu"), p->dpdu[0], p->dpdu[1], p->dpdu[2]);
    glUniform2f(glGetUniformLocation(id, "u_uv"), p->uv[0], p->uv[1]);
    cv_program_dispatch_1d(p->prog, n);
    return cv_buffer_read(p->out, 0, out_bytes, out, err);
}

/* mode 3: one query of `ask` (glsl/trace/bsdf/bsdf_query.glsl's CV_BQ_*
 * bits) per item; `in` holds 12 floats an item (wi0, 0 | wi1, 0 | uc, u,
 * 0), out gets 16 (f0, pdf0 | f1, pdf1 | wi, pdf | f, flags; flags -1: no
 * sample). */
static inline bool probe_query(struct probe *p, unsigned material, const float wo[3], unsigned seed, unsigned ask,
                               const float *in, size_t n, float *out, struct cv_error *err)
{
    if (!probe_reserve(&p->in, &p->cap_in, n * 12 * sizeof(float), err) ||
        !cv_buffer_upload(p->in, 0, n * 12 * sizeof(float), in, err))
        return false;
    glUseProgram(p->prog->id);
    glUniform1ui(glGetUniformLocation(p->prog->id, "u_ask"), ask);
    /* probe_run reads `in` only for modes 1 and 2: already uploaded */
    return probe_run(p, 3, material, wo, seed, NULL, n, out, err);
}

static void probe_close(struct probe *p)
{
    cv_buffer_destroy(&p->materials);
    cv_buffer_destroy(&p->textures);
    cv_buffer_destroy(&p->texels);
    cv_buffer_destroy(&p->in);
    cv_buffer_destroy(&p->out);
}

static inline void probe_dir(double theta_deg, double phi_deg, float w[3])
{
    double t = theta_deg * M_PI / 180, ph = phi_deg * M_PI / 180;
    w[0] = (float)(sin(t) * cos(ph));
    w[1] = (float)(sin(t) * sin(ph));
    w[2] = (float)cos(t);
}

#endif
