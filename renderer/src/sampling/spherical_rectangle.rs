//! Uniform solid-angle sampling of a rectangle seen from a point (Ureña, Fajardo and King 2013,
//! "An Area-Preserving Parametrization for Spherical Rectangles"), and its inverse.
//!
//! In a local frame with the rectangle at height `z0 < 0` (z flipped if needed, so either side of
//! the rectangle works), `u0` picks the abscissa `xu` that cuts off a sub-rectangle of solid angle
//! `u0·Ω`, and `u1` picks `yv` uniformly in `h = y / √(xu² + z0² + y²)` along that line. The
//! solid angles use Van Oosterom–Strackee with exact triple products, and the `y` step uses
//! cancellation-free forms of `1 ± h`, so grazing and tiny rectangles keep their digits.
//! WGSL twin: `sampling/spherical_rectangle.wgsl`.

use super::spherical_triangle::solid_angle_from_vectors;
use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};

/// Largest `|cos|` between the edges accepted as a rectangle.
pub(crate) const MAX_EDGE_COS: f32 = 1e-4;

/// Most safeguarded Newton steps polishing Ureña's closed-form abscissa (one or two suffice
/// unless the view is grazing; each bisection fallback halves the bracket).
pub(crate) const MAX_NEWTON_STEPS: usize = 32;

/// A rectangle `corner + s·edge_u + t·edge_v` (`s, t ∈ [0, 1]`) as seen from a point, ready to be
/// sampled uniformly by solid angle.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    corner: Vec3,
    edge_u: Vec3,
    edge_v: Vec3,
    /// Edge lengths.
    exl: f32,
    eyl: f32,
    /// Local coordinates of the rectangle relative to the point: `[x0, x0+exl] × [y0, y1]` at `z0`.
    x0: f32,
    y0: f32,
    y1: f32,
    z0: f32,
    /// `n0.z`, `n2.z` (normals of the edges at y0 and y1) and `1 - b0²`.
    b0: f32,
    b1: f32,
    one_minus_b0sq: f32,
    /// sin and cos of `k = 2π - γ2 - γ3`, the angles at the x0 edge.
    sin_k: f32,
    cos_k: f32,
    solid_angle: f32,
}

impl SphericalRectangle {
    /// Sets up sampling of the parallelogram `corner + s·edge_u + t·edge_v` from `p`. `None` unless
    /// the edges are perpendicular (within 1e-4 in cosine), `p` is off the plane, and the solid
    /// angle is positive and finite: callers then fall back to area sampling.
    pub fn new(p: Vec3, corner: Vec3, edge_u: Vec3, edge_v: Vec3) -> Option<SphericalRectangle> {
        let (exl, eyl) = (edge_u.length(), edge_v.length());
        if !(exl > 0.0 && eyl > 0.0 && exl.is_finite() && eyl.is_finite()) {
            return None;
        }
        let x = edge_u / exl;
        let y = edge_v / eyl;
        if x.dot(y).abs() > MAX_EDGE_COS {
            return None;
        }
        let y = (y - x.dot(y) * x).normalize(); // make the frame exactly orthonormal
        let d = corner - p;
        // The formulas assume the rectangle lies below the point: flip z when it does not.
        let z0 = -d.dot(x.cross(y)).abs();
        // In the plane up to rounding (or at the corner): no proper solid angle.
        if z0 >= -1e-6 * d.length() || z0.is_nan() {
            return None;
        }
        let (x0, y0) = (d.dot(x), d.dot(y));
        let y1 = y0 + eyl;
        let z2 = z0 * z0;
        // Interior angles at the x0 edge, γ2 at (x0, y1) and γ3 at (x0, y0), as (cos, sin)
        // from the edge-plane normals in closed form.
        let g2 = Vec2::new(x0 * y1, -z0 * (x0 * x0 + y1 * y1 + z2).sqrt()).normalize();
        let g3 = Vec2::new(-x0 * y0, -z0 * (x0 * x0 + y0 * y0 + z2).sqrt()).normalize();
        let mut r = SphericalRectangle {
            corner,
            edge_u,
            edge_v,
            exl,
            eyl,
            x0,
            y0,
            y1,
            z0,
            b0: -y0 / (z2 + y0 * y0).sqrt(),
            b1: y1 / (z2 + y1 * y1).sqrt(),
            one_minus_b0sq: z2 / (z2 + y0 * y0),
            // k = 2π - γ2 - γ3: cos k = cos(γ2 + γ3), sin k = -sin(γ2 + γ3).
            cos_k: g2.x * g3.x - g2.y * g3.y,
            sin_k: -(g2.y * g3.x + g2.x * g3.y),
            solid_angle: 0.0,
        };
        r.solid_angle = r.partial_solid_angle(exl);
        (r.solid_angle > 0.0 && r.solid_angle.is_finite()).then_some(r)
    }

