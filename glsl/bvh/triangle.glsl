// glsl/bvh/triangle.glsl: watertight ray/triangle intersection (Woop, Benthin
// and Wald 2013). The ray is sheared once so that it runs along +z; edge
// functions that come out exactly zero are redone in double precision, so
// rays through shared edges and vertices hit at least one neighbour. Every
// caller (traversal, brute force) must use these same functions so that t
// comes out bit-identical; `precise` stops the compiler from fusing
// differently in different shaders. Drivers may also divide approximately
// (GLSL allows 2.5 ulp; NVIDIA's does not round like IEEE), which moves t
// and the edge functions by an ulp, so every division that decides a hit or
// its t goes through cv_div_rn: the result is then the same, correctly
// rounded float on every driver and on the CPU. That costs a large share
// of the traversal rate against plain division (bench/RESULTS.md,
// "Figures behind the code"). Define CV_BVH_FAST_DIV before
// including for the renderer's form: plain division and the shear as
// matrix rows (cv_ray_tri_row); traversal and brute force in one shader
// still agree exactly, but t may differ by an ulp between drivers.
#ifndef CV_BVH_TRIANGLE_GLSL
#define CV_BVH_TRIANGLE_GLSL

// a / b rounded to nearest even, from the driver's quotient and an exact
// test against the midpoints to its neighbours: a float times a 25-bit
// midpoint is exact in double, so the sign of a - m * b is exact too (fused
// or not). Quotients that are 0, infinite or NaN are left as they are.
float cv_div_rn(float a, float b)
{
    precise float q = a / b;
#ifdef CV_BVH_FAST_DIV
    return q;
#else
    if (q == 0.0 || isinf(q) || isnan(q) || isinf(b))
        return q;
    double da = abs(double(a)), db = abs(double(b));
    uint bits = floatBitsToUint(abs(q));
    for (int i = 0; i < 4; i++) {
        double m_up = (double(uintBitsToFloat(bits)) + double(uintBitsToFloat(bits + 1u))) * 0.5LF;
        double m_dn = (double(uintBitsToFloat(bits)) + double(uintBitsToFloat(bits - 1u))) * 0.5LF;
        precise double r_up = da - m_up * db, r_dn = da - m_dn * db;
        if (r_up > 0.0LF || (r_up == 0.0LF && (bits & 1u) != 0u)) {
            bits++;
        } else if (bits > 1u && (r_dn < 0.0LF || (r_dn == 0.0LF && (bits & 1u) != 0u))) {
            bits--;
        } else {
            break;
        }
    }
    float mag = uintBitsToFloat(bits);
    return q < 0.0 ? -mag : mag;
#endif
}

struct CvRayTri {
    vec3 o;
    ivec3 k;    // kx, ky, kz
    vec3 s;     // Sx, Sy, Sz
#ifdef CV_BVH_FAST_DIV
    // The permutation and shear as rows of a matrix: a vertex's sheared
    // coordinates (x, y, z) = (dot(mx, v - o), dot(my, v - o), dot(mz, v - o)).
    vec3 mx, my, mz;
#endif
};

#ifdef CV_BVH_FAST_DIV
// The renderer's form picks components without indexing: a[k] with a
// per-ray k became a chain of branches on every vertex (NVIDIA), and as
// rows (one-hot for kz, one-hot minus the shear for kx and ky) the shear
// costs three fused operations a coordinate. Each vertex still goes through
// one fixed function of the ray, so edges shared by two triangles get the
// same edge functions and the test stays watertight; the x and y
// coordinates round once instead of twice; both traversal stages got
// markedly faster (bench/RESULTS.md, "Figures behind the code"). The exact
// form keeps the indexed shear of its CPU port (tests/bvh).
float cv_ray_tri_row(vec3 a, vec3 m)
{
    precise float r = fma(a.z, m.z, fma(a.y, m.y, a.x * m.x));
    return r;
}
#endif

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
    r.s = vec3(cv_div_rn(d[kx], d[kz]), cv_div_rn(d[ky], d[kz]), cv_div_rn(1.0, d[kz]));
#ifdef CV_BVH_FAST_DIV
    r.mz = vec3(equal(ivec3(kz), ivec3(0, 1, 2)));
    r.mx = vec3(equal(ivec3(kx), ivec3(0, 1, 2))) - r.s.x * r.mz;
    r.my = vec3(equal(ivec3(ky), ivec3(0, 1, 2))) - r.s.y * r.mz;
