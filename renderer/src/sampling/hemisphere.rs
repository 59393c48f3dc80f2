//! Sampling the +z hemisphere: cosine-weighted (Malley's method) and uniform.
//! WGSL twin: `sampling/hemisphere.wgsl`.

use super::disk::{concentric_polar, invert_uniform_disk_concentric};
use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, TAU};

/// Cosine-weighted direction about +z (pdf `cos θ / π`): a concentric-disk point lifted onto the
/// hemisphere (Malley's method), which keeps the disk map's low distortion.
pub fn sample_cosine_hemisphere(u: Vec2) -> Vec3 {
    let (r, theta) = concentric_polar(u);
    // cos θ = √((1 − |r|)(1 + |r|)) from the radius, not from the rounded disk point: near the
    // horizon 1 − |d|² would amplify the sin/cos rounding by 1/cos θ (and GPU sin/cos are looser).
    let z = safe_sqrt((1.0 - r.abs()) * (1.0 + r.abs()));
    Vec3::new(r * theta.cos(), r * theta.sin(), z)
}

/// Pdf of [`sample_cosine_hemisphere`] with respect to solid angle.
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Inverse of [`sample_cosine_hemisphere`]: projecting to the disk undoes the lift.
pub fn invert_cosine_hemisphere(w: Vec3) -> Vec2 {
    invert_uniform_disk_concentric(Vec2::new(w.x, w.y))
}

/// Uniform direction on the +z hemisphere (pdf `1/2π`): `cos θ = u₀`, `φ = 2π u₁`.
pub fn sample_uniform_hemisphere(u: Vec2) -> Vec3 {
    let z = u.x;
    let r = safe_sqrt((1.0 - z) * (1.0 + z)); // no cancellation near the pole
    let phi = TAU * u.y;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Pdf of [`sample_uniform_hemisphere`] with respect to solid angle.
pub fn uniform_hemisphere_pdf() -> f32 {
    1.0 / TAU
}

/// Inverse of [`sample_uniform_hemisphere`].
pub fn invert_uniform_hemisphere(w: Vec3) -> Vec2 {
    let mut phi = w.y.atan2(w.x);
    if phi < 0.0 {
        phi += TAU;
    }
    Vec2::new(w.z.clamp(0.0, 1.0), (phi / TAU).min(1.0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use crate::sampling::testing::check_grid;
    use std::f32::consts::PI;

    /// A uniform direction on the +z hemisphere by rejection from the cube.
    fn random_hemisphere_dir(rng: &mut Rng) -> Vec3 {
        loop {
            let v = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - Vec3::ONE;
            let l2 = v.length_squared();
            if l2 < 1.0 && l2 > 1e-4 {
                let v = v / l2.sqrt();
                return Vec3::new(v.x, v.y, v.z.abs());
            }
        }
    }

    /// (F(cos θ), φ/2π), with F the analytic CDF of cos θ, are independent uniforms.
    fn check_bins(sample: fn(Vec2) -> Vec3, cdf: fn(f32) -> f32, seed: u32) {
        check_grid(200_000, seed, |u| {
            let w = sample(u);
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0, "{w}");
            Vec2::new(cdf(w.z), w.y.atan2(w.x).rem_euclid(TAU) / TAU)
        });
    }

    #[test]
    fn cosine_hemisphere_matches_its_cdf() {
        // P(cos θ ≤ c) = c² for the cosine distribution.
        check_bins(sample_cosine_hemisphere, |c| c * c, 10);
    }

    #[test]
    fn uniform_hemisphere_matches_its_cdf() {
        check_bins(sample_uniform_hemisphere, |c| c, 11);
    }

    #[test]
    fn pdfs_integrate_test_functions() {
        // E[f/pdf] = ∫ f dω over the hemisphere with f = cos²θ (bounded ratio): 2π/3.
        let n = 200_000;
        let mut rng = Rng::new(12, 0, 0);
        let (mut cos_est, mut uni_est) = (0.0f64, 0.0f64);
        for _ in 0..n {
            let w = sample_cosine_hemisphere(rng.next_2d());
            cos_est += (w.z * w.z / cosine_hemisphere_pdf(w.z)) as f64;
            let w = sample_uniform_hemisphere(rng.next_2d());
            uni_est += (w.z * w.z / uniform_hemisphere_pdf()) as f64;
        }
        let exact = 2.0 * PI as f64 / 3.0;
        // Per-sample std: π·cos has std π/√18 ≈ 0.74; 2π cos² has std ≈ 1.88. 5σ at n = 200k.
        assert!((cos_est / n as f64 - exact).abs() < 5.0 * 0.74 / (n as f64).sqrt());
        assert!((uni_est / n as f64 - exact).abs() < 5.0 * 1.88 / (n as f64).sqrt());
    }

    #[test]
    fn hemispheres_round_trip() {
        let mut rng = Rng::new(13, 0, 0);
        for _ in 0..100_000 {
            let u = rng.next_2d();
            let b = invert_cosine_hemisphere(sample_cosine_hemisphere(u));
            assert!((b - u).abs().max_element() < 2e-6, "{u} -> {b}");
            let b = invert_uniform_hemisphere(sample_uniform_hemisphere(u));
            assert!((b.x - u.x).abs() < 1e-6, "{u} -> {b}");
            // φ is periodic and undefined at the pole; its error grows like ulp / sin θ.
            let dphi = (b.y - u.y).abs();
            let sin_theta = safe_sqrt(1.0 - u.x * u.x).max(1e-3);
            assert!(dphi.min(1.0 - dphi) < 2e-6 / sin_theta, "{u} -> {b}");

            let w = random_hemisphere_dir(&mut rng);
            let v = sample_cosine_hemisphere(invert_cosine_hemisphere(w));
            // z = √(1 - r²) is only good to ~√ε ≈ 3.5e-4 at the horizon.
            assert!((v - w).length() < 5e-4, "{w} -> {v}");
            // u0 = cos θ keeps only ~6e-8 absolute near the pole, so sin θ moves by that / sin θ.
            let v = sample_uniform_hemisphere(invert_uniform_hemisphere(w));
            let sin_theta = (w.x * w.x + w.y * w.y).sqrt();
            assert!((v - w).length() < 2e-6 + 1.2e-7 / sin_theta, "{w} -> {v}");
        }
    }
}
