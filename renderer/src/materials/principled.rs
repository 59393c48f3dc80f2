//! Mitsuba 3.9.1's `principled` BSDF (`src/bsdfs/principled.cpp`), term for term: Burley's
//! Disney BSDF (2012, 2015) as Mitsuba writes it. Lobes: a diffuse base with retro-reflection and
//! the "flatness" fake subsurface, sheen, a GGX main specular lobe whose Fresnel term blends the
//! dielectric's with Schlick terms for metal and tint, a GGX specular transmission, and a GTR1
//! clearcoat ([`super::gtr1`]). Each is weighted as Mitsuba weighs it (brdf = (1 − metallic)(1 −
//! spec_trans), bsdf = (1 − metallic) spec_trans); one lobe is sampled with Mitsuba's
//! probabilities and the sample's pdf is the whole mixture's, so weight = eval/pdf.
//!
//! Sides: the front (+z) is outside; a principled with specular transmission (`transmission`,
//! Mitsuba's `m_has_spec_trans`) also sees its back side as the inside of a dielectric of index
//! `eta` (only the main specular reflection and transmission act there, weighted by the
//! dielectric Fresnel term alone), and transmits ([`super::Material::transmits`]). Without it the
//! back side is black, as every one-sided Mitsuba BSDF.
//!
//! Mitsuba's "has" flags (a parameter given, and not as the number 0) reduce to the values here:
//! every lobe they switch off has a factor that is then 0, except `spec_trans`, whose flag also
//! decides the sides and is kept as `transmission`. Mitsuba's JIT variants (with which the
//! references are rendered) evaluate sheen wherever `sheen_active` holds, even where the diffuse
//! lobe is off (brdf = 0); its scalar variant skips it there. lumis follows the JIT variants.
//! WGSL twin: `materials/principled.wgsl`.

use super::fresnel::{
    fresnel_dielectric, fresnel_dielectric_pair, fresnel_schlick_rgb, schlick_f0_from_ior,
};
use super::{BsdfSample, Distribution, Microfacet, gtr1};
use crate::math::{reflect, refract, safe_sqrt};
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use crate::textures::luminance;
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// The rates that weigh each lobe's selection in sampling (Mitsuba's `*_sampling_rate`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplingRates {
    /// Main specular reflection and transmission (`main_specular_sampling_rate`, default 1).
    pub specular: f32,
    /// Clearcoat (`clearcoat_sampling_rate`, default 1).
    pub clearcoat: f32,
    /// Diffuse (`diffuse_reflectance_sampling_rate`, default 1).
    pub diffuse: f32,
}

impl Default for SamplingRates {
    fn default() -> Self {
        SamplingRates {
            specular: 1.0,
            clearcoat: 1.0,
            diffuse: 1.0,
        }
    }
}

/// Mitsuba's principled BSDF at one point: every parameter in [0, 1] except `eta` (> 0) and the
/// sampling rates (≥ 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Principled {
    /// The colour of the diffuse lobe, the metal's F0, the tints' hue.
    pub base_color: Vec3,
    /// Drives the GGX α (roughness², at least 0.001) and the diffuse retro-reflection.
    pub roughness: f32,
    /// Stretches α along the first tangent, shrinks it along the second.
    pub anisotropic: f32,
    /// Blend from the dielectric lobes to a Schlick metal of F0 `base_color`.
    pub metallic: f32,
    /// Share of the dielectric part that transmits.
    pub spec_trans: f32,
    /// Interior index over exterior (Mitsuba's `eta`, or from `specular`).
    pub eta: f32,
    /// Share of the dielectric reflection tinted towards the base colour.
    pub spec_tint: f32,
    /// Weight of the grazing sheen lobe.
    pub sheen: f32,
    /// Share of the sheen tinted towards the base colour.
    pub sheen_tint: f32,
    /// Blend from the diffuse lobe to the fake subsurface one.
    pub flatness: f32,
    /// Weight of the GTR1 clearcoat lobe.
    pub clearcoat: f32,
    /// The clearcoat's gloss: its α runs from 0.1 (0) to 0.001 (1).
    pub clearcoat_gloss: f32,
    /// How often each lobe is sampled.
    pub rates: SamplingRates,
    /// Mitsuba's `m_has_spec_trans`: the back side is the inside, and light passes through.
    pub transmission: bool,
}

