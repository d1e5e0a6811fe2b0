// glsl/trace/fallback/traverse_brute.glsl: the BVH stage's traversal
// interface (glsl/bvh/traverse.glsl) by testing every triangle. A stand-in
// for tiny test scenes until the BVH lands; same results, linear cost.
#ifndef CV_TRACE_FALLBACK_TRAVERSE_GLSL
#define CV_TRACE_FALLBACK_TRAVERSE_GLSL

struct CvHit {
    float t;
    uint prim;
    float b1;
    float b2;
};

// Moeller-Trumbore; returns t in (tmin, tmax) or -1.
float cv_brute_tri(uint i, vec3 o, vec3 d, float tmin, float tmax, out float b1, out float b2)
{
    uvec4 idx = cv_triangles[i].idx;
    vec3 p0 = cv_vertices[idx.x].pos_u.xyz, p1 = cv_vertices[idx.y].pos_u.xyz,
         p2 = cv_vertices[idx.z].pos_u.xyz;
    vec3 e1 = p1 - p0, e2 = p2 - p0;
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    b1 = 0.0;
    b2 = 0.0;
    if (det == 0.0)
        return -1.0;
    float inv = 1.0 / det;
    vec3 tv = o - p0;
    b1 = dot(tv, pv) * inv;
    if (b1 < 0.0 || b1 > 1.0)
        return -1.0;
    vec3 qv = cross(tv, e1);
    b2 = dot(d, qv) * inv;
    if (b2 < 0.0 || b1 + b2 > 1.0)
        return -1.0;
    float t = dot(e2, qv) * inv;
    return t > tmin && t < tmax ? t : -1.0;
}

bool cv_trace_closest(vec3 o, vec3 d, float tmin, float tmax, out CvHit hit)
{
    hit.t = tmax;
    hit.prim = 0xffffffffu;
    hit.b1 = 0.0;
    hit.b2 = 0.0;
    uint n = uint(cv_triangles.length());
    for (uint i = 0u; i < n; i++) {
        float b1, b2;
        float t = cv_brute_tri(i, o, d, tmin, hit.t, b1, b2);
        if (t > 0.0) {
            hit.t = t;
            hit.prim = i;
            hit.b1 = b1;
            hit.b2 = b2;
        }
    }
    return hit.prim != 0xffffffffu;
}

bool cv_trace_any(vec3 o, vec3 d, float tmin, float tmax)
{
    uint n = uint(cv_triangles.length());
    for (uint i = 0u; i < n; i++) {
        float b1, b2;
        if (cv_brute_tri(i, o, d, tmin, tmax, b1, b2) > 0.0)
            return true;
    }
    return false;
}

#endif
