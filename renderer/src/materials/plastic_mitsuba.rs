//! Mitsuba 3's `plastic` and `roughplastic` (3.9.1, `src/bsdfs/plastic.cpp` and
//! `roughplastic.cpp`): the `"model": "mitsuba"` coupling of lumis' plastic ([`super::Plastic`]).
//! In lumis' directions (`wo` towards the viewer, `wi` towards the light, μ = cosθ):
//!
//! f·cosθi = specular·F(wo·h)·D(h)·G1(wo)·G1(wi)/(4 μo)          (a rough coat; none if smooth)
//!         + base·t(μo)·t(μi)/η² · μi/π,   base = albedo/(1 − R·(albedo if nonlinear, else 1))
//!
//! F is the exact dielectric Fresnel of the relative index η. t(μ) is the fraction of light that
//! crosses the coat into the base: 1 − F(μ) for a smooth coat (with a delta mirror of weight
//! specular·F(μo)); for a rough one, Mitsuba's table of ∫(1 − F)·G1 over the visible normals at
//! 64 μ = i/63 (the first 1e-6), read by linear interpolation. R is the coat's internal
//! reflectance seen from the base, which the base's light bounces under until it escapes (the
//! 1/(1 − R·…) series): smooth, Mitsuba's fit of the diffuse Fresnel reflectance at 1/η; rough,
//! 2·mean(r(μ)·μ) over the same 64 μ, r the coat's reflectance from inside. `nonlinear` makes
//! each bounce tint by the albedo (colours darken and saturate, as under varnish).
//!
//! The coat is picked with probability (1 − t(μo))·w / ((1 − t(μo))·w + t(μo)·(1 − w)),
//! w = s̄/(d̄ + s̄), s̄ and d̄ the channel means of the specular tint and the albedo (Mitsuba's
//! texture means); the coat's lobe is sampled by visible normals, the base by the cosine.
//! Two deliberate differences from Mitsuba: Beckmann masking is the exact G1 (lumis' Beckmann,
//! `materials/beckmann.rs`), and the tables integrate lumis' samplers: both move t and R by far
//! less than the z-tests resolve (`tests/mitsuba_xml_refs.rs`, `plastic_mitsuba_tests.rs`).
//! Not energy conserving in general (the diffuse term is Mitsuba's, not reciprocal-normalised);
//! lumis' own coupling is [`super::plastic`].
//! WGSL twin: `materials/plastic_mitsuba.wgsl`.

use super::microfacet::{Distribution, Microfacet};
use super::{BsdfSample, fresnel, ggx};
use crate::math::reflect;
use crate::quadrature::gauss_legendre;
use crate::sampling::sample_cosine_hemisphere;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::f32::consts::FRAC_1_PI;

/// Entries of the rough transmittance table (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const TRANSMITTANCE_SIZE: usize = 64;

/// μ of table entry `i`: i/63, the first raised to 1e-6 (at 0 the direction is in the plane).
fn node_mu(i: usize) -> f32 {
    (i as f32 / (TRANSMITTANCE_SIZE - 1) as f32).max(1e-6)
}

/// Mitsuba's `fresnel_diffuse_reflectance(eta)`: the hemispherical average of the Fresnel
/// reflectance of a dielectric of relative index `eta`, by Egan and Hilgeman's fit (eta < 1)
/// or d'Eon and Irving's (eta ≥ 1); within 0.6% of the integral for the indices of plastics.
pub fn fresnel_diffuse_reflectance(eta: f32) -> f32 {
    let inv = 1.0 / eta;
    if eta < 1.0 {
        0.0636 * inv + eta * (eta * -1.4399 + 0.7099) + 0.6681
    } else {
        // Horner in 1/η of 0.919317 − 3.4793/η + 6.75335/η² − 7.80989/η³ + 4.98554/η⁴ − 1.36881/η⁵.
        let c = [0.919317, -3.4793, 6.75335, -7.80989, 4.98554, -1.36881];
        c.iter().rev().fold(0.0f32, |acc, &k| acc * inv + k)
    }
}

/// Mitsuba's `eval_transmittance` (`transmit`) or `eval_reflectance` of a rough interface of
/// relative index `eta`, seen from direction (√(1 − μ²), 0, μ): the visible-normal average of
/// (1 − F)·G1 of the refracted direction, or of F·G1 of the reflected one, by Mitsuba's
/// Gauss–Legendre rule over the sampler's unit square (32² nodes for η > 1, else 128²).
pub fn rough_interface(mf: &Microfacet, mu: f32, eta: f32, transmit: bool) -> f32 {
    rough_interface_by(&interface_rule(eta), mf, mu, eta, transmit)
}

