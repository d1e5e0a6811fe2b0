/* rlpath.h: the host side of the rlpath integrator (reinforcement-learning
 * path guiding after Dahm and Keller 2017): the Q-table over a grid of the
 * scene bounds and normal classes times equal-area direction bins (layout:
 * glsl/shared/rlpath.h), its programs (glsl/trace/rlpath: shade.comp
 * replaces the path tracer's shade stage and learns there, rebuild.comp
 * runs after it; the escaped stage learns too, built with CV_RLPATH), and
 * the table layout from the options. The renderer (render.c) owns one,
 * through cv_rlpath_ops, when cv_render_params.integrator is
 * CV_INTEGRATOR_RLPATH. The table lives as
 * long as the renderer, so every pass keeps learning from the ones before. */
#ifndef CV_TRACE_RLPATH_H
#define CV_TRACE_RLPATH_H

#include <stdbool.h>
#include <stdint.h>

#include <epoxy/gl.h>

#include "base/error.h"
#include "glsl/shared/rlpath.h"
#include "gpu/context.h"
#include "gpu/program.h"

/* Fills the uniform block for a grid over the box [bmin, bmax] (world
 * units) with `grid` cells along its longest axis (the other axes get
 * proportionally many, at least 1), `directions` bins on the sphere (split
 * into round(sqrt(directions / 2)) z bands of twice as many phi sectors,
 * so the actual count may differ a little: see dirs.z), guiding weight
 * `mix` in [0, 1] (0: BSDF sampling alone). A grid or directions of 0 and a
 * negative mix select the defaults CV_RL_DEFAULT_*. Fails on a mix above 1
 * or NaN, more than CV_RL_MAX_BINS bins, a grid above 256
 * or a table above 1 GiB. */
bool cv_rlpath_layout(const float bmin[3], const float bmax[3], uint32_t grid,
                      uint32_t directions, float mix, CvRlParams *out, struct cv_error *err);

/* Bytes of the learning table and of the guide table of a layout
 * (glsl/shared/rlpath.h). */
uint64_t cv_rlpath_table_bytes(const CvRlParams *p);
uint64_t cv_rlpath_guide_bytes(const CvRlParams *p);

struct cv_rlpath;

/* Creates the tables (zero: every key unguided until it learns) and the
 * path state for n_paths path slots (glsl/shared/trace.h), and compiles
 * the rebuild program (the renderer builds the shade programs:
 * cv_rlpath_ops.file). guide_indirect: guide by the learned radiance less
 * lamps seen directly (guide.glsl). */
bool cv_rlpath_create(struct cv_gpu *gpu, const CvRlParams *layout, uint32_t n_paths,
                      bool guide_indirect, struct cv_rlpath **out, struct cv_error *err);

/* Binds the tables, path state and uniform block (after the renderer's own
 * bindings; the renderer's queue buffer must be the bound
 * GL_DISPATCH_INDIRECT_BUFFER). */
void cv_rlpath_bind(const struct cv_rlpath *rl);

/* The samples per pixel during which the table learns, from the render
 * parameter rl_train (0: CV_RL_DEFAULT_TRAIN; CV_RL_TRAIN_ALWAYS: every
 * pass, returned as 0). */
uint32_t cv_rlpath_train_spp(uint32_t train);
/* The same for a job's params (both methods' integrator.h train_spp). */
struct cv_render_params;
uint32_t cv_rlpath_job_train_spp(const struct cv_render_params *p);

/* Starts (true) or stops learning from the next pass on: the shade and
 * escaped stages add targets and keep path state only while learning.
 * Writes the parameter block when it changes: between passes only. */
void cv_rlpath_set_learning(struct cv_rlpath *rl, bool learning);

/* Queues the rebuild of the keys that the escaped and shade stages of this
 * iteration changed: run right after the shade stage. (Rebuilding every
 * fourth iteration instead saved no time: the rebuild is a small share of
 * rlpath's GPU time; bench/RESULTS.md, "path against rlpath, second
 * round".) */
void cv_rlpath_update(const struct cv_rlpath *rl);

/* Runs rebuild.comp (a program of trace/rlpath/rebuild.comp) over the keys
 * of layout p: rebuilds the guide texels of every key marked changed in the
 * bound learning table, then a barrier for image reads. Called by
 * cv_rlpath_update; tests call it on a table they filled. */
void cv_rlpath_dispatch_rebuild(const struct cv_program *rebuild, const CvRlParams *p);

/* Accepts NULL; clears the pointer. */
void cv_rlpath_destroy(struct cv_rlpath **rl);

/* The integrator table's entry (trace/integrator.h): the layout from the
 * render parameters and the scene bounds, the tables, shade.comp as the
 * one shade program over both bins, the rebuild after each shade stage. */
struct cv_integrator_ops;
extern const struct cv_integrator_ops cv_rlpath_ops;

#endif
