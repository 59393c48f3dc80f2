// Emitting spheres, the twin of `lights/sphere.rs`: by solid angle (uniform in the cone, tiny
// cones through sin²θ), or by area with the sample re-traced so its point and pdf are exactly what
// the intersection of its f32 direction gives.

// (sin²θ_max, 1 − cos θ_max) of the cone from p; x < 0 when p is inside.
fn sphere_light_cone(l: Light, p: vec3f) -> vec2f {
    let pc = p - l.a.xyz;
    let d2 = dot(pc, pc);
    let r2 = l.a.w * l.a.w;
    if d2 <= r2 {
        return vec2f(-1.0, 0.0);
    }
    let sin2 = r2 / d2;
    var one_minus_cos: f32;
    if sin2 < SMALL_CONE_SIN2 {
        one_minus_cos = 0.5 * sin2;
    } else {
        one_minus_cos = 1.0 - safe_sqrt(1.0 - sin2);
    }
    return vec2f(sin2, one_minus_cos);
}

fn sphere_light_area(l: Light) -> f32 {
    return 4.0 * PI * l.a.w * l.a.w;
}

fn sphere_light_sample(l: Light, p: vec3f, u: vec2f, method: u32) -> LightSample {
    let cone = sphere_light_cone(l, p);
    if cone.x < 0.0 {
        return no_light_sample();
    }
    let sin2_max = cone.x;
    let one_minus_cos_max = cone.y;
    let c = l.a.xyz;
    let r = l.a.w;
    if method == LIGHT_SAMPLING_AREA {
        let n = sample_uniform_sphere(u);
        var s = area_sample(p, c + r * n, n, 1.0 / sphere_light_area(l), l.le.xyz);
        if !s.ok {
            return s;
        }
        // Retrace: where the f32 direction really meets the sphere, and the pdf there.
        let ray = Ray(p, s.wi, inf());
        let t = sphere_intersect(c, r, ray);
        if t < 0.0 {
            return no_light_sample();
        }
        let sp = sphere_surface_point(c, r, ray, t);
        let pdf = area_to_solid_angle(1.0 / sphere_light_area(l), p, sp.p, sp.n);
        if pdf <= 0.0 {
            return no_light_sample();
        }
        s.p = sp.p;
        s.p_error = sp.p_error;
        s.n = sp.n;
        s.pdf = pdf;
        return s;
    }
    var sin2: f32;
    var cos_t: f32;
    if sin2_max < SMALL_CONE_SIN2 {
        sin2 = sin2_max * u.x;
        cos_t = safe_sqrt(1.0 - sin2);
    } else {
        cos_t = 1.0 - u.x * one_minus_cos_max;
        sin2 = max(1.0 - cos_t * cos_t, 0.0);
    }
    let sin_max = sqrt(sin2_max);
    let cos_alpha = sin2 / sin_max + cos_t * safe_sqrt(1.0 - sin2 / sin2_max);
    let sin_alpha = safe_sqrt(1.0 - cos_alpha * cos_alpha);
    let phi = TAU * u.y;
    let frame = frame_from_normal(normalize_glam(p - c));
    let n = to_world(frame, vec3f(sin_alpha * cos(phi), sin_alpha * sin(phi), cos_alpha));
    let y = c + r * n;
    let wi = normalize_glam(y - p);
    if !(dot(n, wi) < 0.0) {
        return no_light_sample();
    }
    let pdf = 1.0 / (TAU * one_minus_cos_max);
    let err = gamma(5.0) * abs(r * n) + gamma(2.0) * abs(y);
    return LightSample(y, err, n, wi, pdf, l.le.xyz, false, true, vec2f(0.0));
}

fn sphere_light_pdf(l: Light, p: vec3f, y: vec3f, ny: vec3f, method: u32) -> f32 {
    let cone = sphere_light_cone(l, p);
    if cone.x < 0.0 {
        return 0.0;
    }
    if method == LIGHT_SAMPLING_AREA {
        return area_to_solid_angle(1.0 / sphere_light_area(l), p, y, ny);
    }
    return 1.0 / (TAU * cone.y);
}
