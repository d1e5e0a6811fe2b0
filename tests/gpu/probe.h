/* probe.h: one run of a probe program (a compute shader under a test/
 * folder of glsl/ that reads its input at CV_BIND_PROBE_IN and writes
 * CV_BIND_PROBE_OUT, n invocations given by u_count, what they do by
 * u_mode). A test sets the probe's own uniforms first, on the program
 * probe_use makes current, then calls probe_dispatch. */
#ifndef CV_TESTS_GPU_PROBE_H
#define CV_TESTS_GPU_PROBE_H

#include <stdbool.h>
#include <stddef.h>

#include <epoxy/gl.h>

#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/program.h"

/* Makes prog current for its uniforms; returns its GL name. */
static inline GLuint probe_use(const struct cv_program *prog)
{
    glUseProgram(prog->id);
    return prog->id;
}

/* Runs prog in mode for n invocations on in_bytes of in (NULL: no input,
 * a 16-byte placeholder bound) and reads out_bytes of its output into
 * out; false with err set when a buffer cannot be made or read. */
static inline bool probe_dispatch(const struct cv_program *prog, unsigned mode, const void *in,
                                  size_t in_bytes, size_t n, void *out, size_t out_bytes,
                                  struct cv_error *err)
{
    GLuint bin = cv_buffer_create(in ? in_bytes : 16, in, "probe in", err);
    GLuint bout = cv_buffer_create(out_bytes, NULL, "probe out", err);
    bool ok = bin && bout;
    if (ok) {
        cv_buffer_bind(bin, CV_BIND_PROBE_IN);
        cv_buffer_bind(bout, CV_BIND_PROBE_OUT);
        GLuint id = probe_use(prog);
        glUniform1ui(glGetUniformLocation(id, "u_mode"), mode);
        glUniform1ui(glGetUniformLocation(id, "u_count"), (GLuint)n);
        cv_program_dispatch_1d(prog, n);
        ok = cv_buffer_read(bout, 0, out_bytes, out, err);
    }
    cv_buffer_destroy(&bin);
    cv_buffer_destroy(&bout);
    return ok;
}

#endif
