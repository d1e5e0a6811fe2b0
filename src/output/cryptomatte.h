/* cryptomatte.h: ID mattes as the public Cryptomatte specification (Psyop,
 * version 1.1.0) lays them out: each name's MurmurHash3_x86_32 (seed 0)
 * stored as a float32 whose exponent is clamped to [1, 254]; per pixel the
 * CV_MATTE_RANK (id, coverage) pairs of most coverage, in RGBA layers
 * "<type>00", "<type>01", ... (R, B: ids; G, A: their coverage); and the
 * header attributes cryptomatte/<key>/name, hash, conversion and manifest
 * (JSON: name -> 8 hex digits of the float's bits), key being the first 7
 * hex digits of the type name's hash, as Blender and Arnold write it. */
#ifndef CV_OUTPUT_CRYPTOMATTE_H
#define CV_OUTPUT_CRYPTOMATTE_H

#include <stddef.h>
#include <stdint.h>

#include "glsl/shared/trace.h"   /* CV_MATTE_RANK */
#include "output/metadata.h"
#include "trace/render.h"        /* struct cv_matte_slots */

/* RGBA layers of one type: two ranks each. */
#define CV_CRYPTO_LAYERS ((CV_MATTE_RANK + 1) / 2)

/* MurmurHash3_x86_32 of len bytes. */
uint32_t cv_murmur3_32(const void *key, size_t len, uint32_t seed);

/* The float a hash is stored as (the specification's uint32_to_float32). */
float cv_crypto_float(uint32_t hash);
/* The id of name: cv_crypto_float of its hash, seed 0. */
float cv_crypto_id(const char *name);

/* One Cryptomatte type of a render. names[i] names matte id i + 1 (the
 * words hold 1 + index; 0: nothing hit); names may repeat, and ids of one
 * name are one matte, as the specification wants. */
struct cv_crypto_type {
    const char *layer;           /* "CryptoObject", "CryptoMaterial" */
    const char *const *names;
    uint32_t n_names;
    uint32_t first_word;         /* CV_MATTE_CRYPTO_OBJECT or _MATERIAL */
};

/* The CV_CRYPTO_LAYERS layers of t, each n_pixels * 4 floats (ids as
 * cv_crypto_float, coverage = the id's weight over the pixel's weight;
 * ranks by coverage, then by id bits; 0 where there is none), from the
 * slots of m (src/trace/render.h). */
void cv_crypto_layers(const struct cv_matte_slots *m, const struct cv_crypto_type *t,
                      float *layers[CV_CRYPTO_LAYERS]);

/* Sets cryptomatte/<key>/name, hash, conversion and manifest for t. */
void cv_crypto_metadata(struct cv_metadata *meta, const struct cv_crypto_type *t);

/* The names of plain ID AOVs (object_id, material_id: 1 + index) as a JSON
 * object "1": names[0], "2": names[1], ... Newly allocated. */
char *cv_id_names_json(const char *const *names, uint32_t n);

/* JSON object of every distinct name of t: "name": "<8 hex digits>".
 * Newly allocated. */
char *cv_crypto_manifest(const struct cv_crypto_type *t);

#endif
