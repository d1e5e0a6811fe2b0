// glsl/trace/medium/vertex.glsl: a path vertex at a collision in a medium
// (volpath, CV_MEDIA; the intersect stage found it: medium/track.glsl), as
// pbrt-v4's VolPathIntegrator treats a real scattering event: the medium's
// emission, then, below the maximum depth, next-event estimation through
// the phase function (a shadow ray whose contribution the shadow stage
// multiplies by the transmittance along it) weighed by the power heuristic
// against phase sampling, and the bounce drawn from the Henyey-Greenstein
// phase function (f / pdf = 1), with the same Russian roulette and the same
// sample dimensions as a surface vertex of that depth (path_vertex.glsl).
// The incoming throughput holds the tracking's T(t) / p(t); the vertex
// multiplies in sigma_s (scattering) or sigma_a Le (emission): pbrt-v4
// chooses between absorption and scattering at random instead, the same
// expectation. Include after surface_inputs.glsl, lights.glsl and
// medium.glsl.
#ifndef CV_TRACE_MEDIUM_VERTEX_GLSL
#define CV_TRACE_MEDIUM_VERTEX_GLSL

void cv_medium_vertex(CvHitItem h, CvRayItem r, out bool push_shadow, out CvShadowItem s,
                      out bool push_ray, out CvRayItem nr)
{
    push_shadow = false;
    push_ray = false;
    uint path = uint(r.o.w);
    uint flags = cv_ray_flags(r);
    uint depth = cv_ray_depth(r);
    uint medium = cv_ray_medium(r);
    vec3 beta = r.beta.rgb;
    // pbrt-v4 counts a scattering event as a vertex of the path: none
    // beyond the maximum depth, and no emission there either
    if (depth >= cv_max_depth() || medium == 0u)
        return;
    vec3 p = r.o.xyz + h.t * r.d.xyz;
    vec3 wo = -r.d.xyz;
    vec3 sigma_a, sigma_s, Le;
    cv_medium_point(medium, p, sigma_a, sigma_s, Le);
    if (cv_media(medium).emissive != 0u)
        cv_film_add(path, beta * sigma_a * Le);
    beta *= sigma_s;
    if (!cv_finite3(beta) || cv_max3(beta) <= 0.0)
        return;
    float g = cv_media(medium).sigma_a.w;
    vec2 u_phase = cv_bounce_2d(path, depth, CV_PAIR_BSDF_U2);
    vec2 u_light = cv_bounce_2d(path, depth, CV_PAIR_LIGHT_U2);
    vec2 u_lc = cv_bounce_2d(path, depth, CV_PAIR_LIGHT_UC);

    if (cv_n_lights() > 0u) {
        CvLightSample ls;
        if (cv_light_sample(p, vec3(0.0), vec3(u_lc.x, u_light), ls) && cv_max3(ls.L) > 0.0) {
            float ph = cv_hg_pdf(dot(wo, ls.wi), g);
            float w = ls.delta ? 1.0 : cv_power_heuristic(ls.pdf, ph);
            vec3 Ld = beta * ph * ls.L * (w / ls.pdf);
            if (ph > 0.0 && cv_finite3(Ld)) {
                push_shadow = true;
                s.o = vec4(p, ls.dist * (1.0 - 1e-4));
                s.d = vec4(ls.wi, float(path));
                s.L = vec4(Ld, 0.0);
                s.m = vec4(float(medium), 0.0, 0.0, 0.0);
            }
        }
    }

    float pdf;
    vec3 wi = cv_hg_sample(wo, g, u_phase, pdf);
    if (!(pdf > 0.0))
        return;
    if (!cv_roulette_survives(depth, u_lc.y, beta))
        return;
    push_ray = true;
    nr.o = vec4(p, r.o.w);
    nr.d = vec4(wi, pdf);
    nr.beta = vec4(beta, cv_ray_meta_in(flags & ~CV_RAYF_SPECULAR, depth + 1u, medium));
}

#endif
