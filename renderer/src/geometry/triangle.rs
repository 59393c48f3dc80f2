//! Triangles: watertight ray intersection (Woop, Benthin & Wald 2013, as in pbrt-v4), area and
//! bounds.
//! WGSL twin: `geometry/triangle.wgsl`.

use super::ray::{Ray, crosses_plane_ahead, gamma};
use crate::math::difference_of_products;
use glam::{Vec3, Vec3Swizzles};

/// A triangle hit: parameter and barycentrics of `v[0], v[1], v[2]`.
#[derive(Clone, Copy, Debug)]
pub struct TriangleHit {
    /// Ray parameter.
    pub t: f32,
    /// Barycentric coordinates.
    pub b: [f32; 3],
}

/// Area of the triangle `v`.
pub fn triangle_area(v: &[Vec3; 3]) -> f32 {
    0.5 * (v[1] - v[0]).cross(v[2] - v[0]).length()
}

/// Unit normal by the right-hand rule of the vertex order, or `None` for a degenerate triangle.
pub fn triangle_normal(v: &[Vec3; 3]) -> Option<Vec3> {
    let n = (v[1] - v[0]).cross(v[2] - v[0]);
    let len = n.length();
    (len > 0.0 && len.is_finite()).then(|| n / len)
}

/// The ray-dependent part of the watertight test (axis permutation and shear), computed once per
/// ray and shared by every triangle it is tested against.
#[derive(Clone, Copy, Debug)]
pub struct TriangleRay {
    o: Vec3,
    d: Vec3,
    /// Index of the direction's largest axis, which becomes z.
    kz: u8,
    /// Shear coefficients `(−d_x/d_z, −d_y/d_z, 1/d_z)` in permuted coordinates.
    s: Vec3,
}

impl TriangleRay {
    /// Prepares `ray` for triangle tests.
    #[inline]
    pub fn new(ray: &Ray) -> TriangleRay {
        let ad = ray.d.abs();
        let kz = if ad.x > ad.y {
            if ad.x > ad.z { 0 } else { 2 }
        } else if ad.y > ad.z {
            1
        } else {
            2
        };
        let d = permute(ray.d, kz);
        TriangleRay {
            o: ray.o,
            d: ray.d,
            kz,
            s: Vec3::new(-d.x / d.z, -d.y / d.z, 1.0 / d.z),
        }
    }
}

/// Cyclic permutation that moves axis `kz` to z (keeps the handedness).
#[inline]
fn permute(v: Vec3, kz: u8) -> Vec3 {
    match kz {
        0 => v.yzx(),
        1 => v.zxy(),
        _ => v,
    }
}

/// Watertight ray–triangle test: no ray slips between two triangles sharing an edge, and the hit is
/// reported only if `t` is provably positive (and below the ray's `t_max`).
#[inline]
pub fn intersect_triangle(ray: &Ray, v: &[Vec3; 3]) -> Option<TriangleHit> {
    intersect_triangle_prepared(&TriangleRay::new(ray), v, ray.t_max)
}

