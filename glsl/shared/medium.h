/* glsl/shared/medium.h: participating media as the host (src/scene/media.c
 * builds them, src/trace/scene_upload.c uploads them) and the volumetric
 * stages (glsl/trace/medium) see them.
 *
 * Media are numbered from 1; 0 is vacuum (no medium), and media[0] is a
 * vacuum placeholder so that a medium's number indexes the buffer. A ray
 * carries the number of the medium it travels in (glsl/shared/trace.h,
 * CV_RAYF_MEDIUM_SHIFT), which leaves room for CV_MAX_MEDIA of them.
 *
 * A surface's MediumInterface sits in its material's `media` word
 * (glsl/shared/scene.h): CV_MEDIA_TRANSITION with inside in bits 0..7 and
 * outside in bits 8..15; 0 where the surface separates no media (pbrt-v4:
 * inside and outside are the same, or none given), and a ray keeps its
 * medium across it. Inside is the side the geometric normal points away
 * from, as pbrt-v4's GetMedium(w). */
#ifndef CV_SHARED_MEDIUM_H
#define CV_SHARED_MEDIUM_H

#include "shared/common.h"

#define CV_MEDIUM_VACUUM 0u
#define CV_MEDIUM_HOMOGENEOUS 1u
#define CV_MEDIUM_UNIFORMGRID 2u   /* pbrt-v4's GridMedium: a density grid */
#define CV_MEDIUM_RGBGRID 3u       /* pbrt-v4's RGBGridMedium: RGB sigma_a, sigma_s, Le grids */
#define CV_MEDIUM_CLOUD 4u         /* pbrt-v4's CloudMedium: a procedural noise density */
#define CV_MEDIUM_NANOVDB 5u       /* pbrt-v4's NanoVDBMedium: a uniformgrid sampled at corners */

#define CV_MAJORANT_RES 16u        /* majorant cells per axis (pbrt-v4's) */
#define CV_NO_GRID 0xffffffffu     /* a grid offset: this grid is absent */
#define CV_BLACKBODY_STEPS 512u    /* entries of a temperature grid's blackbody table */

#define CV_MAX_MEDIA 31u          /* numbers 1..31 fit the ray's 5 bits */
#define CV_MEDIA_TRANSITION 0x80000000u
#define CV_MEDIA_WORD(inside, outside) (CV_MEDIA_TRANSITION | (inside) | ((outside) << 8))

/* Coefficients are per unit of scene length, "scale" applied; the colour
 * channels are the render's RGB (linear Rec.709). In a grid medium at a
 * point inside its bounds, sigma_a is sigma_a.rgb times the lookup of grid
 * A, sigma_s is sigma_s.rgb times the lookup of grid S and the emitted
 * radiance Le.rgb times the lookup of grid E (a grid's lookup is 1 where
 * it is absent; a uniformgrid with a temperature grid emits, where the
 * temperature is above 100 K, grid E times the blackbody of that
 * temperature instead); outside its bounds a grid medium is vacuum. uniformgrid:
 * A and S are the density grid, E the Lescale grid (1 value or nx*ny*nz);
 * rgbgrid: A, S and E are RGB grids, sigma_a and sigma_s hold "scale" and
 * Le "Lescale". cloud: sigma_a and sigma_s times the cloud's density in
 * [0, 1] (glsl/trace/medium/cloud.glsl), not emissive; grids.x is the
 * offset of its 9 parameters (density, wispiness, frequency, the bounds'
 * low corner p0 and size p1 - p0 in medium space), and to_grid and the
 * majorant grid (res.w) are as for the grids.
 * nanovdb: as uniformgrid (A and S the density lattice, E
 * absent, Le "Lescale", emitting only through a temperature grid), but the
 * samples of its lattices run from corner to corner of the unit cube
 * (sample i at i / (res - 1), NanoVDB's voxels) where the other grids'
 * sit at cell centres ((i + 0.5) / res, pbrt-v4's SampledGrid). */
CV_STRUCT(CvMedium) {
    cv_vec4 sigma_a;   /* rgb: absorption; w: Henyey-Greenstein g in (-1, 1) */
    cv_vec4 sigma_s;   /* rgb: scattering; w: unused */
    cv_vec4 Le;        /* rgb: emitted radiance (Le x Lescale); w: unused */
    CV_UINT type;      /* CV_MEDIUM_* */
    CV_UINT emissive;  /* 1 when Le is not black */
    CV_UINT pad0;
    CV_UINT pad1;
    /* grid media only */
    cv_vec4 to_grid[3]; /* rows: render space to the grid's unit cube (p0 -> 0, p1 -> 1) */
    cv_uvec4 res;       /* xyz: nx ny nz of grids A and S; w: the majorant grid's offset */
    cv_uvec4 grids;     /* float offsets in the grid buffer of A, S, E (CV_NO_GRID: absent); w: 1 when A, S, E hold RGB */
    cv_uvec4 le_res;    /* xyz: the resolution of grid E */
    /* a uniformgrid's temperature grid (blackbody emission in place of
     * Le): x its offset (CV_NO_GRID: none; resolution res.xyz), y the
     * offset of its blackbody table (CV_BLACKBODY_STEPS RGB entries from
     * 100 K to temperature.z) */
    cv_uvec4 temperature_grids;
    cv_vec4 temperature; /* x: temperatureoffset, y: temperaturescale, z: the table's top */
} CV_END(CvMedium)
CV_CHECK_SIZE(CvMedium, 192);
/* A medium's texels in its buffer texture (CV_TEXUNIT_MEDIA) */
#define CV_MEDIUM_TEXELS 12

#endif
