//! Mitsuba 3.9.1's `principledthin` BSDF (`src/bsdfs/principledthin.cpp`), term for term: Burley's
//! thin-surface Disney BSDF (2015) as Mitsuba writes it, for sheets with no inside (leaves,
//! paper, cloth). Lobes: a diffuse base with retro-reflection, the "flatness" fake subsurface and
//! sheen; a Lambertian diffuse transmission; and, only with specular transmission
//! (`spec_trans` > 0), a GGX specular reflection and a GGX "thin" specular transmission: the
//! reflection about the microfacet turned to the other side (no bending: both sides are the same
//! medium), its roughness scaled by 0.65η − 0.35 (Burley 2015, Figure 15). Without `spec_trans`
//! the model has no specular lobe at all (Mitsuba's choice, kept). Each lobe is weighted and
//! selected as Mitsuba does; the sample's pdf is the whole mixture's, so weight = eval/pdf.
//!
//! Sides: symmetric. A viewer below sees what a viewer above sees, mirrored: Mitsuba turns both
//! directions to wo's side first. So the material always transmits (its back is never black),
//! and two-sidedness does not apply. `diff_trans` is Mitsuba's, in [0, 2]; the model uses half of
//! it (1 − dt/2 of the diffuse part reflects, dt/2 transmits).
//!
//! Not reciprocal, as Mitsuba's: the transmission lobe asks that wi sees the microfacet from
//! below, a condition stated on wi alone, so a pair can be valid in one direction and not the
//! other ([`PrincipledThin::eval`]). lumis evaluates with wo towards the viewer, as Mitsuba's
//! path tracer (and the references) do.
//! Mitsuba's "has" flags reduce to the values here (every lobe they switch off then has factor
//! 0).
//! WGSL twin: `materials/principled_thin.wgsl`.

use super::fresnel::{fresnel_dielectric, schlick_f0_from_ior};
use super::principled::{calc_schlick, microfacet, schlick_weight, tint};
use super::{BsdfSample, Microfacet};
use crate::math::reflect;
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// The rates that weigh each lobe's selection in sampling (Mitsuba's `*_sampling_rate`, each
/// default 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinRates {
    /// `specular_reflectance_sampling_rate`.
    pub specular_reflection: f32,
    /// `specular_transmittance_sampling_rate`.
    pub specular_transmission: f32,
    /// `diffuse_reflectance_sampling_rate`.
    pub diffuse_reflection: f32,
    /// `diffuse_transmittance_sampling_rate`.
    pub diffuse_transmission: f32,
}

impl ThinRates {
    /// The scene formats' keys, in the order of [`ThinRates::to_array`].
    pub const KEYS: [&'static str; 4] = [
        "specular_reflectance_sampling_rate",
        "specular_transmittance_sampling_rate",
        "diffuse_reflectance_sampling_rate",
        "diffuse_transmittance_sampling_rate",
    ];

    /// The rates in [`ThinRates::KEYS`]' order.
    pub fn to_array(self) -> [f32; 4] {
        [
            self.specular_reflection,
            self.specular_transmission,
            self.diffuse_reflection,
            self.diffuse_transmission,
        ]
    }

    /// The rates from [`ThinRates::KEYS`]' order.
    pub fn from_array([a, b, c, d]: [f32; 4]) -> ThinRates {
        ThinRates {
            specular_reflection: a,
            specular_transmission: b,
            diffuse_reflection: c,
            diffuse_transmission: d,
        }
    }
}

impl Default for ThinRates {
    fn default() -> Self {
        ThinRates::from_array([1.0; 4])
    }
}

/// Mitsuba's thin principled BSDF at one point: every parameter in [0, 1] except `diff_trans`
/// (in [0, 2]), `eta` (> 0) and the sampling rates (≥ 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipledThin {
    /// The colour of the diffuse lobes and of the specular transmission, the tints' hue.
    pub base_color: Vec3,
    /// Drives the GGX α (roughness², at least 0.001) and the diffuse retro-reflection.
    pub roughness: f32,
    /// Stretches α along the first tangent, shrinks it along the second.
    pub anisotropic: f32,
    /// Share of the specular lobes (half reflection, half transmission by selection).
    pub spec_trans: f32,
    /// Share of the specular reflection's Fresnel term tinted towards the base colour.
    pub spec_tint: f32,
    /// Weight of the grazing sheen lobe.
    pub sheen: f32,
    /// Share of the sheen tinted towards the base colour.
    pub sheen_tint: f32,
    /// Blend from the diffuse lobe to the fake subsurface one.
    pub flatness: f32,
    /// Diffuse transmission, Mitsuba's range [0, 2] (half of it is the transmitted share).
    pub diff_trans: f32,
    /// The sheet's index of refraction: its Fresnel term and its transmission's roughness.
    pub eta: f32,
    /// How often each lobe is sampled.
    pub rates: ThinRates,
}