/// [`intersect_triangle`] with the per-ray work done once ([`TriangleRay`]).
#[inline]
pub fn intersect_triangle_prepared(
    r: &TriangleRay,
    v: &[Vec3; 3],
    t_max: f32,
) -> Option<TriangleHit> {
    // Translate to the ray origin, permute, and shear so the ray runs along +z.
    let mut p0t = permute(v[0] - r.o, r.kz);
    let mut p1t = permute(v[1] - r.o, r.kz);
    let mut p2t = permute(v[2] - r.o, r.kz);
    p0t.x += r.s.x * p0t.z;
    p0t.y += r.s.y * p0t.z;
    p1t.x += r.s.x * p1t.z;
    p1t.y += r.s.y * p1t.z;
    p2t.x += r.s.x * p2t.z;
    p2t.y += r.s.y * p2t.z;

    // Edge functions, each rounded once (exact products in f64), so their signs are consistent
    // across triangles that share an edge.
    let e0 = difference_of_products(p1t.x, p2t.y, p1t.y, p2t.x);
    let e1 = difference_of_products(p2t.x, p0t.y, p2t.y, p0t.x);
    let e2 = difference_of_products(p0t.x, p1t.y, p0t.y, p1t.x);
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return None;
    }
    p0t.z *= r.s.z;
    p1t.z *= r.s.z;
    p2t.z *= r.s.z;
    let t_scaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < t_max * det) {
        return None;
    }
    if det > 0.0 && (t_scaled <= 0.0 || t_scaled > t_max * det) {
        return None;
    }
    let inv_det = 1.0 / det;
    let t = t_scaled * inv_det;
    if !t.is_finite() {
        return None;
    }
    // Conservative bound on t's rounding error: reject hits that might be at t <= 0.
    let max_zt = p0t.z.abs().max(p1t.z.abs()).max(p2t.z.abs());
    let delta_z = gamma(3) * max_zt;
    let max_xt = p0t.x.abs().max(p1t.x.abs()).max(p2t.x.abs());
    let max_yt = p0t.y.abs().max(p1t.y.abs()).max(p2t.y.abs());
    let delta_x = gamma(5) * (max_xt + max_zt);
    let delta_y = gamma(5) * (max_yt + max_zt);
    let delta_e = 2.0 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    let max_e = e0.abs().max(e1.abs()).max(e2.abs());
    let delta_t =
        3.0 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * inv_det.abs();
    if t <= delta_t && !close_hit_is_real(r, v) {
        return None;
    }
    Some(TriangleHit {
        t,
        b: [e0 * inv_det, e1 * inv_det, e2 * inv_det],
    })
}

/// Decides a hit too close to the origin for `t`'s error bound (`t ≤ δt`) by the plane test of
/// [`crosses_plane_ahead`], with the plane's normal from the vertices in f64. Rare, so f64 is
/// affordable.
#[cold]
fn close_hit_is_real(r: &TriangleRay, v: &[Vec3; 3]) -> bool {
    let v0 = v[0].as_dvec3();
    let n = (v[1].as_dvec3() - v0).cross(v[2].as_dvec3() - v0);
    crosses_plane_ahead(r.o, r.d, v0, n)
}

/// The hit point from barycentrics (more accurate than `o + t·d`) and its error bound.
pub fn triangle_point(v: &[Vec3; 3], b: [f32; 3]) -> (Vec3, Vec3) {
    let p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
    let abs_sum = (b[0] * v[0]).abs() + (b[1] * v[1]).abs() + (b[2] * v[2]).abs();
    (p, gamma(7) * abs_sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn hits_inside_misses_outside() {
        let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let r = Ray::new(Vec3::new(0.2, 0.2, 1.0), -Vec3::Z);
        let h = intersect_triangle(&r, &v).unwrap();
        assert!((h.t - 1.0).abs() < 1e-6);
        assert!((h.b[1] - 0.2).abs() < 1e-6 && (h.b[2] - 0.2).abs() < 1e-6);
        let r = Ray::new(Vec3::new(0.7, 0.7, 1.0), -Vec3::Z);
        assert!(intersect_triangle(&r, &v).is_none());
        // behind the origin
        let r = Ray::new(Vec3::new(0.2, 0.2, -1.0), -Vec3::Z);
        assert!(intersect_triangle(&r, &v).is_none());
    }

    /// Rays through a shared edge must hit exactly one of two triangles (or both), never neither.
    #[test]
    fn watertight_on_shared_edges() {
        let a = Vec3::new(-1.3, 0.1, 0.2);
        let b = Vec3::new(1.7, 0.3, -0.4);
        let c = Vec3::new(0.1, 2.0, 0.3);
        let d = Vec3::new(0.2, -1.9, 0.1);
        let t1 = [a, b, c];
        let t2 = [b, a, d];
        let mut rng = Rng::new(3, 0, 0);
        for _ in 0..100_000 {
            let s = rng.next_f32();
            let on_edge = a + s * (b - a);
            let o = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, 5.0);
            let ray = Ray::new(o, (on_edge - o).normalize());
            let hit =
                intersect_triangle(&ray, &t1).is_some() || intersect_triangle(&ray, &t2).is_some();
            assert!(hit, "ray slipped through the shared edge at s={s}");
        }
    }
}
