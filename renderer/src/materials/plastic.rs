//! Plastic: a Lambertian base under a GGX dielectric coat (Schlick Fresnel), energy conserving
//! and reciprocal through a Kelemen / Kulla–Conty coupling (the shape of Mitsuba's roughplastic
//! "rough transmittance" tables):
//!
//! f = f_coat + albedo/π · (1 − E(μo))(1 − E(μi)) / (1 − E_avg)
//!
//! where E(μ) is the coat's directional albedo (tint 1) and E_avg = 2∫E(μ)μ dμ. The diffuse term
//! then reflects exactly albedo·(1 − E(μo)), so the total albedo is specular·E + albedo·(1 − E) ≤ 1
//! (up to the table's accuracy, see [`super::coat_albedo`]), and both terms are symmetric in
//! (wo, wi). Sampling picks the coat with probability ∝ its albedo, clamped to [0.05, 0.95].
//! A smooth coat (α < [`ggx::SMOOTH_ALPHA`]) is a delta mirror with E(μ) = F_schlick(μ) exactly.
//! A textured α keeps this material as it is, with the table at the hit's α blended from tables
//! on a grid of α ([`Plastic::set_alpha_from_grid`], [`super::plastic_textured`]).
//!
//! This is the original program's "Microfacet" material done right: its F0 was not squared and
//! both of its lobes used the full colour, so it reflected more energy than it received.
//!
//! A plastic may instead couple its lobes as Mitsuba 3's `plastic`/`roughplastic` do (exact
//! Fresnel, GGX or Beckmann, internal bounces; [`super::plastic_mitsuba`]): one material with two
//! couplings rather than two materials, because both are the same two lobes with the same
//! parameters (albedo, α, IOR, tint, the same textures but a textured α) that the viewer edits
//! alike, and a scene or the viewer can switch one plastic between them.
//! WGSL twin: `materials/plastic.wgsl` (of lumis' coupling; Mitsuba's has its own twin).

use super::coat_albedo::CoatAlbedo;
use super::microfacet::Distribution;
use super::plastic_mitsuba::MitsubaCoat;
use super::plastic_textured::CoatGrid;
use super::{BsdfSample, fresnel, ggx};
use crate::math::{luminance, reflect};
use crate::sampling::sample_cosine_hemisphere;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// 1/(1 − E_avg) of `coat`, or 0 when it reflects everything (no light reaches the base).
fn diffuse_norm(coat: &CoatAlbedo) -> f32 {
    let e_avg = coat.average();
    if 1.0 - e_avg > 1e-6 {
        1.0 / (1.0 - e_avg)
    } else {
        0.0
    }
}

/// How the base is coupled to the coat.
#[derive(Clone, Debug, PartialEq)]
enum Coupling {
    /// lumis': the coat's E(μ) and E_avg, and 1/(1 − E_avg), or 0 when the coat reflects
    /// everything (no light reaches the base).
    Lumis { coat: CoatAlbedo, diffuse_norm: f32 },
    /// Mitsuba 3's.
    Mitsuba(MitsubaCoat),
}

/// A Lambertian base under a (rough) dielectric coat.
#[derive(Clone, Debug, PartialEq)]
pub struct Plastic {
    albedo: Vec3,
    alpha: f32,
    ior: f32,
    specular: Vec3,
    f0: f32,
    coupling: Coupling,
}

impl Plastic {
    /// A plastic with base `albedo`, coat roughness `alpha` (GGX α), coat IOR `ior` and coat tint
    /// `specular`. Builds the coat's albedo table (≈ 1.3 ms in release).
    pub fn new(albedo: Vec3, alpha: f32, ior: f32, specular: Vec3) -> Plastic {
        let f0 = fresnel::schlick_f0_from_ior(ior);
        let coat = CoatAlbedo::new(alpha, f0);
        Plastic {
            albedo,
            alpha,
            ior,
            specular,
            f0,
            coupling: Coupling::Lumis {
                diffuse_norm: diffuse_norm(&coat),
                coat,
            },
        }
    }

