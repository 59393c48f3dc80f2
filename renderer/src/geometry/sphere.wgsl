// Spheres, the twin of `geometry/sphere.rs` (Haines et al., Ray Tracing Gems ch. 7).

// Nearest ray parameter in (slack, t_max), or −1.
fn sphere_intersect(center: vec3f, radius: f32, ray: Ray) -> f32 {
    let inv_len = 1.0 / length(ray.d);
    let d = ray.d * inv_len;
    let f = ray.o - center;
    let b = -dot(f, d);
    let l = f + b * d;
    let disc = radius * radius - dot(l, l);
    if disc < 0.0 {
        return -1.0;
    }
    let c = dot(f, f) - radius * radius;
    // Rust's signum: ±1 by the sign bit, also for ±0.
    let q = b + copysign(1.0, b) * sqrt(disc);
    var t0 = 0.0;
    var t1 = 0.0;
    if q != 0.0 {
        t0 = c / q;
        t1 = q;
    }
    if t0 > t1 {
        let tmp = t0;
        t0 = t1;
        t1 = tmp;
    }
    t0 *= inv_len;
    t1 *= inv_len;
    let slack = gamma(8.0) * (length(f) + radius) * inv_len;
    if t0 > slack && t0 < ray.t_max {
        return t0;
    } else if t1 > slack && t1 < ray.t_max {
        return t1;
    }
    return -1.0;
}

struct SpherePoint {
    p: vec3f,
    p_error: vec3f,
    n: vec3f,
}

fn sphere_surface_point(center: vec3f, radius: f32, ray: Ray, t: f32) -> SpherePoint {
    let local = ray_at(ray, t) - center;
    let n = normalize_or(local, vec3f(0.0, 0.0, 1.0));
    let p = center + n * radius;
    return SpherePoint(p, gamma(5.0) * abs(n * radius) + gamma(2.0) * abs(p), n);
}
