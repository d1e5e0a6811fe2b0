// glsl/bvh/triangle.glsl: watertight ray/triangle intersection (Woop, Benthin
// and Wald 2013). The ray is sheared once so that it runs along +z; edge
// functions that come out exactly zero are redone in double precision, so
// rays through shared edges and vertices hit at least one neighbour. Every
// caller (traversal, brute force) must use these same functions so that t
// comes out bit-identical; `precise` stops the compiler from fusing
// differently in different shaders.
#ifndef CV_BVH_TRIANGLE_GLSL
#define CV_BVH_TRIANGLE_GLSL

struct CvRayTri {
    vec3 o;
    ivec3 k;    // kx, ky, kz
    vec3 s;     // Sx, Sy, Sz
};

CvRayTri cv_ray_tri_setup(vec3 o, vec3 d)
{
    CvRayTri r;
    vec3 a = abs(d);
    int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (d[kz] < 0.0) {
        int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    r.o = o;
    r.k = ivec3(kx, ky, kz);
    r.s = vec3(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
    return r;
}

// True when the ray's line crosses the triangle (any t; the caller checks
// the range). b1, b2 weight v1, v2.
bool cv_ray_tri(CvRayTri r, vec3 v0, vec3 v1, vec3 v2, out float t, out float b1, out float b2)
{
    precise vec3 a = v0 - r.o, b = v1 - r.o, c = v2 - r.o;
    precise float az = a[r.k.z], bz = b[r.k.z], cz = c[r.k.z];
    precise float ax = a[r.k.x] - r.s.x * az, ay = a[r.k.y] - r.s.y * az;
    precise float bx = b[r.k.x] - r.s.x * bz, by = b[r.k.y] - r.s.y * bz;
    precise float cx = c[r.k.x] - r.s.x * cz, cy = c[r.k.y] - r.s.y * cz;
    precise float u = cx * by - cy * bx;
    precise float v = ax * cy - ay * cx;
    precise float w = bx * ay - by * ax;
    if (u == 0.0 || v == 0.0 || w == 0.0) {
        precise double cxby = double(cx) * double(by), cybx = double(cy) * double(bx);
        u = float(cxby - cybx);
        precise double axcy = double(ax) * double(cy), aycx = double(ay) * double(cx);
        v = float(axcy - aycx);
        precise double bxay = double(bx) * double(ay), byax = double(by) * double(ax);
        w = float(bxay - byax);
    }
    t = 0.0;
    b1 = 0.0;
    b2 = 0.0;
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0))
        return false;
    precise float det = u + v + w;
    if (det == 0.0)
        return false;
    precise float tz = r.s.z * az * u + r.s.z * bz * v + r.s.z * cz * w;
    t = tz / det;
    b1 = v / det;
    b2 = w / det;
    return !isnan(t) && !isinf(t);
}

#endif