/// Mitsuba's Gauss–Legendre rule for an interface of relative index `eta`.
fn interface_rule(eta: f32) -> Vec<(f64, f64)> {
    gauss_legendre(if eta > 1.0 { 32 } else { 128 })
}

/// [`rough_interface`] with its rule ([`interface_rule`]) given, built once per table.
fn rough_interface_by(
    rule: &[(f64, f64)],
    mf: &Microfacet,
    mu: f32,
    eta: f32,
    transmit: bool,
) -> f32 {
    let wo = Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    let mut sum = 0.0f64;
    for &(x, wx) in rule {
        for &(y, wy) in rule {
            let u = Vec2::new(0.5 * x as f32 + 0.5, 0.5 * y as f32 + 0.5);
            let m = mf.sample_visible_normal(wo, u);
            let cos = wo.dot(m);
            let f = fresnel::fresnel_dielectric(cos, eta);
            let value = if transmit {
                match crate::math::refract(wo, m, eta) {
                    Some((wt, _)) if wt.z < 0.0 => (1.0 - f) * mf.g1(wt),
                    _ => 0.0,
                }
            } else {
                let wr = reflect(wo, m);
                if wr.z > 0.0 { f * mf.g1(wr) } else { 0.0 }
            };
            sum += value as f64 * wx * wy * 0.25;
        }
    }
    sum as f32
}

/// The coupling's constants: everything but the albedo and tint, which the plastic holds (and a
/// texture may set at each hit).
#[derive(Clone, Debug, PartialEq)]
pub struct MitsubaCoat {
    microfacet: Microfacet,
    eta: f32,
    inv_eta2: f32,
    nonlinear: bool,
    /// t at [`node_mu`] (a rough coat); unused (zero) for a smooth one, whose t is exact.
    transmittance: [f32; TRANSMITTANCE_SIZE],
    internal_reflectance: f32,
    specular_weight: f32,
}

impl MitsubaCoat {
    /// The coat of roughness `alpha` (smooth below [`ggx::SMOOTH_ALPHA`]) of `distribution` and
    /// relative index `eta` over a base of mean albedo `albedo_mean` with tint mean
    /// `specular_mean` (the sampling weight only). A rough coat builds its tables here: 64 μ ×
    /// 32² nodes for t and 64 × 128² for R, on all cores (measured on one: 43 ms for GGX, 227 ms
    /// for Beckmann, whose sampler iterates; release build).
    pub fn new(
        distribution: Distribution,
        alpha: f32,
        eta: f32,
        nonlinear: bool,
        albedo_mean: f32,
        specular_mean: f32,
    ) -> MitsubaCoat {
        let microfacet = Microfacet::new(distribution, alpha, alpha);
        let mut transmittance = [0.0; TRANSMITTANCE_SIZE];
        let internal_reflectance = if microfacet.is_smooth() {
            fresnel_diffuse_reflectance(1.0 / eta)
        } else {
            // Entries in parallel, summed in order: the same R on any number of threads.
            let (outside, inside) = (interface_rule(eta), interface_rule(1.0 / eta));
            let entries: Vec<(f32, f32)> = (0..TRANSMITTANCE_SIZE)
                .into_par_iter()
                .map(|i| {
                    let mu = node_mu(i);
                    let t = rough_interface_by(&outside, &microfacet, mu, eta, true);
                    let r = rough_interface_by(&inside, &microfacet, mu, 1.0 / eta, false);
                    (t, r * mu)
                })
                .collect();
            let mut sum = 0.0f64;
            for (slot, (t, r_mu)) in transmittance.iter_mut().zip(entries) {
                *slot = t;
                sum += r_mu as f64;
            }
            (2.0 * sum / TRANSMITTANCE_SIZE as f64) as f32
        };
        let total = albedo_mean + specular_mean;
        MitsubaCoat {
            microfacet,
            eta,
            inv_eta2: 1.0 / (eta * eta),
            nonlinear,
            transmittance,
            internal_reflectance,
            specular_weight: if total > 0.0 {
                specular_mean / total
            } else {
                0.5
            },
        }
    }

