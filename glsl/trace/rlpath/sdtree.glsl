// glsl/trace/rlpath/sdtree.glsl: the guide of rlpath's sdtree method
// (layout in shared/sdtree.h): the spatial leaf of a point, sampling a
// direction from its directional quadtree and the density of a direction,
// (CV_SD_RECORD) the training records of a path, and (CV_SD_SPLAT) their
// splat into the statistics of the tree being trained. Sampling reuses its
// two random numbers: u.x picks a cell of the quadtree's top block by its
// alias table (shared/sdtree.h), then below the cell, at each node, u.x
// picks the column of quadrants by their marginal and u.y the quadrant in
// it, each rescaled to [0, 1) within the choice, and what is left of them
// places the point in the last quadrant. The density of the point is the
// product of 4 times each quadrant's probability (the top block holds the
// product down to its cells); the pdf function finds the same cell and
// walks the same quadrants for a given point, so the two agree (a point on
// a quadrant edge, where they may part, has measure zero).
// Cost: a lookup is a fetch of its grid cell (with its bounds, in
// parallel) and a walk down the spatial tree below depth 3 g (one texel per
// level; the walk with the leaf's box, which the spatial filter needs,
// from the root); sampling one or two texels of the quadtree's top block
// and a pdf one, then one texel per quadtree level below it.
// Include after the local_size layout line. CV_SD_RECORD: the record
// images read-write (shade, escaped and shadow stages while training);
// CV_SD_SPLAT (with it): the statistics too (what splats a finished path's
// records: sd_flush.comp, at the end of each training pass), whose float
// adds need
// "#extension GL_NV_shader_atomic_float : enable" at the top of the file
// where the driver has it (NVIDIA, Mesa's llvmpipe), else compare-and-swap.
// CV_FROZEN (the programs of the passes after training, render.c):
// cv_sd_learning() is false, and a stage includes neither of the above.
#ifndef CV_RLPATH_SDTREE_GLSL
#define CV_RLPATH_SDTREE_GLSL

#include "shared/sdtree.h"
#include "../../lib/atomic_add.glsl"
#include "../../lib/constants.glsl"   // cv_mean3

layout(std140, binding = CV_UBO_SDTREE) uniform CvSdBlock { CvSdParams u_sd; };
layout(binding = CV_TEXUNIT_SD_TREE) uniform samplerBuffer sd_tree;
#ifdef CV_SD_RECORD
layout(rgba32f, binding = CV_IMAGE_SD_VERTS) uniform imageBuffer sd_verts;
layout(r32ui, binding = CV_IMAGE_SD_COUNTS) uniform uimageBuffer sd_counts;
#endif
#ifdef CV_SD_SPLAT
layout(r32ui, binding = CV_IMAGE_SD_STATS) uniform coherent uimageBuffer sd_stats;
// CV_SD_CAS (tests): compare-and-swap even where float atomics are there
#if defined(GL_NV_shader_atomic_float) && !defined(CV_SD_CAS)
#define CV_SD_FLOAT_ATOMICS
layout(r32f, binding = CV_IMAGE_SD_FLUX) uniform coherent imageBuffer sd_flux;
#endif
#endif

const float CV_SD_PI = 3.14159265358979323846;
const float CV_SD_ONE_MINUS_EPS = 0.99999994;

#ifdef CV_FROZEN
bool cv_sd_learning() { return false; }
#else
bool cv_sd_learning() { return u_sd.learn.x != 0u; }
#endif

// The orientation class of a normal n (shared/sdtree.h).
uint cv_sd_class(vec3 n)
{
    vec3 a = abs(n);
    uint ax = (a.x >= a.y && a.x >= a.z) ? 0u : (a.y >= a.z ? 1u : 2u);
    return 2u * ax + (n[ax] < 0.0 ? 1u : 0u);
}

// The class texel of point p and orientation class cls (shared/sdtree.h),
// -1 past the depth limit (a malformed table).
// Also the box of its spatial leaf: lo and size (the root cube u_sd.cube
// halved along each split's axis on the way down), which the spatial
// filter needs; the full descent from the root (cv_sd_class_texel: the
// same texel, through the grid block).
int cv_sd_class_texel_box(vec3 p, uint cls, out vec3 lo, out vec3 size)
{
    lo = u_sd.cube.xyz;
    size = vec3(u_sd.cube.w);
    int node = 0;
    vec4 n = texelFetch(sd_tree, 0);
    for (uint d = 0u; d < CV_SD_MAX_SPATIAL_DEPTH && n.x < CV_SD_LEAF; d++) {
        int axis = int(n.x);
        size[axis] *= 0.5;
        bool upper = p[axis] >= n.y;
        if (upper)
            lo[axis] = n.y;
        node = int(n.z) + (upper ? 1 : 0);
        n = texelFetch(sd_tree, node);
    }
    return n.x < CV_SD_LEAF ? -1 : int(n.z) + int(cls);
}

