//! Microfacet conductor (metal), GGX or Beckmann, isotropic or not:
//! f = F(wo·h)·D(h)·G1(wo)G1(wi)/(4 cosθo cosθi), sampled by visible normals; a perfect mirror
//! below [`ggx::SMOOTH_ALPHA`] (Mitsuba's `roughconductor` and `conductor`).
//! WGSL twin: `materials/conductor.wgsl`.

#[cfg(test)]
use super::ggx;
use super::{BsdfSample, Microfacet, fresnel};
use crate::math::reflect;
use glam::{Vec2, Vec3};

/// How a conductor's Fresnel reflectance is specified.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConductorFresnel {
    /// Exact Fresnel of a complex IOR η + ik per RGB channel, times a tint (Mitsuba's
    /// `specular_reflectance`; 1 for a physical metal).
    Complex {
        /// Real part of the IOR.
        eta: Vec3,
        /// Extinction coefficient.
        k: Vec3,
        /// Factor on the Fresnel term, each channel in [0, 1].
        tint: Vec3,
    },
    /// Fresnel = 1 times a constant reflectance (an artist's tint).
    Tint(Vec3),
}

impl ConductorFresnel {
    /// Reflectance at incidence cosine `cos` (with the microfacet normal).
    #[inline]
    pub fn eval(&self, cos: f32) -> Vec3 {
        match *self {
            // × 1 is exact: an untinted metal's Fresnel is bit for bit the untinted formula.
            ConductorFresnel::Complex { eta, k, tint } => {
                fresnel::fresnel_conductor(cos, eta, k) * tint
            }
            ConductorFresnel::Tint(r) => r,
        }
    }
}

/// A microfacet conductor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conductor {
    /// Its microfacets; smooth ([`Microfacet::is_smooth`]): a perfect mirror.
    pub microfacet: Microfacet,
    /// Fresnel reflectance.
    pub fresnel: ConductorFresnel,
}

impl Conductor {
    /// True for a perfect mirror.
    #[inline]
    pub fn is_delta(&self) -> bool {
        self.microfacet.is_smooth()
    }

    /// Reflectance at normal incidence (for display).
    pub fn normal_reflectance(&self) -> Vec3 {
        self.fresnel.eval(1.0)
    }

    /// The half vector of a valid reflection pair and wo·h, or `None`.
    #[inline]
    fn half_vector(&self, wo: Vec3, wi: Vec3) -> Option<(Vec3, f32)> {
        if self.is_delta() || wo.z <= 0.0 || wi.z <= 0.0 {
            return None;
        }
        // Both in the upper hemisphere, so wo + wi is never zero.
        Some(super::ggx::half_vector(wo, wi))
    }

