// glsl/trace/medium/grid.glsl: grid media (CV_MEDIUM_UNIFORMGRID,
// CV_MEDIUM_RGBGRID, CV_MEDIUM_NANOVDB; glsl/shared/medium.h) as pbrt-v4
// defines them: the trilinear lookup of SampledGrid (samples at voxel
// centres, zero beyond the outermost ones) or of NanoVDB (samples at the
// lattice's corners), vacuum outside the bounds, and the walk over the
// coarse majorant grid with a 3D DDA (DDAMajorantIterator) for delta
// tracking (track.glsl) and ratio tracking (shadow.comp).
//
// The majorant is one value for all channels, the largest channel's bound
// (pbrt-v4's RGB grid does the same; its density grid keeps one per
// wavelength). Tentative collisions then have the same density in every
// channel, so ratio tracking's transmittance is unbiased per channel on
// its own, and delta tracking needs only the ratios of the channels'
// probabilities of real and null collisions (medium.glsl's one-sample MIS
// over the channels). pbrt-v4's cloud (CV_MEDIUM_CLOUD, cloud.glsl with
// CV_MEDIUM_CLOUDS) takes the same walk: only its point lookup differs.
// Compiled only with CV_MEDIUM_GRIDS; include from medium.glsl.
#ifndef CV_TRACE_MEDIUM_GRID_GLSL
#define CV_TRACE_MEDIUM_GRID_GLSL

// The grid buffer as a buffer texture (CV_TEXUNIT_MEDIUM_GRIDS), four
// floats a texel so that it reaches four times the driver's texel limit
// (GL_MAX_TEXTURE_BUFFER_SIZE; trace/scene_upload.c): float i of it.
// Beyond that limit the store goes on in pages of CV_MEDIUM_GRID_PAGE_TEXELS
// texels, pages 1 .. CV_MEDIUM_GRID_PAGES - 1 at units
// CV_TEXUNIT_MEDIUM_GRID_PAGES up (the loop's index is the same in every
// invocation, as GLSL asks of an index into an array of samplers).
layout(binding = CV_TEXUNIT_MEDIUM_GRIDS) uniform samplerBuffer cv_medium_grid_tex;
#ifdef CV_MEDIUM_GRID_PAGES
layout(binding = CV_TEXUNIT_MEDIUM_GRID_PAGES) uniform samplerBuffer
    cv_medium_grid_pages[CV_MEDIUM_GRID_PAGES - 1];
float cv_grid_float(uint i)
{
    uint t = i >> 2u, page = t / CV_MEDIUM_GRID_PAGE_TEXELS;
    int at = int(t - page * CV_MEDIUM_GRID_PAGE_TEXELS);
    vec4 v = vec4(0.0);
    if (page == 0u)
        v = texelFetch(cv_medium_grid_tex, at);
    for (uint k = 1u; k < uint(CV_MEDIUM_GRID_PAGES); k++)
        if (page == k)
            v = texelFetch(cv_medium_grid_pages[k - 1u], at);
    return v[i & 3u];
}
#else
float cv_grid_float(uint i) { return texelFetch(cv_medium_grid_tex, int(i >> 2u))[i & 3u]; }
#endif

#ifdef CV_MEDIUM_CLOUDS
#include "cloud.glsl"
#endif

bool cv_grid_medium(uint m)
{
    return cv_media(m).type == CV_MEDIUM_UNIFORMGRID || cv_media(m).type == CV_MEDIUM_RGBGRID ||
           cv_media(m).type == CV_MEDIUM_NANOVDB
#ifdef CV_MEDIUM_CLOUDS
           || cv_media(m).type == CV_MEDIUM_CLOUD  // a procedural density (cloud.glsl)
#endif
        ;
}

// Render space to the grid's unit cube (a point with w 1, a vector with 0).
vec3 cv_grid_space(uint m, vec4 p)
{
    return vec3(dot(cv_media(m).to_grid[0], p), dot(cv_media(m).to_grid[1], p),
                dot(cv_media(m).to_grid[2], p));
}

