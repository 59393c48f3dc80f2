//! Materials (BSDFs): Lambertian diffuse, GGX conductor, a rough plastic, a dielectric, a thin
//! dielectric sheet, Mitsuba's principled and thin principled BSDFs and glTF's metallic-roughness
//! material.
//!
//! Everything works in the local shading frame: normal = +z, `wo` points towards the viewer and
//! `wi` towards the light, both unit and pointing away from the surface. The integrator flips the
//! frame of two-sided materials so that `wo.z > 0`; the reflection-only materials give zero for
//! `wo.z <= 0` or `wi.z <= 0`. The transmitting ones ([`Material::transmits`]) see both sides:
//! their frame is never flipped, `wo.z < 0` means the viewer is inside, and `wi` may lie on either
//! side.
//!
//! Conventions (Mitsuba 3): `eval` returns f·cosθi of the non-delta lobes; `pdf` is the solid-angle
//! density with which `sample` produces `wi` through them, including the lobe-selection
//! probability; a sample's `weight` is f·cosθi/pdf, or for a delta lobe its reflectance divided by
//! its discrete selection probability (which is then reported as `pdf`).
//! WGSL twin: `materials/mod.wgsl`. A [`Mix`] of two materials is no BSDF of its own: the scene
//! resolves it to one of them per hit ([`mix`]), before any of this code runs (CPU only).

pub mod beckmann;
pub mod bump_map;
pub mod coat_albedo;
pub mod conductor;
pub mod dielectric;
pub mod diffuse;
pub mod fresnel;
pub mod ggx;
pub mod gltf_pbr;
pub mod gtr1;
pub mod mask;
pub mod microfacet;
pub mod mix;
pub mod normal_map;
pub mod plastic;
pub mod plastic_mitsuba;
pub mod plastic_textured;
pub mod principled;
pub mod principled_thin;
#[cfg(test)]
mod testing;
pub mod textured;
pub mod thin_dielectric;
pub mod two_sided;

pub use conductor::{Conductor, ConductorFresnel};
pub use dielectric::Dielectric;
pub use diffuse::Diffuse;
pub use gltf_pbr::GltfPbr;
pub use microfacet::{Distribution, Microfacet};
pub use mix::Mix;
pub use plastic::Plastic;
pub use principled::Principled;
pub use principled_thin::PrincipledThin;
pub use thin_dielectric::ThinDielectric;

use glam::{Vec2, Vec3};

/// A dielectric reached by code specialised for scenes without one: `Scene::has_transmission` was
/// wrong, which must never happen.
#[cold]
#[inline(never)]
fn no_transmission() -> ! {
    panic!("a dielectric in code specialised for scenes without transmission")
}

/// One sampled direction of a BSDF.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled direction towards the light (local frame, unit; `wi.z > 0` unless the material
    /// transmits, and never 0).
    pub wi: Vec3,
    /// f·cosθi/pdf for a non-delta sample, or the delta lobe's reflectance / selection probability.
    pub weight: Vec3,
    /// Solid-angle pdf including lobe selection; for a delta lobe, its discrete selection
    /// probability.
    pub pdf: f32,
    /// True if `wi` came from a delta (perfectly specular) lobe: `eval`/`pdf` do not see it.
    pub delta: bool,
    /// η' = η(wi side)/η(wo side) of a refraction, 1 for a reflection: the weight of a refraction
    /// holds radiance's 1/η'², which Russian roulette multiplies back out (pbrt-v4's `etaScale`).
    pub eta: f32,
}

impl BsdfSample {
    /// The sample if its pdf is positive and everything is finite; `None` otherwise, so that no
    /// NaN/Inf ever leaves a material.
    /// `transmits` allows `wi` below the surface.
    pub(crate) fn checked(self, transmits: bool) -> Option<BsdfSample> {
        let side_ok = if transmits {
            self.wi.z != 0.0
        } else {
            self.wi.z > 0.0
        };
        let ok = self.pdf > 0.0
            && self.pdf.is_finite()
            && self.weight.is_finite()
            && self.eta.is_finite()
            && side_ok;
        ok.then_some(self)
    }
}

