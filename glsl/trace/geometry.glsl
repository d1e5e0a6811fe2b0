// glsl/trace/geometry.glsl: the surface point of a hit from the scene's
// triangles, and the origin of a ray that leaves it. Stages that trace
// include tracing.glsl first; every stage includes common.glsl first.
#ifndef CV_TRACE_GEOMETRY_GLSL
#define CV_TRACE_GEOMETRY_GLSL

#include "../bvh/mesh_buffers.glsl"
#ifdef CV_HAS_CURVES
#include "../bvh/curves.glsl"
#endif
// (Included files expand once, where first named, whatever #ifdef is
// around them: motion.glsl's own includes come first, outside it.)
#include "../lib/quaternion.glsl"
#include "../bvh/triangle.glsl"
#ifdef CV_HAS_MOTION
#include "../bvh/motion.glsl"
#endif

struct CvSurface {
    vec3 p;
    float p_err; // how far rays leaving p start off the surface (cv_point_error)
    vec3 ng;     // geometric normal (pbrt's orientation, ReverseOrientation applied)
    vec3 ns;     // shading normal, same hemisphere as ng
    vec3 dpdu;
    vec2 uv;
    uint material;
    uint flags;
};

CvSurface cv_surface(uint prim, float b1, float b2)
{
    uvec4 idx = cv_triangles[prim].idx;
    CvVertex v0 = cv_vertices[idx.x], v1 = cv_vertices[idx.y], v2 = cv_vertices[idx.z];
    float b0 = 1.0 - b1 - b2;
    CvSurface s;
    s.flags = idx.w & ~CV_TRI_MATERIAL_MASK;
    s.material = idx.w & CV_TRI_MATERIAL_MASK;
    vec3 p0 = v0.pos_u.xyz, p1 = v1.pos_u.xyz, p2 = v2.pos_u.xyz;
    vec3 n0 = v0.nrm_v.xyz, n1 = v1.nrm_v.xyz, n2 = v2.nrm_v.xyz;
    float xf_err = 0.0;
#ifdef CV_HAS_MOTION
    // A moving shape's triangle (object space) at the time of the ray that
    // hit it, as pbrt-v4 transforms an AnimatedPrimitive's intersection:
    // positions by the transform, normals by its inverse transpose (no
    // flip for a handedness swap: the geometric normal below flips back).
    // Rays leave it by a larger margin: they are carried back into object
    // space, which rounds at the scale of the point and the translation.
    if (prim >= cv_motion_first_prim() && (prim & CV_PRIM_CURVE) == 0u) {
        mat3 m;
        vec3 T;
        cv_motion_xf(cv_motion_of_prim(prim), cv_trace_time, m, T);
        xf_err = cv_point_error(p0, p1, p2) * (length(m[0]) + length(m[1]) + length(m[2]));
        p0 = m * p0 + T;
        p1 = m * p1 + T;
        p2 = m * p2 + T;
        mat3 nm = transpose(inverse(m));
        n0 = nm * n0;
        n1 = nm * n1;
        n2 = nm * n2;
        if (determinant(m) < 0.0)
            s.flags ^= CV_TRI_REVERSE;
        xf_err += (1.0 / 524288.0) * (cv_max3(abs(p0)) + cv_max3(abs(T)));
    }
#endif
    s.p = b0 * p0 + b1 * p1 + b2 * p2;
    s.p_err = cv_point_error(p0, p1, p2) + xf_err;
    vec2 uv0 = vec2(0.0, 0.0), uv1 = vec2(1.0, 0.0), uv2 = vec2(1.0, 1.0);
    if ((s.flags & CV_TRI_HAS_UV) != 0u) {
        uv0 = vec2(v0.pos_u.w, v0.nrm_v.w);
        uv1 = vec2(v1.pos_u.w, v1.nrm_v.w);
        uv2 = vec2(v2.pos_u.w, v2.nrm_v.w);
    }
    s.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
    vec3 e1 = p1 - p0, e2 = p2 - p0;
    vec3 ng = normalize(cross(e1, e2));
    if ((s.flags & CV_TRI_REVERSE) != 0u)
        ng = -ng;
    // dp/du from the uv parameterisation, as pbrt's Triangle
    vec2 duv02 = uv0 - uv2, duv12 = uv1 - uv2;
    vec3 dp02 = p0 - p2, dp12 = p1 - p2;
    float det = duv02.x * duv12.y - duv02.y * duv12.x;
    vec3 dpdu = vec3(0.0);
    if (abs(det) > 1e-9)
        dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
    if (dot(dpdu, dpdu) < 1e-20 || any(isnan(dpdu))) {
        vec3 a = abs(ng.x) > 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        dpdu = normalize(cross(a, ng));
    }
    s.ns = ng;
    if ((s.flags & CV_TRI_HAS_NORMAL) != 0u) {
        vec3 n = b0 * n0 + b1 * n1 + b2 * n2;
        if (dot(n, n) > 0.0) {
            n = normalize(n);
            // pbrt orients the geometric normal by the shading normal
            ng = dot(ng, n) < 0.0 ? -ng : ng;
            s.ns = n;
        }
    }
    s.ng = ng;
    s.dpdu = dpdu;
    return s;
}