    /// The same plastic coupled as Mitsuba 3's `plastic` (α below [`ggx::SMOOTH_ALPHA`]) or
    /// `roughplastic` with microfacets `distribution`, `nonlinear` or not (see
    /// [`super::plastic_mitsuba`]). Builds its tables for a rough coat.
    pub fn new_mitsuba(
        albedo: Vec3,
        alpha: f32,
        ior: f32,
        specular: Vec3,
        distribution: Distribution,
        nonlinear: bool,
    ) -> Plastic {
        // Mitsuba's sampling weight reads the channel means of the tint and (the mean of) the
        // albedo.
        let mean = |c: Vec3| c.element_sum() / 3.0;
        let coat = MitsubaCoat::new(
            distribution,
            alpha,
            ior,
            nonlinear,
            mean(albedo),
            mean(specular),
        );
        Plastic {
            albedo,
            alpha,
            ior,
            specular,
            f0: fresnel::schlick_f0_from_ior(ior),
            coupling: Coupling::Mitsuba(coat),
        }
    }

    /// Mitsuba's coupling, if this plastic has it.
    pub fn mitsuba_coat(&self) -> Option<&MitsubaCoat> {
        match &self.coupling {
            Coupling::Mitsuba(m) => Some(m),
            Coupling::Lumis { .. } => None,
        }
    }

    /// The coat's microfacet distribution (lumis' coupling: GGX).
    pub fn distribution(&self) -> Distribution {
        self.mitsuba_coat()
            .map_or(Distribution::Ggx, |m| m.microfacet().distribution)
    }

    /// Sets the coat roughness to `alpha` (a texture's value at a hit, clamped to [0, 1]) with
    /// the coat table interpolated from `grid`, built for this plastic's IOR
    /// ([`CoatGrid::coat`]): no table is built here. Eval, sample and pdf all read the one
    /// interpolated table, so they stay consistent with each other.
    /// lumis' coupling only (a Mitsuba plastic has no textured α: the scene refuses it).
    pub fn set_alpha_from_grid(&mut self, alpha: f32, grid: &CoatGrid) {
        debug_assert_eq!(grid.f0(), self.f0, "the grid of another IOR");
        self.alpha = alpha.clamp(0.0, 1.0);
        let coat = grid.coat(self.alpha);
        self.coupling = Coupling::Lumis {
            diffuse_norm: diffuse_norm(&coat),
            coat,
        };
    }

    /// Normal reflectance F0 of the coat (Schlick), from its IOR.
    pub fn f0(&self) -> f32 {
        self.f0
    }

    /// Base albedo.
    pub fn albedo(&self) -> Vec3 {
        self.albedo
    }
    /// Sets the base albedo (a texture's value at a hit); nothing else depends on it.
    pub fn set_albedo(&mut self, albedo: Vec3) {
        self.albedo = albedo;
    }
    /// Coat roughness (GGX α).
    pub fn alpha(&self) -> f32 {
        self.alpha
    }
    /// Coat index of refraction.
    pub fn ior(&self) -> f32 {
        self.ior
    }
    /// Coat tint.
    pub fn specular(&self) -> Vec3 {
        self.specular
    }
    /// lumis' coupling's E(μ) table and E_avg (for upload to the GPU); `None` for Mitsuba's.
    pub fn coat(&self) -> Option<&CoatAlbedo> {
        match &self.coupling {
            Coupling::Lumis { coat, .. } => Some(coat),
            Coupling::Mitsuba(_) => None,
        }
    }

    fn is_smooth(&self) -> bool {
        ggx::is_smooth(self.alpha)
    }

    /// The share of light at μ that the coat keeps from the base: its directional albedo E(μ)
    /// with tint 1 (lumis' coupling), 1 − t(μ) (Mitsuba's).
    #[inline]
    pub fn coat_albedo(&self, mu: f32) -> f32 {
        match &self.coupling {
            Coupling::Lumis { coat, .. } => coat.eval(mu),
            Coupling::Mitsuba(m) => 1.0 - m.transmittance(mu),
        }
    }

