/* gl_check.h: no GL error passes silently. After a group of GL calls,
 * cv_gl_check drains glGetError and fails with a label saying what was being
 * done ("uploading scene: GL_OUT_OF_MEMORY"). */
#ifndef CV_GPU_GL_CHECK_H
#define CV_GPU_GL_CHECK_H

#include <stdbool.h>

#include "base/error.h"

bool cv_gl_check(struct cv_error *err, const char *what_fmt, ...) CV_PRINTF(2, 3);
const char *cv_gl_error_name(unsigned code);

#endif