#endif
    return r;
}

// The watertight test proper: false when the ray's line misses the
// triangle; otherwise the edge functions v, w (weights of v1, v2 times det)
// and the hit distance as a fraction, t = tz / det. Closest and any-hit
// queries share it, so they agree on which triangles a ray crosses.
bool cv_ray_tri_edges(CvRayTri r, vec3 v0, vec3 v1, vec3 v2, out float v_out, out float w_out,
                      out float det_out, out float tz_out)
{
    v_out = 0.0;
    w_out = 0.0;
    det_out = 0.0;
    tz_out = 0.0;
    precise vec3 a = v0 - r.o, b = v1 - r.o, c = v2 - r.o;
#ifdef CV_BVH_FAST_DIV
    precise float az = cv_ray_tri_row(a, r.mz), bz = cv_ray_tri_row(b, r.mz), cz = cv_ray_tri_row(c, r.mz);
    precise float ax = cv_ray_tri_row(a, r.mx), ay = cv_ray_tri_row(a, r.my);
    precise float bx = cv_ray_tri_row(b, r.mx), by = cv_ray_tri_row(b, r.my);
    precise float cx = cv_ray_tri_row(c, r.mx), cy = cv_ray_tri_row(c, r.my);
#else
    precise float az = a[r.k.z], bz = b[r.k.z], cz = c[r.k.z];
    precise float ax = a[r.k.x] - r.s.x * az, ay = a[r.k.y] - r.s.y * az;
    precise float bx = b[r.k.x] - r.s.x * bz, by = b[r.k.y] - r.s.y * bz;
    precise float cx = c[r.k.x] - r.s.x * cz, cy = c[r.k.y] - r.s.y * cz;
#endif
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
    if ((u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0))
        return false;
    precise float det = u + v + w;
    if (det == 0.0)
        return false;
    precise float tz = r.s.z * az * u + r.s.z * bz * v + r.s.z * cz * w;
    v_out = v;
    w_out = w;
    det_out = det;
    tz_out = tz;
    return true;
}

// True when the ray's line crosses the triangle (any t; the caller checks
// the range). b1, b2 weight v1, v2.
bool cv_ray_tri(CvRayTri r, vec3 v0, vec3 v1, vec3 v2, out float t, out float b1, out float b2)
{
    t = 0.0;
    b1 = 0.0;
    b2 = 0.0;
    float v, w, det, tz;
    if (!cv_ray_tri_edges(r, v0, v1, v2, v, w, det, tz))
        return false;
    t = cv_div_rn(tz, det);
    // The barycentrics shade but decide nothing: plain division is enough.
    b1 = v / det;
    b2 = w / det;
    return !isnan(t) && !isinf(t);
}

// Any-hit form: true when the ray crosses the triangle at tmin < t < tmax;
// no barycentrics. With CV_BVH_FAST_DIV the range is tested on the
// numerator, tmin * det < tz < tmax * det (for det > 0; flipped below 0),
// without a division: the renderer's t is already only as good as the
// driver's quotient, and this is at most an ulp or two off it; a division
// per triangle is what the shadow stage saves. The same numerator test as a
// pre-filter of closest hits (one reciprocal for t and both weights on a
// pass) made the intersect stage slower, so closest hits divide as before
// (bench/RESULTS.md, "Figures behind the code"). The exact form
// divides as cv_ray_tri does, so tests/bvh still compares any-hit with
// brute force bit for bit.
bool cv_ray_tri_any(CvRayTri r, vec3 v0, vec3 v1, vec3 v2, float tmin, float tmax)
{
#ifdef CV_BVH_FAST_DIV
    float v, w, det, tz;
    if (!cv_ray_tri_edges(r, v0, v1, v2, v, w, det, tz))
        return false;
    // Sign-fold so that det > 0; an infinite or NaN product fails a test.
    float sd = det < 0.0 ? -1.0 : 1.0;
    float n = tz * sd, m = det * sd;
    return n > tmin * m && n < tmax * m;
#else
    float t, b1, b2;
    return cv_ray_tri(r, v0, v1, v2, t, b1, b2) && t > tmin && t < tmax;
#endif
}

#endif