// Sample i of a grid (comps numbers per sample) at offset off, zero
// outside the grid.
vec3 cv_grid_sample(uint off, uvec3 res, uint comps, ivec3 i)
{
    if (any(lessThan(i, ivec3(0))) || any(greaterThanEqual(i, ivec3(res))))
        return vec3(0.0);
    uint k = off + ((uint(i.z) * res.y + uint(i.y)) * res.x + uint(i.x)) * comps;
    return comps == 3u ? vec3(cv_grid_float(k), cv_grid_float(k + 1u), cv_grid_float(k + 2u))
                       : vec3(cv_grid_float(k));
}

// The trilinear lookup at s in sample units (sample i at s = i); 1 for
// an absent grid.
vec3 cv_grid_lookup_at(uint off, uvec3 res, uint comps, vec3 s)
{
    if (off == CV_NO_GRID)
        return vec3(1.0);
    vec3 f = floor(s);
    ivec3 i = ivec3(f);
    vec3 d = s - f;
    vec3 v000 = cv_grid_sample(off, res, comps, i);
    vec3 v100 = cv_grid_sample(off, res, comps, i + ivec3(1, 0, 0));
    vec3 v010 = cv_grid_sample(off, res, comps, i + ivec3(0, 1, 0));
    vec3 v110 = cv_grid_sample(off, res, comps, i + ivec3(1, 1, 0));
    vec3 v001 = cv_grid_sample(off, res, comps, i + ivec3(0, 0, 1));
    vec3 v101 = cv_grid_sample(off, res, comps, i + ivec3(1, 0, 1));
    vec3 v011 = cv_grid_sample(off, res, comps, i + ivec3(0, 1, 1));
    vec3 v111 = cv_grid_sample(off, res, comps, i + ivec3(1, 1, 1));
    vec3 d00 = mix(v000, v100, d.x), d10 = mix(v010, v110, d.x);
    vec3 d01 = mix(v001, v101, d.x), d11 = mix(v011, v111, d.x);
    return mix(mix(d00, d10, d.y), mix(d01, d11, d.y), d.z);
}

// g in the unit cube in sample units of a grid of res samples of medium
// m: at cell centres, or a nanovdb lattice's corners.
vec3 cv_grid_samples(uint m, uvec3 res, vec3 g)
{
    return cv_media(m).type == CV_MEDIUM_NANOVDB ? g * vec3(res - 1u) : g * vec3(res) - 0.5;
}

// pbrt-v4's SampledGrid::Lookup at g in the unit cube; 1 for an absent grid.
vec3 cv_grid_lookup(uint off, uvec3 res, uint comps, vec3 g)
{
    return cv_grid_lookup_at(off, res, comps, g * vec3(res) - 0.5);
}

// sigma_a, sigma_s and emitted radiance of grid medium m at g in its unit
// cube (zero outside it).
void cv_grid_point(uint m, vec3 g, out vec3 sigma_a, out vec3 sigma_s, out vec3 Le)
{
    sigma_a = vec3(0.0);
    sigma_s = vec3(0.0);
    Le = vec3(0.0);
    if (any(lessThan(g, vec3(0.0))) || any(greaterThan(g, vec3(1.0))))
        return;
#ifdef CV_MEDIUM_CLOUDS
    if (cv_media(m).type == CV_MEDIUM_CLOUD) {
        float d = cv_cloud_density_at(m, g);
        sigma_a = cv_media(m).sigma_a.rgb * d;
        sigma_s = cv_media(m).sigma_s.rgb * d;
        return;
    }
#endif
    uvec4 grids = cv_media(m).grids;
    uvec3 res = cv_media(m).res.xyz;
    uint comps = grids.w != 0u ? 3u : 1u;
    vec3 s = cv_grid_samples(m, res, g);
    sigma_a = cv_media(m).sigma_a.rgb * cv_grid_lookup_at(grids.x, res, comps, s);
    sigma_s = cv_media(m).sigma_s.rgb * cv_grid_lookup_at(grids.y, res, comps, s);
    if (cv_media(m).emissive == 0u)
        return;
    uvec3 le_res = cv_media(m).le_res.xyz;
    Le = cv_media(m).Le.rgb * cv_grid_lookup_at(grids.z, le_res, comps, cv_grid_samples(m, le_res, g));
    uvec4 tg = cv_media(m).temperature_grids;
    if (tg.x != CV_NO_GRID) {
        // blackbody emission: the table's linear interpolation
        vec4 tp = cv_media(m).temperature;
        float T = (cv_grid_lookup_at(tg.x, res, 1u, s).x - tp.x) * tp.y;
        if (!(T > 100.0)) {
            Le = vec3(0.0);
            return;
        }
        float x = clamp((T - 100.0) / (tp.z - 100.0), 0.0, 1.0) * float(CV_BLACKBODY_STEPS - 1u);
        uint i = min(uint(x), CV_BLACKBODY_STEPS - 2u);
        uint k = tg.y + 3u * i;
        vec3 b0 = vec3(cv_grid_float(k), cv_grid_float(k + 1u), cv_grid_float(k + 2u));
        vec3 b1 = vec3(cv_grid_float(k + 3u), cv_grid_float(k + 4u), cv_grid_float(k + 5u));
        Le *= mix(b0, b1, x - float(i));
    }
}