/// The texturable parameters, in the order of their texture slots (CPU and GPU), each the
/// [`PrincipledThin`] field of its name.
#[allow(missing_docs)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ThinParam {
    Roughness,
    Anisotropic,
    SpecTrans,
    SpecTint,
    Sheen,
    SheenTint,
    Flatness,
    DiffTrans,
    Eta,
}

impl ThinParam {
    /// Every one, in slot order.
    pub const ALL: [ThinParam; 9] = [
        ThinParam::Roughness,
        ThinParam::Anisotropic,
        ThinParam::SpecTrans,
        ThinParam::SpecTint,
        ThinParam::Sheen,
        ThinParam::SheenTint,
        ThinParam::Flatness,
        ThinParam::DiffTrans,
        ThinParam::Eta,
    ];

    /// Its key in both scene formats (lumis' and Mitsuba's spell them alike).
    pub fn name(self) -> &'static str {
        match self {
            ThinParam::Roughness => "roughness",
            ThinParam::Anisotropic => "anisotropic",
            ThinParam::SpecTrans => "spec_trans",
            ThinParam::SpecTint => "spec_tint",
            ThinParam::Sheen => "sheen",
            ThinParam::SheenTint => "sheen_tint",
            ThinParam::Flatness => "flatness",
            ThinParam::DiffTrans => "diff_trans",
            ThinParam::Eta => "eta",
        }
    }

    /// The range of its values: [0, 1], except `diff_trans` [0, 2] and `eta` (0, 10] (the
    /// dielectric's largest index; 0 itself is not allowed).
    pub fn range(self) -> (f32, f32) {
        match self {
            ThinParam::DiffTrans => (0.0, 2.0),
            ThinParam::Eta => (0.0, super::dielectric::MAX_IOR),
            _ => (0.0, 1.0),
        }
    }

    /// Its value in `p`.
    pub fn get(self, p: &PrincipledThin) -> f32 {
        *self.field(&mut p.clone())
    }

    /// Sets it in `p`.
    pub fn set(self, p: &mut PrincipledThin, value: f32) {
        *self.field(p) = value;
    }

    fn field(self, p: &mut PrincipledThin) -> &mut f32 {
        match self {
            ThinParam::Roughness => &mut p.roughness,
            ThinParam::Anisotropic => &mut p.anisotropic,
            ThinParam::SpecTrans => &mut p.spec_trans,
            ThinParam::SpecTint => &mut p.spec_tint,
            ThinParam::Sheen => &mut p.sheen,
            ThinParam::SheenTint => &mut p.sheen_tint,
            ThinParam::Flatness => &mut p.flatness,
            ThinParam::DiffTrans => &mut p.diff_trans,
            ThinParam::Eta => &mut p.eta,
        }
    }
}

impl Default for PrincipledThin {
    /// Mitsuba's defaults: base colour 0.5, roughness 0.5, η 1.5, the rest 0.
    fn default() -> Self {
        PrincipledThin {
            base_color: Vec3::splat(0.5),
            roughness: 0.5,
            anisotropic: 0.0,
            spec_trans: 0.0,
            spec_tint: 0.0,
            sheen: 0.0,
            sheen_tint: 0.0,
            flatness: 0.0,
            diff_trans: 0.0,
            eta: 1.5,
            rates: ThinRates::default(),
        }
    }
}

/// The lobes' selection probabilities, normalised.
#[derive(Clone, Copy, Debug)]
struct LobeProbabilities {
    specular_reflection: f32,
    specular_transmission: f32,
    diffuse_reflection: f32,
    diffuse_transmission: f32,
}

/// A direction pair turned to wo's side (Mitsuba's eval and pdf preamble).
struct Pair {
    /// wo and wi, both mirrored below the surface if wo is: wo.z > 0.
    wo: Vec3,
    wi: Vec3,
    /// The half vector of wo and wi mirrored to wo's side (the microfacet of both specular
    /// lobes).
    wh: Vec3,
    /// wo·wh = wi_r·wh (wi_r: wi mirrored to wo's side), |wo + wi_r|/2.
    cos_oh: f32,
    reflect: bool,
    refract: bool,
    /// Both see `wh` from the side a reflection (or the thin transmission) needs (Mitsuba's
    /// `mac_mic_compatibility`).
    reflect_ok: bool,
    refract_ok: bool,
}