    /// The coat's microfacets (its distribution and α).
    pub fn microfacet(&self) -> Microfacet {
        self.microfacet
    }
    /// Relative index of refraction η.
    pub fn eta(&self) -> f32 {
        self.eta
    }
    /// Whether the internal bounces tint by the albedo.
    pub fn nonlinear(&self) -> bool {
        self.nonlinear
    }
    /// R, the coat's internal reflectance seen from the base.
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }
    /// w, the coat's share of the lobe choice.
    pub fn specular_weight(&self) -> f32 {
        self.specular_weight
    }
    /// The rough table (for upload to the GPU).
    pub fn table(&self) -> &[f32; TRANSMITTANCE_SIZE] {
        &self.transmittance
    }

    fn is_smooth(&self) -> bool {
        self.microfacet.is_smooth()
    }

    /// t(μ): the fraction of light at μ that crosses the coat (exact if smooth, else the table's
    /// linear interpolation at x = 63μ, as Mitsuba's `lerp_gather`).
    pub fn transmittance(&self, mu: f32) -> f32 {
        if self.is_smooth() {
            return 1.0 - fresnel::fresnel_dielectric(mu, self.eta);
        }
        let x = mu.clamp(0.0, 1.0) * (TRANSMITTANCE_SIZE - 1) as f32;
        let i = (x as usize).min(TRANSMITTANCE_SIZE - 2);
        let (a, b) = (self.transmittance[i], self.transmittance[i + 1]);
        a + (x - i as f32) * (b - a)
    }

    /// The base's albedo after the internal bounces: albedo/(1 − R·albedo) if nonlinear, else
    /// albedo/(1 − R).
    pub fn base(&self, albedo: Vec3) -> Vec3 {
        let r = self.internal_reflectance;
        if self.nonlinear {
            albedo / (Vec3::ONE - albedo * r)
        } else {
            albedo / (1.0 - r)
        }
    }

    /// Probability of sampling the coat given t(μo).
    fn specular_probability(&self, t_o: f32) -> f32 {
        let s = (1.0 - t_o) * self.specular_weight;
        let d = t_o * (1.0 - self.specular_weight);
        if d <= 0.0 {
            1.0
        } else if s <= 0.0 {
            0.0
        } else {
            s / (s + d)
        }
    }

    /// f·cosθi and pdf of the non-delta lobes of the plastic with `albedo` and tint `specular`.
    pub fn eval_pdf(&self, albedo: Vec3, specular: Vec3, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let t_o = self.transmittance(wo.z);
        let t_i = self.transmittance(wi.z);
        let p_coat = self.specular_probability(t_o);
        let mut f = self.base(albedo) * (FRAC_1_PI * t_o * t_i * self.inv_eta2 * wi.z);
        let mut pdf = (1.0 - p_coat) * FRAC_1_PI * wi.z;
        if !self.is_smooth() {
            let mf = &self.microfacet;
            let (h, cos_h) = ggx::half_vector(wo, wi);
            let d_g1o = mf.d(h) * mf.g1(wo) / (4.0 * wo.z);
            let fr = fresnel::fresnel_dielectric(cos_h, self.eta);
            f += specular * (fr * d_g1o * mf.g1(wi));
            pdf += p_coat * d_g1o;
        }
        (f * crate::mutants::plastic_eval(), pdf)
    }

    /// Picks the coat or the base (`u_lobe`), then samples the coat by visible normals (or its
    /// mirror direction) or the base by the cosine.
    pub fn sample(
        &self,
        albedo: Vec3,
        specular: Vec3,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let p_coat = self.specular_probability(self.transmittance(wo.z));
        let wi = if u_lobe < p_coat {
            if self.is_smooth() {
                let f = fresnel::fresnel_dielectric(wo.z, self.eta);
                return Some(BsdfSample {
                    wi: Vec3::new(-wo.x, -wo.y, wo.z),
                    weight: specular * (f / p_coat),
                    pdf: p_coat,
                    delta: true,
                    eta: 1.0,
                });
            }
            reflect(wo, self.microfacet.sample_visible_normal(wo, u)).normalize()
        } else {
            sample_cosine_hemisphere(u)
        };
        let (f, pdf) = self.eval_pdf(albedo, specular, wo, wi);
        (pdf > 0.0).then(|| BsdfSample {
            wi,
            weight: f / pdf,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
#[path = "plastic_mitsuba_tests.rs"]
mod tests;
