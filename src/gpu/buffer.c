/* buffer.c: see buffer.h. */
#include "base/log.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"

/* data NULL: contents zeroed when `zero`, else undefined. */
static GLuint create(size_t bytes, const void *data, bool zero, const char *label,
                     struct cv_error *err)
{
    GLuint buf = 0;
    glCreateBuffers(1, &buf);
    /* A zero-size buffer cannot be bound; keep one word so that empty scene
     * arrays still bind. */
    glNamedBufferStorage(buf, (GLsizeiptr)(bytes ? bytes : 4), bytes ? data : NULL,
                         GL_DYNAMIC_STORAGE_BIT);
    if (zero && (!data || !bytes))
        cv_buffer_zero(buf);
    if (label)
        glObjectLabel(GL_BUFFER, buf, -1, label);
    if (!cv_gl_check(err, "creating buffer %s (%zu bytes)", label ? label : "", bytes)) {
        glDeleteBuffers(1, &buf);
        return 0;
    }
    return buf;
}

GLuint cv_buffer_create(size_t bytes, const void *data, const char *label, struct cv_error *err)
{
    return create(bytes, data, true, label, err);
}

GLuint cv_buffer_create_uninit(size_t bytes, const char *label, struct cv_error *err)
{
    return create(bytes, NULL, false, label, err);
}

void cv_buffer_destroy(GLuint *buf)
{
    if (buf && *buf) {
        glDeleteBuffers(1, buf);
        *buf = 0;
    }
}

bool cv_buffer_upload(GLuint buf, size_t offset, size_t bytes, const void *data,
                      struct cv_error *err)
{
    if (bytes == 0)
        return true;
    GLuint staging = 0;
    glCreateBuffers(1, &staging);
    glNamedBufferStorage(staging, (GLsizeiptr)bytes, data, 0);
    glCopyNamedBufferSubData(staging, buf, 0, (GLintptr)offset, (GLsizeiptr)bytes);
    glDeleteBuffers(1, &staging);
    return cv_gl_check(err, "uploading %zu bytes", bytes);
}

bool cv_buffer_read(GLuint buf, size_t offset, size_t bytes, void *dst, struct cv_error *err)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(buf, (GLintptr)offset, (GLsizeiptr)bytes, dst);
    return cv_gl_check(err, "reading back %zu bytes", bytes);
}

bool cv_buffer_read_staged(GLuint buf, size_t offset, size_t bytes, GLuint staging, void *dst,
                           struct cv_error *err)
{
    GLuint own = staging ? 0 : cv_buffer_create_uninit(bytes, "read-back staging", err);
    GLuint s = staging ? staging : own;
    if (!s)
        return false;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(buf, s, (GLintptr)offset, 0, (GLsizeiptr)bytes);
    bool ok = cv_buffer_read(s, 0, bytes, dst, err);
    cv_buffer_destroy(&own);
    return ok;
}

void cv_buffer_zero(GLuint buf)
{
    GLuint zero = 0;
    glClearNamedBufferData(buf, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void cv_buffer_zero_range(GLuint buf, size_t offset, size_t bytes)
{
    GLuint zero = 0;
    glClearNamedBufferSubData(buf, GL_R32UI, (GLintptr)offset, (GLsizeiptr)bytes, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
}

void cv_buffer_bind(GLuint buf, unsigned binding)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buf);
}

GLuint cv_buffer_texture(GLuint buf, GLenum format, size_t texels, struct cv_error *err)
{
    GLint max = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max);
    if (max > 0 && texels > (size_t)max) {
        cv_fail(err, "%zu texels exceed this GPU's buffer texture limit of %d", texels, max);
        return 0;
    }
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &tex);
    glTextureBuffer(tex, format, buf);
    if (!cv_gl_check(err, "buffer texture of %zu texels", texels)) {
        glDeleteTextures(1, &tex);
        return 0;
    }
    return tex;
}

bool cv_buffer_image_create(struct cv_buffer_image *im, GLuint buf, size_t texels, unsigned unit,
                            GLenum format, GLenum access, struct cv_error *err)
{
    *im = (struct cv_buffer_image){.unit = unit, .format = format, .access = access};
    im->tex = cv_buffer_texture(buf, format, texels, err);
    return im->tex != 0;
}

void cv_buffer_image_bind(const struct cv_buffer_image *im)
{
    glBindImageTexture(im->unit, im->tex, 0, GL_FALSE, 0, im->access, im->format);
}

void cv_buffer_image_destroy(struct cv_buffer_image *im)
{
    if (im->tex)
        glDeleteTextures(1, &im->tex);
    im->tex = 0;
}
