//! A dielectric interface (glass, water): smooth, with delta reflection and refraction weighted by
//! the exact Fresnel term, or rough, Walter et al. 2007 with GGX or Beckmann microfacets
//! (isotropic or not), separable Smith masking and visible-normal sampling (pbrt-v4 `DielectricBxDF`, Mitsuba 3 `roughdielectric`).
//!
//! Sides: the outside (index 1) is where the normal +z points, the inside has index `ior`; `wo.z`
//! and `wi.z` may have either sign, so the integrator never flips the frame of a dielectric.
//! Radiance carried through a refraction from index η_i to η_t is scaled by (η_t/η_o)⁻², written
//! here as 1/η'² with η' = η(wi side)/η(wo side) (pbrt-v4's radiance mode): `eval` and the sample
//! weights already hold it, and [`BsdfSample::eta`] reports η' so that Russian roulette can take it
//! out again. Generalised reciprocity is then `f(wo, wi)/η(wo)² = f(wi, wo)/η(wi)²`.
//! WGSL twin: `materials/dielectric.wgsl`.

use super::fresnel::{fresnel_dielectric, fresnel_dielectric_pair};
use super::{BsdfSample, Microfacet};
use crate::math::{reflect, refract};
use glam::{Vec2, Vec3};

/// The largest `ior` a scene may give (diamond is 2.42; beyond 10 a value is a typo).
pub const MAX_IOR: f32 = 10.0;

/// A dielectric boundary between index 1 (outside) and `ior` (inside).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dielectric {
    /// Index of refraction of the inside relative to the outside (> 0, ≠ 1).
    pub ior: f32,
    /// Its microfacets; smooth ([`Microfacet::is_smooth`]): a delta BSDF.
    pub microfacet: Microfacet,
}

/// The microfacet configuration of a direction pair, shared by `eval`, `pdf` and `sample`.
struct Pair {
    /// Generalised half vector (Walter 2007 eq. 16), facing +z.
    wm: Vec3,
    /// wi·wm and wo·wm.
    cos_im: f32,
    cos_om: f32,
    /// (wi·wm + wo·wm/η')², the refraction Jacobian's denominator.
    denom: f32,
    /// True if `wi` is on the side of `wo` (reflection).
    reflect: bool,
    /// η' = η(wi side)/η(wo side); 1 for reflection.
    etap: f32,
    /// Fresnel reflectance at the microfacet.
    f: f32,
}

impl Dielectric {
    /// True for a smooth interface: every sample is a delta sample and `eval` is 0.
    #[inline]
    pub fn is_delta(&self) -> bool {
        self.microfacet.is_smooth()
    }

    /// η' of a transmission that starts on the side of `wo`: ior if `wo` is outside, 1/ior inside.
    #[inline]
    fn transmission_eta(&self, wo: Vec3) -> f32 {
        if wo.z > 0.0 { self.ior } else { 1.0 / self.ior }
    }

    /// The half vector of a valid rough pair, or `None` (grazing, opposite microfacet sides).
    ///
    /// Computed in f64 from η_i·wi + η_o·wo with the exact side indices (1 and `ior`): near
    /// straight-through refraction with an ior close to 1 that sum cancels, and in f32 the two
    /// directions of a pair would then disagree by ~1e-4 (generalised reciprocity is tested to
    /// that). The same sum serves both directions of the pair, so they see the same microfacet.
    fn pair(&self, wo: Vec3, wi: Vec3) -> Option<Pair> {
        if self.is_delta() || wo.z == 0.0 || wi.z == 0.0 {
            return None;
        }
        let reflect = wo.z * wi.z > 0.0;
        let side = |w: Vec3| if w.z > 0.0 { 1.0 } else { self.ior as f64 };
        let (eta_o, eta_i) = if reflect {
            (1.0, 1.0)
        } else {
            (side(wo), side(wi))
        };
        let (wo64, wi64) = (wo.as_dvec3(), wi.as_dvec3());
        let sum = wi64 * eta_i + wo64 * eta_o;
        let len = sum.length();
        if len == 0.0 || !len.is_finite() {
            return None;
        }
        let wm = sum / len;
        let wm = if wm.z < 0.0 { -wm } else { wm };
        // A reflection's wo·wm = wi·wm = |wo + wi|/2, taken from the length: the dots differ by
        // (|wi|² − |wo|²)/|wo + wi|, which unit-rounded inputs make ~1e-4 at back-scattering.
        let (cos_im, cos_om) = if reflect {
            let c = (0.5 * len).copysign(wo.z as f64);
            (c, c)
        } else {
            (wi64.dot(wm), wo64.dot(wm))
        };
        // Both directions must see the microfacet from their own side of the macro surface.
        if cos_im * wi.z as f64 <= 0.0 || cos_om * wo.z as f64 <= 0.0 {
            return None;
        }
        let etap = if reflect {
            1.0
        } else {
            self.transmission_eta(wo)
        };
        let f = if reflect {
            fresnel_dielectric(cos_om as f32, self.ior)
        } else {
            let (c_out, c_in) = if wo.z > 0.0 {
                (cos_om, cos_im)
            } else {
                (cos_im, cos_om)
            };
            fresnel_dielectric_pair(c_out.abs() as f32, c_in.abs() as f32, self.ior)
        };
        Some(Pair {
            wm: wm.as_vec3(),
            cos_im: cos_im as f32,
            cos_om: cos_om as f32,
            // wi·wm + wo·wm/η' = ±|η_i wi + η_o wo|/η_i.
            denom: (len / eta_i).powi(2) as f32,
            reflect,
            etap,
            f,
        })
    }

