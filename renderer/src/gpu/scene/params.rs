//! The per-dispatch uniform (`Params` in `gpu/bindings.wgsl`) and the tags of the settings it holds.
//! WGSL twin: `gpu/bindings.wgsl` (the uniform's layout).

use super::{GpuScene, v4};
use crate::camera::{PixelFilter, Projection};
use crate::geometry::primitive::NONE;
use crate::gpu::prelude::gpu_tags;
use crate::integrator::{Heuristic, Settings, Strategy};
use crate::lights::{LightSampling, LightSelection};
use crate::sampler::SamplerKind;
use bytemuck::{Pod, Zeroable};

/// The per-sample uniform (`Params` in `gpu/bindings.wgsl`).
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
    /// Camera origin; w = the film's horizontal half-extent ([`crate::camera::Camera::basis`]).
    pub cam_origin: [f32; 4],
    /// Camera forward axis; w = the film's vertical half-extent.
    pub cam_forward: [f32; 4],
    /// Camera right axis; w = the thin lens's aperture radius (0 for other projections).
    pub cam_right: [f32; 4],
    /// Camera up axis; w = the thin lens's focus distance (0 for other projections).
    pub cam_up: [f32; 4],
    /// The principal point offset in pixels in x, y ([`crate::camera::Camera::shift`]).
    pub cam_shift: [f32; 4],
    /// Where the mesh attribute arrays start in the vertex data (`gpu/scene/attributes.rs`).
    pub attr: [u32; 4],
    /// The camera's pixel filter ([`FilterTag`]).
    pub pixel_filter: u32,
    /// The gaussian filter's standard deviation in pixels (0 for the box).
    pub filter_stddev: f32,
    /// The filter's support half-width in pixels ([`PixelFilter::radius`]).
    pub filter_radius: f32,
    /// The sampler ([`SamplerTag`]). A uniform like the strategy rather than a specialisation:
    /// switching samplers (the viewer) then needs no new pipeline, and the one `switch` per draw
    /// in `sampler/mod.wgsl` is cheap next to the Sobol draw itself. It also takes the slot that
    /// rounded the struct to a multiple of 16 bytes, so the size is unchanged.
    pub sampler: u32,
    /// Light selection ([`LightSelectionTag`]).
    pub light_selection: u32,
    /// Offset of the light BVH in the tables (`LightBvh::append_tables`), or `NONE`.
    pub light_bvh: u32,
    /// 1 when camera rays do not see emitters ([`crate::scene::Scene::hide_emitters`]).
    pub hide_emitters: u32,
    /// The camera's projection ([`CameraTag`]); it took the slot that rounded the struct to 16
    /// bytes, so the size is unchanged.
    pub camera: u32,
    /// A Mitchell filter's B and C (then 0, 0); zeros for other filters.
    pub filter_shape: [f32; 4],
    /// A Mitchell filter's piece ends on `[0, 2]` (`PixelFilter::Mitchell::breaks`); zeros for
    /// other filters.
    pub filter_breaks: [[f32; 4]; 2],
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
        /// [`Strategy::MisOptimal`].
        MisOptimal => "STRATEGY_MIS_OPTIMAL",
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
        /// [`LightSampling::SolidAngleCosine`].
        SolidAngleCosine => "LIGHT_SAMPLING_SOLID_ANGLE_COSINE",
        /// [`LightSampling::Adaptive`].
        Adaptive => "LIGHT_SAMPLING_ADAPTIVE",
        /// [`LightSampling::ProjectedSolidAngle`].
        ProjectedSolidAngle => "LIGHT_SAMPLING_PROJECTED_SOLID_ANGLE",
    }
}

impl LightSamplingTag {
    /// The tag of `m`.
    pub fn of(m: LightSampling) -> LightSamplingTag {
        match m {
            LightSampling::Area => LightSamplingTag::Area,
            LightSampling::SolidAngle => LightSamplingTag::SolidAngle,
            LightSampling::SolidAngleCosine => LightSamplingTag::SolidAngleCosine,
            LightSampling::Adaptive => LightSamplingTag::Adaptive,
            LightSampling::ProjectedSolidAngle => LightSamplingTag::ProjectedSolidAngle,
        }
    }
}

gpu_tags! {
    /// [`GpuParams::light_selection`], in the variant order of [`LightSelection`].
    pub enum LightSelectionTag {
        /// [`LightSelection::Power`].
        Power => "LIGHT_SELECTION_POWER",
        /// [`LightSelection::Bvh`].
        Bvh => "LIGHT_SELECTION_BVH",
    }
}

impl LightSelectionTag {
    /// The tag of `s`.
    pub fn of(s: LightSelection) -> LightSelectionTag {
        match s {
            LightSelection::Power => LightSelectionTag::Power,
            LightSelection::Bvh => LightSelectionTag::Bvh,
        }
    }
}

gpu_tags! {
    /// [`GpuParams::sampler`], in the variant order of [`SamplerKind`].
    pub enum SamplerTag {
        /// [`SamplerKind::Independent`].
        Independent => "SAMPLER_INDEPENDENT",
        /// [`SamplerKind::Sobol`].
        Sobol => "SAMPLER_SOBOL",
    }
}

