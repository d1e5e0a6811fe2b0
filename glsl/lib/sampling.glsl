// glsl/lib/sampling.glsl: warps from [0,1)^n to directions and points, with
// their densities, and the sphere <-> square mappings environment maps use.
#ifndef CV_LIB_SAMPLING_GLSL
#define CV_LIB_SAMPLING_GLSL

#include "constants.glsl"

// Shirley-Chiu concentric map: low distortion, so stratification survives.
vec2 cv_sample_disk_concentric(vec2 u)
{
    vec2 o = 2.0 * u - 1.0;
    if (o.x == 0.0 && o.y == 0.0)
        return vec2(0.0);
    float r, theta;
    if (abs(o.x) > abs(o.y)) {
        r = o.x;
        theta = CV_PI_OVER_4 * (o.y / o.x);
    } else {
        r = o.y;
        theta = CV_PI_OVER_2 - CV_PI_OVER_4 * (o.x / o.y);
    }
    return r * vec2(cos(theta), sin(theta));
}

// Cosine-weighted on the +z hemisphere; pdf = cos / pi.
vec3 cv_sample_cosine_hemisphere(vec2 u)
{
    vec2 d = cv_sample_disk_concentric(u);
    return vec3(d, sqrt(max(0.0, 1.0 - dot(d, d))));
}
float cv_cosine_hemisphere_pdf(float cos_theta) { return cos_theta * CV_INV_PI; }

vec3 cv_sample_uniform_sphere(vec2 u)
{
    float z = 1.0 - 2.0 * u.x;
    float r = sqrt(max(0.0, 1.0 - z * z));
    float phi = 2.0 * CV_PI * u.y;
    return vec3(r * cos(phi), r * sin(phi), z);
}

// Barycentrics (b0, b1, b2) uniform over a triangle's area (pbrt-v4's
// area-preserving split of the square).
vec3 cv_sample_uniform_triangle(vec2 u)
{
    float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2.0;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2.0;
        b0 = u.x - b1;
    }
    return vec3(b0, b1, 1.0 - b0 - b1);
}

// pbrt's spherical coordinates: theta from +z, phi in [0, 2pi) from +x.
float cv_spherical_theta(vec3 v) { return acos(clamp(v.z, -1.0, 1.0)); }
float cv_spherical_phi(vec3 v)
{
    float p = atan(v.y, v.x);
    return p < 0.0 ? p + 2.0 * CV_PI : p;
}

// Clarberg's equal-area octahedral mapping as pbrt-v4 uses it
// (EqualAreaSquareToSphere / EqualAreaSphereToSquare); square is [0,1]^2.
vec3 cv_equal_area_square_to_sphere(vec2 p)
{
    float u = 2.0 * p.x - 1.0, v = 2.0 * p.y - 1.0;
    float up = abs(u), vp = abs(v);
    float sd = 1.0 - (up + vp);
    float d = abs(sd);
    float r = 1.0 - d;
    float phi = (r == 0.0 ? 1.0 : (vp - up) / r + 1.0) * CV_PI / 4.0;
    float z = (sd >= 0.0 ? 1.0 : -1.0) * (1.0 - r * r);
    float cos_phi = abs(cos(phi)) * (u >= 0.0 ? 1.0 : -1.0);
    float sin_phi = abs(sin(phi)) * (v >= 0.0 ? 1.0 : -1.0);
    float s = r * sqrt(max(0.0, 2.0 - r * r));
    return vec3(cos_phi * s, sin_phi * s, z);
}

// pbrt-v4's WrapEqualAreaSquare: a point of the square's plane moved into
// [0,1]^2 by mirroring across the edge it left by (the octahedral map's
// neighbours across each edge), once per axis.
vec2 cv_equal_area_wrap(vec2 p)
{
    if (p.x < 0.0 || p.x > 1.0)
        p = vec2(p.x < 0.0 ? -p.x : 2.0 - p.x, 1.0 - p.y);
    if (p.y < 0.0 || p.y > 1.0)
        p = vec2(1.0 - p.x, p.y < 0.0 ? -p.y : 2.0 - p.y);
    return p;
}

vec2 cv_equal_area_sphere_to_square(vec3 d)
{
    float x = abs(d.x), y = abs(d.y), z = abs(d.z);
    float r = sqrt(max(0.0, 1.0 - z));
    float a = max(x, y), b = min(x, y);
    b = a == 0.0 ? 0.0 : b / a;
    float phi = atan(b) * (2.0 / CV_PI);
    if (x < y)
        phi = 1.0 - phi;
    float v = phi * r;
    float u = r - v;
    if (d.z < 0.0) {
        float t = u;
        u = 1.0 - v;
        v = 1.0 - t;
    }
    u = d.x < 0.0 ? -u : u;
    v = d.y < 0.0 ? -v : v;
    return vec2(0.5 * (u + 1.0), 0.5 * (v + 1.0));
}

float cv_power_heuristic(float fpdf, float gpdf)
{
    float f = fpdf * fpdf, g = gpdf * gpdf;
    if (isinf(f))
        return 1.0;
    return f + g > 0.0 ? f / (f + g) : 0.0;
}

#endif