// The cell of coordinate x along axis a of the grid block at texel g
// (shared/sdtree.h), from the guess c, whose bounds texel is b: moved down
// while x is below its lower bound, up while at or above its upper one,
// as the descent's comparisons place x (a guess is off by at most a cell
// but where the cube's float coordinates are coarse against its cells).
int cv_sd_grid_axis(int g, int a, float x, int c, vec2 b)
{
    const int n = int(CV_SD_GRID_CELLS);
    while (c > 0 && x < b.x) {
        c--;
        b = texelFetch(sd_tree, g + a * n + c).xy;
    }
    while (c < n - 1 && x >= b.y) {
        c++;
        b = texelFetch(sd_tree, g + a * n + c).xy;
    }
    return c;
}

// The class texel of point p and orientation class cls, as
// cv_sd_class_texel_box finds it, through the grid block: the cell of p
// from its coordinates in the cube (its bounds and its cell texel fetched
// together, the cell texel again where the bounds move the cell), then the
// descent from the node the cell names.
int cv_sd_class_texel(vec3 p, uint cls)
{
    const int n = int(CV_SD_GRID_CELLS);
    int g = int(u_sd.grid.x), cells = g + 3 * n;
    // the guess, 0 for a point below the cube or not a number
    vec3 t = (p - u_sd.cube.xyz) * (float(n) / u_sd.cube.w);
    ivec3 c0;
    for (int a = 0; a < 3; a++)
        c0[a] = t[a] >= 1.0 ? int(min(t[a], float(n - 1))) : 0;
    int i0 = c0.x + n * (c0.y + n * c0.z);
    vec4 bx = texelFetch(sd_tree, g + c0.x);
    vec4 by = texelFetch(sd_tree, g + n + c0.y);
    vec4 bz = texelFetch(sd_tree, g + 2 * n + c0.z);
    vec4 w = texelFetch(sd_tree, cells + (i0 >> 2));
    ivec3 c = ivec3(cv_sd_grid_axis(g, 0, p.x, c0.x, bx.xy),
                    cv_sd_grid_axis(g, 1, p.y, c0.y, by.xy),
                    cv_sd_grid_axis(g, 2, p.z, c0.z, bz.xy));
    int i = c.x + n * (c.y + n * c.z);
    if ((i >> 2) != (i0 >> 2))
        w = texelFetch(sd_tree, cells + (i >> 2));
    int node = int(w[i & 3]);
    if (node < 0)
        return -1 - node + int(cls);   // a leaf above depth 3 g
    vec4 nd = texelFetch(sd_tree, node);
    for (uint d = 3u * CV_SD_GRID_LOG2; d < CV_SD_MAX_SPATIAL_DEPTH && nd.x < CV_SD_LEAF; d++) {
        node = int(nd.z) + (p[int(nd.x)] >= nd.y ? 1 : 0);
        nd = texelFetch(sd_tree, node);
    }
    return nd.x < CV_SD_LEAF ? -1 : int(nd.z) + int(cls);
}

// The class texel of point p and orientation class cls (shared/sdtree.h):
// x, its quadtree's root (a texel index); y, its guiding weight (0 before
// the first build: the empty table's classes have weight 0); z, its
// training root (cv_sd_light); zero where the table is malformed.
vec4 cv_sd_leaf(vec3 p, uint cls)
{
    int c = cv_sd_class_texel(p, cls);
    return c < 0 ? vec4(0.0) : texelFetch(sd_tree, c);
}

// The class's estimate of the light that a path bouncing on from it
// brings back, its irradiance about its axis (shared/sdtree.h: its
// training root's second texel, z), from the class texel `leaf`; -1 where
// it has none (too few records, or before the first build).
float cv_sd_light(vec4 leaf)
{
    if (!(leaf.z > 0.0))
        return -1.0;
    vec2 e = texelFetch(sd_tree, int(leaf.z) + 1).zw;
    return e.y > 0.0 ? e.x : -1.0;
}

