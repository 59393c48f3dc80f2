//! Uniform sampling of directions in a cone about +z.
//!
//! Everything is written in terms of the versine `h = 1 - cos θmax`, so tiny cones keep their
//! precision: `1 - cos θ = u₀ h` and `sin²θ = u₀h (2 - u₀h)` never cancel. A cone given by its
//! cosine is only as accurate as `1 - cos θmax` is in f32 (exact, but the cosine itself has an
//! absolute resolution of 6e-8). **Sphere lights should use the `_sin2` forms** with
//! `sin²θmax = r²/d²`, which stay exact for arbitrarily small cones without pbrt-v4's Taylor
//! branch (pbrt switches to an approximation below sin²θmax = 0.00068523; here
//! `h = sin²/(1 + cos)` is already free of cancellation).

use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};
use std::f32::consts::TAU;

/// `1 - cos θ` from `sin²θ` for `θ ∈ [0, π/2]`, without cancellation.
#[inline]
pub fn one_minus_cos_from_sin2(sin2_theta: f32) -> f32 {
    let s2 = sin2_theta.clamp(0.0, 1.0);
    s2 / (1.0 + safe_sqrt(1.0 - s2))
}

/// Uniform direction in the cone of half-angle θmax about +z (pdf [`uniform_cone_pdf`]).
/// A degenerate cone (`cos_theta_max ≥ 1`) returns +z.
pub fn sample_uniform_cone(u: Vec2, cos_theta_max: f32) -> Vec3 {
    sample_uniform_cone_versine(u, 1.0 - cos_theta_max)
}

/// Pdf of [`sample_uniform_cone`] with respect to solid angle: `1 / (2π (1 - cos θmax))`;
/// infinite for a degenerate cone, which callers must treat as a delta.
pub fn uniform_cone_pdf(cos_theta_max: f32) -> f32 {
    uniform_cone_pdf_versine(1.0 - cos_theta_max)
}

/// Inverse of [`sample_uniform_cone`] for a unit vector `w` in the cone.
pub fn invert_uniform_cone(w: Vec3, cos_theta_max: f32) -> Vec2 {
    invert_uniform_cone_versine(w, 1.0 - cos_theta_max)
}

/// [`sample_uniform_cone`] for a cone given by `sin²θmax` (θmax ≤ π/2): the robust form for
/// sphere lights, accurate however small the cone.
pub fn sample_uniform_cone_sin2(u: Vec2, sin2_theta_max: f32) -> Vec3 {
    sample_uniform_cone_versine(u, one_minus_cos_from_sin2(sin2_theta_max))
}

/// Pdf of [`sample_uniform_cone_sin2`] with respect to solid angle.
pub fn uniform_cone_pdf_sin2(sin2_theta_max: f32) -> f32 {
    uniform_cone_pdf_versine(one_minus_cos_from_sin2(sin2_theta_max))
}

/// Inverse of [`sample_uniform_cone_sin2`].
pub fn invert_uniform_cone_sin2(w: Vec3, sin2_theta_max: f32) -> Vec2 {
    invert_uniform_cone_versine(w, one_minus_cos_from_sin2(sin2_theta_max))
}

/// Uniform direction in the cone with versine `h = 1 - cos θmax ∈ [0, 2]`.
pub fn sample_uniform_cone_versine(u: Vec2, h: f32) -> Vec3 {
    let t = u.x * h.clamp(0.0, 2.0); // 1 - cos θ
    let sin_theta = safe_sqrt(t * (2.0 - t));
    let phi = TAU * u.y;
    Vec3::new(sin_theta * phi.cos(), sin_theta * phi.sin(), 1.0 - t)
}

/// Pdf of [`sample_uniform_cone_versine`]: `1 / (2π h)`.
pub fn uniform_cone_pdf_versine(h: f32) -> f32 {
    1.0 / (TAU * h.clamp(0.0, 2.0))
}

