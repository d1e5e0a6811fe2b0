// glsl/trace/sss_vertex.glsl: the shade stage's side of the subsurface
// material (CV_HAS_SUBSURFACE), as pbrt-v4's volpath: where the boundary's
// BSDF sampled a transmission into the material, the path does not go on
// as a ray but as a BSSRDF probe segment (cv_sss_enter: axis, channel and
// radius drawn from the profile), which the intersect stage traces
// (sss_probe.glsl) for one of the material's surfaces along it, chosen
// uniformly among them; at that exit point (cv_sss_exit) the path is
// weighted by Sp over the density of having found it and goes on from
// the exit lobe Sw, with next-event estimation and MIS like any vertex
// (path_vertex.glsl), at the same depth as the entry: the probe is no
// bounce. The entry point, its normal, the (mix-resolved) subsurface
// material and its coefficients there (textures evaluated at the entry, as
// pbrt-v4 does) wait for the exit in an image of four texels a path slot
// (CV_IMAGE_SSS_ENTRY); the probe looks for the surface's material as
// the scene names it (a mix, where the subsurface is one of a mix's), as
// pbrt-v4 compares the intersections' materials. Include from
// path_vertex.glsl.
#ifndef CV_TRACE_SSS_VERTEX_GLSL
#define CV_TRACE_SSS_VERTEX_GLSL

#include "bsdf/bssrdf.glsl"

layout(rgba32f, binding = CV_IMAGE_SSS_ENTRY) uniform imageBuffer cv_sss_entry;

// Sample pairs of the probe and of the exit vertex: pairs of their own
// beside the bounce's (common.glsl: any number names a pair).
#define CV_PAIR_SSS 0x20000000u
#define CV_PAIR_SSS_PROBE (CV_PAIR_SSS + 0u)   // x: axis and channel, y: radius
#define CV_PAIR_SSS_ANGLE (CV_PAIR_SSS + 1u)   // x: angle about the axis
#define CV_PAIR_SSS_EXIT (CV_PAIR_SSS + 4u)    // + CV_PAIR_*: the exit vertex's own pairs

// At a hit on a subsurface material whose BSDF sample bs leaves through the
// boundary (into the material): the probe ray nr (o: its start, d.xyz: the
// segment, d.w: the surface's material; beta as the bounce would carry it,
// flagged CV_RAYF_PROBE). False ends the path (no segment: pbrt-v4 does the same).
bool cv_sss_enter(CvSurface sf, CvBsdf b, float path_w, uint path, uint depth, vec3 beta,
                  uint flags, uint medium, out CvRayItem nr)
{
    nr.o = vec4(0.0);
    nr.d = vec4(0.0);
    nr.beta = vec4(0.0);
    vec3 sigma_a, sigma_s;
    cv_bssrdf_sigma(b.material, b.medium.rgb, vec3(b.alpha.zw, b.thickness), sigma_a, sigma_s);
    CvBssrdf s = cv_bssrdf_make(sigma_a, sigma_s, uint(materials[b.material].k.x), b.eta);
    vec2 u = cv_bounce_2d(path, depth, CV_PAIR_SSS_PROBE);
    vec2 ua = cv_bounce_2d(path, depth, CV_PAIR_SSS_ANGLE);
    vec3 ns = b.frame.z;
    vec3 p0, seg;
    if (!cv_bssrdf_probe(s, sf.p, ns, u.x, vec2(u.y, ua.x), p0, seg))
        return false;
    imageStore(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path), vec4(sf.p, float(b.material)));
    imageStore(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 1u), vec4(ns, 0.0));
    imageStore(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 2u), vec4(sigma_a, 0.0));
    imageStore(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 3u), vec4(sigma_s, 0.0));
    nr.o = vec4(p0, path_w);
    nr.d = vec4(seg, float(sf.material));
    nr.beta = vec4(beta, cv_ray_meta_in((flags & ~CV_RAYF_SPECULAR) | CV_RAYF_PROBE, depth, medium));
    return true;
}

// At the probe's result h (hit item of probe ray r): the exit surface sf,
// beta times Sp over the density of the exit (the count of candidates
// along the segment in h.pad0), and the exit lobe as the vertex's BSDF.
// False ends the path (no candidate, or no density there).
bool cv_sss_exit(CvHitItem h, CvRayItem r, uint path, out CvSurface sf, inout vec3 beta,
                 out CvBsdf b)
{
    sf = cv_surface_ray(h.prim, h.b1, h.b2, r.o.xyz, r.d.xyz, h.t);
    vec4 entry = imageLoad(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path));
    vec3 po = entry.xyz;
    uint material = uint(entry.w);
    vec3 ns_o = imageLoad(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 1u)).xyz;
    CvBssrdf s = cv_bssrdf_make(imageLoad(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 2u)).xyz,
                                imageLoad(cv_sss_entry, int(CV_SSS_ENTRY_TEXELS * path + 3u)).xyz,
                                uint(materials[material].k.x), materials[material].eta.x);
    float pdf;
    vec3 sp = cv_bssrdf_sp(s, po, ns_o, sf.p, sf.ng, pdf);
    pdf /= float(max(h.pad0, 1u));
    if (!(pdf > 0.0) || !(cv_max3(sp) > 0.0))
        return false;
    beta *= sp / pdf;
    // the lobe on the side the surface's shading normal faces (pbrt-v4's
    // exit BSDF takes the exit's shading normal as it is, and wo along it)
    vec3 ns = dot(sf.ns, sf.ns) > 0.0 ? normalize(sf.ns) : sf.ng;
    b.type = CV_BSDF_SSS_EXIT;
    b.material = material;
    b.frame = cv_frame_from_xz(sf.dpdu, ns);
    b.ng = sf.ng;
    b.c0 = vec3(0.0);
    b.c1 = vec3(0.0);
    b.alpha = vec4(0.0);
    b.eta = s.eta;
    b.thickness = 0.0;
    b.medium = vec4(0.0);
    b.walk = ivec2(0);
    b.coat_closed = vec2(-1.0);
    b.stream = 0u;
    return true;
}

#endif
