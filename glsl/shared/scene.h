/* glsl/shared/scene.h: the flat, GPU-ready scene as both C (src/scene builds
 * it) and GLSL (src/bvh and src/trace read it) see it. One source of truth:
 * change a field here and both sides follow.
 *
 * Conventions
 * - World space is pbrt's. Colours are linear Rec.709 RGB (the render's
 *   working space); spectra were converted on import.
 * - Triangles index vertices; a triangle's material word holds the material
 *   index in its low 24 bits and CV_TRI_* flags above.
 * - "_tex" fields are indices into the texture table, -1 for none; when a
 *   texture is present it replaces the constant next to it (scale, if any, is
 *   folded into a CV_TEX_SCALE texture by the importer).
 * - Roughness values are stored as microfacet alpha already (remaproughness
 *   applied on import) unless CV_MATF_REMAP_ROUGHNESS is set, which happens
 *   only when the roughness comes from a texture and must be remapped per
 *   lookup. */
#ifndef CV_SHARED_SCENE_H
#define CV_SHARED_SCENE_H

#include "shared/common.h"

/* ---- geometry ---------------------------------------------------------- */

/* pos_u.xyz: position; pos_u.w: u.  nrm_v.xyz: shading normal (all zero when
 * the mesh has none); nrm_v.w: v. */
CV_STRUCT(CvVertex) {
    cv_vec4 pos_u;
    cv_vec4 nrm_v;
} CV_END(CvVertex)
CV_CHECK_SIZE(CvVertex, 32);

#define CV_TRI_MATERIAL_MASK 0x00ffffffu
#define CV_TRI_HAS_UV (1u << 24)      /* else pbrt's default (0,0) (1,0) (1,1) */
#define CV_TRI_HAS_NORMAL (1u << 25)  /* vertex normals are valid */
#define CV_TRI_REVERSE (1u << 26)     /* ReverseOrientation xor handedness flip */

/* idx.xyz: vertex indices; idx.w: material word (see above). */
CV_STRUCT(CvTriangle) {
    cv_uvec4 idx;
} CV_END(CvTriangle)
CV_CHECK_SIZE(CvTriangle, 16);

/* ---- curves ------------------------------------------------------------ */

/* pbrt-v4's curve shape as cubic Bezier pieces (bspline and quadratic
 * input converted on import, src/scene/curves.c), each piece split into
 * 2^splitdepth primitives over [u_min, u_max] of its u. A hit on one is
 * prim = CV_PRIM_CURVE | curve index, with b1 = u and b2 = v (across the
 * width, 0..1) in place of the barycentrics (glsl/bvh/curves.glsl). */
#define CV_CURVE_FLAT 0u     /* a ribbon facing the ray */
#define CV_CURVE_CYLINDER 1u /* facing the ray, its normal bent across the width */
#define CV_CURVE_RIBBON 2u   /* oriented by the normals n0, n1 */
#define CV_PRIM_CURVE 0x80000000u

/* cp[k].xyz: the piece's control points (render space, or a moving
 * shape's object space); cp[0].w, cp[1].w:
 * width at u 0 and 1; cp[2].w, cp[3].w: u_min, u_max. n0, n1: ribbon
 * normals at u 0 and 1, n0.w the angle between them, n1.w 1 / its sine.
 * info.x: material word as a triangle's (material, CV_TRI_REVERSE);
 * info.y: CV_CURVE_* in its low byte (CV_CURVE_TYPE_MASK), above it
 * (CV_CURVE_XF_SHIFT) 0, or 1 + the index of the CvCurveXform whose
 * object space cp, widths and normals are in; info.z: its ID-matte object (scene.h tri_object's
 * numbering); info.w: 0 for a static curve, 1 + its moving shape's index
 * (src/scene/scene.h, cv_motion) for a moving one. */
CV_STRUCT(CvCurve) {
    cv_vec4 cp[4];
    cv_vec4 n0;
    cv_vec4 n1;
    cv_uvec4 info;
} CV_END(CvCurve)
CV_CHECK_SIZE(CvCurve, 112);