// The majorant of cell c of medium m's majorant grid.
float cv_grid_majorant(uint m, ivec3 c)
{
    const uint R = CV_MAJORANT_RES;
    return cv_grid_float(cv_media(m).res.w + (uint(c.z) * R + uint(c.y)) * R + uint(c.x));
}

// A 3D DDA over the majorant cells along a ray (pbrt-v4's
// DDAMajorantIterator, in the grid's unit cube).
struct CvGridWalk {
    vec3 next;    // ray parameter where the walk crosses into the next cell per axis
    vec3 delta;   // ray parameter across one cell per axis
    ivec3 cell;
    ivec3 step;
    float t;      // start of the current cell
    float tmax;
};

// Starts the walk of the ray o + t d (render space, d unit) over [t0, t1]
// through medium m's bounds; false where it misses them.
bool cv_grid_walk_start(uint m, vec3 o, vec3 d, float t0, float t1, out CvGridWalk w)
{
    vec3 go = cv_grid_space(m, vec4(o, 1.0));
    vec3 gd = cv_grid_space(m, vec4(d, 0.0));
    // slab test against the unit cube
    vec3 inv = 1.0 / gd;
    vec3 ta = (vec3(0.0) - go) * inv, tb = (vec3(1.0) - go) * inv;
    vec3 lo = min(ta, tb), hi = max(ta, tb);
    float tin = max(t0, max(lo.x, max(lo.y, lo.z)));
    float tout = min(t1, min(hi.x, min(hi.y, hi.z)));
    w.t = tin;
    w.tmax = tout;
    if (!(tin < tout))
        return false;
    const float R = float(CV_MAJORANT_RES);
    vec3 p = go + tin * gd;
    for (int a = 0; a < 3; a++) {
        w.cell[a] = clamp(int(p[a] * R), 0, int(CV_MAJORANT_RES) - 1);
        w.delta[a] = 1.0 / (abs(gd[a]) * R);
        if (gd[a] >= 0.0) {
            w.next[a] = gd[a] > 0.0 ? tin + (float(w.cell[a] + 1) / R - p[a]) / gd[a] : 3.0e38;
            w.step[a] = 1;
        } else {
            w.next[a] = tin + (float(w.cell[a]) / R - p[a]) / gd[a];
            w.step[a] = -1;
        }
    }
    return true;
}

// The current cell: [ta, tb) along the ray and its majorant; then steps
// to the next. False once the walk has left the bounds or passed t1.
bool cv_grid_walk_next(uint m, inout CvGridWalk w, out float ta, out float tb, out float maj)
{
    if (!(w.t < w.tmax))
        return false;
    int a = w.next.x < w.next.y ? (w.next.x < w.next.z ? 0 : 2) : (w.next.y < w.next.z ? 1 : 2);
    ta = w.t;
    tb = min(w.tmax, w.next[a]);
    maj = cv_grid_majorant(m, w.cell);
    w.t = tb;
    w.cell[a] += w.step[a];
    w.next[a] += w.delta[a];
    if (w.cell[a] < 0 || w.cell[a] >= int(CV_MAJORANT_RES))
        w.t = w.tmax;
    return true;
}