// The square point of a unit direction, and back.
vec2 cv_sd_square(vec3 w)
{
    float u = clamp((w.z + 1.0) * 0.5, 0.0, CV_SD_ONE_MINUS_EPS);
    float v = (atan(w.y, w.x) + CV_SD_PI) * (0.5 / CV_SD_PI);
    return vec2(u, clamp(v, 0.0, CV_SD_ONE_MINUS_EPS));
}

vec3 cv_sd_dir(vec2 s)
{
    float z = clamp(2.0 * s.x - 1.0, -1.0, 1.0);
    float phi = 2.0 * CV_SD_PI * s.y - CV_SD_PI;
    float r = sqrt(max(0.0, 1.0 - z * z));
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Sampling node n (one texel, shared/sdtree.h): its four quadrants'
// probabilities, the fourth derived from the other three (as the host's
// cv_sdtree_node).
vec4 cv_sd_node_probs(vec4 n)
{
    return vec4(n.xyz, max(0.0, 1.0 - (n.x + n.y + n.z)));
}

// The texel of quadrant k's node of sampling node q with code w (its
// texel's w), 0 for a leaf quadrant: its children are consecutive from
// q + (w >> 4), one for each bit of w's low four.
int cv_sd_node_child(int q, float w, int k)
{
    uint code = uint(w), bit = 1u << uint(k);
    return (code & bit) == 0u ? 0 : q + int(code >> 4u) + bitCount(code & (bit - 1u));
}

// Draws a point of the quadtree below node q (on its square) with u in
// [0,1)^2; returns it on that square and its density there.
vec2 cv_sd_walk_sample(int q, vec2 u, out float pdf)
{
    vec2 lo = vec2(0.0);
    float side = 1.0;
    pdf = 1.0;
    for (uint d = 0u; d < CV_SD_MAX_DEPTH; d++) {
        vec4 n = texelFetch(sd_tree, q);
        vec4 p = cv_sd_node_probs(n);
        // the column: ix 0 holds quadrants 0 and 2
        float pc = p.x + p.z;
        int ix = u.x < pc ? 0 : 1;
        u.x = ix == 0 ? u.x / pc : (u.x - pc) / (1.0 - pc);
        float a = ix == 0 ? p.x : p.y, s = ix == 0 ? pc : p.y + p.w;
        float pr = a / s;
        int iy = u.y < pr ? 0 : 1;
        u.y = iy == 0 ? u.y / pr : (u.y - pr) / (1.0 - pr);
        u = clamp(u, vec2(0.0), vec2(CV_SD_ONE_MINUS_EPS));
        int k = ix + 2 * iy;
        pdf *= 4.0 * p[k];
        side *= 0.5;
        lo += side * vec2(float(ix), float(iy));
        int child = cv_sd_node_child(q, n.w, k);
        if (child == 0)
            break;
        q = child;
    }
    return lo + side * u;
}

// The density of point s of node q's square under the quadtree below it.
float cv_sd_walk_pdf(int q, vec2 s)
{
    float pdf = 1.0;
    for (uint d = 0u; d < CV_SD_MAX_DEPTH; d++) {
        vec4 n = texelFetch(sd_tree, q);
        int ix = s.x < 0.5 ? 0 : 1, iy = s.y < 0.5 ? 0 : 1;
        int k = ix + 2 * iy;
        pdf *= 4.0 * cv_sd_node_probs(n)[k];
        // the point in the quadrant, scaled to its square (exact in float)
        s = 2.0 * s - vec2(float(ix), float(iy));
        int child = cv_sd_node_child(q, n.w, k);
        if (child == 0)
            break;
        q = child;
    }
    return pdf;
}

// The most a point drawn in a top block's cell takes of the cell's side:
// above it the sum with the cell's corner could round to the next cell.
const float CV_SD_CELL_MAX = 1.0 - 1.0 / 1048576.0;

// Draws a point of the quadtree at texel root with u in [0,1)^2; returns
// it on the square and its density there (on the square): the cell from
// the top block's alias table with u.x (what is left of u.x, rescaled, and
// u.y place the point in it), then the walk below the cell, if any.
vec2 cv_sd_sample_square(int root, vec2 u, out float pdf)
{
    int l = int(u_sd.grid.y), side = 1 << l, n = side * side, b = root - n;
    float t = u.x * float(n);
    int c = min(int(t), n - 1);
    float f = t - float(c);
    vec4 cell = texelFetch(sd_tree, b + c);
    if (f < cell.y) {
        f = f / cell.y;
    } else {
        f = (f - cell.y) / (1.0 - cell.y);
        c = int(cell.z);
        cell = texelFetch(sd_tree, b + c);
    }
    vec2 p = clamp(vec2(f, u.y), vec2(0.0), vec2(CV_SD_ONE_MINUS_EPS));
    pdf = cell.x;
    if (cell.w != 0.0) {
        float pl;
        p = cv_sd_walk_sample(int(cell.w), p, pl);
        pdf *= pl;
    }
    p = min(p, vec2(CV_SD_CELL_MAX));
    return (vec2(float(c & (side - 1)), float(c >> l)) + p) * (1.0 / float(side));
}

// The density on the square of point s under the quadtree at texel root:
// its cell's in the top block, times the walk's below the cell.
float cv_sd_pdf_square(int root, vec2 s)
{
    int side = 1 << int(u_sd.grid.y);
    // scaling by a power of two and taking the cell off are exact, as the
    // walk's steps are
    vec2 t = s * float(side);
    ivec2 ci = min(ivec2(t), ivec2(side - 1));
    vec4 cell = texelFetch(sd_tree, root - side * side + ci.x + side * ci.y);
    return cell.w != 0.0 ? cell.x * cv_sd_walk_pdf(int(cell.w), t - vec2(ci)) : cell.x;
}

// Solid-angle versions.
vec3 cv_sd_sample(int root, vec2 u, out float pdf)
{
    vec2 s = cv_sd_sample_square(root, u, pdf);
    pdf *= 1.0 / (4.0 * CV_SD_PI);
    return cv_sd_dir(s);
}

float cv_sd_pdf(int root, vec3 w)
{
    return cv_sd_pdf_square(root, cv_sd_square(w)) * (1.0 / (4.0 * CV_SD_PI));
}

#ifdef CV_SD_RECORD
// Texel t of the slot's record k (shared/sdtree.h; u_sd.learn.z: the slots).
int cv_sd_record_texel(uint slot, uint k, uint t)
{
    return int(CV_SD_RECORD_TEXEL(slot, k, t, u_sd.learn.z));
}

// The record of the bounce that leaves the vertex at depth from p (of
// orientation class cls) in direction wi drawn with solid-angle density
// pdf (0: not a vertex the guide serves, skipped), with throughput beta
// after it.
void cv_sd_record(uint slot, uint depth, vec3 p, uint cls, vec3 wi, float pdf, vec3 beta)
{
    if (depth >= CV_SD_MAX_RECORDS)
        return;
    float b = cv_mean3(beta);
    imageStore(sd_verts, cv_sd_record_texel(slot, depth, 0u), vec4(p, b > 0.0 ? pdf : 0.0));
    vec2 s = cv_sd_square(wi) + vec2(float(cls), 0.0);
    imageStore(sd_verts, cv_sd_record_texel(slot, depth, 1u), vec4(s, b, 0.0));
}

// Light L that the path adds to the film (times its throughput: an
// emission hit or an unoccluded shadow ray) from the vertex at depth adds
// to the incident radiance of each bounce before it: L over the
// throughput after that bounce.
void cv_sd_found(uint slot, uint depth, vec3 L)
{
    float c = dot(L, vec3(1.0 / 3.0));
    if (!(c > 0.0) || isinf(c))
        return;
    uint n = min(depth, CV_SD_MAX_RECORDS);
    for (uint k = 0u; k < n; k++) {
        int t = cv_sd_record_texel(slot, k, 1u);
        vec4 r = imageLoad(sd_verts, t);
        if (r.z > 0.0)
            imageStore(sd_verts, t, vec4(r.xyz, r.w + c / r.z));
    }
}

// The path of the slot ended at depth: its records of the bounces before
// wait for the shadow rays of its last vertex, until the pass ends
// (cv_sd_flush).
void cv_sd_path_end(uint slot, uint depth)
{
    imageStore(sd_counts, int(slot), uvec4(min(depth, CV_SD_MAX_RECORDS)));
}

#ifdef CV_SD_SPLAT
// cv_sd_add(w, v): adds the float v to word w of the statistics, exact
// (the compare-and-swap retried until it lands, as the native add is).
#ifdef CV_SD_FLOAT_ATOMICS
CV_ATOMIC_ADD_NATIVE(cv_sd_add, sd_flux)
#else
CV_ATOMIC_ADD_CAS(cv_sd_add, sd_stats, CV_ATOMIC_ADD_RETRY_EXACT)
#endif

// What a record adds to its quadtree (src/trace/sdtree.c, rec_value: the
// same formula): the Monte Carlo estimate of the incident radiance times
// the cosine to its class's axis, L / pdf * max(0, cos); -1 for a record
// that does not count (no density, a value not finite or below 0).
float cv_sd_value(vec3 p, float pdf, uint cls, vec2 s, float L)
{
    float v = L / pdf;
    if (!(pdf > 0.0) || isinf(v) || isnan(v) || !(v >= 0.0) || any(isinf(p)) || any(isnan(p)))
        return -1.0;
    vec3 w = cv_sd_dir(s);
    float c = w[cls / 2u] * ((cls & 1u) != 0u ? -1.0 : 1.0);
    return c > 0.0 ? v * c : 0.0;
}

// The footprint of side h about x in [0, 1] units of a grid of cells of
// side h from origin o, moved inside [o0, o0 + 1 * span] (span: the extent
// the footprint must stay in): the two cells it overlaps, as the centre of
// its part in each (lo, hi) and the share of it there (wlo, 1 - wlo).
// Shared by the spatial and the directional filter.
void cv_sd_footprint(float x, float h, float o, float o0, float span, out float plo,
                     out float phi, out float wlo)
{
    float c = clamp(x, o0 + 0.5 * h, o0 + span - 0.5 * h);
    float a = c - 0.5 * h, b = c + 0.5 * h;
    float t = (a - o) / h;
    float i0 = floor(t);
    float edge = o + (i0 + 1.0) * h;
    wlo = 1.0 - (t - i0);
    plo = 0.5 * (a + edge);
    phi = 0.5 * (edge + b);
}

// The statistics word of the leaf quadrant of point s in the training
// quadtree at texel q (its flux word; its count is 4 words on), and that
// quadrant's side (the record's directional footprint).
int cv_sd_train_leaf(int q, vec2 s, out float side)
{
    side = 1.0;
    for (uint d = 0u; d < CV_SD_MAX_DEPTH; d++) {
        side *= 0.5;
        int ix = s.x < 0.5 ? 0 : 1, iy = s.y < 0.5 ? 0 : 1;
        int k = ix + 2 * iy;
        s = 2.0 * s - vec2(float(ix), float(iy));
        int child = int(texelFetch(sd_tree, q)[k]);
        if (child == 0)
            return int(texelFetch(sd_tree, q + 1).x) + k;
        q = child;
    }
    return -1;   // deeper than the limit: a malformed table
}

// Adds flux v (if above 0) at the leaf quadrant of s in the training
// quadtree at texel q.
void cv_sd_add_leaf(int q, vec2 s, float v)
{
    float side;
    int w = v > 0.0 ? cv_sd_train_leaf(q, s, side) : -1;
    if (w >= 0)
        cv_sd_add(w, v);
}

// Adds flux v of a record at s to the training quadtree at texel q, whose
// leaf quadrant of s the caller found (cv_sd_train_leaf: word w, side h):
// to that leaf quadrant only (the host sums the inner quadrants from their
// children, sdtree.c, so no word above a leaf takes an add).
// With CV_SD_FILTER_DIRECTIONAL, Müller et al.'s box filter: a square of
// the side of that leaf quadrant, about s (moved inside the unit square,
// so that no flux is lost at its edges), overlaps at most four cells of
// that side; each takes the share of the square it holds (the bilinear
// weights of s), added at the leaf quadrant where the centre of that part
// falls (a neighbour split finer than the footprint takes its part
// there).
void cv_sd_splat_flux(int q, vec2 s, float v, int w, float h)
{
    if ((u_sd.learn.y & CV_SD_FILTER_DIRECTIONAL) == 0u) {
        if (w >= 0)
            cv_sd_add(w, v);
        return;
    }
    vec2 plo, phi, wlo;
    cv_sd_footprint(s.x, h, 0.0, 0.0, 1.0, plo.x, phi.x, wlo.x);
    cv_sd_footprint(s.y, h, 0.0, 0.0, 1.0, plo.y, phi.y, wlo.y);
    // four adds, written out: no per-thread array (NVIDIA's local memory)
    cv_sd_add_leaf(q, plo, v * (wlo.x * wlo.y));
    cv_sd_add_leaf(q, vec2(phi.x, plo.y), v * ((1.0 - wlo.x) * wlo.y));
    cv_sd_add_leaf(q, vec2(plo.x, phi.y), v * (wlo.x * (1.0 - wlo.y)));
    cv_sd_add_leaf(q, phi, v * ((1.0 - wlo.x) * (1.0 - wlo.y)));
}

// Splats one record into the tree being trained (shared/sdtree.h,
// "Statistics"), its value at most its class's limit (as the host's
// cv_sdtree_splat): its class's record counts and the count of the leaf
// quadrant it falls in in its own leaf's training quadtree, then its
// flux. With CV_SD_FILTER_SPATIAL, Müller et al.'s spatial box filter: a
// box of its leaf's size about the record (moved inside the root cube)
// overlaps at most eight cells of that size; each part's share of the
// flux goes to the leaf where the part's centre falls (all of it to the
// record's leaf where the neighbours are as large or larger), in the same
// class, through cv_sd_splat_flux. Counts stay with the record's own leaf
// and quadrant: they steer the refinement, which counts records.
void cv_sd_splat(vec3 p, float pdf, uint cls, vec2 s, float L)
{
    float v = cv_sd_value(p, pdf, cls, s, L);
    // the leaf's box for the spatial filter alone
    bool spatial = (u_sd.learn.y & CV_SD_FILTER_SPATIAL) != 0u;
    vec3 lo = vec3(0.0), size = vec3(0.0);
    int c = v < 0.0 ? -1
                    : (spatial ? cv_sd_class_texel_box(p, cls, lo, size) : cv_sd_class_texel(p, cls));
    if (c < 0)
        return;
    vec4 ct = texelFetch(sd_tree, c);
    // the class's limit of a record's value (its training root's second
    // texel, y; 0: none)
    float lim = texelFetch(sd_tree, int(ct.z) + 1).y;
    if (lim > 0.0 && v > lim)
        v = lim;
    int w = int(ct.w);
    imageAtomicAdd(sd_stats, w, 1u);
    if (v > 0.0)
        imageAtomicAdd(sd_stats, w + 1, 1u);
    float h;
    int lw = cv_sd_train_leaf(int(ct.z), s, h);
    if (lw >= 0)
        imageAtomicAdd(sd_stats, lw + 4, 1u);
    if (!(v > 0.0))
        return;
    if (!spatial) {
        cv_sd_splat_flux(int(ct.z), s, v, lw, h);
        return;
    }
    vec3 plo, phi, wlo;
    cv_sd_footprint(p.x, size.x, lo.x, u_sd.cube.x, u_sd.cube.w, plo.x, phi.x, wlo.x);
    cv_sd_footprint(p.y, size.y, lo.y, u_sd.cube.y, u_sd.cube.w, plo.y, phi.y, wlo.y);
    cv_sd_footprint(p.z, size.z, lo.z, u_sd.cube.z, u_sd.cube.w, plo.z, phi.z, wlo.z);
    for (int b = 0; b < 8; b++) {
        vec3 x = vec3((b & 1) != 0 ? phi.x : plo.x, (b & 2) != 0 ? phi.y : plo.y,
                      (b & 4) != 0 ? phi.z : plo.z);
        float f = ((b & 1) != 0 ? 1.0 - wlo.x : wlo.x) * ((b & 2) != 0 ? 1.0 - wlo.y : wlo.y) *
                  ((b & 4) != 0 ? 1.0 - wlo.z : wlo.z);
        if (!(f > 0.0))
            continue;
        int cb = cv_sd_class_texel(x, cls);
        if (cb < 0)
            continue;
        int qb = int(texelFetch(sd_tree, cb).z);
        float hb;
        int wb = cv_sd_train_leaf(qb, s, hb);
        cv_sd_splat_flux(qb, s, v * f, wb, hb);
    }
}

// Splats the finished path's records into the tree's statistics, before
// the slot's next path overwrites them: at the end of each training pass,
// which gives each slot one path (sd_flush.comp).
void cv_sd_flush(uint slot)
{
    uint n = imageLoad(sd_counts, int(slot)).x;
    if (n == 0u)
        return;
    imageStore(sd_counts, int(slot), uvec4(0u));
    for (uint k = 0u; k < n; k++) {
        vec4 a = imageLoad(sd_verts, cv_sd_record_texel(slot, k, 0u));
        if (a.w > 0.0) {
            vec4 b = imageLoad(sd_verts, cv_sd_record_texel(slot, k, 1u));
            float cls = floor(b.x);
            if (cls >= 0.0 && cls < float(CV_SD_CLASSES))
                cv_sd_splat(a.xyz, a.w, uint(cls), vec2(b.x - cls, b.y), b.w);
        }
    }
}
#endif
#endif

#endif
