//! Deliberate, named errors ("mutants") for measuring what the tests detect.
//!
//! `docs/testing.md` holds a table of which image test catches which local bias, made by running
//! the real test binaries with one mutant switched on at a time (`tools/power_table.py`). The
//! mutation points are compiled in only with the `mutants` cargo feature, which nothing enables by
//! default; without it every factor below is the constant 1 and the renderer never calls
//! [`apply_to_desc`], so shipped builds carry no trace of them. [`scale_albedo`] and
//! [`scale_emission`] are plain functions; the normal suite uses them for its in-suite power checks.
//!
//! The mutant is chosen by the environment variable `LUMIS_MUTANT`, read once:
//!
//! | value | effect |
//! |---|---|
//! | `emission:I` | shape `I`'s emission × 1.03 (scene level, so CPU and GPU alike) |
//! | `emission_all:F` | every emission × `F` (the whole image; for the heavy-tailed cases) |
//! | `albedo:NAME` | material `NAME`'s albedo (diffuse, plastic base, a conductor's Fresnel reflectance) × 1.03 |
//! | `light_pdf:KIND` | the pdf of lights of `KIND` (`triangle`, `polygon`, `quad`, `disk`, `sphere`, `background`) × 1.03, in sampling and evaluation alike |
//! | `bsdf_pdf:KIND` | the non-delta pdf of materials of `KIND` (`diffuse`, `conductor`, `plastic`) × 1.03 (weights ÷ 1.03) |
//! | `plastic_eval` | the plastic's f (both lobes, non-delta) × 1.03, in eval and sample alike |
//! | `sampler:light_camera` | the light sample draws the camera's dimensions (ZSobol) |
//! | `sampler:shared_bounces` | every bounce's BSDF direction draws bounce 0's dimensions (ZSobol) |
//! | `optimal:pure_zero` | mis-optimal: a pure sample's control-variate term is 0 instead of `−α_own` |
//! | `optimal:occluded_combined` | mis-optimal: a blocked light sample is weighed as if BSDF sampling could reach it (CPU only) |
//!
//! On the GPU the same points are constants of the generated WGSL prelude
//! (`gpu::prelude::mutant_constants`, built with the feature), so a mutant reaches both backends; a value ending
//! in `@gpu` (`light_pdf:disk@gpu`) mutates only the WGSL twin, as a bug on that side alone would.

#[cfg(feature = "mutants")]
use std::sync::OnceLock;

/// The factor by which a mutant scales what it touches.
pub const FACTOR: f32 = 1.03;

/// One mutant, parsed from `LUMIS_MUTANT`.
#[derive(Clone, Debug, PartialEq)]
pub enum Mutant {
    /// No mutant (the variable is unset or empty).
    None,
    /// Shape index whose emission is scaled.
    Emission(usize),
    /// Every emission scaled by this factor.
    EmissionAll(f64),
    /// Material name whose albedo is scaled.
    Albedo(String),
    /// Light kind tag ([`crate::gpu::scene::LightTag`]) whose pdf is scaled.
    LightPdf(u32),
    /// Material kind tag ([`crate::gpu::scene::MaterialTag`]) whose pdf is scaled.
    BsdfPdf(u32),
    /// The plastic's f is scaled.
    PlasticEval,
    /// The light sample reuses the camera's sampler dimensions.
    SamplerLightCamera,
    /// Every bounce's BSDF direction reuses bounce 0's sampler dimensions.
    SamplerSharedBounces,
    /// mis-optimal's pure samples add no control-variate term.
    OptimalPureZero,
    /// mis-optimal's blocked light samples are combined outcomes.
    OptimalOccludedCombined,
}

/// The tag named `kind` in a GPU tag list (`LIGHT_DISK` for `disk` with prefix `LIGHT_`): the
/// kinds are those of the one definition the GPU encoder uses too.
fn tag_of<T: Copy + Into<u32>>(all: &[(T, &str)], prefix: &str, kind: &str) -> Option<u32> {
    all.iter()
        .find(|(_, name)| name.strip_prefix(prefix) == Some(kind.to_uppercase().as_str()))
        .map(|(t, _)| (*t).into())
}

