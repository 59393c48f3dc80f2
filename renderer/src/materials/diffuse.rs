//! Lambertian diffuse reflection, sampled by cosine-weighted hemisphere sampling.

use super::BsdfSample;
use crate::math::safe_sqrt;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4};

/// An ideal diffuse (Lambertian) reflector: f = albedo/π.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    /// Directional-hemispherical reflectance, each channel in [0, 1].
    pub albedo: Vec3,
}

/// Shirley–Chiu concentric square-to-disk map (keeps strata compact and the warp continuous).
// Private copy; `crate::sampling` will own it once both land (the same warp, deduplicated later).
#[inline]
pub(crate) fn concentric_disk(u: Vec2) -> Vec2 {
    let o = 2.0 * u - Vec2::ONE;
    if o.x == 0.0 && o.y == 0.0 {
        return Vec2::ZERO;
    }
    let (r, theta) = if o.x.abs() > o.y.abs() {
        (o.x, FRAC_PI_4 * (o.y / o.x))
    } else {
        (o.y, FRAC_PI_2 - FRAC_PI_4 * (o.x / o.y))
    };
    let (s, c) = theta.sin_cos();
    r * Vec2::new(c, s)
}

/// Cosine-weighted direction on the +z hemisphere (Malley's method); pdf = cosθ/π.
#[inline]
pub(crate) fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = concentric_disk(u);
    Vec3::new(d.x, d.y, safe_sqrt(1.0 - d.length_squared()))
}

impl Diffuse {
    /// f·cosθi.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.albedo * (FRAC_1_PI * wi.z)
    }

    /// cosθi/π on the upper hemisphere.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        FRAC_1_PI * wi.z
    }

    /// Cosine-weighted sample; the weight f·cos/pdf is exactly the albedo.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine_hemisphere(u);
        // wi.z = 0 only on the disk's rim (u on the square's edge): pdf 0, no sample.
        if wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: self.albedo,
            pdf: FRAC_1_PI * wi.z,
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn cosine_warp_moments() {
        // E[z] = 2/3, E[z²] = 1/2, E[x] = E[y] = 0 under pdf cosθ/π.
        let mut rng = Rng::new(3, 1, 4);
        let n = 200_000;
        let mut m = [0.0f64; 4];
        for _ in 0..n {
            let w = cosine_hemisphere(rng.next_2d());
            assert!((w.length() - 1.0).abs() < 1e-5 && w.z >= 0.0);
            for (acc, v) in m.iter_mut().zip([w.x, w.y, w.z, w.z * w.z]) {
                *acc += v as f64 / n as f64;
            }
        }
        // Each mean has σ ≤ 1/√n ≈ 2.2e-3 at most (≈1e-3 in practice); 5e-3 is ≥ 2σ-safe.
        for (got, want) in m.iter().zip([0.0, 0.0, 2.0 / 3.0, 0.5]) {
            assert!((got - want).abs() < 5e-3, "{m:?}");
        }
    }

    #[test]
    fn diffuse_passes_material_checks() {
        let m = Material::Diffuse(Diffuse {
            albedo: Vec3::new(0.8, 0.5, 0.2),
        });
        for r in testing::check_material(&m, 1) {
            // pdf integrates to exactly 1 (quadrature error ~1e-5) and reflects the albedo.
            assert!((r.pdf_integral - 1.0).abs() < 1e-3, "{r:?}");
            assert!(
                (r.albedo_mc - glam::DVec3::new(0.8, 0.5, 0.2))
                    .abs()
                    .max_element()
                    < 1e-5,
                "{r:?}"
            );
        }
    }

    #[test]
    fn white_diffuse_albedo_is_exactly_one() {
        let m = Material::Diffuse(Diffuse { albedo: Vec3::ONE });
        let mut rng = Rng::new(9, 9, 9);
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let n = 100_000;
        let mut sum = Vec3::ZERO.as_dvec3();
        for _ in 0..n {
            if let Some(s) = m.sample(wo, rng.next_f32(), rng.next_2d()) {
                sum += s.weight.as_dvec3();
            }
        }
        assert_eq!(sum / n as f64, glam::DVec3::ONE);
    }
}
