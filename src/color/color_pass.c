/* color_pass.c: see color.h. OpenColorIO's generated function is spliced
 * into glsl/color/display.comp and the result built through the program
 * cache (gpu/program.h); the program may be shared with other passes of the
 * same processor, so the pass sets its uniforms and sampler units before
 * each run. The LUT textures are the pass's own. */
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "color/color.h"
#include "color/ocio.h"
#include "glsl/shared/bindings.h"
#include "gpu/buf.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

#define PASS_PATH "color/display.comp"
#define PASS_MARKER "//@cavalry-ocio-function"
#define PASS_FUNCTION "cv_ocio_display"
#define GENERATED_NAME "color/ocio-generated"

struct color_texture {
    GLuint id;
    GLenum target;
    char *sampler;             /* the sampler uniform's name */
};

struct cv_color_pass {
    struct cv_gpu *gpu;
    struct cv_buf *out;   /* display-referred RGBA; grows with the image */
    struct cv_ocio *ocio;
    struct cv_program prog;    /* a copy; the program cache owns the program */
    struct color_texture *textures;
    unsigned n_textures;
    GLint u_count;
};

/* Compiles display.comp with OpenColorIO's function in place of the
 * marker, through the program cache like every other program: the same
 * config and view in the next job (or the next process, from the disk
 * cache) need no compile. */
static bool build_program(struct cv_gpu *gpu, struct cv_color_pass *pass, struct cv_error *err)
{
    const struct cv_glsl_splice splice = {
        .marker = PASS_MARKER,
        .text = cv_ocio_gpu_source(pass->ocio),
        .name = GENERATED_NAME,
    };
    struct cv_program *prog = cv_program_get_spliced(gpu, PASS_PATH, NULL, &splice, err);
    if (!prog)
        return false;
    pass->prog = *prog;
    pass->u_count = glGetUniformLocation(prog->id, "u_count");
    return cv_gl_check(err, "building glsl/%s", PASS_PATH);
}

/* LUTs are uploaded for GL_LINEAR / GL_CLAMP_TO_EDGE lookups, as OCIO's
 * GLSL expects, but display.comp interpolates them itself from texel
 * fetches (glsl/color/lut_filter.glsl): hardware texture units blend with
 * fixed-point weights (8 fractional bits on NVIDIA), which put a coarse 3D
 * LUT ~1e-3 off OCIO's CPU result. The filter settings still serve any
 * lookup OCIO makes outside texture(). */
static bool upload_textures(struct cv_color_pass *pass, struct cv_error *err)
{
    unsigned n = cv_ocio_gpu_texture_count(pass->ocio);
    GLint max_units = 16;
    glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &max_units);
    if ((GLint)n > max_units)
        return cv_fail(err, "the colour transform needs %u LUT textures; this GPU binds %d", n,
                       max_units);
    pass->textures = cv_xcalloc(n ? n : 1, sizeof(*pass->textures));
    for (unsigned i = 0; i < n; i++) {
        struct cv_ocio_texture t;
        if (!cv_ocio_gpu_texture(pass->ocio, i, &t, err))
            return false;
        GLenum target = t.dims == 3 ? GL_TEXTURE_3D : t.dims == 2 ? GL_TEXTURE_2D : GL_TEXTURE_1D;
        GLenum internal = t.channels == 1 ? GL_R32F : GL_RGB32F;
        GLenum format = t.channels == 1 ? GL_RED : GL_RGB;
        GLint filter = t.linear ? GL_LINEAR : GL_NEAREST;
        struct color_texture *ct = &pass->textures[pass->n_textures++];
        ct->target = target;
        glGenTextures(1, &ct->id);
        glBindTexture(target, ct->id);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexParameteri(target, GL_TEXTURE_MIN_FILTER, filter);
        glTexParameteri(target, GL_TEXTURE_MAG_FILTER, filter);
        glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        if (target == GL_TEXTURE_3D)
            glTexImage3D(target, 0, (GLint)internal, (GLsizei)t.width, (GLsizei)t.height,
                         (GLsizei)t.depth, 0, format, GL_FLOAT, t.values);
        else if (target == GL_TEXTURE_2D)
            glTexImage2D(target, 0, (GLint)internal, (GLsizei)t.width, (GLsizei)t.height, 0,
                         format, GL_FLOAT, t.values);
        else
            glTexImage1D(target, 0, (GLint)internal, (GLsizei)t.width, 0, format, GL_FLOAT,
                         t.values);
        glBindTexture(target, 0);
        ct->sampler = cv_xstrdup(t.sampler);
        if (!cv_gl_check(err, "uploading colour LUT \"%s\" (%ux%ux%u)", t.sampler, t.width,
                         t.height, t.depth))
            return false;
    }
    return true;
}

