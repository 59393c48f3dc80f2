//! glTF 2.0's metallic-roughness material as its specification defines it (Appendix B, "BRDF
//! implementation"), for models read from glTF files and for scenes that name it (`gltf_pbr`):
//!
//! ```text
//! material        = mix(dielectric_brdf, metal_brdf, metallic)
//! metal_brdf      = conductor_fresnel(f0 = baseColor, bsdf = specular_brdf(α = roughness²))
//! dielectric_brdf = fresnel_mix(ior, base = diffuse_brdf(baseColor), layer = specular_brdf(α))
//! ```
//!
//! with Schlick's Fresnel F = f0 + (1 − f0)(1 − |V·H|)⁵ in both (the metal's f0 the base colour,
//! the dielectric's ((ior − 1)/(ior + 1))²), `fresnel_mix` = (1 − F)·diffuse + F·specular,
//! diffuse = baseColor/π and specular_brdf = D·G/(4|N·L||N·V|) with GGX's D and, as the
//! specification writes G, the *separable* Smith masking-shadowing G1(L)·G1(V) (its
//! `V_GGX` formula; [`crate::materials::ggx::g2_separable`]), not the height-correlated form some
//! viewers use. V·H = L·H for a reflection, so the BRDF is reciprocal.
//!
//! Roughness 0 is α = 0.001 ([`ggx::SMOOTH_ALPHA`], as the principled's floor): a lobe 0.06°
//! wide, no delta lobe, so every glTF material has a smooth part for light sampling.
//!
//! `KHR_materials_specular` (its ratified `fresnel_mix`): the dielectric's f0 becomes
//! min(f0·specularColor, 1) (RGB), F_d = specular·(f0 + (1 − f0)(1 − V·H)⁵), and the dielectric
//! (1 − max(F_d))·diffuse + F_d·specular_brdf; at its defaults (1, white) this is the plain
//! specification's formula above.
//!
//! Sampling: a mixture of GGX visible normals (the repo's sampler) and cosine-weighted diffuse,
//! the specular lobe chosen with probability w_s/(w_s + w_d) where w_s = (1 − metallic)·
//! luminance(F_d) + metallic·luminance(F_m) and w_d = (1 − metallic)(1 − max(F_d))·
//! luminance(baseColor) are the two
//! lobes' Fresnel weights at the view direction (V·H ≈ N·V), at least [`MIN_SPECULAR_RATE`]
//! while the diffuse lobe exists. The pdf is the mixture's over both lobes, so weight =
//! eval/pdf exactly and MIS sees the density the sampler draws.
//! WGSL twin: `materials/gltf_pbr.wgsl`.

use super::fresnel::{fresnel_schlick_rgb, schlick_f0_from_ior};
use super::{BsdfSample, ggx};
use crate::math::{luminance, reflect};
use crate::sampling::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use glam::{Vec2, Vec3};
use std::f32::consts::FRAC_1_PI;

/// The specular lobe's smallest selection probability while a diffuse lobe exists: the Fresnel
/// estimate is 0 at normal view for ior 1, where the lobe still reflects at other V·H.
pub const MIN_SPECULAR_RATE: f32 = 0.05;

/// The glTF metallic-roughness material at one point: `base_color`, `metallic`, `roughness` and
/// `specular` in [0, 1], `ior` ≥ 1 (`KHR_materials_ior`), `specular_color` ≥ 0
/// (`KHR_materials_specular`, which allows it above 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GltfPbr {
    /// The diffuse albedo of the dielectric part and the metal's f0.
    pub base_color: Vec3,
    /// The metal's share: 0 dielectric, 1 metal.
    pub metallic: f32,
    /// Perceptual roughness; GGX α = roughness².
    pub roughness: f32,
    /// The dielectric's index of refraction (its f0 only: nothing refracts).
    pub ior: f32,
    /// `KHR_materials_specular`'s `specularFactor`: the dielectric's Fresnel weight.
    pub specular: f32,
    /// `KHR_materials_specular`'s `specularColorFactor`: the dielectric's f0 colour.
    pub specular_color: Vec3,
}

impl Default for GltfPbr {
    /// glTF's defaults: base colour 1, metallic 1, roughness 1; `KHR_materials_ior`'s 1.5;
    /// `KHR_materials_specular`'s 1 and white.
    fn default() -> Self {
        GltfPbr {
            base_color: Vec3::ONE,
            metallic: 1.0,
            roughness: 1.0,
            ior: 1.5,
            specular: 1.0,
            specular_color: Vec3::ONE,
        }
    }
}

