// Cylinders, the twin of `geometry/cylinder.rs` (Mitsuba 3.9.1's open tube, no end caps).
// Its primitive record (as `geometry/primitive.wgsl` lays it out): a.xyz = p0, b.xyz = axis
// (p1 − p0), c.xyz = unit u axis, d.w = radius, negated when the normal points towards the axis.
// Only in programs of scenes with a cylinder.

// #if HAS_CYLINDER_SHAPE

// `Cylinder::intersect`: the nearest ray parameter in (slack, t_max) between the end circles,
// or −1.
fn cylinder_intersect(p0: vec3f, axis: vec3f, u_axis: vec3f, radius: f32, ray: Ray) -> f32 {
    return cylinder_intersect_beyond(p0, axis, u_axis, radius, ray, 0.0);
}

// `Cylinder::intersect_beyond`: the nearest in (after, t_max) too, the far wall past a mask
// (`cylinder_intersect` is it with after = 0).
fn cylinder_intersect_beyond(p0: vec3f, axis: vec3f, u_axis: vec3f, radius: f32, ray: Ray, after: f32) -> f32 {
    let z = normalize(axis);
    let y = cross(z, u_axis);
    let f = ray.o - p0;
    let o2 = vec2f(dot(f, u_axis), dot(f, y));
    let d2 = vec2f(dot(ray.d, u_axis), dot(ray.d, y));
    let len2 = length(d2);
    if len2 == 0.0 {
        return -1.0;
    }
    let inv_len = 1.0 / len2;
    let u = d2 * inv_len;
    let b = -dot(o2, u);
    let l = o2 + b * u;
    let roots = careful_roots(b, dot(l, l), dot(o2, o2), radius, inv_len);
    if !roots.found {
        return -1.0;
    }
    let t0 = roots.t0;
    let t1 = roots.t1;
    let slack = gamma(8.0) * (length(f) + radius) * inv_len;
    let oz = dot(f, z);
    let dz = dot(ray.d, z);
    let h = length(axis);
    let z0 = oz + t0 * dz;
    if t0 > slack && t0 > after && t0 < ray.t_max && z0 >= 0.0 && z0 <= h {
        return t0;
    }
    let z1 = oz + t1 * dz;
    if t1 > slack && t1 > after && t1 < ray.t_max && z1 >= 0.0 && z1 <= h {
        return t1;
    }
    return -1.0;
}

struct CylinderPoint {
    p: vec3f,
    p_error: vec3f,
    n: vec3f,
}

// `Cylinder::surface_point`: the hit reprojected onto the tube, its error bound and normal
// (`signed_radius` < 0: towards the axis).
fn cylinder_surface_point(p0: vec3f, axis: vec3f, u_axis: vec3f, signed_radius: f32, ray: Ray, t: f32) -> CylinderPoint {
    let radius = abs(signed_radius);
    let z = normalize(axis);
    let rel = ray_at(ray, t) - p0;
    let along = z * dot(rel, z);
    let out = normalize_or(rel - along, u_axis);
    let p = p0 + along + out * radius;
    let p_error = gamma(6.0) * (abs(p0) + abs(along) + abs(out * radius));
    return CylinderPoint(p, p_error, select(out, -out, signed_radius < 0.0));
}

// #if HAS_TEXTURES
// `Cylinder::uv` (`turn_fraction` is `geometry/primitive.wgsl`'s).
fn cylinder_uv(p0: vec3f, axis: vec3f, u_axis: vec3f, y: vec3f) -> vec2f {
    let z = normalize(axis);
    let rel = y - p0;
    return vec2f(turn_fraction(atan2_precise(dot(rel, cross(z, u_axis)), dot(rel, u_axis))), dot(rel, z) / length(axis));
}
// #endif
// #endif