/* A curve whose transform is no similarity (a non-uniform scale or a
 * shear) is kept in its object space, as pbrt-v4 keeps every curve: its
 * width is an object-space width there, which no one scale factor carries
 * to render space. The ray is taken into that space to be intersected
 * and the hit's frame back (glsl/bvh/curves.glsl). to_world: rows of the
 * 3x4 affine transform from the curve's object space to the space its
 * tree lives in (render space, or a moving shape's object space);
 * to_object: its inverse. */
#define CV_CURVE_TYPE_MASK 0xffu
#define CV_CURVE_XF_SHIFT 8u
CV_STRUCT(CvCurveXform) {
    cv_vec4 to_world[3];
    cv_vec4 to_object[3];
} CV_END(CvCurveXform)
CV_CHECK_SIZE(CvCurveXform, 96);

/* ---- textures ---------------------------------------------------------- */

/* Pixel filters the renderer samples (src/scene/filter.h names them and
 * holds their defaults; CvPassParams.filter_type carries one). */
#define CV_FILTER_ID_BOX 0u
#define CV_FILTER_ID_TRIANGLE 1u
#define CV_FILTER_ID_GAUSSIAN 2u
#define CV_FILTER_ID_MITCHELL 3u
#define CV_FILTER_ID_SINC 4u

#define CV_TEX_CONSTANT 0u     /* value_a */
#define CV_TEX_IMAGE 1u        /* texels[offset..], width x height, mip chain */
#define CV_TEX_CHECKERBOARD 2u /* 2D checker of tex_a/value_a and tex_b/value_b */
#define CV_TEX_SCALE 3u        /* tex_a/value_a * tex_b/value_b */
#define CV_TEX_MIX 4u          /* lerp(tex_a/value_a, tex_b/value_b, amount_tex/amount) */
/* Composite textures (checkerboard, scale, mix) nest at most this deep
 * under a material: the shaders walk the root's operands and theirs
 * (bsdf/texture.glsl: cv_tex_eval); a composite deeper reads as its
 * value_a. The importer warns where a scene nests deeper. */
#define CV_TEX_MAX_NESTING 2

#define CV_TEXF_SRGB (1u << 0)        /* source was sRGB-encoded; texels are stored linear */
#define CV_TEXF_WRAP_CLAMP (1u << 1)  /* else repeat */
#define CV_TEXF_WRAP_BLACK (1u << 2)
#define CV_TEXF_INVERT (1u << 3)      /* 1 - value (v4 "invert") */
#define CV_TEXF_FLOAT (1u << 4)       /* a float texture: the average of r, g, b (grey images: r) */
/* Set by the loader on an image whose alpha pbrt-v4 keeps and that is not
 * 1 everywhere (an RGBA PNG, an EXR with A); the shaders do not read it. A
 * float texture of such an image is pbrt-v4's alpha (MIPMap::Bilerp<Float>):
 * it gets a copy of the texels with the alpha in r, g and b (scene/
 * texture.c), so the shaders' average is the alpha. */
#define CV_TEXF_ALPHA (1u << 9)
#define CV_TEXF_BILERP (1u << 5)      /* filter bilinear only (no mip) */
/* Sphere maps of image infinite lights (set by the loader, never by a
 * scene's "wrap"): the texels past an edge are those of the sphere there. */
#define CV_TEXF_WRAP_OCTAHEDRAL (1u << 6) /* pbrt-v4 equal-area square: an edge mirrors about its midpoint */
#define CV_TEXF_WRAP_LATLONG (1u << 7)    /* lat-long: repeat in u (longitude), clamp in v (the poles) */
#define CV_TEXF_RGBA32F (1u << 8)     /* texels in 32-bit float, else half */

