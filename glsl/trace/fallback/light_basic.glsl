// glsl/trace/fallback/light_basic.glsl: a stand-in for the light stage's
// interface (glsl/trace/light/light.glsl): point, spot (no falloff
// smoothing), distant, triangle area and constant environment lights, chosen
// by the power CDF; image environments read as constant. Only for testing the
// pipeline before the real lights land.
#ifndef CV_TRACE_FALLBACK_LIGHT_GLSL
#define CV_TRACE_FALLBACK_LIGHT_GLSL

struct CvLightSample {
    vec3 wi;
    float dist;
    vec3 L;
    float pdf;
    bool delta;
};

float cv_light_pmf(uint i)
{
    return cv_light_cdf[i] - (i == 0u ? 0.0 : cv_light_cdf[i - 1u]);
}

bool cv_light_sample(vec3 p, vec3 n, vec3 u3, out CvLightSample s)
{
    s.wi = vec3(0.0, 0.0, 1.0);
    s.dist = 0.0;
    s.L = vec3(0.0);
    s.pdf = 0.0;
    s.delta = false;
    uint nl = uint(cv_lights.length());
    if (nl == 0u)
        return false;
    uint i = 0u;
    for (uint k = 0u; k + 1u < nl; k++)
        i += u3.x >= cv_light_cdf[k] ? 1u : 0u;
    float pmf = cv_light_pmf(i);
    if (pmf <= 0.0)
        return false;
    CvLight l = cv_lights[i];
    if (l.type == CV_LIGHT_POINT || l.type == CV_LIGHT_SPOT) {
        vec3 d = l.position.xyz - p;
        float d2 = dot(d, d);
        s.dist = sqrt(d2);
        s.wi = d / s.dist;
        s.L = l.L.rgb / d2;
        if (l.type == CV_LIGHT_SPOT) {
            float c = dot(-s.wi, normalize(l.direction.xyz));
            s.L *= smoothstep(l.direction.w, l.position.w, c);
        }
        s.pdf = pmf;
        s.delta = true;
    } else if (l.type == CV_LIGHT_DISTANT) {
        s.wi = -normalize(l.direction.xyz);
        s.dist = 1e30;
        s.L = l.L.rgb;
        s.pdf = pmf;
        s.delta = true;
    } else if (l.type == CV_LIGHT_AREA) {
        uvec4 idx = cv_triangles[l.prim].idx;
        vec3 p0 = cv_vertices[idx.x].pos_u.xyz, p1 = cv_vertices[idx.y].pos_u.xyz,
             p2 = cv_vertices[idx.z].pos_u.xyz;
        float su = sqrt(u3.y);
        float b0 = 1.0 - su, b1 = u3.z * su;
        vec3 pl = b0 * p0 + b1 * p1 + (1.0 - b0 - b1) * p2;
        vec3 nl3 = cross(p1 - p0, p2 - p0);
        float area = 0.5 * length(nl3);
        nl3 = normalize(nl3);
        if ((idx.w & CV_TRI_REVERSE) != 0u)
            nl3 = -nl3;
        vec3 d = pl - p;
        float d2 = dot(d, d);
        s.dist = sqrt(d2);
        s.wi = d / s.dist;
        float c = dot(-s.wi, nl3);
        if (abs(dot(p - p0, nl3)) < 1e-5 * (1.0 + length(p0)))
            return false; // p lies on the light's plane: no light reaches it
        bool front = c > 0.0;
        if (!front && (l.flags & CV_LIGHTF_TWO_SIDED) == 0u)
            return false;
        if (abs(c) < 1e-7)
            return false;
        s.L = l.L.rgb;
        s.pdf = pmf * d2 / (abs(c) * area);
    } else {
        // uniform sphere
        float z = 1.0 - 2.0 * u3.y, r = sqrt(max(0.0, 1.0 - z * z)), phi = 2.0 * CV_PI * u3.z;
        s.wi = vec3(r * cos(phi), r * sin(phi), z);
        s.dist = 1e30;
        s.L = l.L.rgb;
        s.pdf = pmf / (4.0 * CV_PI);
    }
    return s.pdf > 0.0;
}

float cv_light_pdf_area(uint light, vec3 p, vec3 p_light, vec3 n_light)
{
    CvLight l = cv_lights[light];
    uvec4 idx = cv_triangles[l.prim].idx;
    vec3 p0 = cv_vertices[idx.x].pos_u.xyz, p1 = cv_vertices[idx.y].pos_u.xyz,
         p2 = cv_vertices[idx.z].pos_u.xyz;
    float area = 0.5 * length(cross(p1 - p0, p2 - p0));
    vec3 d = p_light - p;
    float d2 = dot(d, d);
    float c = abs(dot(normalize(d), n_light));
    return c > 0.0 ? cv_light_pmf(light) * d2 / (c * area) : 0.0;
}

vec3 cv_light_Le_area(uint light, vec3 wo_from_light, vec2 uv, bool front)
{
    CvLight l = cv_lights[light];
    if (!front && (l.flags & CV_LIGHTF_TWO_SIDED) == 0u)
        return vec3(0.0);
    return l.L.rgb;
}

vec3 cv_env_Le(vec3 dir)
{
    vec3 L = vec3(0.0);
    for (uint i = 0u; i < uint(cv_lights.length()); i++)
        if (cv_lights[i].type == CV_LIGHT_INFINITE || cv_lights[i].type == CV_LIGHT_INFINITE_MAP)
            L += cv_lights[i].L.rgb;
    return L;
}

float cv_env_pdf(vec3 dir)
{
    float pdf = 0.0;
    for (uint i = 0u; i < uint(cv_lights.length()); i++)
        if (cv_lights[i].type == CV_LIGHT_INFINITE || cv_lights[i].type == CV_LIGHT_INFINITE_MAP)
            pdf += cv_light_pmf(i) / (4.0 * CV_PI);
    return pdf;
}

#endif
