/* shade_bins.h: which shade bin of the hit queue shades each material
 * (glsl/shared/trace.h: CV_Q_HITS, CV_Q_HITS_B, CV_Q_HITS_C), the one home
 * of that choice. A bin's kernel carries the code and registers of every
 * BSDF its materials may resolve to, so the choice is by cost: bin 0 the
 * diffuse material (BSDF code cut down to it), bin 1 every other material
 * but those that may take the coated walk (glsl/trace/bsdf/layered.glsl),
 * bin 2 those, whose walk is by far the largest code (compile time) and
 * register set (occupancy) of the library. */
#ifndef CV_TRACE_SHADE_BINS_H
#define CV_TRACE_SHADE_BINS_H

#include <stdbool.h>
#include <stdint.h>

#include "glsl/shared/scene.h"

enum { CV_SHADE_BIN_DIFFUSE = 0, CV_SHADE_BIN_OTHER = 1, CV_SHADE_BIN_WALK = 2 };

/* The bin of material i of ms[0..n): of a mix, the largest of its
 * components' (at least CV_SHADE_BIN_OTHER, whose kernel resolves mixes). */
uint32_t cv_shade_bin(const CvMaterial *ms, uint32_t n, uint32_t i);

/* Writes every material's bin into its flags (CV_MATF_SHADE_BIN_SHIFT),
 * for the intersect stage's binning. */
void cv_shade_bins_mark(CvMaterial *ms, uint32_t n);

/* Which bins the scene's materials use (*bins: bit b for bin b; a bin no
 * material uses needs no program, but bin 0's always runs) and what the
 * bin-2 kernel must hold: *walk_closed, whether one of its materials may
 * also take the closed-form coat (coated_closed.glsl). */
void cv_shade_bins_features(const CvMaterial *ms, uint32_t n, uint32_t *bins, bool *walk_closed);

/* The bins (bit b for bin b) whose kernel reads a texture for one of the
 * materials it shades: a BSDF input, a normal or bump map, or a mix's
 * amount, its components' included (bsdf.glsl: cv_material_resolve,
 * cv_bsdf_at); a cut-out's alpha is the intersect and shadow stages'. A
 * bin outside the mask is built with CV_NO_TEXTURES where the scene's
 * lights read none either (trace/render.c): the texture walk is a large
 * part of the coated walk's build. */
uint32_t cv_shade_bins_textured(const CvMaterial *ms, uint32_t n);

/* The bins (bit b for bin b) holding a material of a type rlpath's guide
 * may serve (glsl/shared/rlpath.h: CV_RL_DIFFUSE_LIKE, and
 * CV_RL_GUIDED_WHERE_ROUGH where rough or of textured roughness; a mix as
 * its components). A bin outside the mask is built with CV_RL_UNGUIDED,
 * without the guide's lookups, which cost its kernel registers even where
 * they never run (trace/render.c). (The coated walk's bin is never guided
 * whatever its materials: rlpath/guides.glsl, cv_rl_guides.) */
uint32_t cv_shade_bins_guided(const CvMaterial *ms, uint32_t n);

/* Whether no material of bin 2 is a mix: then its kernel only ever shades
 * a coated diffuse or a coated conductor, and is built with
 * CV_BSDF_WALK_ONLY (glsl/trace/bsdf/bsdf.glsl; trace/render.c) without
 * the other types' code, which a mix may resolve to. */
bool cv_shade_bins_walk_only(const CvMaterial *ms, uint32_t n);

#endif