/* Texels of all image textures live in one buffer of 8-byte slots. A
 * texel takes one slot in half-float RGBA (packHalf2x16(r,g),
 * packHalf2x16(b,a)), or with CV_TEXF_RGBA32F two slots of float RGBA
 * (floatBitsToUint r, g, b, a): images of high dynamic range (EXR, PFM,
 * Radiance HDR) are kept so, since half floats end at 65504 (an HDRI sun is
 * brighter) and lose precision long before; 8-bit images stay in half.
 * Level L of a texture starts at `offset` + the slots of levels 0..L-1,
 * each level half the size of the last (rounded down, at least 1). */
#define CV_TEX_SLOTS(flags) (((flags) & CV_TEXF_RGBA32F) != 0u ? 2u : 1u)
CV_STRUCT(CvTexture) {
    CV_UINT type;
    CV_UINT flags;
    CV_UINT offset;     /* in texel slots (8 bytes) */
    CV_UINT levels;
    CV_UINT width;
    CV_UINT height;
    CV_INT tex_a;
    CV_INT tex_b;
    cv_vec4 value_a;
    cv_vec4 value_b;
    cv_vec4 uv_map;     /* u' = su*u + du, v' = sv*v + dv: (su, sv, du, dv) */
    CV_INT amount_tex;
    CV_FLOAT amount;
    CV_FLOAT scale;     /* multiplies the result (pbrt "scale") */
    CV_UINT pad;
} CV_END(CvTexture)
CV_CHECK_SIZE(CvTexture, 96);

/* ---- materials --------------------------------------------------------- */

#define CV_MAT_DIFFUSE 0u              /* matte / diffuse: reflectance */
#define CV_MAT_CONDUCTOR 1u            /* metal / conductor: eta, k (or reflectance), roughness */
#define CV_MAT_DIELECTRIC 2u           /* glass / dielectric: eta, roughness, (v3 Kr/Kt in reflectance/specular) */
#define CV_MAT_THIN_DIELECTRIC 3u      /* thindielectric: eta */
#define CV_MAT_MIRROR 4u               /* mirror: reflectance = Kr */
#define CV_MAT_COATED_DIFFUSE 5u       /* plastic / substrate / coateddiffuse */
#define CV_MAT_COATED_CONDUCTOR 6u     /* coatedconductor: interface roughness/eta, conductor roughness2/eta/k */
#define CV_MAT_DIFFUSE_TRANSMISSION 7u /* reflectance = R, specular = T */
#define CV_MAT_MIX 8u                  /* mix_a, mix_b by amount */
#define CV_MAT_INTERFACE 9u            /* no surface: rays pass through */
#define CV_MAT_PLASTIC 10u             /* v3 plastic: Kd in reflectance, Ks in specular, roughness */
#define CV_MAT_HAIR 11u                /* hair: reflectance.rgb (see CV_MATF_HAIR_*), eta.x, roughness = beta_m, beta_n, alpha (degrees) */
#define CV_MAT_SUBSURFACE 12u          /* subsurface: a dielectric boundary (eta.x, roughness) over a BSSRDF:
                                          reflectance.rgb sigma_a, specular.rgb sigma_s [1 / scene unit],
                                          k.x its table (glsl/shared/bssrdf.h); see CV_MATF_SSS_POINT */
#define CV_MAT_MEASURED 13u            /* measured (RGL BRDF): mix_a = word offset of its tables (glsl/shared/measured.h) */

#define CV_MATF_REMAP_ROUGHNESS (1u << 0) /* remap textured roughness per lookup */
/* ... by pbrt-v3's polynomial (a pbrt-v3 material), not pbrt-v4's sqrt */
#define CV_MATF_ROUGHNESS_V3 (1u << 7)
#define CV_MATF_CONDUCTOR_REFLECTANCE (1u << 1) /* conductor given by reflectance, not eta/k */
#define CV_MATF_TWO_SIDED (1u << 2)
/* Which colour a hair material's reflectance.rgb holds (pbrt-v4's order:
 * sigma_a wins over reflectance, reflectance over the melanins): */
