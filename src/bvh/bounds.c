/* bounds.c: see bounds.h. */
#include "bvh/bounds.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"

/* Each workgroup of bounds.comp takes 1024 elements per step; at most this
 * many groups, whose invocations then stride over several steps. */
#define BOUNDS_GROUPS 4096u

static uint32_t bounds_groups(uint32_t n)
{
    uint32_t g = (n + 1023) / 1024;
    return g < 1 ? 1 : g > BOUNDS_GROUPS ? BOUNDS_GROUPS : g;
}

uint64_t cv_bvh_bounds_bytes(uint32_t n)
{
    return (1 + (uint64_t)bounds_groups(n)) * 32;
}

void cv_bvh_bounds_dispatch(struct cv_program *bounds, uint32_t n, GLuint out, GLuint counter)
{
    cv_buffer_zero(counter);
    cv_buffer_bind(out, CV_BIND_BOUNDS_OUT);
    cv_buffer_bind(counter, CV_BIND_BOUNDS_DONE);
    cv_program_set_uint(bounds, "u_n", n);
    cv_program_dispatch_1d(bounds, (uint64_t)bounds_groups(n) * bounds->local_size[0]);
}
