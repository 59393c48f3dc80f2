//! Uniform sampling of the unit sphere (Archimedes: z is uniform).
//! WGSL twin: `sampling/sphere.wgsl`.

use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// Uniform direction on the unit sphere (pdf `1/4π`): `z = 1 - 2u₀`, `φ = 2π u₁`.
pub fn sample_uniform_sphere(u: Vec2) -> Vec3 {
    let z = 1.0 - 2.0 * u.x;
    // 1 - z² = 4u₀(1 - u₀): no cancellation near the poles.
    let r = 2.0 * safe_sqrt(u.x * (1.0 - u.x));
    let phi = TAU * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Pdf of [`sample_uniform_sphere`] with respect to solid angle.
pub fn uniform_sphere_pdf() -> f32 {
    1.0 / (4.0 * PI)
}

/// Inverse of [`sample_uniform_sphere`] for a unit vector `w`.
pub fn invert_uniform_sphere(w: Vec3) -> Vec2 {
    // Near the +z pole, (1 - z)/2 has lost the sample's low bits; x² + y² still has them.
    let u0 = if w.z > 0.0 {
        (w.x * w.x + w.y * w.y) / (2.0 * (1.0 + w.z))
    } else {
        0.5 * (1.0 - w.z)
    };
    let mut phi = w.y.atan2(w.x);
    if phi < 0.0 {
        phi += TAU;
    }
    Vec2::new(u0.clamp(0.0, 1.0), (phi / TAU).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::testing::check_grid;

    #[test]
    fn sphere_matches_its_cdf() {
        // (1 - z)/2 and φ/2π are independent uniforms for uniform directions.
        check_grid(200_000, 20, |u| {
            let w = sample_uniform_sphere(u);
            assert!((w.length() - 1.0).abs() < 1e-5, "{w}");
            Vec2::new(0.5 * (1.0 - w.z), w.y.atan2(w.x).rem_euclid(TAU) / TAU)
        });
        let n = 200_000;
        let mut rng = Rng::new(22, 0, 0);
        let sum_z2: f64 = (0..n)
            .map(|_| sample_uniform_sphere(rng.next_2d()).z.powi(2) as f64)
            .sum();
        // ∫ z² dω · pdf = 1/3; z² has std √(4/45) ≈ 0.30, 5σ.
        assert!((sum_z2 / n as f64 - 1.0 / 3.0).abs() < 5.0 * 0.30 / (n as f64).sqrt());
        // The pdf is the reciprocal of the sphere's area.
        assert!((uniform_sphere_pdf() * 4.0 * PI - 1.0).abs() < 1e-6);
    }

    #[test]
    fn sphere_round_trips() {
        let mut rng = Rng::new(21, 0, 0);
        for i in 0..100_000 {
            let u = if i == 0 {
                Vec2::new(1e-7, 0.3)
            } else {
                rng.next_2d()
            };
            let b = invert_uniform_sphere(sample_uniform_sphere(u));
            // u₀ is recovered to a few ulps relative near both poles.
            assert!(
                (b.x - u.x).abs() < 2e-6 * u.x.min(1.0 - u.x).max(0.05),
                "{u} -> {b}"
            );
            let sin_theta = 2.0 * (u.x * (1.0 - u.x)).sqrt();
            let dphi = (b.y - u.y).abs();
            assert!(
                dphi.min(1.0 - dphi) < 2e-6 / sin_theta.max(1e-3),
                "{u} -> {b}"
            );

            let w = sample_uniform_sphere(rng.next_2d());
            let v = sample_uniform_sphere(invert_uniform_sphere(w));
            assert!((v - w).length() < 2e-6, "{w} -> {v}");
        }
    }
}