/// Parses a `LUMIS_MUTANT` value; an unknown one is an error (a typo must not measure nothing).
pub fn parse(text: &str) -> Result<Mutant, String> {
    let text = text.trim();
    if text.is_empty() {
        return Ok(Mutant::None);
    }
    let (name, arg) = text.split_once(':').unwrap_or((text, ""));
    use crate::gpu::scene::{LightTag, MaterialTag};
    let unknown = || format!("LUMIS_MUTANT={text}: unknown kind {arg:?}");
    Ok(match name {
        "emission" => Mutant::Emission(
            arg.parse()
                .map_err(|_| format!("LUMIS_MUTANT={text}: expected a shape index"))?,
        ),
        "emission_all" => Mutant::EmissionAll(
            arg.parse()
                .map_err(|_| format!("LUMIS_MUTANT={text}: expected a factor"))?,
        ),
        "albedo" if !arg.is_empty() => Mutant::Albedo(arg.to_string()),
        "light_pdf" => Mutant::LightPdf(tag_of(LightTag::ALL, "LIGHT_", arg).ok_or_else(unknown)?),
        "bsdf_pdf" => {
            Mutant::BsdfPdf(tag_of(MaterialTag::ALL, "MATERIAL_", arg).ok_or_else(unknown)?)
        }
        "plastic_eval" if arg.is_empty() => Mutant::PlasticEval,
        "sampler" if arg == "light_camera" => Mutant::SamplerLightCamera,
        "sampler" if arg == "shared_bounces" => Mutant::SamplerSharedBounces,
        "optimal" if arg == "pure_zero" => Mutant::OptimalPureZero,
        "optimal" if arg == "occluded_combined" => Mutant::OptimalOccludedCombined,
        _ => return Err(format!("LUMIS_MUTANT={text}: unknown mutant")),
    })
}

/// The active mutant: always [`Mutant::None`] without the `mutants` feature.
#[cfg(not(feature = "mutants"))]
#[inline(always)]
pub fn active() -> &'static Mutant {
    static NONE: Mutant = Mutant::None;
    &NONE
}

/// The mutant the CPU's mutation points see: always [`Mutant::None`] without the feature.
#[cfg(not(feature = "mutants"))]
#[inline(always)]
pub fn active_on_cpu() -> &'static Mutant {
    active()
}

/// The active mutant, from `LUMIS_MUTANT` (read once; an unknown value panics, on purpose: this
/// is a measuring tool, and a misspelt mutant would silently measure the unmutated renderer).
#[cfg(feature = "mutants")]
pub fn active() -> &'static Mutant {
    &from_env().0
}

/// The mutant the CPU's mutation points see: [`active`], or none when `LUMIS_MUTANT` ends in
/// `@gpu` (a bug in a WGSL twin only, which the GPU tests' comparisons with the CPU must see).
#[cfg(feature = "mutants")]
pub fn active_on_cpu() -> &'static Mutant {
    static NONE: Mutant = Mutant::None;
    let (m, gpu_only) = from_env();
    if *gpu_only { &NONE } else { m }
}

/// `LUMIS_MUTANT` parsed once: the mutant and whether it is for the GPU only.
#[cfg(feature = "mutants")]
fn from_env() -> &'static (Mutant, bool) {
    static ACTIVE: OnceLock<(Mutant, bool)> = OnceLock::new();
    ACTIVE.get_or_init(|| {
        let text = std::env::var("LUMIS_MUTANT").unwrap_or_default();
        let (text, gpu_only) = match text.strip_suffix("@gpu") {
            Some(t) => (t.to_string(), true),
            None => (text, false),
        };
        let m = parse(&text).unwrap_or_else(|e| panic!("{e}"));
        if gpu_only
            && matches!(
                m,
                Mutant::Emission(_) | Mutant::EmissionAll(_) | Mutant::Albedo(_)
            )
        {
            panic!("LUMIS_MUTANT: a scene-level mutant reaches both backends, not only the GPU");
        }
        if m != Mutant::None {
            eprintln!(
                "lumis: mutant active: {m:?}{}",
                if gpu_only { " (GPU only)" } else { "" }
            );
        }
        (m, gpu_only)
    })
}

/// Factor on the pdf of lights of kind `tag`.
#[inline(always)]
pub fn light_pdf(tag: u32) -> f32 {
    if cfg!(feature = "mutants") && *active_on_cpu() == Mutant::LightPdf(tag) {
        FACTOR
    } else {
        1.0
    }
}

/// Factor on the non-delta pdf of materials of kind `tag`.
#[inline(always)]
pub fn bsdf_pdf(tag: u32) -> f32 {
    if cfg!(feature = "mutants") && *active_on_cpu() == Mutant::BsdfPdf(tag) {
        FACTOR
    } else {
        1.0
    }
}

/// Factor on the plastic's f.
#[inline(always)]
pub fn plastic_eval() -> f32 {
    if cfg!(feature = "mutants") && *active_on_cpu() == Mutant::PlasticEval {
        FACTOR
    } else {
        1.0
    }
}

/// Whether the light sample draws the camera's dimensions (a dimension-allocation bug).
#[inline(always)]
pub fn sampler_light_reuses_camera() -> bool {
    cfg!(feature = "mutants") && *active_on_cpu() == Mutant::SamplerLightCamera
}

