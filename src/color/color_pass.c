/* color_pass.c: see color.h. The program is built here rather than through
 * the program cache: its source differs per processor (OpenColorIO's
 * generated function is spliced into glsl/color/display.comp), and it owns
 * LUT textures that live and die with the pass. */
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "base/mem.h"
#include "color/color.h"
#include "color/ocio.h"
#include "glsl/shared/bindings.h"
#include "gpu/gl_check.h"
#include "gpu/glsl_source.h"
#include "gpu/program.h"

#define PASS_PATH "color/display.comp"
#define PASS_MARKER "//@cavalry-ocio-function"
#define PASS_FUNCTION "cv_ocio_display"
#define GENERATED_NAME "color/ocio-generated"

struct color_texture {
    GLuint id;
    GLenum target;
};

struct cv_color_pass {
    struct cv_ocio *ocio;
    struct cv_program prog;
    struct color_texture *textures;
    unsigned n_textures;
    GLint u_count;
};

/* 1-based line of the marker in glsl/color/display.comp, 0 when missing. */
static int marker_line(const char *text)
{
    int line = 1;
    for (const char *p = text; *p; line++) {
        const char *end = strchr(p, '\n');
        size_t n = end ? (size_t)(end - p) : strlen(p);
        if (n >= strlen(PASS_MARKER) && strncmp(p, PASS_MARKER, strlen(PASS_MARKER)) == 0)
            return line;
        if (!end)
            break;
        p = end + 1;
    }
    return 0;
}

/* The assembled pass source with the generated function in place of the
 * marker; *names gains GENERATED_NAME as the file of the generated lines. */
static bool splice_source(const char *generated, char **out, char ***names, struct cv_error *err)
{
    char *raw;
    if (!cv_glsl_read(PASS_PATH, &raw, err))
        return false;
    int line = marker_line(raw);
    free(raw);
    char *src;
    if (!cv_glsl_assemble(PASS_PATH, NULL, &src, names, err))
        return false;
    char *at = strstr(src, PASS_MARKER);
    if (!line || !at) {
        free(src);
        return cv_fail(err, "glsl/%s: the line \"%s\" is missing", PASS_PATH, PASS_MARKER);
    }
    int n_names = 0;
    while ((*names)[n_names])
        n_names++;
    /* the loader's table has room to spare: it holds up to 256 entries */
    (*names)[n_names] = cv_xstrdup(GENERATED_NAME);
    const char *rest = at + strlen(PASS_MARKER);
    *out = cv_xasprintf("%.*s#line 1 %d\n%s\n#line %d 0\n%s", (int)(at - src), src, n_names,
                        generated, line + 1, rest);
    free(src);
    return true;
}

static char *info_log(GLuint obj, bool program)
{
    GLint len = 0;
    if (program)
        glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else
        glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    char *log = cv_xcalloc(1, (size_t)len + 1);
    if (len > 0 && program)
        glGetProgramInfoLog(obj, len, NULL, log);
    else if (len > 0)
        glGetShaderInfoLog(obj, len, NULL, log);
    return log;
}