/// The texturable scalars, in the order of their texture slots (CPU and GPU), each the
/// [`GltfPbr`] field of its name.
#[allow(missing_docs)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GltfParam {
    Roughness,
    Metallic,
}

impl GltfParam {
    /// Every one, in slot order.
    pub const ALL: [GltfParam; 2] = [GltfParam::Roughness, GltfParam::Metallic];

    /// Its key in the scene format.
    pub fn name(self) -> &'static str {
        match self {
            GltfParam::Roughness => "roughness",
            GltfParam::Metallic => "metallic",
        }
    }

    /// Its value in `p`.
    pub fn get(self, p: &GltfPbr) -> f32 {
        match self {
            GltfParam::Roughness => p.roughness,
            GltfParam::Metallic => p.metallic,
        }
    }

    /// Sets it in `p`.
    pub fn set(self, p: &mut GltfPbr, value: f32) {
        match self {
            GltfParam::Roughness => p.roughness = value,
            GltfParam::Metallic => p.metallic = value,
        }
    }
}

impl GltfPbr {
    /// GGX α = roughness², at least [`ggx::SMOOTH_ALPHA`].
    #[inline]
    pub fn alpha(&self) -> f32 {
        (self.roughness * self.roughness).max(ggx::SMOOTH_ALPHA)
    }

    /// The dielectric's normal-incidence reflectance min(((ior − 1)/(ior + 1))²·specularColor, 1).
    #[inline]
    pub fn dielectric_f0(&self) -> Vec3 {
        (schlick_f0_from_ior(self.ior) * self.specular_color).min(Vec3::ONE)
    }

    /// The dielectric (non-metal) part's Fresnel weight specular·Schlick(f0, cos) (RGB).
    #[inline]
    fn non_metal_fresnel(&self, cos: f32) -> Vec3 {
        self.specular * fresnel_schlick_rgb(self.dielectric_f0(), cos)
    }

    /// The probability of sampling the specular lobe from `wo` (module doc).
    #[inline]
    pub fn specular_probability(&self, wo: Vec3) -> f32 {
        let m = self.metallic;
        let f_d = self.non_metal_fresnel(wo.z);
        let f_m = fresnel_schlick_rgb(self.base_color, wo.z);
        let w_d = (1.0 - m) * (1.0 - f_d.max_element()) * luminance(self.base_color);
        if w_d <= 0.0 {
            return 1.0;
        }
        let w_s = (1.0 - m) * luminance(f_d) + m * luminance(f_m);
        (w_s / (w_s + w_d)).max(MIN_SPECULAR_RATE)
    }

    /// f·cosθi: (1 − m)[(1 − max(F_d))·c/π·cosθi + F_d·S] + m·F_m·S with S =
    /// D·G1(wo)G1(wi)/(4 cosθo) (the specular BRDF times cosθi) and F_d, F_m Schlick's at V·H.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        let (h, cos_h) = ggx::half_vector(wo, wi);
        let alpha = self.alpha();
        let s = ggx::d(alpha, h) * ggx::g2_separable(alpha, wo, wi) / (4.0 * wo.z);
        let m = self.metallic;
        let f_d = self.non_metal_fresnel(cos_h);
        let f_m = fresnel_schlick_rgb(self.base_color, cos_h);
        let non_metal = (1.0 - f_d.max_element()) * FRAC_1_PI * wi.z * self.base_color + f_d * s;
        (1.0 - m) * non_metal + m * s * f_m
    }

    /// The mixture's density: p_s·VNDF(h)/(4 wo·h) + (1 − p_s)·cosθi/π.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let p_s = self.specular_probability(wo);
        let (h, _) = ggx::half_vector(wo, wi);
        let alpha = self.alpha();
        // VNDF/(4 wo·h) = G1(wo)·D(h)/(4 cosθo).
        let specular = ggx::g1(alpha, wo) * ggx::d(alpha, h) / (4.0 * wo.z);
        p_s * specular + (1.0 - p_s) * cosine_hemisphere_pdf(wi.z)
    }

    /// A visible-normal reflection with probability p_s, else a cosine-weighted direction; the
    /// weight is eval/pdf of the whole mixture.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = if u_lobe < self.specular_probability(wo) {
            let h = ggx::sample_visible_normal(self.alpha(), wo, u);
            reflect(wo, h).normalize()
        } else {
            sample_cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf(wo, wi);
        Some(BsdfSample {
            wi,
            weight: self.eval(wo, wi) / pdf,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
#[path = "gltf_pbr_tests.rs"]
mod tests;
