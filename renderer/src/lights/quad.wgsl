// Emitting parallelograms, the twin of `lights/quad.rs`: by area, or by solid angle (spherical
// rectangle) when the quad is a rectangle and its solid angle suits the warp, optionally through
// the cosine warp, or by whichever pays from p (`Adaptive`), or by projected solid angle
// (`lights/projected.wgsl`).

fn quad_light_faces(l: Light, p: vec3f) -> bool {
    return dot(p - l.a.xyz, l.d.xyz) > 0.0;
}

// #if HAS_TEXTURES
// `QuadLight::triangle_point`: which of the quad's two triangles holds y, a point of the quad
// (k: 0 for [corner, +u, +u+v], 1 for [corner, +u+v, +v]), and y's barycentrics (b1, b2) there.
struct QuadTrianglePoint {
    k: u32,
    b: vec2f,
}

fn quad_light_triangle_point(l: Light, y: vec3f) -> QuadTrianglePoint {
    let d = y - l.a.xyz;
    let s = clamp(dot(cross(d, l.c.xyz), l.d.xyz) / l.le.w, 0.0, 1.0);
    let t = clamp(dot(cross(l.b.xyz, d), l.d.xyz) / l.le.w, 0.0, 1.0);
    if t <= s {
        return QuadTrianglePoint(0u, vec2f(s - t, t));
    }
    return QuadTrianglePoint(1u, vec2f(s, t - s));
}
// #endif

// `QuadLight::corners` + `LightSampling::cosine_weights`: the warp's corner weights.
fn quad_cosine_weights(l: Light, p: vec3f, ns: vec3f) -> vec4f {
    let c = l.a.xyz - p;
    return cosine_corner_weights(ns, c, c + l.b.xyz, c + l.c.xyz, c + l.b.xyz + l.c.xyz);
}

// The quad seen from p in frame f, clipped to the horizon (`QuadLight::outline`).
fn quad_psa_piece(l: Light, p: vec3f, f: Frame) -> PsaPolygon {
    let c = l.a.xyz;
    return psa_piece(p, f, c, c + l.b.xyz, c + l.b.xyz + l.c.xyz, c + l.c.xyz, 4u);
}

// `QuadLight::point_along`: where the ray from p along wi meets the plane, clamped onto the quad.
fn quad_point_along(l: Light, p: vec3f, wi: vec3f) -> vec3f {
    let n = l.d.xyz;
    let t = dot(n, l.a.xyz - p) / dot(n, wi);
    let d = p + t * wi - l.a.xyz;
    let s = clamp(dot(cross(d, l.c.xyz), n) / l.le.w, 0.0, 1.0);
    let r = clamp(dot(cross(l.b.xyz, d), n) / l.le.w, 0.0, 1.0);
    return l.a.xyz + s * l.b.xyz + r * l.c.xyz;
}

fn quad_light_sample(l: Light, p: vec3f, ns: vec3f, u_in: vec2f, method: u32) -> LightSample {
    if !quad_light_faces(l, p) {
        return no_light_sample();
    }
    if light_sampling_projects(method, ns) {
        let f = psa_frame(ns);
        let poly = quad_psa_piece(l, p, f);
        if poly.n < 3u {
            return no_light_sample();
        }
        if psa_conditioned(poly.area, poly.abs_sum) {
            let wi = normalize_glam(to_world(f, psa_sample(poly, u_in)));
            var s = area_sample(p, quad_point_along(l, p, wi), l.d.xyz, 1.0 / l.le.w, l.le.xyz);
            s.pdf = psa_light_pdf(ns, s.wi, poly.area);
            return s;
        }
    }
    var u = u_in;
    if light_sampling_spherical_for(method, p, l.a.xyz + 0.5 * (l.b.xyz + l.c.xyz), l.d.xyz, l.le.w) {
        let rect = sph_rect_new(p, l.a.xyz, l.b.xyz, l.c.xyz);
        if rect.ok && spherical_ok(rect.solid_angle) {
            var warp_pdf = 1.0;
            if light_sampling_warps(method, ns) {
                let w = quad_cosine_weights(l, p, ns);
                u = sample_bilinear(u, w);
                warp_pdf = bilinear_pdf(u, w);
            }
            let y = sph_rect_sample(rect, u);
            var s = area_sample(p, y, l.d.xyz, 1.0 / l.le.w, l.le.xyz);
            s.pdf = warp_pdf / rect.solid_angle;
            return s;
        }
    }
    let y = l.a.xyz + u.x * l.b.xyz + u.y * l.c.xyz;
    return area_sample(p, y, l.d.xyz, 1.0 / l.le.w, l.le.xyz);
}

fn quad_light_pdf(l: Light, p: vec3f, ns: vec3f, wi: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    if !quad_light_faces(l, p) {
        return 0.0;
    }
    if light_sampling_projects(method, ns) {
        let poly = quad_psa_piece(l, p, psa_frame(ns));
        if poly.n < 3u {
            return 0.0;
        }
        if psa_conditioned(poly.area, poly.abs_sum) {
            return psa_light_pdf(ns, wi, poly.area);
        }
    }
    if light_sampling_spherical_for(method, p, l.a.xyz + 0.5 * (l.b.xyz + l.c.xyz), l.d.xyz, l.le.w) {
        let rect = sph_rect_new(p, l.a.xyz, l.b.xyz, l.c.xyz);
        if rect.ok && spherical_ok(rect.solid_angle) {
            if light_sampling_warps(method, ns) {
                return bilinear_pdf(sph_rect_invert(rect, y), quad_cosine_weights(l, p, ns)) / rect.solid_angle;
            }
            return 1.0 / rect.solid_angle;
        }
    }
    return area_to_solid_angle(1.0 / l.le.w, p, y, ny);
}
