//! Uniform solid-angle sampling of the spherical triangle a planar triangle subtends from a point
//! (Arvo 1995, "Stratified Sampling of Spherical Triangles"), and its inverse.
//!
//! Arvo's warp, as usually written, loses precision for tiny spherical triangles (the cosine of
//! the sampled arc is computed near 1) and for ones covering almost a hemisphere, so pbrt-v4 (and
//! callers here) sample by area below [`MIN_SPHERICAL_SAMPLE_AREA`] or above
//! [`MAX_SPHERICAL_SAMPLE_AREA`]. This version evaluates the arc through versines and half-angle
//! identities, so it stays accurate far below the minimum (round trip ~1e-5 in `u` at 1e-5 sr,
//! limited only by f32 directions); towards 2π it still degrades (~3e-4 at 6.23 sr).
//! WGSL twin: `sampling/spherical_triangle.wgsl`.

use crate::math::{difference_of_products, safe_sqrt};
use glam::{Vec2, Vec3};

/// Below this solid angle (sr), sample the triangle by area instead.
pub const MIN_SPHERICAL_SAMPLE_AREA: f32 = 3e-4;
/// Above this solid angle (sr, just under 2π), sample the triangle by area instead.
pub const MAX_SPHERICAL_SAMPLE_AREA: f32 = 6.22;

/// A direction sampled uniformly within a spherical triangle.
#[derive(Clone, Copy, Debug)]
pub struct SphericalTriangleSample {
    /// Unit direction from the reference point.
    pub dir: Vec3,
    /// Barycentrics of the point where `dir` meets the planar triangle.
    pub barycentrics: [f32; 3],
    /// Solid-angle pdf: 1 / solid angle.
    pub pdf: f32,
}

/// Solid angle of the spherical triangle with unit vertices `a, b, c` (Van Oosterom–Strackee:
/// `tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)`, accurate for tiny and huge triangles alike).
pub fn spherical_triangle_area(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    // a·((b-a)×(c-a)) = a·(b×c), but the edge differences keep small triangles' digits.
    let triple = a.dot((b - a).cross(c - a));
    2.0 * crate::math::atan2(triple.abs(), 1.0 + a.dot(b) + b.dot(c) + c.dot(a))
}

/// Van Oosterom–Strackee for vertex vectors of any length: `triple_abs` is `|a·(b×c)|`, which
/// callers can often compute exactly from the geometry.
pub(crate) fn solid_angle_from_vectors(triple_abs: f32, a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * crate::math::atan2(triple_abs, den)
}

/// Solid angle the triangle `v` subtends from `p` (0 when degenerate or when `p` is in its plane).
pub fn spherical_triangle_solid_angle(v: &[Vec3; 3], p: Vec3) -> f32 {
    Arvo::new(v, p).map_or(0.0, |t| t.area)
}

/// The quantities both directions of Arvo's map need.
struct Arvo {
    a: Vec3,
    b: Vec3,
    c: Vec3,
    area: f32,
    alpha: f32,
    cos_alpha: f32,
    sin_alpha: f32,
}