// Delta tracking through grid medium m over [t0, t1] of the ray o + t d,
// with tentative collisions against the majorant and each one real with
// the hero channel's probability sigma_t / majorant. u(n) are the walk's
// random numbers (key, n). True with t at a real collision. As
// cv_medium_sample_distance, the caller multiplies its throughput by
// weight and r is renormalised: a null collision weighs
// sigma_n / mean(r sigma_n), a real one 1 / mean(r sigma_t), the vertex
// then multiplying in sigma_s (the majorant and its transmittance are the
// same in every channel and cancel).
bool cv_grid_sample_distance(uint m, vec3 o, vec3 d, float t0, float t1, uint hero, uvec3 key,
                             inout uint n, inout vec3 r, out float t, out vec3 weight)
{
    weight = vec3(1.0);
    t = t1;
    CvGridWalk w;
    if (!cv_grid_walk_start(m, o, d, t0, t1, w))
        return false;
    float tau = -log(1.0 - cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++)));
    float ta, tb, maj;
    uint events = 0u;
    while (cv_grid_walk_next(m, w, ta, tb, maj)) {
        float tc = ta;
        while (maj > 0.0 && events < 4096u) {
            float dt = tau / maj;
            if (tc + dt >= tb) {
                tau -= maj * (tb - tc);
                break;
            }
            tc += dt;
            events++;
            vec3 sa, ss, Le;
            cv_grid_point(m, cv_grid_space(m, vec4(o + tc * d, 1.0)), sa, ss, Le);
            vec3 st = sa + ss;
            float u = cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++));
            if (u * maj < st[hero]) {
                float q = dot(r * st, vec3(1.0 / 3.0));
                weight = q > 0.0 ? weight / q : vec3(0.0);
                r = q > 0.0 ? r * st / q : r;
                t = tc;
                return true;
            }
            vec3 sn = max(vec3(maj) - st, vec3(0.0));
            float q = dot(r * sn, vec3(1.0 / 3.0));
            if (!(q > 0.0)) {
                weight = vec3(0.0);
                return false;
            }
            weight *= sn / q;
            r = r * sn / q;
            tau = -log(1.0 - cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++)));
        }
        if (events >= 4096u) {  // a runaway walk: the path ends here
            weight = vec3(0.0);
            return false;
        }
    }
    return false;
}

// Ratio tracking's estimate of the transmittance through grid medium m
// over [t0, t1] of the ray o + t d (pbrt-v4's TraceTransmittance, with its
// Russian roulette once every channel is below 0.05).
vec3 cv_grid_transmittance(uint m, vec3 o, vec3 d, float t0, float t1, uvec3 key)
{
    vec3 T = vec3(1.0);
    CvGridWalk w;
    if (!cv_grid_walk_start(m, o, d, t0, t1, w))
        return T;
    uint n = 0u;
    float tau = -log(1.0 - cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++)));
    float ta, tb, maj;
    while (cv_grid_walk_next(m, w, ta, tb, maj)) {
        float tc = ta;
        while (maj > 0.0) {
            float dt = tau / maj;
            if (tc + dt >= tb) {
                tau -= maj * (tb - tc);
                break;
            }
            tc += dt;
            vec3 sa, ss, Le;
            cv_grid_point(m, cv_grid_space(m, vec4(o + tc * d, 1.0)), sa, ss, Le);
            T *= max(vec3(maj) - sa - ss, vec3(0.0)) / maj;
            if (cv_max3(T) < 0.05) {
                if (cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++)) < 0.75)
                    return vec3(0.0);
                T /= 0.25;
            }
            if (n > 8192u)
                return vec3(0.0);
            tau = -log(1.0 - cv_uint_to_unit(cv_hash4(key.x, key.y, key.z, n++)));
        }
    }
    return T;
}

#endif
