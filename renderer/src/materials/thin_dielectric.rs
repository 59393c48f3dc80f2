//! A thin dielectric sheet (a window pane, a soap film), Mitsuba 3's `thindielectric`: two parallel
//! smooth interfaces so close together that a ray leaves where it entered, undeflected.
//!
//! The rule, stated once: with r the Fresnel reflectance of one interface at |cosθ| (the same
//! from either side), the light bouncing between the two faces sums to a reflectance
//! R = r + t²r + t²r³ + … = r + (1−r)²r/(1−r²) = 2r/(1+r) and a transmittance T = 1 − R; the
//! sheet reflects as a mirror with probability R and passes light straight through (wi = −wo,
//! η' = 1) with probability T, from both sides alike. Both lobes are delta: `eval` and `pdf` are
//! 0, so light reaches the far side only by BSDF sampling, as in Mitsuba (whose transmission is a
//! null lobe that still blocks shadow rays in its `path` integrator).
//! WGSL twin: `materials/thin_dielectric.wgsl`.

use super::BsdfSample;
use super::fresnel::fresnel_dielectric;
use glam::{Vec2, Vec3};

/// A thin sheet of index `ior` relative to its surroundings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinDielectric {
    /// Index of refraction of the sheet relative to the outside (> 0; 1 lets everything through).
    pub ior: f32,
}

impl ThinDielectric {
    /// The sheet's reflectance R = 2r/(1+r) seen at `cos_theta` (either sign).
    #[inline]
    pub fn reflectance(&self, cos_theta: f32) -> f32 {
        let r = fresnel_dielectric(cos_theta.abs(), self.ior);
        2.0 * r / (1.0 + r)
    }

    /// Mirror reflection with probability R, else straight through; `u` is unused (both lobes are
    /// delta), kept so that every material samples with the same arguments.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let r = self.reflectance(wo.z);
        let (wi, pdf) = if u_lobe < r {
            (Vec3::new(-wo.x, -wo.y, wo.z), r)
        } else {
            (-wo, 1.0 - r)
        };
        Some(BsdfSample {
            wi,
            weight: Vec3::ONE,
            pdf,
            delta: true,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;
    use crate::rng::Rng;

    /// The closed form against the sum it stands for, bounce by bounce: catches a wrong
    /// inter-reflection factor (e.g. r alone, or r + (1−r)²r without the geometric series).
    #[test]
    fn reflectance_is_the_sum_of_the_bounces_between_the_faces() {
        for ior in [0.7, 1.0, 1.33, 1.5, 2.4] {
            let sheet = ThinDielectric { ior };
            for i in 0..=50 {
                let cos = i as f32 / 50.0;
                let r = fresnel_dielectric(cos, ior) as f64;
                let t = 1.0 - r;
                // R = r + Σₖ t·r^(2k+1)·t, summed until the terms vanish.
                let mut sum = r;
                let mut term = t * r * t;
                for _ in 0..10_000 {
                    sum += term;
                    term *= r * r;
                }
                let closed = sheet.reflectance(cos) as f64;
                assert!(
                    (closed - sum).abs() < 1e-5,
                    "ior {ior} cos {cos}: {closed} vs {sum}"
                );
                assert_eq!(sheet.reflectance(cos), sheet.reflectance(-cos));
            }
        }
    }

    /// Every sample is a mirror or a pass-through with weight 1, chosen with probability R:
    /// the sheet loses no energy, and the reflected fraction converges to R from both sides.
    #[test]
    fn samples_reflect_with_probability_r_and_otherwise_pass_straight_through() {
        let sheet = ThinDielectric { ior: 1.5 };
        let mut rng = Rng::new(7301, 0, 0);
        for wo in [
            Vec3::new(0.3, -0.2, 0.9).normalize(),
            Vec3::new(-0.8, 0.1, -0.3).normalize(),
        ] {
            let n = 100_000;
            let mut reflected = 0;
            for _ in 0..n {
                let s = sheet.sample(wo, rng.next_f32(), Vec2::ZERO).unwrap();
                assert_eq!(s.weight, Vec3::ONE);
                assert!(s.delta && s.eta == 1.0);
                if s.wi == Vec3::new(-wo.x, -wo.y, wo.z) {
                    reflected += 1;
                    assert_eq!(s.pdf, sheet.reflectance(wo.z));
                } else {
                    assert_eq!(s.wi, -wo);
                    assert_eq!(s.pdf, 1.0 - sheet.reflectance(wo.z));
                }
            }
            // Binomial: 5 standard deviations, a false alarm below 1e-6.
            let r = sheet.reflectance(wo.z) as f64;
            let sd = (r * (1.0 - r) / n as f64).sqrt();
            let got = reflected as f64 / n as f64;
            assert!((got - r).abs() < 5.0 * sd, "{wo}: reflected {got}, R = {r}");
        }
    }

    #[test]
    fn passes_the_shared_material_checks_and_conserves_energy() {
        let m = Material::ThinDielectric(ThinDielectric { ior: 1.33 });
        for r in testing::check_material(&m, 330) {
            assert!((r.albedo_mc - 1.0).abs().max_element() < 1e-5, "{r:?}");
        }
    }
}
