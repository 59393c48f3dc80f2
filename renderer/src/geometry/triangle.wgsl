// Watertight ray–triangle intersection (Woop, Benthin & Wald 2013), the twin of
// `geometry/triangle.rs`: edge functions rounded about once (FMA), t's error bound, and close hits
// settled by the plane-side test.

struct TriangleRay {
    o: vec3f,
    d: vec3f,
    kz: u32,
    s: vec3f,
}

fn tri_permute(v: vec3f, kz: u32) -> vec3f {
    if kz == 0u {
        return v.yzx;
    } else if kz == 1u {
        return v.zxy;
    }
    return v;
}

fn triangle_ray_new(r: Ray) -> TriangleRay {
    let ad = abs(r.d);
    var kz = 2u;
    if ad.x > ad.y {
        if ad.x > ad.z {
            kz = 0u;
        }
    } else if ad.y > ad.z {
        kz = 1u;
    }
    let d = tri_permute(r.d, kz);
    return TriangleRay(r.o, r.d, kz, vec3f(-d.x / d.z, -d.y / d.z, 1.0 / d.z));
}

// The plane test with the triangle's normal from its vertices in double-f32.
fn tri_close_hit_is_real(r: TriangleRay, v0: vec3f, v1: vec3f, v2: vec3f) -> bool {
    let ax = df_from_diff(v1.x, v0.x);
    let ay = df_from_diff(v1.y, v0.y);
    let az = df_from_diff(v1.z, v0.z);
    let bx = df_from_diff(v2.x, v0.x);
    let by = df_from_diff(v2.y, v0.y);
    let bz = df_from_diff(v2.z, v0.z);
    let nx = df_add(df_mul(ay, bz), -df_mul(az, by));
    let ny = df_add(df_mul(az, bx), -df_mul(ax, bz));
    let nz = df_add(df_mul(ax, by), -df_mul(ay, bx));
    return crosses_plane_ahead_df(r.o, r.d, vec2f(v0.x, 0.0), vec2f(v0.y, 0.0), vec2f(v0.z, 0.0), nx, ny, nz);
}

// t and barycentrics (b0, b1, b2) of a hit in (0, t_max); t < 0 for a miss.
fn intersect_triangle_prepared(r: TriangleRay, v0: vec3f, v1: vec3f, v2: vec3f, t_max: f32) -> vec4f {
    let miss = vec4f(-1.0, 0.0, 0.0, 0.0);
    var p0t = tri_permute(v0 - r.o, r.kz);
    var p1t = tri_permute(v1 - r.o, r.kz);
    var p2t = tri_permute(v2 - r.o, r.kz);
    p0t.x += r.s.x * p0t.z;
    p0t.y += r.s.y * p0t.z;
    p1t.x += r.s.x * p1t.z;
    p1t.y += r.s.y * p1t.z;
    p2t.x += r.s.x * p2t.z;
    p2t.y += r.s.y * p2t.z;
    let e0 = difference_of_products(p1t.x, p2t.y, p1t.y, p2t.x);
    let e1 = difference_of_products(p2t.x, p0t.y, p2t.y, p0t.x);
    let e2 = difference_of_products(p0t.x, p1t.y, p0t.y, p1t.x);
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return miss;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return miss;
    }
    p0t.z *= r.s.z;
    p1t.z *= r.s.z;
    p2t.z *= r.s.z;
    let t_scaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
        return miss;
    }
    if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
        return miss;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if !is_finite_f(t) {
        return miss;
    }
    let max_zt = max(max(abs(p0t.z), abs(p1t.z)), abs(p2t.z));
    let delta_z = gamma(3.0) * max_zt;
    let max_xt = max(max(abs(p0t.x), abs(p1t.x)), abs(p2t.x));
    let max_yt = max(max(abs(p0t.y), abs(p1t.y)), abs(p2t.y));
    let delta_x = gamma(5.0) * (max_xt + max_zt);
    let delta_y = gamma(5.0) * (max_yt + max_zt);
    let delta_e = 2.0 * (gamma(2.0) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = max(max(abs(e0), abs(e1)), abs(e2));
    let delta_t = 3.0 * (gamma(3.0) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * abs(inv_det);
    if t <= delta_t && !tri_close_hit_is_real(r, v0, v1, v2) {
        return miss;
    }
    return vec4f(t, e0 * inv_det, e1 * inv_det, e2 * inv_det);
}

// `triangle_point`: the hit point from barycentrics and its error bound.
fn triangle_point(v0: vec3f, v1: vec3f, v2: vec3f, b: vec3f) -> array<vec3f, 2> {
    let p = b.x * v0 + b.y * v1 + b.z * v2;
    let abs_sum = abs(b.x * v0) + abs(b.y * v1) + abs(b.z * v2);
    return array<vec3f, 2>(p, gamma(7.0) * abs_sum);
}
