// Spheres, the twin of `geometry/sphere.rs` (Haines et al., Ray Tracing Gems ch. 7).

// Nearest ray parameter in (slack, t_max), or −1.
fn sphere_intersect(center: vec3f, radius: f32, ray: Ray) -> f32 {
    let inv_len = 1.0 / length(ray.d);
    let d = ray.d * inv_len;
    let f = ray.o - center;
    let b = -dot(f, d);
    let l = f + b * d;
    let roots = careful_roots(b, dot(l, l), dot(f, f), radius, inv_len);
    if !roots.found {
        return -1.0;
    }
    let t0 = roots.t0;
    let t1 = roots.t1;
    let slack = gamma(8.0) * (length(f) + radius) * inv_len;
    if t0 > slack && t0 < ray.t_max {
        return t0;
    } else if t1 > slack && t1 < ray.t_max {
        return t1;
    }
    return -1.0;
}

// #if HAS_MASKS
// `Sphere::intersect_beyond`: the nearest in (after, t_max), the far side past a mask (the same
// roots as `sphere_intersect`, which programs without masks keep as it was).
fn sphere_intersect_beyond(center: vec3f, radius: f32, ray: Ray, after: f32) -> f32 {
    let inv_len = 1.0 / length(ray.d);
    let d = ray.d * inv_len;
    let f = ray.o - center;
    let b = -dot(f, d);
    let l = f + b * d;
    let roots = careful_roots(b, dot(l, l), dot(f, f), radius, inv_len);
    let slack = gamma(8.0) * (length(f) + radius) * inv_len;
    if roots.found && roots.t0 > slack && roots.t0 > after && roots.t0 < ray.t_max {
        return roots.t0;
    } else if roots.found && roots.t1 > slack && roots.t1 > after && roots.t1 < ray.t_max {
        return roots.t1;
    }
    return -1.0;
}
// #endif

struct Roots {
    found: bool,
    t0: f32,
    t1: f32,
}

// `sphere::careful_roots`: the roots, in order, of |f + s·u|² = r² along a unit direction u from
// b = −f·u, l2 = |f + b·u|² and f2 = |f|², each times inv_len; not found where the line misses.
// The sphere's intersection, and the cylinder's in the plane across its axis.
fn careful_roots(b: f32, l2: f32, f2: f32, r: f32, inv_len: f32) -> Roots {
    let disc = r * r - l2;
    if disc < 0.0 {
        return Roots(false, 0.0, 0.0);
    }
    let c = f2 - r * r;
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
    return Roots(true, t0 * inv_len, t1 * inv_len);
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