static bool build_program(struct cv_color_pass *pass, struct cv_error *err)
{
    char *src = NULL, **names = NULL;
    if (!splice_source(cv_ocio_gpu_source(pass->ocio), &src, &names, err))
        return false;
    GLuint sh = glCreateShader(GL_COMPUTE_SHADER);
    const GLchar *srcs[1] = {src};
    glShaderSource(sh, 1, srcs, NULL);
    glCompileShader(sh);
    GLint status = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &status);
    char *raw = info_log(sh, false);
    char *log = cv_glsl_map_log(raw, names);
    free(raw);
    bool ok = true;
    if (!status) {
        ok = cv_fail(err, "compiling glsl/%s with OpenColorIO's function failed:\n%s", PASS_PATH,
                     log);
    } else {
        GLuint prog = glCreateProgram();
        glAttachShader(prog, sh);
        glLinkProgram(prog);
        glGetProgramiv(prog, GL_LINK_STATUS, &status);
        if (!status) {
            char *plog = info_log(prog, true);
            ok = cv_fail(err, "linking glsl/%s failed:\n%s", PASS_PATH, plog);
            free(plog);
            glDeleteProgram(prog);
        } else {
            GLint size[3] = {1, 1, 1};
            glGetProgramiv(prog, GL_COMPUTE_WORK_GROUP_SIZE, size);
            pass->prog.id = prog;
            for (int i = 0; i < 3; i++)
                pass->prog.local_size[i] = (uint32_t)size[i];
            pass->prog.path = cv_xstrdup(PASS_PATH);
            pass->u_count = glGetUniformLocation(prog, "u_count");
        }
    }
    glDeleteShader(sh);
    free(log);
    free(src);
    for (char **n = names; *n; n++)
        free(*n);
    free(names);
    return ok && cv_gl_check(err, "building glsl/%s", PASS_PATH);
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
        GLint loc = glGetUniformLocation(pass->prog.id, t.sampler);
        if (loc >= 0)
            glProgramUniform1i(pass->prog.id, loc, (GLint)i);
        if (!cv_gl_check(err, "uploading colour LUT \"%s\" (%ux%ux%u)", t.sampler, t.width,
                         t.height, t.depth))
            return false;
    }
    return true;
}

static bool set_uniforms(struct cv_color_pass *pass, struct cv_error *err)
{
    GLuint prog = pass->prog.id;
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
    (void)gpu;
    *out = NULL;
    struct cv_color_pass *pass = cv_xcalloc(1, sizeof(*pass));
    bool ok = cv_ocio_create(p, &pass->ocio, err) &&
              cv_ocio_gpu_extract(pass->ocio, PASS_FUNCTION, err) &&
              build_program(pass, err) && upload_textures(pass, err) &&
              set_uniforms(pass, err);
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

static bool check_size(GLuint buf, const char *what, GLint64 need, struct cv_error *err)
{
    GLint64 size = 0;
    glGetNamedBufferParameteri64v(buf, GL_BUFFER_SIZE, &size);
    if (!cv_gl_check(err, "querying the colour pass %s buffer", what))
        return false;
    if (size < need)
        return cv_fail(err, "colour pass: the %s buffer holds %lld bytes, the image needs %lld",
                       what, (long long)size, (long long)need);
    return true;
}

bool cv_color_pass_run(struct cv_color_pass *pass, GLuint in_rgba, GLuint out_rgba,
                       uint32_t width, uint32_t height, struct cv_error *err)
{
    uint64_t n = (uint64_t)width * height;
    if (n == 0)
        return true;
    if (n > UINT32_MAX)
        return cv_fail(err, "colour pass: %ux%u pixels is too many", width, height);
    if (!check_size(in_rgba, "input", (GLint64)(n * 16), err) ||
        !check_size(out_rgba, "output", (GLint64)(n * 16), err))
        return false;
    glProgramUniform1ui(pass->prog.id, pass->u_count, (GLuint)n);
    for (unsigned i = 0; i < pass->n_textures; i++) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(pass->textures[i].target, pass->textures[i].id);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CV_BIND_STAGE0, in_rgba);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CV_BIND_STAGE0 + 1, out_rgba);
    cv_program_dispatch_1d(&pass->prog, n);
    for (unsigned i = 0; i < pass->n_textures; i++) {
        glActiveTexture(GL_TEXTURE0 + i);
        glBindTexture(pass->textures[i].target, 0);
    }
    glActiveTexture(GL_TEXTURE0);
    return cv_gl_check(err, "running the colour pass (%ux%u)", width, height);
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
    for (unsigned i = 0; i < p->n_textures; i++)
        glDeleteTextures(1, &p->textures[i].id);
    free(p->textures);
    if (p->prog.id)
        glDeleteProgram(p->prog.id);
    free(p->prog.path);
    cv_ocio_destroy(&p->ocio);
    free(p);
    *pass = NULL;
}
