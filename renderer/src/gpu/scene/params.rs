//! The per-dispatch uniform (`Params` in `bindings.wgsl`) and the tags of the settings it holds.
//! WGSL twin: `bindings.wgsl` (the uniform's layout).

use super::{GpuScene, v4};
use crate::geometry::primitive::NONE;
use crate::gpu::prelude::gpu_tags;
use crate::integrator::{Heuristic, Settings, Strategy};
use crate::lights::LightSampling;
use bytemuck::{Pod, Zeroable};

/// The per-sample uniform (`Params` in `bindings.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuParams {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Random seed.
    pub seed: u32,
    /// Sample index (the CPU's `s`).
    pub sample: u32,
    /// Strategy ([`StrategyTag`]).
    pub strategy: u32,
    /// Heuristic ([`HeuristicTag`]).
    pub heuristic: u32,
    /// Light sampling ([`LightSamplingTag`]).
    pub light_sampling: u32,
    /// Maximum path length (−1 unlimited).
    pub max_depth: i32,
    /// Russian roulette starts at this many segments.
    pub rr_depth: u32,
    /// Number of lights.
    pub n_lights: u32,
    /// Background light index or `NONE`.
    pub background: u32,
    /// Offset of the light-selection CDF in the tables, or `NONE`.
    pub light_cdf: u32,
    /// Offset of the light-selection pmf in the tables, or `NONE`.
    pub light_pmf: u32,
    /// The mixture's light-sampling probability.
    pub mix_weight: f32,
    /// Samples of one dispatch (its z layers), from `sample` on; see `GpuProgressive`.
    pub samples_per_dispatch: u32,
    /// Where the texture records start in the vertex data (`gpu/scene/textures.rs`).
    pub textures: u32,
    /// Camera origin; w = tan of the half horizontal field of view.
    pub cam_origin: [f32; 4],
    /// Camera forward axis; w = tan of the half vertical field of view.
    pub cam_forward: [f32; 4],
    /// Camera right axis.
    pub cam_right: [f32; 4],
    /// Camera up axis.
    pub cam_up: [f32; 4],
    /// Where the mesh attribute arrays start in the vertex data (`gpu/scene/attributes.rs`).
    pub attr: [u32; 4],
}

/// Uniform slots are this far apart (the largest `min_uniform_buffer_offset_alignment` wgpu
/// allows), so one buffer holds the parameters of many dispatches.
pub const PARAMS_STRIDE: u64 = 256;

gpu_tags! {
    /// [`GpuParams::strategy`], in the variant order of [`Strategy`].
    pub enum StrategyTag {
        /// [`Strategy::Light`].
        Light => "STRATEGY_LIGHT",
        /// [`Strategy::Bsdf`].
        Bsdf => "STRATEGY_BSDF",
        /// [`Strategy::Mixture`].
        Mixture => "STRATEGY_MIXTURE",
        /// [`Strategy::Mis`].
        Mis => "STRATEGY_MIS",
    }
}

gpu_tags! {
    /// [`GpuParams::heuristic`], in the variant order of [`Heuristic`].
    pub enum HeuristicTag {
        /// [`Heuristic::Balance`].
        Balance => "HEURISTIC_BALANCE",
        /// [`Heuristic::Power`].
        Power => "HEURISTIC_POWER",
    }
}

impl HeuristicTag {
    /// The tag of `h`.
    pub fn of(h: Heuristic) -> HeuristicTag {
        match h {
            Heuristic::Balance => HeuristicTag::Balance,
            Heuristic::Power => HeuristicTag::Power,
        }
    }
}

gpu_tags! {
    /// [`GpuParams::light_sampling`], in the variant order of [`LightSampling`].
    pub enum LightSamplingTag {
        /// [`LightSampling::Area`].
        Area => "LIGHT_SAMPLING_AREA",
        /// [`LightSampling::SolidAngle`].
        SolidAngle => "LIGHT_SAMPLING_SOLID_ANGLE",
    }
}

impl LightSamplingTag {
    /// The tag of `m`.
    pub fn of(m: LightSampling) -> LightSamplingTag {
        match m {
            LightSampling::Area => LightSamplingTag::Area,
            LightSampling::SolidAngle => LightSamplingTag::SolidAngle,
        }
    }
}

impl GpuScene {
    /// The uniform for sample `sample` of a render with `settings` and `seed`.
    pub fn params(&self, settings: &Settings, seed: u32, sample: u32) -> GpuParams {
        let scene = self.scene();
        let cam = &scene.camera;
        let (forward, right, up, tan_x, tan_y) = cam.basis();
        // The heuristic matters only to MIS; the others send the default's tag.
        let balance = HeuristicTag::Balance;
        let (strategy, heuristic, mix_weight) = match settings.strategy {
            Strategy::Light => (StrategyTag::Light, balance, 1.0),
            Strategy::Bsdf => (StrategyTag::Bsdf, balance, 0.0),
            Strategy::Mixture { light_weight } => (StrategyTag::Mixture, balance, light_weight),
            Strategy::Mis { heuristic } => (StrategyTag::Mis, HeuristicTag::of(heuristic), 0.0),
        };
        GpuParams {
            width: cam.width,
            height: cam.height,
            seed,
            sample,
            strategy: strategy.gpu_tag(),
            heuristic: heuristic.gpu_tag(),
            light_sampling: LightSamplingTag::of(settings.light_sampling).gpu_tag(),
            max_depth: settings.max_depth.unwrap_or(scene.max_depth),
            rr_depth: settings.rr_depth,
            n_lights: scene.lights.len() as u32,
            background: scene.background_light.unwrap_or(NONE),
            light_cdf: self.light_cdf,
            light_pmf: self.light_pmf,
            mix_weight,
            samples_per_dispatch: 1,
            textures: self.textures,
            cam_origin: v4(cam.origin, tan_x),
            cam_forward: v4(forward, tan_y),
            cam_right: v4(right, 0.0),
            cam_up: v4(up, 0.0),
            attr: self.attr,
        }
    }
}