    /// Solid angle of the sub-rectangle `[x0, x0 + width] × [y0, y1]`, as two triangles whose
    /// triple products are exactly `|z0|·width·eyl`.
    fn partial_solid_angle(&self, width: f32) -> f32 {
        let (x0, x1, y0, y1, z0) = (self.x0, self.x0 + width, self.y0, self.y1, self.z0);
        let v00 = Vec3::new(x0, y0, z0);
        let v01 = Vec3::new(x0, y1, z0);
        let v10 = Vec3::new(x1, y0, z0);
        let v11 = Vec3::new(x1, y1, z0);
        let triple = -z0 * width * self.eyl;
        solid_angle_from_vectors(triple, v00, v10, v11)
            + solid_angle_from_vectors(triple, v00, v11, v01)
    }

    /// Width `w ∈ [0, exl]` of the sub-rectangle `[x0, x0 + w] × [y0, y1]` of solid angle `target`.
    /// Ureña's closed form loses all its digits at grazing views (b0 ≈ b1 ≈ 1 and cos(au) ≈ 1
    /// cancel), so it only seeds Newton's method on the partial solid angle, which is exact up to
    /// rounding and is what `invert` uses; `dΩ/dx = |z0| (h1 - h0) / (x² + z0²)`. Steps that
    /// leave the bracket bisect instead.
    fn solve_width(&self, target: f32, guess: f32) -> f32 {
        let (y0, y1, z0) = (self.y0, self.y1, self.z0);
        let (mut lo, mut hi) = (0.0, self.exl);
        let mut w = if guess.is_nan() {
            0.5 * self.exl
        } else {
            guess.clamp(lo, hi)
        };
        for _ in 0..MAX_NEWTON_STEPS {
            let f = self.partial_solid_angle(w) - target;
            if f == 0.0 {
                break;
            } else if f > 0.0 {
                hi = w;
            } else {
                lo = w;
            }
            let x = self.x0 + w;
            let dd2 = x * x + z0 * z0;
            let newton = w - f * dd2 / (-z0 * h_diff(y0, y1, dd2));
            if newton > lo && newton < hi {
                let step = newton - w;
                w = newton;
                // Quadratic convergence: the next error is ~step²/dd (the slope varies on the
                // scale of the distance dd to the line), so stop once that is negligible.
                if step.abs() <= 1e-4 * dd2.sqrt() {
                    break;
                }
            } else {
                w = 0.5 * (lo + hi);
                if hi - lo <= 4.0 * f32::EPSILON * self.exl {
                    break;
                }
            }
        }
        w
    }

    /// Solid angle of the rectangle seen from the point (sr).
    pub fn solid_angle(&self) -> f32 {
        self.solid_angle
    }

    /// Solid-angle pdf of [`SphericalRectangle::sample`]: `1 / solid_angle`.
    pub fn pdf(&self) -> f32 {
        1.0 / self.solid_angle
    }

    /// The point on the rectangle for `u ∈ [0,1)²`; its direction from `p` is uniform in solid angle.
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let (x0, y0, y1, z0) = (self.x0, self.y0, self.y1, self.z0);
        // au = k + u0·Ω (the sub-rectangle's angles at the new edge), by angle addition so small
        // Ω keeps its digits.
        let (sd, cd) = (u.x * self.solid_angle).sin_cos();
        let sin_au = self.sin_k * cd + self.cos_k * sd;
        let cos_au = self.cos_k * cd - self.sin_k * sd;
        let fu = self.b0.mul_add(cos_au, -self.b1) / sin_au;
        // xu = -cu z0 / √(1 - cu²) with cu = sign(fu)/√(fu² + b0²), simplified; fu = ±∞ gives 0.
        let xu = (-z0 / safe_sqrt(fu.mul_add(fu, -self.one_minus_b0sq))).copysign(fu);
        let width = self.solve_width(u.x * self.solid_angle, xu - x0);
        let xu = x0 + width;

