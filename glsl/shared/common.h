/* glsl/shared/common.h: lets one header declare a GPU struct for both C and
 * GLSL, so buffer layouts have a single source of truth. Layouts are std430:
 * use only 4-byte scalars and 16-byte vectors (no vec3, no vec2 after a
 * scalar), and keep every struct a multiple of 16 bytes. The C side checks
 * sizes with CV_CHECK_SIZE. The vector types are spelled cv_vec4, cv_uvec4
 * and cv_ivec4 on both sides: C structs here, GLSL's vec4, uvec4, ivec4.
 *
 * Naming, one rule for the tree: a type that exists on the GPU (declared
 * here for both languages, or in GLSL alone) is CvName, since GLSL has no
 * struct tags and C sees the same name through CV_STRUCT's typedef; a type
 * of the host alone is `struct cv_name`, never typedef'd. */
#ifndef CV_SHARED_COMMON_H
#define CV_SHARED_COMMON_H

/* Luminance of linear Rec.709 RGB, the render's space: one set of weights
 * for C and GLSL. */
#define CV_LUMA(r, g, b) (0.2126 * (r) + 0.7152 * (g) + 0.0722 * (b))

#ifdef GL_core_profile
#define CV_GLSL 1
#define CV_UINT uint
#define CV_INT int
#define CV_FLOAT float
#define cv_vec4 vec4
#define cv_uvec4 uvec4
#define cv_ivec4 ivec4
#define CV_STRUCT(name) struct name
#define CV_END(name) ;
#define CV_CHECK_SIZE(name, bytes)
#else
#include <stdint.h>
typedef struct { float x, y, z, w; } cv_vec4;
typedef struct { uint32_t x, y, z, w; } cv_uvec4;
typedef struct { int32_t x, y, z, w; } cv_ivec4;
#define CV_UINT uint32_t
#define CV_INT int32_t
#define CV_FLOAT float
#define CV_STRUCT(name) typedef struct name
#define CV_END(name) name;
#define CV_CHECK_SIZE(name, bytes) \
    _Static_assert(sizeof(name) == (bytes), #name " must be " #bytes " bytes (std430)")
#endif

#endif
