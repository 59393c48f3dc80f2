// Emitting triangles, the twin of `lights/triangle.rs`: uniform by area, or by solid angle (Arvo),
// optionally through the cosine warp, or the one that pays from p (`Adaptive`), or by projected
// solid angle (`lights/projected.wgsl`).

fn triangle_solid_angle(v0: vec3f, v1: vec3f, v2: vec3f, p: vec3f) -> f32 {
    return spherical_triangle_area(normalize_or_zero(v0 - p), normalize_or_zero(v1 - p), normalize_or_zero(v2 - p));
}

fn triangle_light_faces(l: Light, p: vec3f) -> bool {
    return dot(p - l.a.xyz, l.d.xyz) > 0.0;
}

fn triangle_light_sample(l: Light, p: vec3f, ns: vec3f, u_in: vec2f, method: u32) -> LightSample {
    if !triangle_light_faces(l, p) {
        return no_light_sample();
    }
    let v0 = l.a.xyz;
    let v1 = l.b.xyz;
    let v2 = l.c.xyz;
    if light_sampling_projects(method, ns) {
        let f = psa_frame(ns);
        let poly = psa_piece(p, f, v0, v1, v2, v2, 3u);
        if poly.n < 3u {
            return no_light_sample();
        }
        if psa_conditioned(poly.area, poly.abs_sum) {
            let wi = normalize_glam(to_world(f, psa_sample(poly, u_in)));
            let b = barycentrics_along(v0, v1, v2, p, wi);
            return triangle_sample(v0, v1, v2, b, l.d.xyz, l.le.xyz, wi, psa_light_pdf(ns, wi, poly.area));
        }
    }
    var u = u_in;
    let spherical = light_sampling_spherical_for(method, p, (v0 + v1 + v2) / 3.0, l.d.xyz, l.le.w);
    if spherical && spherical_ok(triangle_solid_angle(v0, v1, v2, p)) {
        var warp_pdf = 1.0;
        if light_sampling_warps(method, ns) {
            let w = spherical_triangle_cosine_weights(v0, v1, v2, p, ns);
            u = sample_bilinear(u, w);
            warp_pdf = bilinear_pdf(u, w);
        }
        let s = sample_spherical_triangle(v0, v1, v2, p, u);
        if !s.ok {
            return no_light_sample();
        }
        let b = s.barycentrics;
        return triangle_sample(v0, v1, v2, b, l.d.xyz, l.le.xyz, s.dir, s.pdf * warp_pdf);
    }
    let b = sample_uniform_triangle(u);
    let y = b.x * v0 + b.y * v1 + b.z * v2;
    var s = area_sample(p, y, l.d.xyz, 1.0 / l.le.w, l.le.xyz);
    s.b = b.yz;
    return s;
}

fn triangle_light_pdf(l: Light, p: vec3f, ns: vec3f, wi: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    if !triangle_light_faces(l, p) {
        return 0.0;
    }
    if light_sampling_projects(method, ns) {
        let poly = psa_piece(p, psa_frame(ns), l.a.xyz, l.b.xyz, l.c.xyz, l.c.xyz, 3u);
        if poly.n < 3u {
            return 0.0;
        }
        if psa_conditioned(poly.area, poly.abs_sum) {
            return psa_light_pdf(ns, wi, poly.area);
        }
    }
    if light_sampling_spherical_for(method, p, (l.a.xyz + l.b.xyz + l.c.xyz) / 3.0, l.d.xyz, l.le.w) {
        let omega = triangle_solid_angle(l.a.xyz, l.b.xyz, l.c.xyz, p);
        if spherical_ok(omega) {
            if light_sampling_warps(method, ns) {
                let w = spherical_triangle_cosine_weights(l.a.xyz, l.b.xyz, l.c.xyz, p, ns);
                return bilinear_pdf(invert_spherical_triangle(l.a.xyz, l.b.xyz, l.c.xyz, p, wi), w) / omega;
            }
            return 1.0 / omega;
        }
    }
    return area_to_solid_angle(1.0 / l.le.w, p, y, ny);
}
