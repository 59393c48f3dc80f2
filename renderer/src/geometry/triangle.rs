//! Triangles: watertight ray intersection (Woop, Benthin & Wald 2013, as in pbrt-v4), area and
//! bounds.

use super::ray::{Ray, gamma};
use crate::math::difference_of_products;
use glam::{DVec3, Vec3};

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

#[inline]
fn permute(v: Vec3, kx: usize, ky: usize, kz: usize) -> Vec3 {
    Vec3::new(v[kx], v[ky], v[kz])
}

/// Watertight ray–triangle test: no ray slips between two triangles sharing an edge, and the hit is
/// reported only if `t` is provably positive (within the ray's `t_max`).
pub fn intersect_triangle(ray: &Ray, v: &[Vec3; 3]) -> Option<TriangleHit> {
    let mut p0t = v[0] - ray.o;
    let mut p1t = v[1] - ray.o;
    let mut p2t = v[2] - ray.o;
    // Permute so the ray direction's largest component is z.
    let ad = ray.d.abs();
    let kz = if ad.x > ad.y { if ad.x > ad.z { 0 } else { 2 } } else if ad.y > ad.z { 1 } else { 2 };
    let kx = (kz + 1) % 3;
    let ky = (kx + 1) % 3;
    let d = permute(ray.d, kx, ky, kz);
    p0t = permute(p0t, kx, ky, kz);
    p1t = permute(p1t, kx, ky, kz);
    p2t = permute(p2t, kx, ky, kz);
    // Shear so the ray runs along +z.
    let sx = -d.x / d.z;
    let sy = -d.y / d.z;
    let sz = 1.0 / d.z;
    p0t.x += sx * p0t.z;
    p0t.y += sy * p0t.z;
    p1t.x += sx * p1t.z;
    p1t.y += sy * p1t.z;
    p2t.x += sx * p2t.z;
    p2t.y += sy * p2t.z;

    let mut e0 = difference_of_products(p1t.x, p2t.y, p1t.y, p2t.x);
    let mut e1 = difference_of_products(p2t.x, p0t.y, p2t.y, p0t.x);
    let mut e2 = difference_of_products(p0t.x, p1t.y, p0t.y, p1t.x);
    // An edge function of exactly 0 is where f32 cannot decide the side: redo it in f64.
    if e0 == 0.0 || e1 == 0.0 || e2 == 0.0 {
        let (a, b, c) = (p0t.as_dvec3(), p1t.as_dvec3(), p2t.as_dvec3());
        let ef = |p: DVec3, q: DVec3| (p.x * q.y - p.y * q.x) as f32;
        e0 = ef(b, c);
        e1 = ef(c, a);
        e2 = ef(a, b);
    }
    if (e0 < 0.0 || e1 < 0.0 || e2 < 0.0) && (e0 > 0.0 || e1 > 0.0 || e2 > 0.0) {
        return None;
    }
    let det = e0 + e1 + e2;
    if det == 0.0 {
        return None;
    }
    p0t.z *= sz;
    p1t.z *= sz;
    p2t.z *= sz;
    let t_scaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
    if det < 0.0 && (t_scaled >= 0.0 || t_scaled < ray.t_max * det) {
        return None;
    }
    if det > 0.0 && (t_scaled <= 0.0 || t_scaled > ray.t_max * det) {
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
    if t <= delta_t {
        return None;
    }
    Some(TriangleHit { t, b: [e0 * inv_det, e1 * inv_det, e2 * inv_det] })
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
            let hit = intersect_triangle(&ray, &t1).is_some() || intersect_triangle(&ray, &t2).is_some();
            assert!(hit, "ray slipped through the shared edge at s={s}");
        }
    }
}