impl Arvo {
    fn new(v: &[Vec3; 3], p: Vec3) -> Option<Arvo> {
        let a = (v[0] - p).normalize_or_zero();
        let b = (v[1] - p).normalize_or_zero();
        let c = (v[2] - p).normalize_or_zero();
        let triple = a.dot((b - a).cross(c - a));
        // Exactly 0 when p is in the plane (the VOS formula would then say 0 or 2π) or any edge
        // or vector is degenerate; NaN inputs fail the area test below.
        if triple == 0.0 {
            return None;
        }
        // As `spherical_triangle_area`, reusing the triple product.
        let area = 2.0 * crate::math::atan2(triple.abs(), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
        Arvo::from_dirs([a, b, c], area)
    }

    /// From the unit directions and the solid angle [`spherical_triangle_area`] gives for them.
    fn from_dirs([a, b, c]: [Vec3; 3], area: f32) -> Option<Arvo> {
        if !(area > 0.0 && area.is_finite()) {
            return None;
        }
        // Angle at vertex a between the great circles towards b and c (a×b = a×(b-a), etc.).
        let n_ab = a.cross(b - a).normalize_or_zero();
        let n_ac = a.cross(c - a).normalize_or_zero();
        let cos_alpha = n_ab.dot(n_ac).clamp(-1.0, 1.0);
        let sin_alpha = n_ab.cross(n_ac).length().min(1.0);
        let alpha = crate::math::atan2(sin_alpha, cos_alpha);
        Some(Arvo {
            a,
            b,
            c,
            area,
            alpha,
            cos_alpha,
            sin_alpha,
        })
    }
}

/// The points the corners `(0,0), (1,0), (0,1), (1,1)` of the sample square go to under
/// [`sample_spherical_triangle`] (its `u.x` sweeps the arc `v0 → v2`, its `u.y` runs from `v1`
/// to that arc): where a bilinear warp in front of it ([`super::bilinear`]) puts its corner
/// weights.
#[inline]
pub fn spherical_triangle_corners(v: &[Vec3; 3]) -> [Vec3; 4] {
    [v[1], v[1], v[0], v[2]]
}

/// Unit tangent at unit vector `from` along the great circle towards `from + e`; taking the
/// difference `e` rather than the endpoint keeps the digits when the two are close.
fn tangent(from: Vec3, e: Vec3) -> Vec3 {
    (e - e.dot(from) * from).normalize_or_zero()
}

/// Samples a direction from `p` uniformly in the solid angle of triangle `v`. `None` when the
/// solid angle is 0 or not finite (degenerate triangle, `p` in its plane or on a vertex).
/// Works for either winding and either side of the triangle.
pub fn sample_spherical_triangle(
    v: &[Vec3; 3],
    p: Vec3,
    u: Vec2,
) -> Option<SphericalTriangleSample> {
    sample_arvo(&Arvo::new(v, p)?, v, p, u)
}

/// [`sample_spherical_triangle`] for a caller that already has the unit directions from `p` to
/// the vertices (`(v[i] − p).normalize_or_zero()`) and their [`spherical_triangle_area`], as
/// polygon lights do when they pick a triangle by solid angle. Same result, bit for bit.
pub fn sample_spherical_triangle_from_dirs(
    v: &[Vec3; 3],
    p: Vec3,
    dirs: [Vec3; 3],
    area: f32,
    u: Vec2,
) -> Option<SphericalTriangleSample> {
    sample_arvo(&Arvo::from_dirs(dirs, area)?, v, p, u)
}

fn sample_arvo(t: &Arvo, v: &[Vec3; 3], p: Vec3, u: Vec2) -> Option<SphericalTriangleSample> {
    let (a, b, c) = (t.a, t.b, t.c);
    // Sub-triangle (a, b, c') of area A' = u0·A, with c' on the arc a→c. Arvo gives cos of the
    // arc a→c' as q = n/d; we evaluate 1 - q = (d - n)/d instead, rewritten with half-angle
    // identities so that no term cancels for small triangles:
    //   d - n = v (1 - cos A') + u sin A',
    //   u = cos(A' - α) - cos α = 2 sin(A'/2) sin(α - A'/2),
    //   v = sin(A' - α) + sin α cos c = sin α ((1 - cos A') - (1 - cos c)) + cos α sin A'.
    let ap = u.x * t.area;
    let (sin_ap, cos_ap) = ap.sin_cos();
    let sin_half = (0.5 * ap).sin();
    let vers_ap = 2.0 * sin_half * sin_half; // 1 - cos A'
    let vers_c = 0.5 * (a - b).length_squared(); // 1 - a·b
    let uu = 2.0 * sin_half * (t.alpha - 0.5 * ap).sin();
    let vv = t.sin_alpha * (vers_ap - vers_c) + t.cos_alpha * sin_ap;
    // φ = A' - α: sin φ = sin A' cos α - cos A' sin α, cos φ = cos A' cos α + sin A' sin α.
    let sin_phi = difference_of_products(sin_ap, t.cos_alpha, cos_ap, t.sin_alpha);
    let cos_phi = difference_of_products(cos_ap, t.cos_alpha, -sin_ap, t.sin_alpha);
    let den = difference_of_products(vv, sin_phi, -uu, cos_phi) * t.sin_alpha;
    let num = difference_of_products(vv, vers_ap, -uu, sin_ap);
    let mut vers_l = (num / den).clamp(0.0, 2.0); // 1 - cos of the arc a→c'
    if vers_l.is_nan() {
        vers_l = 0.0; // 0/0 only for a zero-area sub-triangle: c' = a
    }
    let sin_l = safe_sqrt(vers_l * (2.0 - vers_l));
    let a_to_cp = sin_l * tangent(a, c - a) - vers_l * a; // c' - a

    // Along the arc b→c', 1 - cos θ is uniform in [0, 1 - c'·b]; versines avoid cancellation.
    let b_to_cp = (a - b) + a_to_cp;
    let vt = u.y * 0.5 * b_to_cp.length_squared();
    let sin_theta = safe_sqrt(vt * (2.0 - vt));
    let dir = (b + (sin_theta * tangent(b, b_to_cp) - vt * b)).normalize_or_zero();

    Some(SphericalTriangleSample {
        dir,
        barycentrics: barycentrics_along(v, p, dir),
        pdf: 1.0 / t.area,
    })
}

/// Barycentrics of the point where the ray from `p` along `dir` meets the plane of triangle `v`
/// (Möller–Trumbore), clamped onto the triangle: for a direction sampled within the triangle's
/// solid angle, the point it hits. A third each where the ray is parallel to the plane.
pub fn barycentrics_along(v: &[Vec3; 3], p: Vec3, dir: Vec3) -> [f32; 3] {
    let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
    let s1 = dir.cross(e2);
    let det = s1.dot(e1);
    if det == 0.0 {
        return [1.0 / 3.0; 3];
    }
    let o = p - v[0];
    let b1 = (o.dot(s1) / det).clamp(0.0, 1.0);
    let b2 = (dir.dot(o.cross(e1)) / det).clamp(0.0, 1.0);
    let sum = b1 + b2;
    let (b1, b2) = if sum > 1.0 {
        (b1 / sum, b2 / sum)
    } else {
        (b1, b2)
    };
    [(1.0 - b1 - b2).max(0.0), b1, b2]
}

/// Inverse of [`sample_spherical_triangle`]: the `u` that samples direction `w` (from `p`, inside
/// the spherical triangle). Degenerate inputs give `(0.5, 0.5)`.
pub fn invert_spherical_triangle(v: &[Vec3; 3], p: Vec3, w: Vec3) -> Vec2 {
    let Some(t) = Arvo::new(v, p) else {
        return Vec2::splat(0.5);
    };
    let (a, b, c) = (t.a, t.b, t.c);
    let w = w.normalize_or_zero();
    // c' is where the great circle through b and w crosses the arc a→c.
    let n_bw = b.cross(w - b);
    let n_ca = c.cross(a - c);
    let mut cp = n_bw.cross(n_ca).normalize_or_zero();
    if cp == Vec3::ZERO {
        return Vec2::new(0.5, 0.0); // w = b: u0 is arbitrary on the collapsed arc
    }
    if cp.dot(a + c) < 0.0 {
        cp = -cp;
    }
    let u0 = spherical_triangle_area(a, b, cp) / t.area;
    let u1 = (w - b).length_squared() / (cp - b).length_squared();
    Vec2::new(u0, u1).clamp(Vec2::ZERO, Vec2::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::sample_uniform_triangle;
    use crate::sampling::testing::{brute_force_solid_angle, check_fractions};

    const TRI: [Vec3; 3] = [
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(0.2, 1.0, 1.0),
    ];

    /// Triangles and viewpoints: in front, behind, reversed winding, very close (Ω ≈ 5.8 sr), far
    /// and oblique (Ω ≈ 0.02 sr), and small (Ω ≈ 3.2e-4, just above the minimum).
    fn configs() -> Vec<([Vec3; 3], Vec3)> {
        let rev = [TRI[0], TRI[2], TRI[1]];
        let small = TRI.map(|x| x * 0.053 + Vec3::new(0.0, 0.0, 2.0));
        vec![
            (TRI, Vec3::new(0.3, 0.3, 0.0)),
            (TRI, Vec3::new(-0.5, 0.2, 1.7)),
            (rev, Vec3::new(0.6, -0.3, -0.4)),
            (TRI, Vec3::new(0.35, 0.3, 0.97)),
            (TRI, Vec3::new(2.0, -1.0, -3.0)),
            (small, Vec3::new(0.3, 0.2, 0.0)),
        ]
    }

    /// Barycentrics (unclamped) where the ray p + t·d, t > 0, meets the triangle's plane.
    fn plane_hit(v: &[Vec3; 3], p: Vec3, d: Vec3) -> Option<[f32; 3]> {
        let (e1, e2) = (v[1] - v[0], v[2] - v[0]);
        let (s1, o) = (d.cross(e2), p - v[0]);
        let det = s1.dot(e1);
        let (b1, b2, t) = (
            o.dot(s1) / det,
            d.dot(o.cross(e1)) / det,
            e2.dot(o.cross(e1)) / det,
        );
        (t > 0.0).then_some([1.0 - b1 - b2, b1, b2])
    }

    #[test]
    fn solid_angle_matches_brute_force() {
        for (k, (v, p)) in configs().into_iter().enumerate() {
            let omega = spherical_triangle_solid_angle(&v, p);
            let hits = |w| plane_hit(&v, p, w).is_some_and(|b| b.iter().all(|&x| x >= 0.0));
            let (est, se) = brute_force_solid_angle(p, &v, 400_000, 70 + k as u32, hits);
            // 4 standard errors of the binomial estimate.
            assert!(
                (omega as f64 - est).abs() < 4.0 * se,
                "config {k}: {omega} vs {est} ± {se}"
            );
            let s = sample_spherical_triangle(&v, p, Vec2::splat(0.5)).unwrap();
            assert!((s.pdf * omega - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn samples_are_uniform_and_inside() {
        for (k, (v, p)) in configs().into_iter().enumerate() {
            let omega = spherical_triangle_solid_angle(&v, p);
            // Midpoint subdivision: region i is the corner sub-triangle where b_i > 1/2, 3 the
            // middle; each should get its share of the solid angle.
            let m = [
                (v[0] + v[1]) * 0.5,
                (v[1] + v[2]) * 0.5,
                (v[2] + v[0]) * 0.5,
            ];
            let subs = [
                [v[0], m[0], m[2]],
                [m[0], v[1], m[1]],
                [m[2], m[1], v[2]],
                m,
            ];
            let expect = subs.map(|s| spherical_triangle_solid_angle(&s, p) / omega);
            assert!((expect.iter().sum::<f32>() - 1.0).abs() < 1e-4);
            let mut counts = [0u32; 4];
            let mut rng = Rng::new(80 + k as u32, 0, 0);
            for _ in 0..200_000 {
                let s = sample_spherical_triangle(&v, p, rng.next_2d()).unwrap();
                assert!((s.dir.length() - 1.0).abs() < 1e-5);
                let b = plane_hit(&v, p, s.dir).expect("direction misses the plane");
                assert!(b.iter().all(|&x| x > -1e-4), "config {k}: outside {b:?}");
                let q = s.barycentrics;
                let y = q[0] * v[0] + q[1] * v[1] + q[2] * v[2];
                assert!(
                    ((y - p).normalize() - s.dir).length() < 1e-3,
                    "config {k}: {q:?}"
                );
                counts[(0..3).find(|&i| q[i] > 0.5).unwrap_or(3)] += 1;
            }
            check_fractions(&counts, &expect);
        }
    }

    #[test]
    fn round_trips() {
        // The configurations, then Ω ≈ 1.2e-5 (far below the minimum) and Ω ≈ 6.23 (above the max).
        let mut cs = configs();
        cs.push((
            TRI.map(|x| x * 0.01 + Vec3::new(0.0, 0.0, 2.0)),
            Vec3::new(0.3, 0.2, 0.0),
        ));
        cs.push((TRI, Vec3::new(0.35, 0.3, 0.997)));
        for (k, (v, p)) in cs.into_iter().enumerate() {
            let omega = spherical_triangle_solid_angle(&v, p);
            let mut rng = Rng::new(90 + k as u32, 0, 0);
            let mut worst = [0.0f32; 3];
            for _ in 0..50_000 {
                let u = rng.next_2d();
                let s = sample_spherical_triangle(&v, p, u).unwrap();
                let back = invert_spherical_triangle(&v, p, s.dir);
                // The arc b→c' has length ∝ √u1, so u0 is only defined to ~δ/√u1 near vertex b.
                worst[0] = worst[0].max((back.x - u.x).abs() * u.y.sqrt());
                worst[1] = worst[1].max((back.y - u.y).abs());
                // sample(invert(w)) for a uniform point of the planar triangle, relative to the
                // spherical triangle's angular size √Ω.
                let b = sample_uniform_triangle(rng.next_2d());
                let w = (b[0] * v[0] + b[1] * v[1] + b[2] * v[2] - p).normalize();
                let w2 = sample_spherical_triangle(&v, p, invert_spherical_triangle(&v, p, w));
                worst[2] = worst[2].max((w2.unwrap().dir - w).length() / omega.sqrt());
            }
            // Measured: ≤ 2e-5 within [MIN, MAX]; ~7e-5 at 1.2e-5 sr (f32 directions resolve a
            // triangle of angular size θ only to ε/θ); ~3e-4 at 6.23 sr (Arvo degrades towards 2π,
            // hence MAX_SPHERICAL_SAMPLE_AREA).
            let tol = if k < 6 { 5e-5 } else { 1e-3 };
            assert!(
                worst.iter().all(|&e| e < tol),
                "config {k} (Ω = {omega}): {worst:?}"
            );
        }
    }

    #[test]
    fn degenerate_cases_are_rejected() {
        let u = Vec2::splat(0.3);
        // p in the plane (inside and outside the triangle), p at a vertex, a collinear triangle.
        assert!(sample_spherical_triangle(&TRI, Vec3::new(0.3, 0.3, 1.0), u).is_none());
        assert!(sample_spherical_triangle(&TRI, Vec3::new(3.0, -2.0, 1.0), u).is_none());
        assert!(sample_spherical_triangle(&TRI, TRI[1], u).is_none());
        let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        assert!(sample_spherical_triangle(&line, Vec3::Y, u).is_none());
        assert_eq!(spherical_triangle_solid_angle(&line, Vec3::Y), 0.0);
    }
}