/// Inverse of [`sample_uniform_cone_versine`].
pub fn invert_uniform_cone_versine(w: Vec3, h: f32) -> Vec2 {
    // 1 - cos θ from x² + y² near +z, where z alone has lost the information.
    let t = if w.z > 0.0 {
        (w.x * w.x + w.y * w.y) / (1.0 + w.z)
    } else {
        1.0 - w.z
    };
    let u0 = if h > 0.0 {
        (t / h).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut phi = w.y.atan2(w.x);
    if phi < 0.0 {
        phi += TAU;
    }
    Vec2::new(u0, (phi / TAU).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::testing::check_grid;

    /// (F(w), φ/2π), with F the analytic CDF of the polar angle, are independent uniforms;
    /// F ≤ 1 means the sample is inside the cone.
    fn check_cone(sample: impl Fn(Vec2) -> Vec3, cdf: impl Fn(Vec3) -> f32, seed: u32) {
        check_grid(200_000, seed, |u| {
            let w = sample(u);
            assert!((w.length() - 1.0).abs() < 1e-5, "{w}");
            let f = cdf(w);
            assert!(f <= 1.0 + 1e-4, "outside the cone: {w}, F = {f}");
            Vec2::new(f, w.y.atan2(w.x).rem_euclid(TAU) / TAU)
        });
    }

    #[test]
    fn wide_cones_are_uniform() {
        for (k, cos_max) in [0.9f32, 0.3, -0.5].into_iter().enumerate() {
            let cdf = |w: Vec3| (1.0 - w.z) / (1.0 - cos_max);
            check_cone(|u| sample_uniform_cone(u, cos_max), cdf, 30 + k as u32);
        }
        let sin2 = 0.36f32; // θmax ≈ 36.9°
        check_cone(
            |u| sample_uniform_cone_sin2(u, sin2),
            |w| (1.0 - w.z) / (1.0 - (1.0 - sin2).sqrt()),
            35,
        );
    }

    #[test]
    fn tiny_cones_are_uniform_and_inside() {
        // sin²θ / sin²θmax is uniform up to O(h) for a tiny cone; it is computed from x, y only.
        let cos_max = 1.0 - 1e-7f32; // rounds to 1 - 2⁻²³
        let h = 1.0 - cos_max;
        check_cone(
            |u| sample_uniform_cone(u, cos_max),
            |w| (w.x * w.x + w.y * w.y) / (h * (2.0 - h)),
            36,
        );
        for (k, sin2) in [1e-12f32, 1e-6, 6e-4].into_iter().enumerate() {
            let cdf = |w: Vec3| (w.x * w.x + w.y * w.y) / sin2;
            check_cone(|u| sample_uniform_cone_sin2(u, sin2), cdf, 37 + k as u32);
            // Solid angle 2π(1 - cos) ≈ π sin² for a tiny cone.
            let omega = 1.0 / uniform_cone_pdf_sin2(sin2);
            let rel = (omega / (std::f32::consts::PI * sin2) - 1.0).abs();
            assert!(rel < sin2 + 1e-6, "{omega}");
        }
    }

    #[test]
    fn pdf_matches_brute_force_solid_angle() {
        // Fraction of uniform sphere directions inside the cone, times 4π, estimates 1/pdf.
        let cos_max = 0.6f32;
        let n = 400_000;
        let mut rng = Rng::new(40, 0, 0);
        let hits = (0..n)
            .filter(|_| crate::sampling::sample_uniform_sphere(rng.next_2d()).z >= cos_max)
            .count();
        let f = hits as f64 / n as f64;
        let sigma = (f * (1.0 - f) / n as f64).sqrt();
        let exact = 1.0 / (uniform_cone_pdf(cos_max) as f64 * 4.0 * std::f64::consts::PI);
        assert!((f - exact).abs() < 5.0 * sigma, "{f} vs {exact}");
    }

    #[test]
    fn cones_round_trip() {
        let mut rng = Rng::new(41, 0, 0);
        for &cos_max in &[0.95f32, 0.0, -0.8, 1.0 - 1e-7] {
            for _ in 0..20_000 {
                let u = rng.next_2d();
                let w = sample_uniform_cone(u, cos_max);
                let b = invert_uniform_cone(w, cos_max);
                assert!((b.x - u.x).abs() < 2e-6, "{u} -> {b} for {cos_max}");
                let dphi = (b.y - u.y).abs();
                assert!(
                    dphi.min(1.0 - dphi) < 2e-6 / u.x.sqrt().max(1e-3),
                    "{u} -> {b}"
                );
                let v = sample_uniform_cone(invert_uniform_cone(w, cos_max), cos_max);
                // x, y relative to the cone's size, so tiny cones are held to the same standard;
                // z = 1 - t may round differently by an ulp.
                let size = (1.0 - cos_max * cos_max).sqrt();
                assert!((v - w).truncate().length() < 4e-6 * size, "{w} -> {v}");
                assert!((v.z - w.z).abs() < 1.2e-7 + 4e-6 * size, "{w} -> {v}");
            }
        }
        for &sin2 in &[0.5f32, 1e-3, 1e-9, 1e-14] {
            for _ in 0..20_000 {
                let u = rng.next_2d();
                let b = invert_uniform_cone_sin2(sample_uniform_cone_sin2(u, sin2), sin2);
                assert!((b.x - u.x).abs() < 2e-6, "{u} -> {b} for {sin2}");
                let dphi = (b.y - u.y).abs();
                assert!(
                    dphi.min(1.0 - dphi) < 2e-6 / u.x.sqrt().max(1e-3),
                    "{u} -> {b}"
                );
            }
        }
    }
}