        // yv uniform in h between h(y0) and h(y1); 1 ± hv as convex combinations of the
        // endpoints' (cancellation-free) 1 ± h.
        let dd2 = xu * xu + z0 * z0;
        let (h0, m0, p0) = h_terms(y0, dd2);
        let (_, m1, p1) = h_terms(y1, dd2);
        let hv = h0 + u.y * h_diff(y0, y1, dd2);
        let one_minus = (1.0 - u.y) * m0 + u.y * m1;
        let one_plus = (1.0 - u.y) * p0 + u.y * p1;
        let mut yv = hv * dd2.sqrt() / (one_minus * one_plus).sqrt();
        if yv.is_nan() {
            yv = y0 + u.y * self.eyl;
        }
        let yv = yv.clamp(y0, y1);
        let s = width / self.exl;
        let t = ((yv - y0) / self.eyl).clamp(0.0, 1.0);
        self.corner + s * self.edge_u + t * self.edge_v
    }

    /// Inverse of [`SphericalRectangle::sample`]: the `u` that samples `point` (on the rectangle).
    pub fn invert(&self, point: Vec3) -> Vec2 {
        // Parallelogram coordinates (s, t) by the 2×2 normal equations (exact for skewed edges).
        let r = point - self.corner;
        let (uu, uv, vv) = (
            self.edge_u.length_squared(),
            self.edge_u.dot(self.edge_v),
            self.edge_v.length_squared(),
        );
        let (ru, rv) = (r.dot(self.edge_u), r.dot(self.edge_v));
        let det = uu * vv - uv * uv;
        let s = ((ru * vv - rv * uv) / det).clamp(0.0, 1.0);
        let t = ((rv * uu - ru * uv) / det).clamp(0.0, 1.0);
        let u0 = self.partial_solid_angle(s * self.exl) / self.solid_angle;
        let xu = self.x0 + s * self.exl;
        let yv = self.y0 + t * self.eyl;
        let dd2 = xu * xu + self.z0 * self.z0;
        let u1 = h_diff(self.y0, yv, dd2) / h_diff(self.y0, self.y1, dd2);
        Vec2::new(u0, u1).clamp(Vec2::ZERO, Vec2::ONE)
    }
}

/// `(h, 1 - h, 1 + h)` for `h = y / √(dd² + y²)`, each without cancellation.
fn h_terms(y: f32, dd2: f32) -> (f32, f32, f32) {
    let r = (dd2 + y * y).sqrt();
    if y > 0.0 {
        (y / r, dd2 / (r * (r + y)), (r + y) / r)
    } else {
        (y / r, (r - y) / r, dd2 / (r * (r - y)))
    }
}

