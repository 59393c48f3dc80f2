//! Lambertian diffuse reflection, sampled by cosine-weighted hemisphere sampling.
//! WGSL twin: `materials/diffuse.wgsl`.

use super::BsdfSample;
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// An ideal diffuse (Lambertian) reflector: f = albedo/π.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diffuse {
    /// Directional-hemispherical reflectance, each channel in [0, 1].
    pub albedo: Vec3,
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
        cosine_hemisphere_pdf(wi.z)
    }

    /// Cosine-weighted sample; the weight f·cos/pdf is exactly the albedo.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = sample_cosine_hemisphere(u);
        // wi.z = 0 only on the disk's rim (u on the square's edge): pdf 0, no sample.
        if wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: self.albedo,
            pdf: FRAC_1_PI * wi.z,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;
    use crate::rng::Rng;

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