/* The processor's uniforms and LUT sampler units, on the (shared) program. */
static bool set_uniforms(struct cv_color_pass *pass, struct cv_error *err)
{
    GLuint prog = pass->prog.id;
    for (unsigned i = 0; i < pass->n_textures; i++) {
        GLint loc = glGetUniformLocation(prog, pass->textures[i].sampler);
        if (loc >= 0)
            glProgramUniform1i(prog, loc, (GLint)i);
    }
    unsigned n = cv_ocio_gpu_uniform_count(pass->ocio);
    for (unsigned i = 0; i < n; i++) {
        struct cv_ocio_uniform u;
        if (!cv_ocio_gpu_uniform(pass->ocio, i, &u, err))
            return false;
        GLint loc = glGetUniformLocation(prog, u.name);
        if (loc < 0)
            continue;   /* optimised away by the compiler */
        switch (u.type) {
        case CV_OCIO_UNIFORM_FLOAT:
            glProgramUniform1f(prog, loc, u.v[0]);
            break;
        case CV_OCIO_UNIFORM_BOOL:
            glProgramUniform1i(prog, loc, u.b ? 1 : 0);
            break;
        case CV_OCIO_UNIFORM_FLOAT3:
            glProgramUniform3f(prog, loc, u.v[0], u.v[1], u.v[2]);
            break;
        case CV_OCIO_UNIFORM_FLOAT_ARRAY:
            if (u.count > 0)
                glProgramUniform1fv(prog, loc, u.count, u.fv);
            break;
        case CV_OCIO_UNIFORM_INT_ARRAY:
            if (u.count > 0)
                glProgramUniform1iv(prog, loc, u.count, u.iv);
            break;
        }
        if (!cv_gl_check(err, "setting colour uniform \"%s\"", u.name))
            return false;
    }
    return true;
}

bool cv_color_pass_create(struct cv_gpu *gpu, const struct cv_color_params *p,
                          struct cv_color_pass **out, struct cv_error *err)
{
    *out = NULL;
    struct cv_color_pass *pass = cv_xcalloc(1, sizeof(*pass));
    pass->gpu = gpu;
    bool ok = cv_ocio_create(p, &pass->ocio, err) &&
              cv_ocio_gpu_extract(pass->ocio, PASS_FUNCTION, err) &&
              build_program(gpu, pass, err) && upload_textures(pass, err);
    if (!ok) {
        cv_color_pass_destroy(&pass);
        return false;
    }
    cv_debug("colour: %s (config %s, %u LUT textures, %u uniforms)",
             cv_ocio_description(pass->ocio), cv_ocio_config_source(pass->ocio),
             pass->n_textures, cv_ocio_gpu_uniform_count(pass->ocio));
    *out = pass;
    return true;
}

bool cv_color_pass_run(struct cv_color_pass *pass, const struct cv_buf *in, uint32_t width,
                       uint32_t height, float *out_rgba, struct cv_error *err)
{
    uint64_t n = (uint64_t)width * height;
    if (n == 0)
        return true;
    if (n > UINT32_MAX)
        return cv_fail(err, "colour pass: %ux%u pixels is too many", width, height);
    size_t bytes = (size_t)n * 16;
    if (in->params.size < bytes)
        return cv_fail(err, "colour pass: the input buffer holds %zu bytes, the image needs %zu",
                       in->params.size, bytes);
    if (pass->out && pass->out->params.size < bytes)
        cv_buf_destroy(&pass->out);
    if ((!pass->out &&
         !(pass->out = cv_buf_create(pass->gpu, &(struct cv_buf_params){
                                                    .size = bytes, .storable = true,
                                                    .host_readable = true,
                                                    .label = "colour pass output"},
                                     err))) ||
        !set_uniforms(pass, err))
        return false;
    glProgramUniform1ui(pass->prog.id, pass->u_count, (GLuint)n);
    for (unsigned i = 0; i < pass->n_textures; i++) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(pass->textures[i].target, pass->textures[i].id);
    }
    cv_buf_bind(in, CV_BIND_COLOR_IN);
    cv_buf_bind(pass->out, CV_BIND_COLOR_OUT);
    cv_program_dispatch_1d(&pass->prog, n);
    for (unsigned i = 0; i < pass->n_textures; i++) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(pass->textures[i].target, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    return cv_gl_check(err, "running the colour pass (%ux%u)", width, height) &&
           cv_buf_read(pass->out, 0, bytes, out_rgba, err);
}

const char *cv_color_pass_description(const struct cv_color_pass *pass)
{
    return cv_ocio_description(pass->ocio);
}

const char *cv_color_pass_config_source(const struct cv_color_pass *pass)
{
    return cv_ocio_config_source(pass->ocio);
}

enum cv_display_encoding cv_color_pass_encoding(const struct cv_color_pass *pass)
{
    return cv_ocio_display_encoding(pass->ocio);
}

bool cv_color_apply_cpu(const struct cv_color_pass *pass, float *rgba, size_t n,
                        struct cv_error *err)
{
    return cv_ocio_apply_cpu(pass->ocio, rgba, n, err);
}

void cv_color_pass_destroy(struct cv_color_pass **pass)
{
    if (!pass || !*pass)
        return;
    struct cv_color_pass *p = *pass;
    for (unsigned i = 0; i < p->n_textures; i++) {
        glDeleteTextures(1, &p->textures[i].id);
        free(p->textures[i].sampler);
    }
    free(p->textures);
    cv_buf_destroy(&p->out);
    cv_ocio_destroy(&p->ocio);
    free(p);
    *pass = NULL;
}
