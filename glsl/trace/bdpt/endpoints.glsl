// glsl/trace/bdpt/endpoints.glsl: the ends of bdpt's subpaths, as pbrt-v4's
// BDPT sees them: the camera's importance We, its density of directions
// (PDF_We) and its sampling of a point on the lens towards a scene point
// (SampleWi), for a perspective camera (pinhole or thin lens) and an
// orthographic one (pinhole, or thin lens as glsl/trace/camera.glsl makes
// its rays), at the pose of the path's time (a moving camera); the lights'
// emission sampling (SampleLe) and its densities (PDF_Le) for area (one
// triangle, diffuse), point and spot lights (infinite lights: bdpt.comp).
// Include after lights.glsl and camera.glsl.
#ifndef CV_TRACE_BDPT_ENDPOINTS_GLSL
#define CV_TRACE_BDPT_ENDPOINTS_GLSL

// ---- camera --------------------------------------------------------------

// The camera's pose at the time of the path in flight (cv_bdpt_camera_at):
// camera to world (columns; it may mirror, as pbrt's Scale -1 1 1), its
// inverse, and the camera-space origin in world space.
mat3 g_cam_m = mat3(1.0), g_cam_inv = mat3(1.0);
vec3 g_cam_o = vec3(0.0);

// Sets the pose at the time of the uniform u_time (camera.glsl: a still
// camera ignores it), as the path's camera ray saw it, so that every
// connection to the lens (t = 1) finds the camera where that ray left it.
void cv_bdpt_camera_at(float u_time)
{
    g_cam_m = mat3(cv_camera_to_world(vec3(1.0, 0.0, 0.0), 0.0, u_time),
                   cv_camera_to_world(vec3(0.0, 1.0, 0.0), 0.0, u_time),
                   cv_camera_to_world(vec3(0.0, 0.0, 1.0), 0.0, u_time));
    g_cam_o = cv_camera_to_world(vec3(0.0), 1.0, u_time);
    g_cam_inv = inverse(g_cam_m);
}

bool cv_bdpt_ortho() { return u_pass.camera_type == CV_CAMERA_ORTHOGRAPHIC; }

// Whether a light subpath vertex can be joined to the lens (t = 1): not
// through an orthographic pinhole, whose rays all leave in one direction
// (a delta density: pbrt-v4's bdpt takes no such camera; its camera
// vertex is marked delta, cv_bdpt_camera_delta, so that the MIS weights
// count no strategy that would need it), nor into a spherical camera,
// whose importance pbrt-v4 does not define either: its image is the
// camera subpaths' strategies alone, the same image with more noise in
// caustics seen directly.
bool cv_bdpt_camera_connectible()
{
    return u_pass.camera_type == CV_CAMERA_PERSPECTIVE ||
           (cv_bdpt_ortho() && u_pass.lens_radius > 0.0);
}
bool cv_bdpt_camera_delta() { return !cv_bdpt_camera_connectible(); }

// Area of the screen window: on the camera-space plane z = 1 for a
// perspective camera (pbrt-v4's A), on the plane z = 0 (the film itself,
// the area camera rays start from) for an orthographic one.
float cv_bdpt_film_area()
{
    vec4 s = u_pass.screen;
    float t = cv_bdpt_ortho() ? 1.0 : u_pass.tan_half_fov;
    return abs((s.y - s.x) * (s.w - s.z)) * t * t;
}

float cv_bdpt_lens_area()
{
    float r = u_pass.lens_radius;
    return r > 0.0 ? CV_PI * r * r : 1.0;
}

// Raster position (full film pixels) of screen position sc (camera.glsl's
// sx, sy).
vec2 cv_bdpt_screen_raster(vec2 sc)
{
    vec4 s = u_pass.screen;
    vec2 film = vec2(u_pass.film.xy);
    return vec2((sc.x - s.x) / (s.y - s.x) * film.x, (s.w - sc.y) / (s.w - s.z) * film.y);
}

// Raster position of camera-space direction dc from the lens centre of a
// perspective camera (cv_camera_ray's inverse); false behind the camera.
bool cv_bdpt_raster(vec3 dc, out vec2 raster)
{
    raster = vec2(0.0);
    if (!(dc.z > 0.0))
        return false;
    raster = cv_bdpt_screen_raster(dc.xy / (dc.z * u_pass.tan_half_fov));
    return true;
}

vec3 cv_bdpt_to_camera_dir(vec3 w) { return g_cam_inv * w; }
vec3 cv_bdpt_to_camera_point(vec3 p) { return g_cam_inv * (p - g_cam_o); }