/// Every material, a closed set (the WGSL `switch` mirrors this variant order).
// Plastic holds its coat table inline (~300 bytes): materials are borrowed, not moved, except
// where a textured one is built at a hit, which must not allocate.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug, PartialEq)]
pub enum Material {
    /// Lambertian.
    Diffuse(Diffuse),
    /// GGX metal (or a perfect mirror below [`ggx::SMOOTH_ALPHA`]).
    Conductor(Conductor),
    /// Lambert base under a GGX dielectric coat, energy conserving.
    Plastic(Plastic),
    /// Glass: smooth or rough reflection and refraction between index 1 and `ior`.
    Dielectric(Dielectric),
    /// A thin sheet of glass: mirror reflection or straight transmission, both delta.
    ThinDielectric(ThinDielectric),
    /// Mitsuba's principled BSDF (Burley's Disney BSDF); transmits where it has specular
    /// transmission.
    Principled(Principled),
    /// Mitsuba's thin principled BSDF: a sheet with the same two sides, which transmits.
    PrincipledThin(PrincipledThin),
    /// glTF 2.0's metallic-roughness material (its specification's Appendix B).
    GltfPbr(GltfPbr),
}

impl Material {
    /// f(wo, wi)·cosθi of the non-delta part.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_specialised::<true>(wo, wi)
    }

    /// [`Material::eval`] compiled for scenes with (`TRANSMISSION = true`) or without a
    /// dielectric (the integrator's specialisation, see `integrator::path`): without, the
    /// dielectric's code is left out of the dispatch, and reaching it is a logic error that panics.
    #[inline(always)]
    pub fn eval_specialised<const TRANSMISSION: bool>(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self {
            Material::Diffuse(m) => m.eval(wo, wi),
            Material::Conductor(m) => m.eval(wo, wi),
            Material::Plastic(m) => m.eval(wo, wi),
            Material::GltfPbr(m) => m.eval(wo, wi),
            Material::Principled(m) if !m.transmission || TRANSMISSION => m.eval(wo, wi),
            Material::Dielectric(m) if TRANSMISSION => Vec3::splat(m.eval_pdf(wo, wi).0),
            Material::PrincipledThin(m) if TRANSMISSION => m.eval(wo, wi),
            Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::Principled(_)
            | Material::PrincipledThin(_)
                if !TRANSMISSION =>
            {
                no_transmission()
            }
            Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::Principled(_)
            | Material::PrincipledThin(_) => Vec3::ZERO,
        }
    }

    /// Solid-angle pdf of `sample` producing `wi` through its non-delta lobes.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.pdf_specialised::<true>(wo, wi)
    }

    /// [`Material::pdf`], specialised like [`Material::eval_specialised`].
    #[inline(always)]
    pub fn pdf_specialised<const TRANSMISSION: bool>(&self, wo: Vec3, wi: Vec3) -> f32 {
        let pdf = match self {
            Material::Diffuse(m) => m.pdf(wo, wi),
            Material::Conductor(m) => m.pdf(wo, wi),
            Material::Plastic(m) => m.pdf(wo, wi),
            Material::GltfPbr(m) => m.pdf(wo, wi),
            Material::Principled(m) if !m.transmission || TRANSMISSION => m.pdf(wo, wi),
            Material::Dielectric(m) if TRANSMISSION => m.eval_pdf(wo, wi).1,
            Material::PrincipledThin(m) if TRANSMISSION => m.pdf(wo, wi),
            Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::Principled(_)
            | Material::PrincipledThin(_)
                if !TRANSMISSION =>
            {
                no_transmission()
            }
            Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::Principled(_)
            | Material::PrincipledThin(_) => 0.0,
        };
        pdf * crate::mutants::bsdf_pdf(self.kind_tag())
    }

    /// This material's kind tag, for [`crate::mutants`].
    #[inline(always)]
    fn kind_tag(&self) -> u32 {
        crate::gpu::scene::MaterialTag::of(self).gpu_tag()
    }

    /// Samples `wi`; `u_lobe` picks a lobe, `u` warps within it. `None` if no valid direction.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        self.sample_specialised::<true>(wo, u_lobe, u)
    }

    /// [`Material::sample`], specialised like [`Material::eval_specialised`].
    #[inline(always)]
    pub fn sample_specialised<const TRANSMISSION: bool>(
        &self,
        wo: Vec3,
        u_lobe: f32,
        u: Vec2,
    ) -> Option<BsdfSample> {
        let mut s = match self {
            Material::Diffuse(m) => m.sample(wo, u),
            Material::Conductor(m) => m.sample(wo, u),
            Material::Plastic(m) => m.sample(wo, u_lobe, u),
            Material::GltfPbr(m) => m.sample(wo, u_lobe, u),
            Material::Principled(m) if !m.transmission || TRANSMISSION => m.sample(wo, u_lobe, u),
            Material::Dielectric(m) if TRANSMISSION => m.sample(wo, u_lobe, u),
            Material::ThinDielectric(m) if TRANSMISSION => m.sample(wo, u_lobe, u),
            Material::PrincipledThin(m) if TRANSMISSION => m.sample(wo, u_lobe, u),
            Material::Dielectric(_)
            | Material::ThinDielectric(_)
            | Material::Principled(_)
            | Material::PrincipledThin(_) => no_transmission(),
        }?;
        if cfg!(feature = "mutants") && !s.delta {
            let k = crate::mutants::bsdf_pdf(self.kind_tag());
            s.pdf *= k;
            s.weight /= k;
        }
        s.checked(TRANSMISSION && self.transmits())
    }

    /// True if `eval` can be non-zero, i.e. light sampling is worth doing.
    pub fn has_smooth_part(&self) -> bool {
        match self {
            Material::Diffuse(_) => true,
            Material::Conductor(m) => !m.is_delta(),
            Material::Plastic(m) => m.has_smooth_part(),
            Material::Dielectric(m) => !m.is_delta(),
            Material::ThinDielectric(_) => false,
            // Its diffuse or its rough (α ≥ 0.001) specular lobes.
            Material::Principled(_) | Material::PrincipledThin(_) | Material::GltfPbr(_) => true,
        }
    }

    /// True if a rough microfacet lobe has α_u ≠ α_v: its BSDF depends on the shading frame's
    /// tangents (`geometry/tangent.rs`), the others' only on the normal.
    #[inline]
    pub fn is_anisotropic(&self) -> bool {
        match self {
            Material::Conductor(c) => !c.is_delta() && c.microfacet.is_anisotropic(),
            Material::Dielectric(d) => !d.is_delta() && d.microfacet.is_anisotropic(),
            Material::Principled(p) => p.is_anisotropic(),
            Material::PrincipledThin(p) => p.is_anisotropic(),
            Material::Diffuse(_)
            | Material::Plastic(_)
            | Material::ThinDielectric(_)
            | Material::GltfPbr(_) => false,
        }
    }

    /// True if light passes through: `wo` and `wi` may lie on either side, the frame is never
    /// flipped, and two-sidedness does not apply.
    #[inline]
    pub fn transmits(&self) -> bool {
        match self {
            Material::Dielectric(_) | Material::ThinDielectric(_) => true,
            // Symmetric: its back side is its front side mirrored.
            Material::PrincipledThin(_) => true,
            Material::Principled(p) => p.transmission,
            Material::Diffuse(_)
            | Material::Conductor(_)
            | Material::Plastic(_)
            | Material::GltfPbr(_) => false,
        }
    }

    /// Purely specular: `eval` is always 0 and every sample is a delta sample.
    pub fn is_delta(&self) -> bool {
        !self.has_smooth_part()
    }

    /// A rough colour of the surface, for display (e.g. the viewer's albedo AOV).
    pub fn albedo_hint(&self) -> Vec3 {
        match self {
            Material::Diffuse(m) => m.albedo,
            Material::Conductor(m) => m.normal_reflectance(),
            Material::Plastic(m) => m.albedo_hint(),
            Material::Principled(m) => m.base_color,
            Material::PrincipledThin(m) => m.base_color,
            Material::GltfPbr(m) => m.base_color,
            Material::Dielectric(_) | Material::ThinDielectric(_) => Vec3::ONE,
        }
    }
}
