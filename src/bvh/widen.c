/* widen.c: see widen.h. */
#include "bvh/widen.h"
#include "glsl/shared/bindings.h"
#include "gpu/buffer.h"
#include "gpu/gl_check.h"
#include "gpu/program.h"

static void bind_all(const struct cv_bvh_widen *w)
{
    cv_buffer_bind(w->bin, CV_BIND_WIDEN_BIN);
    cv_buffer_bind(w->info, CV_BIND_WIDEN_INFO);
    cv_buffer_bind(w->queue, CV_BIND_WIDEN_QUEUE);
    cv_buffer_bind(w->flags, CV_BIND_WIDEN_FLAGS);
    cv_buffer_bind(w->need, CV_BIND_WIDEN_NEED);
    cv_buffer_bind(w->cost, CV_BIND_WIDEN_COST);
    cv_buffer_bind(w->up, CV_BIND_WIDEN_UP);
}

static const char *const widen_files[5] = {"bvh/widen_next.comp", "bvh/widen_level.comp",
                                           "bvh/widen_emit.comp", "bvh/widen_up.comp",
                                           "bvh/widen_cost.comp"};

void cv_bvh_widen_prefetch(struct cv_gpu *gpu)
{
    for (int i = 0; i < 5; i++)
        cv_program_request(gpu, widen_files[i], NULL);
}

bool cv_bvh_widen_find(const struct cv_bvh_widen *w, uint32_t words[CV_BVH_INFO_WORDS],
                       struct cv_error *err)
{
    struct cv_program *next, *level, *up, *cost;
    if (!(next = cv_program_get(w->gpu, widen_files[0], NULL, err)) ||
        !(level = cv_program_get(w->gpu, widen_files[1], NULL, err)) ||
        !(up = cv_program_get(w->gpu, widen_files[3], NULL, err)) ||
        !(cost = cv_program_get(w->gpu, widen_files[4], NULL, err)))
        return false;
    GLint64 queue_bytes = 0;
    glGetNamedBufferParameteri64v(w->queue, GL_BUFFER_SIZE, &queue_bytes);
    cv_buffer_zero(w->flags);
    bind_all(w);
    /* The binary node count is on the GPU only: both passes run over the
     * most there can be and stop at info[CV_BVH_INFO_NODES]. */
    cv_program_set_uint(up, "u_n", w->n_max);
    cv_program_dispatch_1d(up, w->n_max);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    cv_program_set_uint(cost, "u_n", w->n_max);
    cv_program_dispatch_1d(cost, w->n_max);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, w->info);
    bool ok = true;
    /* Every level but the last finds a node, and there are fewer nodes
     * than queue entries, so the levels end before this bound. */
    uint32_t batch = w->levels ? w->levels : CV_BVH_WIDEN_LEVELS;
    uint64_t most = (uint64_t)queue_bytes / 4 + batch;
    for (uint64_t levels = 0; ok;) {
        for (uint32_t l = 0; l < batch; l++, levels++) {
            cv_program_set_uint(next, "u_start", levels == 0);
            cv_program_dispatch(next, 1, 1, 1);
            glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
            cv_program_dispatch_indirect(level, CV_BVH_INFO_DISPATCH * 4, 0);
        }
        ok = cv_buffer_read_staged(w->info, 0, CV_BVH_INFO_WORDS * 4, 0, words, err);
        if (!ok)
            break;
        uint32_t found = words[CV_BVH_INFO_WIDE];
        if ((uint64_t)found > (uint64_t)queue_bytes / 4)
            ok = cv_fail(err, "widening found more wide nodes (%u) than it has room for (%lld)",
                         found, (long long)(queue_bytes / 4));
        else if (found == words[CV_BVH_INFO_LEVEL_HI])
            break;
        else if (levels >= most)
            ok = cv_fail(err, "widening did not end after %llu levels", (unsigned long long)levels);
    }
    glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    return ok && cv_gl_check(err, "finding the 4-wide tree's nodes");
}

bool cv_bvh_widen_emit(const struct cv_bvh_widen *w, struct cv_scan *scan, uint32_t n_bin,
                       uint32_t n_wide, GLuint out, struct cv_error *err)
{
    struct cv_program *emit = cv_program_get(w->gpu, widen_files[2], NULL, err);
    if (!emit || !cv_scan_exclusive(scan, w->flags, n_bin, err))
        return false;
    bind_all(w);
    cv_buffer_bind(out, CV_BIND_BVH_NODES);
    cv_program_set_uint(emit, "u_n", n_wide);
    cv_program_dispatch_1d(emit, n_wide);
    return cv_gl_check(err, "writing the 4-wide tree's %u nodes", n_wide);
}
