/* rlpath_sd.h: the host side of rlpath's sdtree method (rlpath.method:
 * sdtree; trace/rlpath_sd.c, the tree build in trace/sdtree.h, the shaders
 * in glsl/trace/rlpath/sdtree.glsl and sd_shade.comp). The renderer owns
 * one through cv_rlpath_sd_ops (trace/integrator.h: cv_integrator_for). */
#ifndef CV_TRACE_RLPATH_SD_H
#define CV_TRACE_RLPATH_SD_H

#include <stdbool.h>
#include <stdint.h>

#include "base/error.h"
#include "gpu/context.h"
#include "trace/sdtree.h"

struct cv_rlpath_sd;

/* Creates the record, count and statistics buffers for n_paths path
 * slots and an empty guide (one unguided leaf) over the box [bmin, bmax]
 * (the flush program, sd_flush.comp, is first waited for at the end of the
 * first training iteration: a set-up does not wait for it). mix: guiding
 * weight of a leaf that learned (negative: cv_sdtree_defaults.mix); train:
 * the render parameter rl_train (cv_rlpath_train_spp). */
bool cv_rlpath_sd_create(struct cv_gpu *gpu, const float bmin[3], const float bmax[3],
                         uint32_t n_paths, float mix, uint32_t train, struct cv_rlpath_sd **out,
                         struct cv_error *err);

/* Binds the parameter block and images (after the renderer's bindings). */
void cv_rlpath_sd_bind(const struct cv_rlpath_sd *sd);

/* The spp at which the current training iteration ends (the renderer ends
 * a pass there), or, once training is over, where it ended. */
uint32_t cv_rlpath_sd_learn_until(const struct cv_rlpath_sd *sd);

/* Starts or stops recording from the next pass on (between passes). */
void cv_rlpath_sd_set_learning(struct cv_rlpath_sd *sd, bool learning);

/* Sets the training splat's filters (CV_SD_FILTER_* bits; default
 * cv_sdtree_defaults.filter). */
void cv_rlpath_sd_set_filter(struct cv_rlpath_sd *sd, uint32_t filter);

/* The most levels of the top blocks of the tables uploaded from now on
 * (cv_sdtree_opts.block_log2): tests, for the fewer levels a table with
 * many quadtrees that guide gets. */
void cv_rlpath_sd_set_block_log2(struct cv_rlpath_sd *sd, uint32_t levels);

/* After a pass that ends with spp_done samples per pixel: while training,
 * splats the records of every slot's path of the pass (one path a slot:
 * integrator.h, learn_path_a_slot) into the statistics; at the end of a
 * training iteration, reads them back, refines the guide and uploads it.
 * Waits for the GPU: once per training iteration. */
bool cv_rlpath_sd_pass_done(struct cv_rlpath_sd *sd, uint32_t spp_done, struct cv_error *err);

/* Learns the guide from n records on the host (cv_sdtree_learn_records)
 * and uploads it; tests call it with records of their own. */
bool cv_rlpath_sd_build(struct cv_rlpath_sd *sd, const struct cv_sd_record *rec, size_t n,
                        struct cv_error *err);

/* Splats n records (as the shaders keep them) through the shaders' flush
 * (sd_flush.comp, the shipped splat; cas: its compare-and-swap adds even
 * where the driver has float atomics) into zeroed statistics of the
 * current guide's training tree, and reads them back: *stats is allocated
 * (free it, also on failure), *words its length; tests. */
bool cv_rlpath_sd_splat(struct cv_rlpath_sd *sd, const struct cv_sd_record *rec, size_t n,
                        bool cas, uint32_t **stats, size_t *words, struct cv_error *err);

/* Accepts NULL; clears the pointer. */
void cv_rlpath_sd_destroy(struct cv_rlpath_sd **sd);

extern const struct cv_integrator_ops cv_rlpath_sd_ops;

#endif