/// Whether every bounce's BSDF direction draws bounce 0's dimensions (a dimension-allocation
/// bug: the bounce is not advanced).
#[inline(always)]
pub fn sampler_bounces_share_dimensions() -> bool {
    cfg!(feature = "mutants") && *active_on_cpu() == Mutant::SamplerSharedBounces
}

/// Whether mis-optimal's pure samples forget their `−α_own` (the failure mass dropped).
#[inline(always)]
pub fn optimal_pure_zero() -> bool {
    cfg!(feature = "mutants") && *active_on_cpu() == Mutant::OptimalPureZero
}

/// Whether mis-optimal weighs blocked light samples as combined outcomes (the two techniques
/// classify an outcome differently).
#[inline(always)]
pub fn optimal_occluded_combined() -> bool {
    cfg!(feature = "mutants") && *active_on_cpu() == Mutant::OptimalOccludedCombined
}

/// Applies a scene-level mutant (emission, albedo) to a description before it is built.
pub fn apply_to_desc(desc: &mut crate::scene::SceneDesc) {
    let r = match active() {
        Mutant::Emission(i) => scale_emission(desc, *i, FACTOR as f64),
        Mutant::EmissionAll(k) => {
            desc.shapes.iter_mut().for_each(|s| s.emission *= *k);
            Ok(())
        }
        Mutant::Albedo(name) => scale_albedo(desc, name, FACTOR as f64),
        _ => Ok(()),
    };
    // A mutant that finds nothing to change would measure the unmutated scene.
    if let Err(e) = r {
        panic!("LUMIS_MUTANT: {e}");
    }
}

/// Scales shape `index`'s emission by `factor`; an error if it does not emit. Also used directly
/// by the tests that check the z-test's power within the normal suite.
pub fn scale_emission(
    desc: &mut crate::scene::SceneDesc,
    index: usize,
    factor: f64,
) -> Result<(), String> {
    match desc.shapes.get_mut(index) {
        Some(s) if s.emission.max_element() > 0.0 => {
            s.emission *= factor;
            Ok(())
        }
        _ => Err(format!("shape {index} is not an emitter of this scene")),
    }
}

/// Scales the albedo of material `name` by `factor`: a diffuse or plastic base albedo, a
/// principled's (thin or not) or glTF material's base colour, or a conductor's Fresnel
/// reflectance; an error if there is no such material or it has no albedo (a conductor given by
/// a complex IOR).
pub fn scale_albedo(
    desc: &mut crate::scene::SceneDesc,
    name: &str,
    factor: f64,
) -> Result<(), String> {
    use crate::scene::desc::{FresnelDesc, MaterialDesc};
    let m = desc
        .materials
        .iter_mut()
        .find(|m| m.name == name)
        .ok_or_else(|| format!("no material {name} in this scene"))?;
    match &mut m.material {
        MaterialDesc::Diffuse { albedo } | MaterialDesc::Plastic { albedo, .. } => {
            *albedo *= factor
        }
        MaterialDesc::Conductor {
            fresnel: FresnelDesc::Reflectance(r),
            ..
        } => *r *= factor,
        MaterialDesc::Conductor { .. } => {
            return Err(format!("conductor {name} has a complex IOR, no albedo"));
        }
        MaterialDesc::Dielectric { .. } | MaterialDesc::ThinDielectric { .. } => {
            return Err(format!("dielectric {name} has no albedo"));
        }
        MaterialDesc::Principled(p) => p.base_color *= factor,
        MaterialDesc::PrincipledThin(p) => p.base_color *= factor,
        MaterialDesc::GltfPbr(p) => p.base_color *= factor,
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_mutant_and_rejects_typos() {
        assert_eq!(parse("").unwrap(), Mutant::None);
        assert_eq!(parse("emission:3").unwrap(), Mutant::Emission(3));
        assert_eq!(parse("emission_all:1.1").unwrap(), Mutant::EmissionAll(1.1));
        assert_eq!(parse("albedo:red").unwrap(), Mutant::Albedo("red".into()));
        assert_eq!(parse("light_pdf:disk").unwrap(), Mutant::LightPdf(3));
        assert_eq!(parse("bsdf_pdf:plastic").unwrap(), Mutant::BsdfPdf(2));
        assert_eq!(parse("plastic_eval").unwrap(), Mutant::PlasticEval);
        for bad in [
            "emision:3",
            "light_pdf:disc",
            "emission:x",
            "albedo",
            "plastic_eval:1",
        ] {
            assert!(parse(bad).is_err(), "{bad}");
        }
    }

    #[cfg(not(feature = "mutants"))]
    #[test]
    fn without_the_feature_every_factor_is_one() {
        for t in 0..6 {
            assert_eq!(light_pdf(t), 1.0);
        }
        for t in 0..3 {
            assert_eq!(bsdf_pdf(t), 1.0);
        }
        assert_eq!(plastic_eval(), 1.0);
    }
}