    /// True if `eval` can be non-zero: a rough coat, or a base that receives light.
    pub fn has_smooth_part(&self) -> bool {
        let receives = match &self.coupling {
            Coupling::Lumis { diffuse_norm, .. } => *diffuse_norm > 0.0,
            Coupling::Mitsuba(_) => true,
        };
        !self.is_smooth() || (self.albedo.max_element() > 0.0 && receives)
    }

    /// Probability of sampling the coat given E(μo): proportional to each lobe's albedo.
    fn coat_probability(&self, e_o: f32, diffuse_norm: f32) -> f32 {
        let s = (luminance(self.specular) * e_o).max(0.0);
        let d = if diffuse_norm > 0.0 {
            (luminance(self.albedo) * (1.0 - e_o)).max(0.0)
        } else {
            0.0
        };
        if d <= 0.0 {
            1.0
        } else if s <= 0.0 {
            0.0
        } else {
            (s / (s + d)).clamp(0.05, 0.95)
        }
    }

    /// f·cosθi and pdf of the non-delta lobes, computed together so that they always agree.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (coat, diffuse_norm) = match &self.coupling {
            Coupling::Lumis { coat, diffuse_norm } => (coat, *diffuse_norm),
            Coupling::Mitsuba(m) => return m.eval_pdf(self.albedo, self.specular, wo, wi),
        };
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let e_o = coat.eval(wo.z);
        let e_i = coat.eval(wi.z);
        let p_coat = self.coat_probability(e_o, diffuse_norm);
        let k = FRAC_1_PI * (1.0 - e_o) * (1.0 - e_i) * diffuse_norm * wi.z;
        let mut f = self.albedo * k;
        let mut pdf = (1.0 - p_coat) * FRAC_1_PI * wi.z;
        if !self.is_smooth() {
            let a = self.alpha;
            let (h, cos_h) = ggx::half_vector(wo, wi);
            let d_g1o = ggx::d(a, h) * ggx::g1(a, wo) / (4.0 * wo.z);
            let fr = fresnel::fresnel_schlick(self.f0, cos_h);
            f += self.specular * (fr * d_g1o * ggx::g1(a, wi));
            pdf += p_coat * d_g1o;
        }
        (f * crate::mutants::plastic_eval(), pdf)
    }

    /// f·cosθi of the non-delta lobes.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_pdf(wo, wi).0
    }

    /// Mixture pdf of the non-delta lobes (coat VNDF reflection and cosine-weighted base).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf(wo, wi).1
    }

    /// Picks the coat with probability ∝ its albedo (`u_lobe`), then samples it by visible normals
    /// (or its mirror direction) or the base by the cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let (coat, diffuse_norm) = match &self.coupling {
            Coupling::Lumis { coat, diffuse_norm } => (coat, *diffuse_norm),
            Coupling::Mitsuba(m) => return m.sample(self.albedo, self.specular, wo, u_lobe, u),
        };
        if wo.z <= 0.0 {
            return None;
        }
        let p_coat = self.coat_probability(coat.eval(wo.z), diffuse_norm);
        let wi = if u_lobe < p_coat {
            if self.is_smooth() {
                let wi = Vec3::new(-wo.x, -wo.y, wo.z);
                let weight = self.specular * (fresnel::fresnel_schlick(self.f0, wo.z) / p_coat);
                return Some(BsdfSample {
                    wi,
                    weight,
                    pdf: p_coat,
                    delta: true,
                    eta: 1.0,
                });
            }
            reflect(wo, ggx::sample_visible_normal(self.alpha, wo, u)).normalize()
        } else {
            sample_cosine_hemisphere(u)
        };
        let (f, pdf) = self.eval_pdf(wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            weight: f / pdf,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    /// Rough display colour: the base seen through the coat plus the coat at normal incidence.
    pub fn albedo_hint(&self) -> Vec3 {
        let e = self.coat_albedo(1.0);
        self.albedo * (1.0 - e) + self.specular * e
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Material, testing};
    use super::*;
    use crate::materials::coat_albedo::tests::e_reference;
    use glam::DVec3;

    /// Runs the shared checks and compares the albedo with specular·E(μo) + albedo·(1 − E(μo)).
    fn check(albedo: Vec3, specular: Vec3, alphas: &[f32], seed: u32) -> Vec<(f32, f32, DVec3)> {
        let mut out = Vec::new();
        for &alpha in alphas {
            for ior in [1.1, 1.5, 3.0] {
                let p = Plastic::new(albedo, alpha, ior, specular);
                for r in testing::check_material(&Material::Plastic(p.clone()), seed) {
                    let mu = r.theta_deg.to_radians().cos();
                    let (e_true, e_tab) = (e_reference(alpha, p.f0, mu), p.coat_albedo(mu));
                    let expect = (specular * e_true + albedo * (1.0 - e_tab)).as_dvec3();
                    // Quadrature error of the check (2e-3) plus the reference's (1e-4).
                    let tol = 2.1e-3;
                    let d = (r.albedo_quad - expect).abs().max_element();
                    assert!(d < tol, "a {alpha} ior {ior} {r:?}: expected {expect}");
                    eprintln!(
                        "plastic a={alpha} ior={ior} θ={}: albedo {:.4} (±{:.4}), expected {:.4}",
                        r.theta_deg,
                        r.albedo_mc,
                        r.albedo_sigma.max_element(),
                        expect
                    );
                    out.push((alpha, ior, r.albedo_mc));
                }
            }
        }
        out
    }

    const ALPHAS: [f32; 4] = [0.0, 0.05, 0.3, 1.0];

    #[test]
    fn coloured_plastic_smooth_coat() {
        check(
            Vec3::new(0.8, 0.4, 0.1),
            Vec3::new(1.0, 0.9, 0.8),
            &ALPHAS[..1],
            7,
        );
    }

    #[test]
    fn coloured_plastic_rough_coat() {
        check(
            Vec3::new(0.8, 0.4, 0.1),
            Vec3::new(1.0, 0.9, 0.8),
            &ALPHAS[1..],
            8,
        );
    }

    #[test]
    fn white_plastic_preserves_energy() {
        // Albedo 1 and tint 1 reflect E_true + (1 − E_table) = 1 up to the table's error
        // (≤ 4e-4 at these α) and 5σ of Monte Carlo noise.
        for (alpha, ior, a) in check(Vec3::ONE, Vec3::ONE, &ALPHAS, 9) {
            assert!(
                (a - DVec3::ONE).abs().max_element() < 4e-3,
                "a {alpha} ior {ior}: {a}"
            );
        }
    }

    #[test]
    fn diffuse_term_reflects_albedo_times_one_minus_e() {
        // With the coat untinted to zero, only the coupled base remains; it must reflect exactly
        // albedo·(1 − E(μo)), which is what makes E_avg's normalisation right.
        for alpha in [0.0, 0.02, 0.3] {
            let p = Plastic::new(Vec3::splat(0.5), alpha, 1.5, Vec3::ZERO);
            for r in testing::check_material(&Material::Plastic(p.clone()), 3) {
                let e = p.coat_albedo(r.theta_deg.to_radians().cos());
                let expect = 0.5 * (1.0 - e) as f64;
                assert!(
                    (r.albedo_quad.x - expect).abs() < 1e-3,
                    "{alpha} {r:?} vs {expect}"
                );
            }
        }
    }

    #[test]
    fn black_base_under_smooth_coat_is_a_mirror() {
        // A black base under a smooth coat is a pure mirror.
        let m = Material::Plastic(Plastic::new(Vec3::ZERO, 0.0, 1.5, Vec3::ONE));
        assert!(m.is_delta());
        let s = m
            .sample(Vec3::new(0.6, 0.0, 0.8), 0.5, Vec2::splat(0.5))
            .unwrap();
        assert!(
            s.delta
                && s.pdf == 1.0
                && (s.weight.x - fresnel::fresnel_schlick(0.04, 0.8)).abs() < 1e-7
        );
        assert!(Material::Plastic(Plastic::new(Vec3::ZERO, 0.1, 1.5, Vec3::ONE)).has_smooth_part());
    }
}
