// glsl/lib/frame.glsl: orthonormal frames (local shading space has z along
// the normal) and the helpers BSDFs use on local directions.
#ifndef CV_LIB_FRAME_GLSL
#define CV_LIB_FRAME_GLSL

struct CvFrame { vec3 x; vec3 y; vec3 z; };

// Duff et al. 2017, "Building an orthonormal basis, revisited": continuous
// except on the z = 0 half plane's sign flip.
CvFrame cv_frame_from_z(vec3 z)
{
    float sgn = z.z >= 0.0 ? 1.0 : -1.0;
    float a = -1.0 / (sgn + z.z);
    float b = z.x * z.y * a;
    return CvFrame(vec3(1.0 + sgn * z.x * z.x * a, sgn * b, -sgn * z.x), vec3(b, sgn + z.y * z.y * a, -z.y), z);
}

// x follows `x_hint` projected onto the plane of z (pbrt's Frame::FromXZ
// after Gram-Schmidt); falls back to an arbitrary frame when degenerate.
CvFrame cv_frame_from_xz(vec3 x_hint, vec3 z)
{
    vec3 x = x_hint - z * dot(z, x_hint);
    float l2 = dot(x, x);
    if (!(l2 > 1e-12))
        return cv_frame_from_z(z);
    x *= inversesqrt(l2);
    return CvFrame(x, cross(z, x), z);
}

vec3 cv_to_local(CvFrame f, vec3 v) { return vec3(dot(v, f.x), dot(v, f.y), dot(v, f.z)); }
vec3 cv_from_local(CvFrame f, vec3 v) { return f.x * v.x + f.y * v.y + f.z * v.z; }

float cv_cos_theta(vec3 w) { return w.z; }
float cv_cos2_theta(vec3 w) { return w.z * w.z; }
float cv_abs_cos_theta(vec3 w) { return abs(w.z); }
float cv_sin2_theta(vec3 w) { return max(0.0, 1.0 - w.z * w.z); }
float cv_tan2_theta(vec3 w) { return cv_sin2_theta(w) / (w.z * w.z); }
float cv_cos_phi(vec3 w)
{
    float s = sqrt(cv_sin2_theta(w));
    return s == 0.0 ? 1.0 : clamp(w.x / s, -1.0, 1.0);
}
float cv_sin_phi(vec3 w)
{
    float s = sqrt(cv_sin2_theta(w));
    return s == 0.0 ? 0.0 : clamp(w.y / s, -1.0, 1.0);
}
bool cv_same_hemisphere(vec3 a, vec3 b) { return a.z * b.z > 0.0; }

#endif
