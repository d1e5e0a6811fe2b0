/* timer_test.c: the GPU timer (gpu/timer.h) adds each scope to its row and
 * to its slot, keeps rows that never ran at zero, logs one line per row that
 * took time, and does nothing when NULL (a stage's timer turned off). Times
 * themselves are not compared with any figure. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/log.h"
#include "gpu/buffer.h"
#include "gpu/program.h"
#include "gpu/timer.h"
#include "tests/gpu/gpu_test_util.h"

static void work(struct cv_program *prog, uint32_t n)
{
    glUseProgram(prog->id);
    glUniform1ui(glGetUniformLocation(prog->id, "u_count"), n);
    cv_program_dispatch_1d(prog, n);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

int main(void)
{
    struct cv_gpu *gpu = test_gpu_open(CV_BACKEND_AUTO);
    struct cv_error err = {{0}};
    const char *defines[] = {"SELFTEST_MUL=3u", NULL};
    struct cv_program *prog = cv_program_get(gpu, "gpu/selftest.comp", defines, &err);
    const uint32_t n = 1u << 20;
    GLuint b_in = cv_buffer_create(n * 4, NULL, "timer in", &err);
    GLuint b_out = cv_buffer_create(n * 4, NULL, "timer out", &err);
    if (!tap_ok(prog && b_in && b_out, "program and buffers: %s", err.msg))
        return tap_done();
    cv_buffer_bind(b_in, 0);
    cv_buffer_bind(b_out, 1);

    static const char *const names[] = {"first", "second", "never"};
    struct cv_gpu_timer *t = cv_gpu_timer_create(
        gpu, &(struct cv_gpu_timer_params){.names = names, .n_names = 3, .n_slots = 2});
    cv_gpu_timer_begin(t, 0, 0);
    work(prog, n);
    cv_gpu_timer_end(t);
    cv_gpu_timer_begin(t, 0, 1);
    work(prog, n);
    cv_gpu_timer_end(t);
    cv_gpu_timer_begin(t, 1, 5);  /* past n_slots: the row only */
    work(prog, n);
    cv_gpu_timer_end(t);
    cv_gpu_timer_collect(t);
    double r0 = cv_gpu_timer_ms(t, 0), s0 = cv_gpu_timer_slot_ms(t, 0, 0),
           s1 = cv_gpu_timer_slot_ms(t, 0, 1);
    tap_ok(r0 > 0 && s0 > 0 && s1 > 0, "timed work takes time: row %g ms, slots %g + %g", r0, s0,
           s1);
    tap_ok(r0 == s0 + s1, "a row is the sum of its slots' scopes");
    tap_ok(cv_gpu_timer_ms(t, 1) > 0 && cv_gpu_timer_slot_ms(t, 1, 0) == 0 &&
               cv_gpu_timer_slot_ms(t, 1, 1) == 0,
           "a scope without a slot counts in its row only");
    tap_ok(cv_gpu_timer_ran(t, 0) && cv_gpu_timer_ran(t, 1) && !cv_gpu_timer_ran(t, 2) &&
               cv_gpu_timer_ms(t, 2) == 0,
           "a row that never ran has no time");
    cv_gpu_timer_collect(t);
    tap_ok(cv_gpu_timer_ms(t, 0) == r0, "collecting again adds nothing");

    char *log = NULL;
    size_t log_len = 0;
    FILE *mem = open_memstream(&log, &log_len);
    cv_log_set_stream(mem);
    cv_gpu_timer_report(t, "phase");
    cv_log_set_stream(NULL);
    fclose(mem);
    tap_ok(strstr(log, "phase first ") && strstr(log, "phase second ") && !strstr(log, "never"),
           "the report has a line per row that took time");
    tap_diag("%s", log);
    free(log);
    cv_gpu_timer_destroy(&t);
    tap_ok(t == NULL, "destroy clears the pointer");

    struct cv_gpu_timer *off = NULL;
    cv_gpu_timer_begin(off, 0, 0);
    work(prog, 16);
    cv_gpu_timer_end(off);
    cv_gpu_timer_collect(off);
    cv_gpu_timer_report(off, "phase");
    tap_ok(cv_gpu_timer_ms(off, 0) == 0 && !cv_gpu_timer_ran(off, 0), "a NULL timer is off");
    cv_gpu_timer_destroy(&off);

    cv_buffer_destroy(&b_in);
    cv_buffer_destroy(&b_out);
    cv_gpu_destroy(&gpu);
    return tap_done();
}
