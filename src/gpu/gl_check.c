/* gl_check.c: see gl_check.h. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include <epoxy/gl.h>

#include "gpu/gl_check.h"

const char *cv_gl_error_name(unsigned code)
{
    switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_CONTEXT_LOST: return "GL_CONTEXT_LOST (GPU reset)";
    default: return "unknown GL error";
    }
}

bool cv_gl_check(struct cv_error *err, const char *what_fmt, ...)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR)
        return true;
    char what[512], names[512] = "";
    va_list ap;
    va_start(ap, what_fmt);
    vsnprintf(what, sizeof(what), what_fmt, ap);
    va_end(ap);
    /* Errors queue up (one flag per kind); report them all. */
    for (int i = 0; e != GL_NO_ERROR && i < 8; i++, e = glGetError()) {
        size_t n = strlen(names);
        snprintf(names + n, sizeof(names) - n, "%s%s", n ? ", " : "", cv_gl_error_name(e));
        if (e == GL_CONTEXT_LOST)
            break;
    }
    return cv_fail(err, "%s: %s", what, names);
}