// The material word (material, CV_TRI_* flags) of a hit's primitive.
uint cv_prim_word(uint prim)
{
#ifdef CV_HAS_CURVES
    if ((prim & CV_PRIM_CURVE) != 0u)
        return cv_curve_at(prim & ~CV_PRIM_CURVE).info.x;
#endif
    return cv_triangles[prim].idx.w;
}

// The surface at hit (prim, b1, b2, t) of ray o + t d: a triangle's
// (cv_surface), or a curve's, whose frame depends on the ray
// (cv_curve_frame; uv = (u, v), v across the width).
CvSurface cv_surface_ray(uint prim, float b1, float b2, vec3 o, vec3 d, float t)
{
#ifdef CV_HAS_CURVES
    if ((prim & CV_PRIM_CURVE) != 0u) {
        CvSurface s;
        vec3 n;
        uint word;
        uint ci = prim & ~CV_PRIM_CURVE;
        s.p = o + t * d;
#ifdef CV_HAS_MOTION
        uint shape = cv_curve_at(ci).info.w;
        if (shape != 0u) {
            // A moving shape's curve (object space) at the time of the ray
            // that hit it, as pbrt-v4 transforms an AnimatedPrimitive's
            // intersection: the frame built in object space with the ray
            // carried there, then dp/du by the transform and the normal by
            // its inverse transpose. Rays leave it by the margin of the
            // moving triangles (cv_surface).
            mat3 m;
            vec3 T;
            cv_motion_xf(shape - 1u, cv_trace_time, m, T);
            cv_curve_frame(ci, b1, b2, inverse(m) * d, s.dpdu, n, s.p_err, word);
            s.dpdu = m * s.dpdu;
            n = normalize(transpose(inverse(m)) * n);
            s.p_err = s.p_err * max(length(m[0]), max(length(m[1]), length(m[2]))) +
                      (1.0 / 524288.0) * (cv_max3(abs(s.p)) + cv_max3(abs(T)));
        } else
#endif
            cv_curve_frame(ci, b1, b2, d, s.dpdu, n, s.p_err, word);
        s.ng = n;
        s.ns = n;
        s.uv = vec2(b1, b2);
        s.material = word & CV_TRI_MATERIAL_MASK;
        s.flags = word & ~CV_TRI_MATERIAL_MASK;
        return s;
    }
#endif
    return cv_surface(prim, b1, b2);
}

// Origin of a ray leaving surface s in direction w: off the surface on w's
// side (cv_offset_ray).
vec3 cv_spawn_origin(CvSurface s, vec3 w)
{
    return cv_offset_ray(s.p, s.p_err, dot(w, s.ng) > 0.0 ? s.ng : -s.ng);
}

#endif