impl SamplerTag {
    /// The tag of `k`.
    pub fn of(k: SamplerKind) -> SamplerTag {
        match k {
            SamplerKind::Independent => SamplerTag::Independent,
            SamplerKind::Sobol => SamplerTag::Sobol,
        }
    }
}

gpu_tags! {
    /// [`GpuParams::pixel_filter`], in the variant order of [`PixelFilter`].
    pub enum FilterTag {
        /// [`PixelFilter::Box`].
        Box => "FILTER_BOX",
        /// [`PixelFilter::Gaussian`].
        Gaussian => "FILTER_GAUSSIAN",
        /// [`PixelFilter::Tent`].
        Tent => "FILTER_TENT",
        /// [`PixelFilter::Lanczos`].
        Lanczos => "FILTER_LANCZOS",
        /// [`PixelFilter::Mitchell`].
        Mitchell => "FILTER_MITCHELL",
    }
}

impl FilterTag {
    /// The tag of `f` and its (σ, radius): σ is 0 (unused) but for the gaussian.
    pub fn of(f: PixelFilter) -> (FilterTag, f32, f32) {
        match f {
            PixelFilter::Box => (FilterTag::Box, 0.0, f.radius()),
            PixelFilter::Gaussian { stddev, radius } => (FilterTag::Gaussian, stddev, radius),
            PixelFilter::Tent { radius } => (FilterTag::Tent, 0.0, radius),
            PixelFilter::Lanczos { .. } => (FilterTag::Lanczos, 0.0, f.radius()),
            PixelFilter::Mitchell { .. } => (FilterTag::Mitchell, 0.0, f.radius()),
        }
    }

    /// A Mitchell filter's `(B, C, 0, 0)` and piece ends as two vec4s (`GpuParams::filter_shape`,
    /// `filter_breaks`); zeros for the others.
    pub fn shape(f: PixelFilter) -> ([f32; 4], [[f32; 4]; 2]) {
        match f {
            PixelFilter::Mitchell { b, c, breaks } => (
                [b, c, 0.0, 0.0],
                [
                    [breaks[0], breaks[1], breaks[2], breaks[3]],
                    [breaks[4], breaks[5], breaks[6], breaks[7]],
                ],
            ),
            _ => ([0.0; 4], [[0.0; 4]; 2]),
        }
    }
}

gpu_tags! {
    /// [`GpuParams::camera`], in the variant order of [`Projection`].
    pub enum CameraTag {
        /// [`Projection::Perspective`].
        Perspective => "CAMERA_PERSPECTIVE",
        /// [`Projection::ThinLens`].
        ThinLens => "CAMERA_THIN_LENS",
        /// [`Projection::Orthographic`].
        Orthographic => "CAMERA_ORTHOGRAPHIC",
    }
}

impl CameraTag {
    /// The tag of `p` and its (aperture radius, focus distance), 0 for what has no lens.
    pub fn of(p: Projection) -> (CameraTag, f32, f32) {
        match p {
            Projection::Perspective => (CameraTag::Perspective, 0.0, 0.0),
            Projection::ThinLens {
                aperture_radius,
                focus_distance,
            } => (CameraTag::ThinLens, aperture_radius, focus_distance),
            Projection::Orthographic => (CameraTag::Orthographic, 0.0, 0.0),
        }
    }
}