/// `h(yb) - h(ya)` without cancellation when `ya` and `yb` are close or far out on one side.
fn h_diff(ya: f32, yb: f32, dd2: f32) -> f32 {
    let ra = (dd2 + ya * ya).sqrt();
    let rb = (dd2 + yb * yb).sqrt();
    if ya * yb > 0.0 {
        dd2 * (yb - ya) * (yb + ya) / (ra * rb * (yb * ra + ya * rb))
    } else {
        yb / rb - ya / ra
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Frame;
    use crate::rng::Rng;
    use crate::sampling::testing::{brute_force_solid_angle, check_fractions};

    /// A 2 × 1 rectangle in a tilted frame: (corner, edge_u, edge_v).
    fn rect() -> (Vec3, Vec3, Vec3) {
        let f = Frame::from_normal(Vec3::new(0.3, -0.2, 1.0).normalize());
        (Vec3::new(0.5, -0.3, 1.0), 2.0 * f.s, f.t)
    }

    /// Viewpoints as (s, t, height) over the rectangle: in front, behind, far away (Ω ≈ 5e-4),
    /// near a corner (outside it), very close above the middle (Ω ≈ 6.1), grazing along v, and
    /// grazing along u (Ω ≈ 4e-4, where Ureña's closed form alone loses every digit).
    const VIEWS: [(f32, f32, f32); 7] = [
        (0.4, 0.3, 1.5),
        (0.8, 0.9, -0.7),
        (-15.0, 20.0, 40.0),
        (-0.01, -0.02, 0.03),
        (0.5, 0.5, 0.02),
        (0.5, 3.0, 0.1),
        (1.5, 0.5, 0.001),
    ];

    /// (p, corner, edge_u, edge_v) for every view.
    fn configs() -> impl Iterator<Item = (Vec3, Vec3, Vec3, Vec3)> {
        let (c, eu, ev) = rect();
        let n = eu.cross(ev).normalize();
        VIEWS
            .into_iter()
            .map(move |(s, t, h)| (c + s * eu + t * ev + h * n, c, eu, ev))
    }

    /// Whether the ray p + λd, λ > 0, meets the rectangle.
    fn hits(p: Vec3, d: Vec3, c: Vec3, eu: Vec3, ev: Vec3) -> bool {
        let n = eu.cross(ev);
        let lambda = (c - p).dot(n) / d.dot(n);
        let r = p + lambda * d - c;
        let st = Vec2::new(
            r.dot(eu) / eu.length_squared(),
            r.dot(ev) / ev.length_squared(),
        );
        lambda > 0.0 && st.cmpge(Vec2::ZERO).all() && st.cmple(Vec2::ONE).all()
    }

    #[test]
    fn solid_angle_matches_brute_force() {
        for (k, (p, c, eu, ev)) in configs().enumerate() {
            let r = SphericalRectangle::new(p, c, eu, ev).unwrap();
            let corners = [c, c + eu, c + ev, c + eu + ev];
            let hit = |d| hits(p, d, c, eu, ev);
            let (est, se) = brute_force_solid_angle(p, &corners, 400_000, 100 + k as u32, hit);
            // 4 standard errors of the binomial estimate.
            let omega = r.solid_angle() as f64;
            assert!(
                (omega - est).abs() < 4.0 * se,
                "view {k}: {omega} vs {est} ± {se}"
            );
            assert!((r.pdf() as f64 * omega - 1.0).abs() < 1e-6);
        }
    }

    #[test]
    fn samples_are_uniform_and_on_the_rectangle() {
        for (k, (p, c, eu, ev)) in configs().enumerate() {
            let r = SphericalRectangle::new(p, c, eu, ev).unwrap();
            // 2×2 sub-rectangles: expected fractions are their solid angles over the whole.
            let expect = [(0.0, 0.0), (0.5, 0.0), (0.0, 0.5), (0.5, 0.5)].map(|(s, t)| {
                let sub = SphericalRectangle::new(p, c + s * eu + t * ev, 0.5 * eu, 0.5 * ev);
                sub.unwrap().solid_angle() / r.solid_angle()
            });
            assert!(
                (expect.iter().sum::<f32>() - 1.0).abs() < 1e-4,
                "{expect:?}"
            );
            let mut counts = [0u32; 4];
            let mut rng = Rng::new(110 + k as u32, 0, 0);
            for _ in 0..200_000 {
                // On the rectangle: in its plane, within its edges (up to rounding).
                let q = r.sample(rng.next_2d()) - c;
                let st = Vec2::new(
                    q.dot(eu) / eu.length_squared(),
                    q.dot(ev) / ev.length_squared(),
                );
                assert!(
                    q.dot(eu.cross(ev).normalize()).abs() < 1e-6,
                    "view {k}: off the plane"
                );
                let ok =
                    st.cmpge(Vec2::splat(-1e-6)).all() && st.cmple(Vec2::splat(1.0 + 1e-6)).all();
                assert!(ok, "view {k}: {st}");
                counts[(st.x >= 0.5) as usize + 2 * (st.y >= 0.5) as usize] += 1;
            }
            check_fractions(&counts, &expect);
        }
    }

    #[test]
    fn round_trips() {
        for (k, (p, c, eu, ev)) in configs().enumerate() {
            let r = SphericalRectangle::new(p, c, eu, ev).unwrap();
            let mut rng = Rng::new(120 + k as u32, 0, 0);
            let (mut du, mut dw) = (0.0f32, 0.0f32);
            for _ in 0..50_000 {
                let u = rng.next_2d();
                du = du.max((r.invert(r.sample(u)) - u).abs().max_element());
                // sample(invert(q)) for a uniform point q, compared as directions from p.
                let q = c + rng.next_f32() * eu + rng.next_f32() * ev;
                let q2 = r.sample(r.invert(q));
                dw = dw.max(((q2 - p).normalize() - (q - p).normalize()).length());
            }
            // Measured: du ≤ 1.1e-5 (largest close to 2π and far off-axis, where the point's f32
            // coordinates relative to p limit it), dw ≤ 1e-5, except dw ≈ 5e-4 at Ω ≈ 6.1: there
            // the grazing part of the rectangle is squeezed into a sliver of u, so the map is
            // ill-conditioned (one reason for the caller's maximum solid angle).
            let dw_tol = if r.solid_angle() > 5.0 { 2e-3 } else { 5e-5 };
            assert!(
                du < 5e-5 && dw < dw_tol,
                "view {k} (Ω = {}): {du} {dw}",
                r.solid_angle()
            );
        }
    }

    #[test]
    fn rejects_non_rectangles_and_in_plane_points() {
        let (c, eu, ev) = rect();
        let p = c + 0.5 * eu + eu.cross(ev).normalize();
        assert!(SphericalRectangle::new(p, c, eu, ev + 0.01 * eu).is_none());
        assert!(SphericalRectangle::new(p, c, eu, ev + 1e-5 * eu).is_some());
        // In the plane (up to rounding), inside and outside the rectangle, and at the corner.
        assert!(SphericalRectangle::new(c + 0.5 * eu + 0.5 * ev, c, eu, ev).is_none());
        assert!(SphericalRectangle::new(c + 3.0 * eu, c, eu, ev).is_none());
        assert!(SphericalRectangle::new(c, c, eu, ev).is_none());
        assert!(SphericalRectangle::new(p, c, Vec3::ZERO, ev).is_none());
    }
}