#define CV_MATF_HAIR_SIGMA_A (1u << 3)     /* absorption sigma_a (per radius) */
#define CV_MATF_HAIR_REFLECTANCE (1u << 4) /* colour, turned into sigma_a over beta_n */
                                           /* neither: (eumelanin, pheomelanin, -) */
#define CV_MATF_COAT_CLOSED (1u << 5) /* coated diffuse: closed form allowed, roughness2.xy its integrals */
/* conductor (or coated conductor's base) given by spectra: Fresnel from the
 * table k.w (glsl/shared/conductor_fresnel.h); eta.rgb, k.rgb keep RGB
 * averages */
#define CV_MATF_CONDUCTOR_FRESNEL (1u << 6)
/* Subsurface with textured coefficients: reflectance.rgb and specular.rgb
 * (and their textures) are sigma_a and sigma_s as given, times k.y (the
 * material's scale) per point; with CV_MATF_SSS_DIFFUSE, reflectance and
 * mfp, inverted through the table per point (pbrt-v4's
 * SubsurfaceFromDiffuse). */
#define CV_MATF_SSS_POINT (1u << 12)
#define CV_MATF_SSS_DIFFUSE (1u << 13)
/* Coats up to this alpha take the closed form (where allowed): pbrt-v4's
 * smooth coats (alpha below 1e-3) and alpha 1e-3 itself, what exporters
 * write for "smooth" (the coffee scene). At alpha 0.01 the rough coat's
 * walk already differs from it at grazing angles beyond noise (the
 * figures are in the commit that added bsdf_coat_closed_test). Read by
 * the shader (bsdf.glsl) and by the host's shade bins
 * (src/trace/shade_bins.c). */
#define CV_COAT_CLOSED_ALPHA 0.001f
/* The shade bin of the hit queue that shades the material (glsl/shared/
 * trace.h), set by the host on upload (src/trace/shade_bins.c): bits
 * CV_MATF_SHADE_BIN_SHIFT and up. */
#define CV_MATF_SHADE_BIN_SHIFT 30u

CV_STRUCT(CvMaterial) {
    CV_UINT type;
    CV_UINT flags;
    CV_INT displacement_tex;  /* float texture for bump mapping */
    CV_INT normal_tex;        /* tangent-space normal map image */

    cv_vec4 reflectance;      /* rgb: Kd, conductor reflectance, Kr, diffuse-transmission R */
    cv_vec4 specular;         /* rgb: plastic Ks, dielectric Kt, diffuse-transmission T, coat albedo */
    cv_vec4 eta;              /* rgb: conductor eta; .x: dielectric/interface eta */
    cv_vec4 k;                /* rgb: conductor k */
    cv_vec4 roughness;        /* x,y: alpha u,v; z: coat thickness; w: coat g */
    cv_vec4 roughness2;       /* x,y: coated conductor's base alpha u,v (coated diffuse: the closed form's
                                 r_in, t_out, src/scene/coat_closed.h); z: maxdepth; w: nsamples */

    CV_INT reflectance_tex;
    CV_INT specular_tex;
    CV_INT roughness_u_tex;
    CV_INT roughness_v_tex;

    CV_INT alpha_tex;         /* cut-out: alpha < 0.5 (or random test) passes through */
    CV_FLOAT alpha;           /* 1: opaque */
    CV_INT mix_a;             /* material indices */
    CV_INT mix_b;

    CV_INT amount_tex;        /* mix amount (probability of mix_b) */
    CV_FLOAT amount;
    CV_INT eta_tex;           /* spectrally constant eta as float texture, rarely used */
    CV_UINT media;            /* the surface's MediumInterface (glsl/shared/medium.h) */
} CV_END(CvMaterial)
CV_CHECK_SIZE(CvMaterial, 160);

/* ---- lights ------------------------------------------------------------ */