impl PrincipledThin {
    /// The specular reflection's GGX microfacets (Mitsuba's `calc_dist_params`).
    pub fn microfacet(&self) -> Microfacet {
        microfacet(self.roughness, self.anisotropic)
    }

    /// The specular transmission's: the roughness scaled by 0.65η − 0.35.
    pub fn transmission_microfacet(&self) -> Microfacet {
        microfacet((0.65 * self.eta - 0.35) * self.roughness, self.anisotropic)
    }

    /// True if either lobe's α_u ≠ α_v.
    pub fn is_anisotropic(&self) -> bool {
        self.microfacet().is_anisotropic() || self.transmission_microfacet().is_anisotropic()
    }

    /// Half of Mitsuba's `diff_trans`: the transmitted share of the diffuse part.
    fn dt(&self) -> f32 {
        0.5 * self.diff_trans
    }

    fn probabilities(&self) -> LobeProbabilities {
        let (st, dt, r) = (self.spec_trans, self.dt(), &self.rates);
        let sr = st * r.specular_reflection * 0.5;
        let tr = st * r.specular_transmission * 0.5;
        let dr = r.diffuse_reflection * (1.0 - st) * (1.0 - dt);
        let dtr = r.diffuse_transmission * (1.0 - st) * dt;
        let norm = 1.0 / (sr + tr + dr + dtr);
        LobeProbabilities {
            specular_reflection: sr * norm,
            specular_transmission: tr * norm,
            diffuse_reflection: dr * norm,
            diffuse_transmission: dtr * norm,
        }
    }

    fn pair(&self, wo: Vec3, wi: Vec3) -> Option<Pair> {
        let flip = if wo.z >= 0.0 { 1.0 } else { -1.0 };
        let (wo, wi) = (wo * flip, wi * flip);
        let wi_r = Vec3::new(wi.x, wi.y, wi.z.abs());
        let sum = wo + wi_r;
        let len = sum.length();
        let wh = sum / len;
        if !wh.is_finite() {
            return None;
        }
        let (o, i) = (wo.dot(wh), wi.dot(wh));
        Some(Pair {
            wo,
            wi,
            wh,
            // wo·wh = wi_r·wh exactly, from the length.
            cos_oh: 0.5 * len,
            reflect: wi.z > 0.0,
            refract: wi.z < 0.0,
            reflect_ok: o > 0.0 && i > 0.0,
            refract_ok: o > 0.0 && i < 0.0,
        })
    }

    /// Whether the specular transmission's validity (wi sees the microfacet from below) is the
    /// same for (wo, wi) and (wi, wo): where it is, the model is reciprocal (its D, G and Fresnel
    /// terms are symmetric); where not, only one of the two directions has the lobe.
    pub fn transmission_is_reciprocal(&self, wo: Vec3, wi: Vec3) -> bool {
        let ok = |a: Vec3, b: Vec3| self.pair(a, b).is_some_and(|p| p.refract && p.refract_ok);
        ok(wo, wi) == ok(wi, wo)
    }