/// The texturable scalar parameters, in the order of their texture slots (CPU and GPU), each the
/// [`Principled`] field of its name.
#[allow(missing_docs)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrincipledParam {
    Roughness,
    Anisotropic,
    Metallic,
    SpecTrans,
    SpecTint,
    Sheen,
    SheenTint,
    Flatness,
    Clearcoat,
    ClearcoatGloss,
}

impl PrincipledParam {
    /// Every one, in slot order.
    pub const ALL: [PrincipledParam; 10] = [
        PrincipledParam::Roughness,
        PrincipledParam::Anisotropic,
        PrincipledParam::Metallic,
        PrincipledParam::SpecTrans,
        PrincipledParam::SpecTint,
        PrincipledParam::Sheen,
        PrincipledParam::SheenTint,
        PrincipledParam::Flatness,
        PrincipledParam::Clearcoat,
        PrincipledParam::ClearcoatGloss,
    ];

    /// Its key in both scene formats (lumis' and Mitsuba's spell them alike).
    pub fn name(self) -> &'static str {
        match self {
            PrincipledParam::Roughness => "roughness",
            PrincipledParam::Anisotropic => "anisotropic",
            PrincipledParam::Metallic => "metallic",
            PrincipledParam::SpecTrans => "spec_trans",
            PrincipledParam::SpecTint => "spec_tint",
            PrincipledParam::Sheen => "sheen",
            PrincipledParam::SheenTint => "sheen_tint",
            PrincipledParam::Flatness => "flatness",
            PrincipledParam::Clearcoat => "clearcoat",
            PrincipledParam::ClearcoatGloss => "clearcoat_gloss",
        }
    }

    /// Its value in `p`.
    pub fn get(self, p: &Principled) -> f32 {
        *self.field(&mut p.clone())
    }

    /// Sets it in `p`.
    pub fn set(self, p: &mut Principled, value: f32) {
        *self.field(p) = value;
    }

    fn field(self, p: &mut Principled) -> &mut f32 {
        match self {
            PrincipledParam::Roughness => &mut p.roughness,
            PrincipledParam::Anisotropic => &mut p.anisotropic,
            PrincipledParam::Metallic => &mut p.metallic,
            PrincipledParam::SpecTrans => &mut p.spec_trans,
            PrincipledParam::SpecTint => &mut p.spec_tint,
            PrincipledParam::Sheen => &mut p.sheen,
            PrincipledParam::SheenTint => &mut p.sheen_tint,
            PrincipledParam::Flatness => &mut p.flatness,
            PrincipledParam::Clearcoat => &mut p.clearcoat,
            PrincipledParam::ClearcoatGloss => &mut p.clearcoat_gloss,
        }
    }
}