impl GpuScene {
    /// The uniform for sample `sample` of a render with `settings` and `seed`.
    pub fn params(&self, settings: &Settings, seed: u32, sample: u32) -> GpuParams {
        let scene = self.scene();
        let cam = &scene.camera;
        let (forward, right, up, half_x, half_y) = cam.basis();
        let (camera, aperture_radius, focus_distance) = CameraTag::of(cam.projection);
        // The heuristic matters only to MIS; the others send the default's tag.
        let balance = HeuristicTag::Balance;
        let (strategy, heuristic, mix_weight) = match settings.strategy {
            Strategy::Light => (StrategyTag::Light, balance, 1.0),
            Strategy::Bsdf => (StrategyTag::Bsdf, balance, 0.0),
            Strategy::Mixture { light_weight } => (StrategyTag::Mixture, balance, light_weight),
            Strategy::Mis { heuristic } => (StrategyTag::Mis, HeuristicTag::of(heuristic), 0.0),
            Strategy::MisOptimal => (StrategyTag::MisOptimal, balance, 0.0),
        };
        let (filter, filter_stddev, filter_radius) = FilterTag::of(cam.filter);
        let (filter_shape, filter_breaks) = FilterTag::shape(cam.filter);
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
            cam_origin: v4(cam.origin, half_x),
            cam_forward: v4(forward, half_y),
            cam_right: v4(right, aperture_radius),
            cam_up: v4(up, focus_distance),
            cam_shift: {
                let s = cam.shift();
                [s.x, s.y, 0.0, 0.0]
            },
            attr: self.attr,
            pixel_filter: filter.gpu_tag(),
            filter_stddev,
            filter_radius,
            sampler: SamplerTag::of(settings.sampler).gpu_tag(),
            light_selection: LightSelectionTag::of(settings.light_selection).gpu_tag(),
            light_bvh: self.light_bvh,
            hide_emitters: u32::from(scene.hide_emitters),
            camera: camera.gpu_tag(),
            filter_shape,
            filter_breaks,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::shader::{Features, path_tracer_source};
    use std::mem::offset_of;
    use wgpu::naga;

    /// `GpuParams` is `Params` byte for byte: the same size as naga lays the WGSL struct out and
    /// every member at the offset WGSL gives it, within [`PARAMS_STRIDE`]. Catches a member added
    /// on one side only or in another order, and a size that is not the struct's (deliberate bug
    /// tried: `filter_stddev` and `filter_radius` swapped in `GpuParams`: failed, offsets 152 and
    /// 148 against WGSL's 148 and 152).
    #[test]
    fn gpu_params_has_the_wgsl_layout() {
        let src = path_tracer_source(&Features::default()).unwrap();
        let module = naga::front::wgsl::parse_str(&src).unwrap_or_else(|e| panic!("{e}"));
        let ty = module
            .types
            .iter()
            .map(|(_, t)| t)
            .find(|t| t.name.as_deref() == Some("Params"))
            .expect("Params");
        let naga::TypeInner::Struct { members, span } = &ty.inner else {
            panic!("Params is not a struct");
        };
        assert_eq!(*span as usize, size_of::<GpuParams>());
        assert!(size_of::<GpuParams>() as u64 <= PARAMS_STRIDE);
        let rust = [
            ("width", offset_of!(GpuParams, width)),
            ("height", offset_of!(GpuParams, height)),
            ("seed", offset_of!(GpuParams, seed)),
            ("sample", offset_of!(GpuParams, sample)),
            ("strategy", offset_of!(GpuParams, strategy)),
            ("heuristic", offset_of!(GpuParams, heuristic)),
            ("light_sampling", offset_of!(GpuParams, light_sampling)),
            ("max_depth", offset_of!(GpuParams, max_depth)),
            ("rr_depth", offset_of!(GpuParams, rr_depth)),
            ("n_lights", offset_of!(GpuParams, n_lights)),
            ("background", offset_of!(GpuParams, background)),
            ("light_cdf", offset_of!(GpuParams, light_cdf)),
            ("light_pmf", offset_of!(GpuParams, light_pmf)),
            ("mix_weight", offset_of!(GpuParams, mix_weight)),
            (
                "samples_per_dispatch",
                offset_of!(GpuParams, samples_per_dispatch),
            ),
            ("textures", offset_of!(GpuParams, textures)),
            ("cam_origin", offset_of!(GpuParams, cam_origin)),
            ("cam_forward", offset_of!(GpuParams, cam_forward)),
            ("cam_right", offset_of!(GpuParams, cam_right)),
            ("cam_up", offset_of!(GpuParams, cam_up)),
            ("cam_shift", offset_of!(GpuParams, cam_shift)),
            ("attr", offset_of!(GpuParams, attr)),
            ("pixel_filter", offset_of!(GpuParams, pixel_filter)),
            ("filter_stddev", offset_of!(GpuParams, filter_stddev)),
            ("filter_radius", offset_of!(GpuParams, filter_radius)),
            ("sampler", offset_of!(GpuParams, sampler)),
            ("light_selection", offset_of!(GpuParams, light_selection)),
            ("light_bvh", offset_of!(GpuParams, light_bvh)),
            ("hide_emitters", offset_of!(GpuParams, hide_emitters)),
            ("camera", offset_of!(GpuParams, camera)),
            ("filter_shape", offset_of!(GpuParams, filter_shape)),
            ("filter_breaks", offset_of!(GpuParams, filter_breaks)),
        ];
        let wgsl: Vec<(&str, usize)> = members
            .iter()
            .map(|m| (m.name.as_deref().unwrap(), m.offset as usize))
            .collect();
        assert_eq!(wgsl, rust);
    }

    /// The sampler tags follow [`SamplerKind`]'s variant order (and the prelude's tags are
    /// consecutive from 0, `prelude.rs`), so `sampler/mod.wgsl`'s cases are `SamplerKind`'s.
    #[test]
    fn sampler_tags_follow_the_variant_order() {
        for (i, &(tag, _)) in SamplerTag::ALL.iter().enumerate() {
            let kind = [SamplerKind::Independent, SamplerKind::Sobol][i];
            assert_eq!(SamplerTag::of(kind), tag);
            assert_eq!(kind as u32, tag.gpu_tag());
        }
    }

    /// The light-selection tags follow [`LightSelection`]'s variant order, so the `switch`es of
    /// `lights/light_bvh.wgsl` are its `match`es.
    #[test]
    fn light_selection_tags_follow_the_variant_order() {
        for (i, &(tag, _)) in LightSelectionTag::ALL.iter().enumerate() {
            let s = [LightSelection::Power, LightSelection::Bvh][i];
            assert_eq!(LightSelectionTag::of(s), tag);
            assert_eq!(s as u32, tag.gpu_tag());
        }
    }
}