    /// f·|cosθi| (Mitsuba's `eval`).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z == 0.0 {
            return Vec3::ZERO;
        }
        let Some(p) = self.pair(wo, wi) else {
            return Vec3::ZERO;
        };
        let (st, dt) = (self.spec_trans, self.dt());
        let cos_o = p.wo.z;
        let cos_i = p.wi.z.abs();
        let mut value = Vec3::ZERO;
        if st > 0.0 && ((p.reflect && p.reflect_ok) || (p.refract && p.refract_ok)) {
            let f = fresnel_dielectric(p.cos_oh, self.eta);
            if p.reflect {
                let mf = self.microfacet();
                let d = mf.d(p.wh);
                let g = mf.g2_separable(p.wo, p.wi);
                // Mitsuba's `thin_fresnel`: the dielectric's term blended with a Schlick term
                // of F0 the tinted dielectric's.
                let mut fresnel = Vec3::splat(f);
                if self.spec_tint != 0.0 {
                    let f0 = tint(self.base_color) * schlick_f0_from_ior(self.eta);
                    let schlick = calc_schlick(f0, p.cos_oh, self.eta);
                    fresnel += (schlick - fresnel) * self.spec_tint;
                }
                value += fresnel * (st * d * g / (4.0 * cos_o));
            } else {
                let mf = self.transmission_microfacet();
                let d = mf.d(p.wh);
                let g = mf.g2_separable(p.wo, p.wi);
                value += self.base_color * (st * (1.0 - f) * d * g / (4.0 * cos_o));
            }
        }
        if p.reflect && st < 1.0 && dt < 1.0 {
            let f_o = schlick_weight(cos_i);
            let f_i = schlick_weight(cos_o);
            let f_diff = (1.0 - 0.5 * f_i) * (1.0 - 0.5 * f_o);
            let cos_d = p.wh.dot(p.wi);
            let rr = 2.0 * self.roughness * cos_d * cos_d;
            let f_retro = rr * (f_o + f_i + f_o * f_i * (rr - 1.0));
            let mut lobe = f_diff + f_retro;
            if self.flatness != 0.0 {
                // Hanrahan–Krueger's fake subsurface; Fss90 flattens the retro-reflection.
                let fss90 = 0.5 * rr;
                let fss = (1.0 + (fss90 - 1.0) * f_o) * (1.0 + (fss90 - 1.0) * f_i);
                let f_ss = 1.25 * (fss * (1.0 / (cos_i + cos_o) - 0.5) + 0.5);
                lobe += (f_ss - lobe) * self.flatness;
            }
            let diffuse = (1.0 - st) * cos_i * FRAC_1_PI * (1.0 - dt) * lobe;
            value += self.base_color * diffuse;
            if self.sheen > 0.0 {
                let fd = schlick_weight(cos_d.abs());
                let c_sheen = if self.sheen_tint != 0.0 {
                    Vec3::ONE + (tint(self.base_color) - Vec3::ONE) * self.sheen_tint
                } else {
                    Vec3::ONE
                };
                value += c_sheen * (self.sheen * (1.0 - st) * fd * (1.0 - dt) * cos_i);
            }
        }
        if p.refract && st < 1.0 && dt > 0.0 {
            value += self.base_color * ((1.0 - st) * dt * FRAC_1_PI * cos_i);
        }
        value
    }

    /// The solid-angle density with which [`PrincipledThin::sample`] produces `wi` (every lobe).
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z == 0.0 {
            return 0.0;
        }
        let Some(p) = self.pair(wo, wi) else {
            return 0.0;
        };
        let prob = self.probabilities();
        // dwh/dwi of the reflection (the transmission mirrors it, which keeps the Jacobian).
        let dwh_dwi = (1.0 / (4.0 * p.cos_oh)).abs();
        let mut pdf = 0.0;
        if p.reflect && p.reflect_ok {
            let vnd = self.microfacet().visible_normal_pdf(p.wo, p.wh);
            pdf += prob.specular_reflection * vnd * dwh_dwi;
        }
        if p.refract && p.refract_ok {
            let vnd = self
                .transmission_microfacet()
                .visible_normal_pdf(p.wo, p.wh);
            pdf += prob.specular_transmission * vnd * dwh_dwi;
        }
        if p.reflect {
            pdf += prob.diffuse_reflection * cosine_hemisphere_pdf(p.wi.z);
        }
        if p.refract {
            pdf += prob.diffuse_transmission * cosine_hemisphere_pdf(-p.wi.z);
        }
        pdf
    }

    /// One lobe chosen by `u_lobe` with Mitsuba's probabilities (specular reflection, specular
    /// transmission, diffuse reflection, diffuse transmission, in its order), `u` warped within
    /// it.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let flip = if wo.z > 0.0 { 1.0 } else { -1.0 };
        let w = wo * flip;
        let prob = self.probabilities();
        // Each lobe's direction, and whether it is one that lobe can give (Mitsuba's masks: the
        // sampled microfacet seen from the sides the lobe needs): a direction that fails is no
        // sample, as the pdf counts each lobe only where it is valid.
        let wi = if u_lobe < prob.specular_reflection {
            let m = self.microfacet().sample_visible_normal(w, u);
            let wi = reflect(w, m);
            if !(w.dot(m) > 0.0 && wi.dot(m) > 0.0 && wi.z > 0.0) {
                return None;
            }
            wi
        } else if u_lobe < prob.specular_reflection + prob.specular_transmission {
            let m = self.transmission_microfacet().sample_visible_normal(w, u);
            let r = reflect(w, m);
            let wi = Vec3::new(r.x, r.y, -r.z);
            if !(w.dot(m) > 0.0 && wi.dot(m) < 0.0 && wi.z < 0.0) {
                return None;
            }
            wi
        } else if u_lobe
            < prob.specular_reflection + prob.specular_transmission + prob.diffuse_reflection
        {
            sample_cosine_hemisphere(u)
        } else {
            -sample_cosine_hemisphere(u)
        };
        let wi = wi * flip;
        if wi.z == 0.0 {
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
            eta: 1.0,
        })
    }
}

#[cfg(test)]
#[path = "principled_thin_tests.rs"]
mod tests;