impl Default for Principled {
    /// Mitsuba's defaults: base colour 0.5, roughness 0.5, specular 0.5 (η = 1.5), the rest 0.
    fn default() -> Self {
        Principled {
            base_color: Vec3::splat(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            metallic: 0.0,
            spec_trans: 0.0,
            eta: eta_from_specular(0.5),
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            clearcoat: 0.0,
            clearcoat_gloss: 0.0,
            rates: SamplingRates::default(),
            transmission: false,
        }
    }
}

/// The index of refraction whose normal-incidence reflectance is 0.08·`specular` (Burley's
/// "specular" parameter): 2/(1 − √(0.08 s)) − 1.
pub fn eta_from_specular(specular: f32) -> f32 {
    2.0 / (1.0 - (0.08 * specular).sqrt()) - 1.0
}

/// The η of a principled given `eta` or `specular` (at most one; neither: specular 0.5), as
/// Mitsuba's constructor sets it: with specular transmission, η = 1 becomes 1.001 and specular 0
/// becomes 1e-3 (no refraction at index 1).
pub fn mitsuba_eta(eta: Option<f32>, specular: Option<f32>, transmission: bool) -> f32 {
    match eta {
        Some(e) if transmission && e == 1.0 => 1.001,
        Some(e) => e,
        None => {
            let s = specular.unwrap_or(0.5);
            eta_from_specular(if transmission && s == 0.0 { 1e-3 } else { s })
        }
    }
}

/// Schlick's weight (1 − cos)⁵, the argument clamped to [0, 1].
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Mitsuba's `calc_schlick`: Schlick's approximation with F0 `r0`, at the cosine of the incident
/// side when that side has the lower index, else at the cosine of the transmitted direction (1 at
/// total internal reflection).
pub(super) fn calc_schlick(r0: Vec3, cos_i: f32, eta: f32) -> Vec3 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    let eta_ti = 1.0 / eta_it;
    let cos_t = safe_sqrt(1.0 - (1.0 - cos_i * cos_i) * eta_ti * eta_ti);
    fresnel_schlick_rgb(r0, if eta_it > 1.0 { cos_i.abs() } else { cos_t })
}

/// Mitsuba's `calc_dist_params`: GGX with α = max(0.001, roughness²), stretched by the aspect
/// √(1 − 0.9·anisotropic) (α_u = α/aspect, α_v = α·aspect, each at least 0.001).
pub(super) fn microfacet(roughness: f32, anisotropic: f32) -> Microfacet {
    let r2 = roughness * roughness;
    let aspect = (1.0 - 0.9 * anisotropic).sqrt();
    Microfacet {
        distribution: Distribution::Ggx,
        alpha_u: (r2 / aspect).max(0.001),
        alpha_v: (r2 * aspect).max(0.001),
    }
}

/// `base` over its luminance (a hue of luminance 1), or white for black.
pub(super) fn tint(base: Vec3) -> Vec3 {
    let lum = luminance(base);
    if lum > 0.0 { base / lum } else { Vec3::ONE }
}

/// The lobes' selection probabilities, normalised, at a Fresnel term `f` of the main lobe.
#[derive(Clone, Copy, Debug)]
struct LobeProbabilities {
    diffuse: f32,
    clearcoat: f32,
    transmission: f32,
    reflection: f32,
}

/// A direction pair's microfacet configuration (Mitsuba's eval and pdf preamble).
struct Pair {
    /// The (generalised) half vector, facing +z.
    wh: Vec3,
    reflect: bool,
    refract: bool,
    /// wo·wh.
    cos_oh: f32,
    /// Dielectric Fresnel term at wo·wh.
    f: f32,
    /// Both directions see `wh` from the side a reflection (or refraction) needs.
    reflect_ok: bool,
    refract_ok: bool,
    /// η of the path: η seen from outside, 1/η from inside.
    eta_path: f32,
}

impl Principled {
    /// The weights of the reflection-only and the transmitting dielectric parts.
    fn brdf_bsdf(&self) -> (f32, f32) {
        let dielectric = 1.0 - self.metallic;
        (
            dielectric * (1.0 - self.spec_trans),
            dielectric * self.spec_trans,
        )
    }

    /// The main lobes' GGX microfacets ([`microfacet`]).
    pub fn microfacet(&self) -> Microfacet {
        microfacet(self.roughness, self.anisotropic)
    }

    /// True if the main lobes' α_u ≠ α_v.
    pub fn is_anisotropic(&self) -> bool {
        let m = self.microfacet();
        m.alpha_u != m.alpha_v
    }