    /// f·cosθi = F·D·G1(wo)G1(wi)/(4 cosθo) (the cosθi cancels).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let Some((h, cos_h)) = self.half_vector(wo, wi) else {
            return Vec3::ZERO;
        };
        let m = &self.microfacet;
        let s = m.d(h) * m.g2_separable(wo, wi) / (4.0 * wo.z);
        self.fresnel.eval(cos_h) * s
    }

    /// VNDF pdf / (4 wo·h) = G1(wo)·D(h)/(4 cosθo).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some((h, _)) = self.half_vector(wo, wi) else {
            return 0.0;
        };
        self.microfacet.g1(wo) * self.microfacet.d(h) / (4.0 * wo.z)
    }

    /// Mirror (delta) or visible-normal sample.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        if self.is_delta() {
            let wi = Vec3::new(-wo.x, -wo.y, wo.z);
            let weight = self.fresnel.eval(wo.z);
            return Some(BsdfSample {
                wi,
                weight,
                pdf: 1.0,
                delta: true,
                eta: 1.0,
            });
        }
        let m = &self.microfacet;
        let h = m.sample_visible_normal(wo, u);
        let wi = reflect(wo, h).normalize();
        // pdf and weight from the half vector of (wo, wi), exactly as `pdf`/`eval` see it, so the
        // invariants hold to rounding even where D is steep. f·cos/pdf simplifies to F·G1(wi).
        let (h, cos_h) = self.half_vector(wo, wi)?;
        let pdf = m.g1(wo) * m.d(h) / (4.0 * wo.z);
        let weight = self.fresnel.eval(cos_h) * m.g1(wi);
        Some(BsdfSample {
            wi,
            weight,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;

    fn fresnels() -> [ConductorFresnel; 3] {
        [
            // Gold-like complex IOR and a coloured tint.
            ConductorFresnel::Complex {
                eta: Vec3::new(0.143, 0.374, 1.442),
                k: Vec3::new(3.983, 2.385, 1.603),
                tint: Vec3::ONE,
            },
            ConductorFresnel::Tint(Vec3::new(0.95, 0.64, 0.54)),
            ConductorFresnel::Complex {
                eta: Vec3::new(0.2, 0.92, 1.1),
                k: Vec3::new(3.9, 2.45, 2.14),
                tint: Vec3::new(0.9, 0.6, 0.3),
            },
        ]
    }

    /// The tint multiplies the complex Fresnel, and nothing else: eval and sample weights scale
    /// by it, pdf and directions stay (Mitsuba's `specular_reflectance` on a conductor).
    #[test]
    fn a_tint_scales_the_complex_fresnel() {
        let [plain, _, _] = fresnels();
        let ConductorFresnel::Complex { eta, k, .. } = plain else {
            unreachable!()
        };
        let tint = Vec3::new(0.9, 0.6, 0.3);
        let tinted = ConductorFresnel::Complex { eta, k, tint };
        let mf = Microfacet::ggx(0.3);
        let (a, b) = (
            Conductor {
                microfacet: mf,
                fresnel: plain,
            },
            Conductor {
                microfacet: mf,
                fresnel: tinted,
            },
        );
        let (wo, wi) = (
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(-0.3, 0.4, 0.866).normalize(),
        );
        // Equal up to the order of the products (an ulp).
        let (fa, fb) = (a.eval(wo, wi), b.eval(wo, wi));
        assert!(
            ((fb - fa * tint) / fb).abs().max_element() < 1e-6,
            "{fb} vs {fa}"
        );
        assert_eq!(b.pdf(wo, wi), a.pdf(wo, wi));
        let u = Vec2::new(0.3, 0.7);
        let (sa, sb) = (a.sample(wo, u).unwrap(), b.sample(wo, u).unwrap());
        assert_eq!((sb.wi, sb.pdf), (sa.wi, sa.pdf));
        assert!((sb.weight - sa.weight * tint).abs().max_element() < 1e-6);
    }

    fn check(microfacets: &[Microfacet]) {
        for &microfacet in microfacets {
            for (i, fresnel) in fresnels().into_iter().enumerate() {
                let c = Conductor {
                    microfacet,
                    fresnel,
                };
                let reports = testing::check_material(&Material::Conductor(c), 100 + i as u32);
                for r in &reports {
                    let cos = r.theta_deg.to_radians().cos();
                    if c.is_delta() {
                        // A mirror reflects exactly F(cosθo), every sample.
                        let f = c.fresnel.eval(cos).as_dvec3();
                        assert!((r.albedo_mc - f).abs().max_element() < 1e-6, "{r:?}");
                    } else {
                        // Never more than the Fresnel maximum (≤ 1): microfacets only lose energy.
                        assert!(r.albedo_quad.max_element() <= 1.0 + 2e-3, "{r:?}");
                    }
                    eprintln!(
                        "conductor {microfacet:?} F#{i} θ={}: albedo {:.4}",
                        r.theta_deg, r.albedo_mc
                    );
                }
            }
        }
    }

    fn ggx(alphas: &[f32]) -> Vec<Microfacet> {
        alphas.iter().map(|&a| Microfacet::ggx(a)).collect()
    }

    #[test]
    fn conductor_smooth() {
        check(&ggx(&[0.0, 0.0005]));
    }

    #[test]
    fn conductor_narrow() {
        check(&ggx(&[0.01, 0.1]));
    }

    #[test]
    fn conductor_wide() {
        check(&ggx(&[0.5, 1.0]));
    }

    #[test]
    fn conductor_beckmann() {
        use super::super::Distribution::Beckmann;
        check(&[
            Microfacet::new(Beckmann, 0.0, 0.0),
            Microfacet::new(Beckmann, 0.05, 0.05),
            Microfacet::new(Beckmann, 0.5, 0.5),
        ]);
    }

    #[test]
    fn conductor_anisotropic() {
        use super::super::Distribution::{Beckmann, Ggx};
        // 1:10 and 10:1; the checks view along x, so both orientations matter.
        check(&[
            Microfacet::new(Ggx, 0.05, 0.5),
            Microfacet::new(Beckmann, 0.5, 0.05),
        ]);
    }

    #[test]
    fn smooth_alpha_is_still_a_consistent_lobe() {
        // The narrowest non-delta lobe: D peaks at 1/(πα²) ≈ 3e5, still within f32 comfort.
        for fresnel in fresnels() {
            testing::check_material(
                &Material::Conductor(Conductor {
                    microfacet: Microfacet::ggx(ggx::SMOOTH_ALPHA),
                    fresnel,
                }),
                5,
            );
        }
    }

    #[test]
    fn smooth_threshold() {
        assert!(
            Conductor {
                microfacet: Microfacet::ggx(0.0),
                fresnel: fresnels()[1]
            }
            .is_delta()
        );
        assert!(
            Conductor {
                microfacet: Microfacet::ggx(0.0005),
                fresnel: fresnels()[1]
            }
            .is_delta()
        );
        assert!(
            !Conductor {
                microfacet: Microfacet::ggx(ggx::SMOOTH_ALPHA),
                fresnel: fresnels()[1]
            }
            .is_delta()
        );
        let m = Material::Conductor(Conductor {
            microfacet: Microfacet::ggx(0.0),
            fresnel: fresnels()[0],
        });
        assert!(m.is_delta() && !m.has_smooth_part());
        assert_eq!(
            m.eval(Vec3::new(-0.6, 0.0, 0.8), Vec3::new(0.6, 0.0, 0.8)),
            Vec3::ZERO
        );
    }
}