#define CV_LIGHT_POINT 0u
#define CV_LIGHT_SPOT 1u
#define CV_LIGHT_DISTANT 2u
#define CV_LIGHT_AREA 3u           /* one emitting triangle: prim */
#define CV_LIGHT_INFINITE 4u       /* constant environment: L */
#define CV_LIGHT_INFINITE_MAP 5u   /* image environment: tex (scaled by L) */

#define CV_LIGHTF_TWO_SIDED (1u << 0)
#define CV_LIGHTF_EQUAL_AREA (1u << 1) /* v4 octahedral map, else v3 lat-long */
/* an area light whose triangle's material is cut out (alpha): its points
 * emit nothing where the cut-out masks them (glsl/trace/light/light.glsl) */
#define CV_LIGHTF_ALPHA (1u << 2)
/* bits 8..15: the medium the light sits in (glsl/shared/medium.h; pbrt-v4's
 * outside medium where the light was made): where bdpt's light subpaths
 * start, unless an area light's surface is a medium transition */
#define CV_LIGHTF_MEDIUM_SHIFT 8u

CV_STRUCT(CvLight) {
    CV_UINT type;
    CV_UINT flags;
    CV_INT tex;           /* emission texture (area) or environment image */
    CV_UINT prim;         /* CV_LIGHT_AREA: triangle index */
    cv_vec4 L;            /* rgb: radiance (area, infinite) or intensity (point, spot)
                           * or radiance scale (distant: irradiance); w: area of prim */
    cv_vec4 position;     /* xyz: point/spot position; w: cos of spot falloff start */
    cv_vec4 direction;    /* xyz: spot/distant direction the light travels; w: cos of spot total width */
    cv_vec4 to_light[3];  /* rows of the world-to-light rotation (environment maps, spot) */
} CV_END(CvLight)
CV_CHECK_SIZE(CvLight, 112);

/* ---- camera ------------------------------------------------------------ */

#define CV_CAMERA_PERSPECTIVE 0u
#define CV_CAMERA_ORTHOGRAPHIC 1u
#define CV_CAMERA_EQUAL_AREA 2u  /* pbrt-v4's spherical, mapping "equalarea" */
#define CV_CAMERA_EQUIRECT 3u    /* ... "equirectangular"; pbrt-v3's environment */

/* A raster point (px, py) in [0,w)x[0,h) of the full film maps to screen
 * space sx = screen.x + (px / w) * (screen.y - screen.x),
 *              sy = screen.w - (py / h) * (screen.w - screen.z);
 * perspective: camera-space direction (sx * tan_half_fov, sy * tan_half_fov, 1),
 * orthographic: origin (sx, sy, 0), direction (0, 0, 1); both as in pbrt.
 * Thin lens as pbrt: lens.x radius, lens.y focal distance. The spherical
 * cameras ignore screen and lens: the raster point's (u, v) = (px / w,
 * py / h) maps to a direction d of the sphere, pbrt-v4's equal-area square
 * (lib/sampling.glsl) or theta = pi v, phi = 2 pi u about z, and the ray
 * leaves the origin along (d.x, d.z, d.y). to_world rows map camera space
 * to world space (3x4 affine). */
CV_STRUCT(CvCamera) {
    cv_vec4 to_world[3];
    cv_vec4 screen;       /* xmin, xmax, ymin, ymax */
    cv_vec4 lens;         /* x: lens radius, y: focal distance, z: tan(fov/2), w: unused */
    cv_uvec4 film;        /* full resolution x, y; crop origin x, y (pixels) */
    cv_uvec4 crop;        /* crop size x, y (pixels rendered); z, w: 0 */
    CV_UINT type;         /* CV_CAMERA_* */
    CV_UINT pad[3];
    /* Motion over the shutter: to_world_end at the end time, to_world at
     * the start time (pbrt's ActiveTransform / TransformTimes); equal rows
     * for a camera that does not move. time: x, y shutter open, close;
     * z, w the transforms' start, end times. */
    cv_vec4 to_world_end[3];
    cv_vec4 time;
} CV_END(CvCamera)
CV_CHECK_SIZE(CvCamera, 192);

#endif