    fn probabilities(&self, front: bool, f: f32) -> LobeProbabilities {
        let (brdf, bsdf) = self.brdf_bsdf();
        let bsdf = if self.transmission { bsdf } else { 0.0 };
        let r = &self.rates;
        let (reflection, transmission, clearcoat, diffuse) = if front {
            (
                r.specular * (1.0 - bsdf * (1.0 - f)),
                r.specular * bsdf * (1.0 - f),
                0.25 * self.clearcoat * r.clearcoat,
                brdf * r.diffuse,
            )
        } else {
            let t = if self.transmission { 1.0 - f } else { 0.0 };
            (f, t, 0.0, 0.0)
        };
        let norm = 1.0 / (reflection + transmission + clearcoat + diffuse);
        LobeProbabilities {
            diffuse: diffuse * norm,
            clearcoat: clearcoat * norm,
            transmission: transmission * norm,
            reflection: reflection * norm,
        }
    }

    fn pair(&self, wo: Vec3, wi: Vec3) -> Option<Pair> {
        let front = wo.z > 0.0;
        let eta_path = if front { self.eta } else { 1.0 / self.eta };
        let reflect = wo.z * wi.z > 0.0;
        let refract = wo.z * wi.z < 0.0;
        // Mitsuba's wo + η_path·wi, written as η(wo side)·wo + η(wi side)·wi (the same
        // direction) in f64, like the dielectric's: the two directions of a pair then see the
        // same microfacet bit for bit, which reciprocity needs in the far tail of a refraction,
        // where the sum nearly cancels in z.
        let side = |w: Vec3| {
            if reflect || w.z > 0.0 {
                1.0
            } else {
                self.eta as f64
            }
        };
        let sum = wo.as_dvec3() * side(wo) + wi.as_dvec3() * side(wi);
        let len = sum.length();
        let wh = (sum / len).as_vec3();
        if !wh.is_finite() {
            return None;
        }
        let wh = if wh.z < 0.0 { -wh } else { wh };
        // A reflection's wo·wh = wi·wh = |wo + wi|/2 exactly, taken from the length so that
        // both directions of the pair see the same Fresnel term (as the dielectric's).
        let cos_oh = if reflect {
            (0.5 * len as f32).copysign(wo.z)
        } else {
            wo.dot(wh)
        };
        // A refraction's Fresnel term from both cosines (the same value as from wo's alone, but
        // the same for the pair's two directions, which reciprocity needs where 1 − F is tiny).
        let f = if refract {
            let (c_out, c_in) = if front {
                (wo.dot(wh), wi.dot(wh))
            } else {
                (wi.dot(wh), wo.dot(wh))
            };
            fresnel_dielectric_pair(c_out.abs(), c_in.abs(), self.eta)
        } else {
            fresnel_dielectric(cos_oh, self.eta)
        };
        // Mitsuba's `mac_mic_compatibility`, with the microfacet turned to wo's side.
        let m = if front { wh } else { -wh };
        let (o, i) = (wo.dot(m), wi.dot(m));
        Some(Pair {
            wh,
            reflect,
            refract,
            cos_oh,
            f,
            reflect_ok: o > 0.0 && i > 0.0,
            refract_ok: o > 0.0 && i < 0.0,
            eta_path,
        })
    }

    /// The main lobe's Fresnel term (Mitsuba's `principled_fresnel`): on the front, the
    /// dielectric's blended with Schlick terms for the metal (F0 the base colour) and the tint
    /// (F0 the tinted dielectric's); on the back, the dielectric's weighted by bsdf.
    fn fresnel(&self, f_dielectric: f32, cos: f32, front: bool) -> Vec3 {
        let (_, bsdf) = self.brdf_bsdf();
        if !front {
            return Vec3::splat(bsdf * f_dielectric);
        }
        let mut schlick = Vec3::ZERO;
        if self.metallic != 0.0 {
            schlick += self.metallic * calc_schlick(self.base_color, cos, self.eta);
        }
        if self.spec_tint != 0.0 {
            let eta_it = if cos >= 0.0 { self.eta } else { 1.0 / self.eta };
            let f0 = tint(self.base_color) * schlick_f0_from_ior(eta_it);
            schlick += (1.0 - self.metallic) * self.spec_tint * calc_schlick(f0, cos, self.eta);
        }
        Vec3::splat((1.0 - self.metallic) * (1.0 - self.spec_tint) * f_dielectric) + schlick
    }

