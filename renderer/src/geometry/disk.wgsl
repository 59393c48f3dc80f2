// Disks, the twin of `geometry/disk.rs`.

// Ray parameter of the hit, or −1.
fn disk_intersect(center: vec3f, n: vec3f, radius: f32, ray: Ray) -> f32 {
    let denom = dot(ray.d, n);
    if denom == 0.0 {
        return -1.0;
    }
    let t = dot(center - ray.o, n) / denom;
    if !(t > 0.0 && t < ray.t_max) {
        return -1.0;
    }
    let p = ray_at(ray, t);
    let pc = p - center;
    if dot(pc, pc) > radius * radius {
        return -1.0;
    }
    // Hits that may lie behind the origin once t's error is counted go to the plane test.
    let t_err = gamma(7.0) * (dot(abs(center - ray.o), abs(n)) / abs(denom));
    if t > t_err || crosses_plane_ahead(ray.o, ray.d, center, n) {
        return t;
    }
    return -1.0;
}

// The hit point projected onto the plane, and its error bound.
fn disk_surface_point(center: vec3f, n: vec3f, ray: Ray, t: f32) -> array<vec3f, 2> {
    let p0 = ray_at(ray, t);
    let p = p0 - n * dot(p0 - center, n);
    return array<vec3f, 2>(p, gamma(6.0) * (abs(center) + abs(p - center)));
}