// pbrt-v4's PerspectiveCamera::PDF_We: density per solid angle of a camera
// ray leaving the lens in world direction w. The film is not bounded here:
// the camera rays of border pixels leave it by the filter's radius, and
// light tracing splats there too (cv_bdpt_splat). An orthographic thin
// lens sends the ray of lens offset pl along (-pl, focal distance) from
// any film point: the lens's uniform density seen as directions; an
// orthographic pinhole's one direction is a delta (0 here, as a specular
// bounce's, which the MIS weights take as such); a spherical camera's
// vertex counts as delta too (cv_bdpt_camera_connectible): 0.
float cv_bdpt_camera_pdf_dir(vec3 w)
{
    if (u_pass.camera_type >= CV_CAMERA_EQUAL_AREA)
        return 0.0;
    vec3 dc = cv_bdpt_to_camera_dir(w);
    float c = dc.z / length(dc);
    if (!(c > 0.0))
        return 0.0;
    if (cv_bdpt_ortho()) {
        float r = u_pass.lens_radius, fd = u_pass.focal_distance;
        if (!(r > 0.0) || length(dc.xy) * fd > r * dc.z)
            return 0.0;
        return fd * fd / (cv_bdpt_lens_area() * c * c * c);
    }
    return 1.0 / (cv_bdpt_film_area() * c * c * c);
}

// pbrt-v4's SampleWi: a point on the lens seen from world point pref with
// uniform u_lens: the lens point, the raster position its ray through pref
// lands on, and We / pdf (pdf per solid angle at pref). False: behind the
// camera, or an orthographic pinhole (cv_bdpt_camera_connectible).
bool cv_bdpt_camera_sample(vec3 pref, vec2 u_lens, out vec3 p_lens, out vec2 raster,
                           out float we_over_pdf, out float cos_lens)
{
    p_lens = g_cam_o;
    raster = vec2(0.0);
    we_over_pdf = 0.0;
    cos_lens = 0.0;
    vec3 pc = cv_bdpt_to_camera_point(pref);
    vec3 pl = vec3(0.0);
    if (u_pass.lens_radius > 0.0)
        pl = vec3(u_pass.lens_radius * cv_sample_disk_concentric(u_lens), 0.0);
    if (cv_bdpt_ortho()) {
        // the ray of lens offset pl runs along (-pl, fd): it reaches pref
        // from the film point pc - (pc.z / fd) (-pl, fd) - pl. With the
        // camera ray's density 1 / (A pi r^2) fd^2 / cos^3 and the lens
        // point's pdf per area (fd / pc.z)^2 / (pi r^2), We / pdf comes to
        // 1 / (A cos), A the film's area.
        float fd = u_pass.focal_distance;
        if (!cv_bdpt_camera_connectible() || !(pc.z > 0.0) || !(fd > 0.0))
            return false;
        vec2 o = pc.xy + pl.xy * (pc.z / fd);
        raster = cv_bdpt_screen_raster(o - pl.xy);
        p_lens = g_cam_m * vec3(o, 0.0) + g_cam_o;
        float c = fd * inversesqrt(dot(pl.xy, pl.xy) + fd * fd);
        cos_lens = c;
        we_over_pdf = 1.0 / (cv_bdpt_film_area() * c);
        return true;
    }
    vec3 dl = pc - pl;  // camera space, from the lens point
    if (!(dl.z > 0.0))
        return false;
    // the point of the plane of focus the ray crosses, seen from the lens centre
    vec3 dir = dl;
    if (u_pass.lens_radius > 0.0)
        dir = pl + dl * (u_pass.focal_distance / dl.z);
    if (!cv_bdpt_raster(dir, raster))
        return false;
    p_lens = g_cam_m * pl + g_cam_o;
    float d2 = dot(dl, dl);
    float c = dl.z * inversesqrt(d2);
    cos_lens = c;
    float lens = cv_bdpt_lens_area();
    float we = 1.0 / (cv_bdpt_film_area() * lens * c * c * c * c);
    float pdf = d2 / (c * lens);
    we_over_pdf = we / pdf;
    return true;
}

// ---- lights --------------------------------------------------------------

// Density per solid angle of light `li`'s emission (pbrt-v4's PDF_Le
// pdfDir) in direction w from its point with normal n (area lights).
float cv_bdpt_light_pdf_dir(uint li, vec3 n, vec3 w)
{
    CvLight l = lights[li];
    if (l.type == CV_LIGHT_AREA) {
        float c = dot(n, w);
        if ((l.flags & CV_LIGHTF_TWO_SIDED) != 0u)
            return abs(c) * CV_INV_PI * 0.5;
        return max(c, 0.0) * CV_INV_PI;
    }
    if (l.type == CV_LIGHT_POINT)
        return CV_INV_4PI;
    if (l.type == CV_LIGHT_SPOT) {
        float cos_total = l.direction.w;
        if (dot(normalize(l.direction.xyz), w) < cos_total)
            return 0.0;
        return 1.0 / (2.0 * CV_PI * (1.0 - cos_total));
    }
    return 0.0;
}