    /// f·|cosθi| (Mitsuba's `eval`; radiance mode: a refraction holds 1/η'²).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z == 0.0 {
            return Vec3::ZERO;
        }
        let Some(p) = self.pair(wo, wi) else {
            return Vec3::ZERO;
        };
        let front = wo.z > 0.0;
        let (brdf, bsdf) = self.brdf_bsdf();
        let (cos_o, cos_i) = (wo.z, wi.z);
        let mf = self.microfacet();
        let d = mf.d(p.wh);
        let g = mf.g2_separable(wo, wi);
        let mut value = Vec3::ZERO;
        if p.reflect && p.reflect_ok && p.f > 0.0 {
            let f = self.fresnel(p.f, p.cos_oh, front);
            value += f * (d * g / (4.0 * cos_o.abs()));
        }
        if self.transmission && bsdf > 0.0 && p.refract && p.refract_ok && p.f < 1.0 {
            // Radiance mode: 1/η_path² undoes the η_path² of the Jacobian.
            let scale = 1.0 / (p.eta_path * p.eta_path);
            let (oh, ih) = (wo.dot(p.wh), wi.dot(p.wh));
            let denom = oh + p.eta_path * ih;
            let t = (scale * (1.0 - p.f) * d * g * p.eta_path * p.eta_path * oh * ih
                / (cos_o * denom * denom))
                .abs();
            value += self.base_color.map(f32::sqrt) * (bsdf * t);
        }
        if !(front && p.reflect) {
            return value;
        }
        if self.clearcoat > 0.0 && p.reflect_ok {
            let fcc = calc_schlick(Vec3::splat(0.04), p.cos_oh, self.eta).x;
            let dcc = gtr1::d(gtr1::clearcoat_alpha(self.clearcoat_gloss), p.wh);
            let gcc = gtr1::clearcoat_g(wo, wi, p.wh);
            value += Vec3::splat(self.clearcoat * 0.25 * fcc * dcc * gcc * cos_i.abs());
        }
        let f_i = schlick_weight(cos_i.abs());
        let f_o = schlick_weight(cos_o.abs());
        let cos_d = p.wh.dot(wi);
        if brdf > 0.0 {
            let f_diff = (1.0 - 0.5 * f_o) * (1.0 - 0.5 * f_i);
            let rr = 2.0 * self.roughness * cos_d * cos_d;
            let f_retro = rr * (f_i + f_o + f_i * f_o * (rr - 1.0));
            let mut lobe = f_diff + f_retro;
            if self.flatness != 0.0 {
                // Hanrahan–Krueger's fake subsurface; Fss90 flattens the retro-reflection.
                let fss90 = 0.5 * rr;
                let fss = (1.0 + (fss90 - 1.0) * f_i) * (1.0 + (fss90 - 1.0) * f_o);
                let f_ss = 1.25 * (fss * (1.0 / (cos_i.abs() + cos_o.abs()) - 0.5) + 0.5);
                lobe += (f_ss - lobe) * self.flatness;
            }
            value += self.base_color * (brdf * cos_i.abs() * FRAC_1_PI * lobe);
        }
        if self.sheen > 0.0 && 1.0 - self.metallic > 0.0 {
            let fd = schlick_weight(cos_d.abs());
            let c_sheen = if self.sheen_tint != 0.0 {
                Vec3::ONE + (tint(self.base_color) - Vec3::ONE) * self.sheen_tint
            } else {
                Vec3::ONE
            };
            value += c_sheen * (self.sheen * (1.0 - self.metallic) * fd * cos_i.abs());
        }
        value
    }

    /// The solid-angle density with which [`Principled::sample`] produces `wi` (every lobe).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 {
            return 0.0;
        }
        let Some(p) = self.pair(wo, wi) else {
            return 0.0;
        };
        let front = wo.z > 0.0;
        let prob = self.probabilities(front, p.f);
        let ih = wi.dot(p.wh);
        let dwh_dwi = if self.transmission && !p.reflect {
            let denom = wo.dot(p.wh) + p.eta_path * ih;
            (p.eta_path * p.eta_path * ih / (denom * denom)).abs()
        } else {
            (1.0 / (4.0 * ih)).abs()
        };
        let mf = self.microfacet();
        let wo_up = if front { wo } else { -wo };
        let mut pdf = 0.0;
        if p.reflect && p.reflect_ok {
            pdf += prob.reflection * mf.visible_normal_pdf(wo_up, p.wh) * dwh_dwi;
        }
        if p.reflect {
            pdf += prob.diffuse * cosine_hemisphere_pdf(wi.z);
        }
        if self.transmission && p.refract && p.refract_ok {
            pdf += prob.transmission * mf.visible_normal_pdf(wo_up, p.wh) * dwh_dwi;
        }
        if p.reflect && p.reflect_ok && prob.clearcoat > 0.0 {
            let alpha = gtr1::clearcoat_alpha(self.clearcoat_gloss);
            pdf += prob.clearcoat * gtr1::pdf(alpha, p.wh) * dwh_dwi;
        }
        pdf
    }

    /// One lobe chosen by `u_lobe` with Mitsuba's probabilities (diffuse, clearcoat,
    /// transmission, reflection, in its order), `u` warped within it.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let front = wo.z > 0.0;
        let (_, bsdf) = self.brdf_bsdf();
        if !(front || (self.transmission && bsdf > 0.0)) {
            return None;
        }
        let mf = self.microfacet();
        let flip = if front { 1.0 } else { -1.0 };
        let m = mf.sample_visible_normal(wo * flip, u);
        let f = fresnel_dielectric(wo.dot(m), self.eta);
        let prob = self.probabilities(front, f);
        // Each lobe's direction, and whether it is one that lobe can give (Mitsuba's masks:
        // `mac_mic_compatibility` of the lobe's own microfacet, and the side): a direction that
        // fails is no sample, even where another lobe's density covers it, for the pdf below
        // counts each lobe only where it is valid.
        let side = flip;
        let sees = |m: Vec3, wi: Vec3, across: bool| {
            let m = m * side;
            let i = if across { -wi.dot(m) } else { wi.dot(m) };
            wo.dot(m) > 0.0 && i > 0.0 && ((wi.z * wo.z < 0.0) == across)
        };
        let (wi, eta) = if u_lobe < prob.diffuse {
            let wi = sample_cosine_hemisphere(u);
            (wi, 1.0)
        } else if u_lobe < prob.diffuse + prob.clearcoat {
            let m = gtr1::sample(gtr1::clearcoat_alpha(self.clearcoat_gloss), u);
            let wi = reflect(wo, m);
            if !sees(m, wi, false) {
                return None;
            }
            (wi, 1.0)
        } else if u_lobe < prob.diffuse + prob.clearcoat + prob.transmission {
            let (wi, etap) = refract(wo, m, self.eta)?;
            if !sees(m, wi, true) {
                return None;
            }
            (wi, etap)
        } else {
            let wi = reflect(wo, m);
            if !sees(m, wi, false) {
                return None;
            }
            (wi, 1.0)
        };
        if wi.z * wo.z == 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        if pdf.is_nan() || pdf <= 0.0 {
            return None;
        }
        let weight = self.eval(wo, wi) / pdf;
        Some(BsdfSample {
            wi,
            weight,
            pdf,
            delta: false,
            eta,
        })
    }
}

#[cfg(test)]
#[path = "principled_tests.rs"]
mod tests;