    /// f·|cosθi| and the pdf of `sample` producing `wi`, from one evaluation of the pair.
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (f32, f32) {
        let Some(p) = self.pair(wo, wi) else {
            return (0.0, 0.0);
        };
        let m = &self.microfacet;
        let d = m.d(p.wm);
        let g = m.g2_separable(wo, wi);
        let (cos_o, cos_im, cos_om) = (wo.z.abs(), p.cos_im, p.cos_om);
        // Visible-normal density of wm seen from wo: G1(wo)·|wo·wm|·D(wm)/|cosθo|.
        let vndf = m.g1(wo) * cos_om.abs() * d / cos_o;
        if p.reflect {
            let f = p.f * d * g / (4.0 * cos_o);
            let pdf = vndf / (4.0 * cos_om.abs()) * p.f;
            (f, pdf)
        } else {
            let denom = p.denom;
            let t = 1.0 - p.f;
            // Walter 2007 eq. 21 times |cosθi|, with the radiance-mode 1/η'².
            let f = t * d * g * (cos_im * cos_om / (cos_o * denom)).abs() / (p.etap * p.etap);
            let pdf = vndf * cos_im.abs() / denom * t;
            (f, pdf)
        }
    }

    /// Samples reflection or refraction by the Fresnel term (at the visible microfacet normal for
    /// a rough interface).
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.is_delta() {
            let r = fresnel_dielectric(wo.z, self.ior);
            if u_lobe < r {
                return Some(BsdfSample {
                    wi: Vec3::new(-wo.x, -wo.y, wo.z),
                    weight: Vec3::ONE,
                    pdf: r,
                    delta: true,
                    eta: 1.0,
                });
            }
            let (wi, etap) = refract(wo, Vec3::Z, self.ior)?;
            return Some(BsdfSample {
                wi,
                weight: Vec3::splat(1.0 / (etap * etap)),
                pdf: 1.0 - r,
                delta: true,
                eta: etap,
            });
        }
        // Microfacet normals face +z; seen from inside, the visible ones are those visible from
        // −wo (D is even in the tangent plane, anisotropic or not), and Fresnel and Snell then
        // see wo·wm < 0, i.e. the index 1/ior.
        let flip = if wo.z < 0.0 { -1.0 } else { 1.0 };
        let wm = self.microfacet.sample_visible_normal(wo * flip, u);
        let r = fresnel_dielectric(wo.dot(wm), self.ior);
        let reflection = u_lobe < r;
        let (wi, eta) = if reflection {
            (reflect(wo, wm).normalize(), 1.0)
        } else {
            let (wi, etap) = refract(wo, wm, self.ior)?;
            (wi.normalize(), etap)
        };
        // pdf and weight from the pair (wo, wi) exactly as `eval_pdf` sees it: the invariants
        // weight = f/pdf and pdf = pdf(wo, wi) then hold to rounding. A refraction that comes
        // out on wo's side (or a reflection that does not) has no valid pair: no sample.
        let (f, pdf) = self.eval_pdf(wo, wi);
        if pdf <= 0.0 || (wi.z * wo.z > 0.0) != reflection {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: Vec3::splat(f / pdf),
            pdf,
            delta: false,
            eta,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;

    const IORS: [f32; 3] = [1.1, 1.5, 2.4];

    fn check(alphas: &[f32]) {
        check_microfacets(
            &alphas
                .iter()
                .map(|&a| Microfacet::ggx(a))
                .collect::<Vec<_>>(),
        );
    }

    fn check_microfacets(microfacets: &[Microfacet]) {
        for &microfacet in microfacets {
            let alpha = (microfacet.alpha_u, microfacet.alpha_v);
            for (i, ior) in IORS.into_iter().enumerate() {
                let d = Dielectric { ior, microfacet };
                for r in testing::check_material(&Material::Dielectric(d), 300 + i as u32) {
                    let side = if r.inside { "inside" } else { "outside" };
                    eprintln!(
                        "dielectric {:?} a={alpha:?} ior={ior} θ={} {side}: energy {:.4} (quadrature {:.4})",
                        microfacet.distribution, r.theta_deg, r.albedo_mc.x, r.albedo_quad.x
                    );
                    if d.is_delta() {
                        // A smooth interface loses nothing: R + T = 1 for every sample.
                        assert!((r.albedo_mc - 1.0).abs().max_element() < 1e-5, "{r:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn dielectric_smooth() {
        check(&[0.0]);
    }

    #[test]
    fn dielectric_narrow() {
        check(&[0.01, 0.05]);
    }

    #[test]
    fn dielectric_medium() {
        check(&[0.1, 0.3]);
    }

    #[test]
    fn dielectric_wide() {
        check(&[0.6, 1.0]);
    }

    #[test]
    fn dielectric_beckmann_and_anisotropic() {
        use super::super::Distribution::{Beckmann, Ggx};
        check_microfacets(&[
            Microfacet::new(Beckmann, 0.05, 0.05),
            Microfacet::new(Beckmann, 0.4, 0.4),
            Microfacet::new(Beckmann, 0.05, 0.5),
            Microfacet::new(Ggx, 0.5, 0.05),
        ]);
    }

    /// A smooth interface: the exact mirror and Snell directions, reflection with probability F,
    /// transmission weights 1/η'², and total internal reflection beyond the critical angle.
    #[test]
    fn smooth_dielectric_directions_and_weights() {
        let d = Dielectric {
            ior: 1.5,
            microfacet: Microfacet::ggx(0.0),
        };
        let m = Material::Dielectric(d);
        assert!(m.is_delta() && m.transmits());
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let r = fresnel_dielectric(0.8, 1.5);
        let s = m.sample(wo, r * 0.5, Vec2::ZERO).unwrap();
        assert!(s.delta && s.wi == Vec3::new(-0.6, 0.0, 0.8) && s.weight == Vec3::ONE);
        assert_eq!((s.pdf, s.eta), (r, 1.0));
        let t = m.sample(wo, r + 0.5 * (1.0 - r), Vec2::ZERO).unwrap();
        assert!(t.delta && t.wi.z < 0.0 && (t.wi.x + 0.6 / 1.5).abs() < 1e-6);
        assert!((t.pdf - (1.0 - r)).abs() < 1e-6 && t.eta == 1.5);
        assert!((t.weight - Vec3::splat(1.0 / 2.25)).abs().max_element() < 1e-6);
        // From inside, the same pair in reverse carries radiance × η'² = 2.25.
        let back = m.sample(t.wi, 0.999, Vec2::ZERO).unwrap();
        assert!((back.wi - wo).length() < 1e-5 && (back.eta - 1.0 / 1.5).abs() < 1e-7);
        assert!((back.weight - Vec3::splat(2.25)).abs().max_element() < 1e-4);
        // 60° inside is beyond the critical angle 41.8°: every sample reflects.
        let inside = Vec3::new(60f32.to_radians().sin(), 0.0, -0.5);
        for u in [0.0, 0.5, 0.999_999_9] {
            let s = m.sample(inside, u, Vec2::ZERO).unwrap();
            assert!(s.wi.z < 0.0 && s.weight == Vec3::ONE && s.pdf == 1.0);
        }
    }
}