// Density per unit area (pbrt-v4's pdfPos) of the light's sampled points.
float cv_bdpt_light_pdf_pos(uint li)
{
    CvLight l = lights[li];
    if (l.type == CV_LIGHT_AREA)
        return l.L.w > 0.0 ? 1.0 / l.L.w : 0.0;
    return 1.0;
}

bool cv_bdpt_light_is_delta(uint li)
{
    uint t = lights[li].type;
    return t == CV_LIGHT_POINT || t == CV_LIGHT_SPOT;
}

// What a point or spot light emits in direction w (intensity).
vec3 cv_bdpt_light_I(uint li, vec3 w)
{
    CvLight l = lights[li];
    vec3 I = l.L.rgb;
    if (l.type == CV_LIGHT_SPOT)
        I *= cv_smoothstep(l.direction.w, l.position.w, dot(normalize(l.direction.xyz), w));
    return I;
}

// A point on light li (uniform u): position, normal (0: no surface), the
// surface coordinates, its rounding error.
void cv_bdpt_light_point(uint li, vec2 u, out vec3 p, out vec3 n, out vec2 uv, out float err)
{
    CvLight l = lights[li];
    p = l.position.xyz;
    n = vec3(0.0);
    uv = vec2(0.0);
    err = 0.0;
    if (l.type != CV_LIGHT_AREA)
        return;
    CvTriangle t = cv_triangles[l.prim];
    vec3 b = cv_sample_uniform_triangle(u);
    CvVertex v0 = cv_vertices[t.idx.x], v1 = cv_vertices[t.idx.y], v2 = cv_vertices[t.idx.z];
    p = b.x * v0.pos_u.xyz + b.y * v1.pos_u.xyz + b.z * v2.pos_u.xyz;
    uv = (t.idx.w & CV_TRI_HAS_UV) != 0u
             ? b.x * vec2(v0.pos_u.w, v0.nrm_v.w) + b.y * vec2(v1.pos_u.w, v1.nrm_v.w) +
                   b.z * vec2(v2.pos_u.w, v2.nrm_v.w)
             : b.y * vec2(1.0, 0.0) + b.z * vec2(1.0);
    n = cv_light_triangle_normal(l.prim, b);
    err = cv_point_error(v0.pos_u.xyz, v1.pos_u.xyz, v2.pos_u.xyz);
}

// pbrt-v4's SampleLe direction for light li from its point with normal n:
// false where the light has no such direction.
bool cv_bdpt_light_dir(uint li, vec3 n, vec2 u, out vec3 w, out float pdf_dir)
{
    CvLight l = lights[li];
    w = vec3(0.0, 0.0, 1.0);
    pdf_dir = 0.0;
    if (l.type == CV_LIGHT_AREA) {
        bool two = (l.flags & CV_LIGHTF_TWO_SIDED) != 0u;
        vec3 side = n;
        if (two) {
            if (u.x < 0.5) {
                u.x = min(u.x * 2.0, 0.99999994);
            } else {
                u.x = min((u.x - 0.5) * 2.0, 0.99999994);
                side = -n;
            }
        }
        vec3 wl = cv_sample_cosine_hemisphere(u);
        w = cv_from_local(cv_frame_from_z(side), wl);
        pdf_dir = cv_cosine_hemisphere_pdf(wl.z) * (two ? 0.5 : 1.0);
    } else if (l.type == CV_LIGHT_POINT) {
        w = cv_sample_uniform_sphere(u);
        pdf_dir = CV_INV_4PI;
    } else if (l.type == CV_LIGHT_SPOT) {
        float cos_total = l.direction.w;
        float c = mix(1.0, cos_total, u.x);  // uniform in the cone
        float s = sqrt(max(0.0, 1.0 - c * c)), phi = 2.0 * CV_PI * u.y;
        w = cv_from_local(cv_frame_from_z(normalize(l.direction.xyz)), vec3(s * cos(phi), s * sin(phi), c));
        pdf_dir = 1.0 / (2.0 * CV_PI * (1.0 - cos_total));
    } else {
        return false;
    }
    return pdf_dir > 0.0;
}

// Radiance (area) or intensity (point, spot) light li sends in direction w
// from its point p (normal n, surface coordinates uv).
vec3 cv_bdpt_light_emit(uint li, vec3 p, vec3 n, vec2 uv, vec3 w)
{
    if (lights[li].type == CV_LIGHT_AREA)
        return cv_light_Le_area(li, w, uv, dot(w, n) > 0.0, p);
    return cv_bdpt_light_I(li, w);
}

#endif
