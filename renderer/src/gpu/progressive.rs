//! [`GpuProgressive`]: the GPU twin of [`crate::engine::Progressive`].
//!
//! Each dispatch renders up to [`GpuProgressive::samples_per_dispatch`] samples per pixel (its z
//! layers, folded into the accumulation in sample order by a second small dispatch, so the image
//! does not depend on the layering), all dispatches of a `render_pass` call in one submission;
//! per-dispatch parameters sit in one uniform buffer at 256-byte dynamic offsets. The
//! accumulation stays on the GPU in f32: the running mean, Welford's M2 and the mean of the
//! even-numbered samples, from which [`GpuProgressive::film`] rebuilds the CPU's Σx, Σx² and
//! even-sample sums (Welford's update keeps the variance accurate where plain f32 sums of x²
//! would cancel).
//!
//! [`Strategy::MisOptimal`] adds five planes per pixel after those three (its moments and the
//! α of its current stage, `gpu/film.wgsl`), and three scratch planes per sample of a multi-sample
//! dispatch for the moments `fold` adds in order; dispatches are split where a stage starts
//! ([`crate::integrator::optimal::is_stage_start`]), so that α is solved once per stage from the
//! moments of the samples before it, as on the CPU.

use super::scene::{GpuParams, GpuScene, PARAMS_STRIDE};
use super::shader::{create_module, path_tracer_source};
use super::{GpuContext, GpuError};
use crate::engine::{Film, PixelSums};
use crate::integrator::optimal::{FIRST_STAGE, stage_start};
use crate::integrator::{Settings, Strategy};
use crate::scene::Scene;
use std::sync::Arc;

/// Dispatches recorded per submission (the uniform buffer holds this many parameter slots).
const DISPATCHES_PER_SUBMIT: u32 = 64;

/// The workgroup of the render kernel (`@workgroup_size(8, 8, 1)` in `gpu/film.wgsl`).
const TILE: u32 = 8;

/// Threads a dispatch should have to fill a large GPU (an H100 holds 132 × 2048): images with
/// fewer pixels render several samples per dispatch. At 256² one sample per dispatch ran at 0.65×
/// the samples/s of 1024² there.
const TARGET_THREADS: u64 = 1 << 18;

/// Most samples per dispatch (each needs a scratch plane of the image).
const MAX_SAMPLES_PER_DISPATCH: u32 = 8;

/// The path tracer's entry points, compiled from one module: `render` (the samples) and `fold`
/// (adds a multi-sample dispatch's samples to the accumulation).
#[derive(Clone, Debug)]
pub struct PathPipelines {
    /// `gpu/film.wgsl`'s `render`.
    pub render: wgpu::ComputePipeline,
    /// `gpu/film.wgsl`'s `fold`.
    pub fold: wgpu::ComputePipeline,
}

/// Where the accumulated image lives on the GPU, for showing it without a readback.
#[derive(Clone, Copy, Debug)]
pub struct AccumulationView<'a> {
    /// The buffer: three planes of `width·height` `vec4<f32>` (16 bytes each, row-major, row 0 at
    /// the top): the running mean (the image, rgb + unused w), Welford's M2, and the mean of the
    /// even-numbered samples (scratch planes of multi-sample dispatches may follow).
    pub buffer: &'a wgpu::Buffer,
    /// Byte offset of the mean plane (0), so a display shader can bind just that range.
    pub mean_offset: u64,
    /// Bytes per plane.
    pub plane_size: u64,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Samples per pixel accumulated so far.
    pub spp: u32,
}

/// A progressive render on the GPU.
pub struct GpuProgressive {
    gpu: GpuScene,
    settings: Settings,
    seed: u32,
    spp: u32,
    pipelines: PathPipelines,
    samples_per_dispatch: u32,
    params: wgpu::Buffer,
    accum: wgpu::Buffer,
    counters: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

impl GpuProgressive {
    /// A new, empty render on the default adapter ([`GpuError::NoAdapter`] when there is none).
    pub fn new(
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
    ) -> Result<GpuProgressive, GpuError> {
        GpuProgressive::with_context(GpuContext::new()?, scene, settings, seed)
    }

    /// A new, empty render on an existing device (the viewer's, or one shared by tests).
    pub fn with_context(
        ctx: Arc<GpuContext>,
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
    ) -> Result<GpuProgressive, GpuError> {
        GpuProgressive::with_context_and_bvh2(ctx, scene, settings, seed, false)
    }

    /// As [`GpuProgressive::with_context`], traversing a BVH2 instead of the CWBVH when `bvh2`
    /// is set (see [`GpuScene::with_bvh2`]): for measuring the two, same estimator and image.
    pub fn with_context_and_bvh2(
        ctx: Arc<GpuContext>,
        scene: Arc<Scene>,
        settings: Settings,
        seed: u32,
        bvh2: bool,
    ) -> Result<GpuProgressive, GpuError> {
        GpuProgressive::from_scene(GpuScene::with_bvh2(ctx, scene, bvh2)?, settings, seed)
    }

    /// A new, empty render of an uploaded scene.
    pub(crate) fn from_scene(
        gpu: GpuScene,
        settings: Settings,
        seed: u32,
    ) -> Result<GpuProgressive, GpuError> {
        let ctx = gpu.context().clone();
        let device = &ctx.device;
        let source = path_tracer_source(&gpu.features())?;
        let pipelines = ctx.pipeline(&source, || {
            let module = create_module(device, "lumis path tracer", &source)?;
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("lumis path tracer"),
                bind_group_layouts: &[Some(gpu.layout())],
                immediate_size: 0,
            });
            let entry = |name: &str| {
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("lumis path tracer"),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some(name),
                    compilation_options: Default::default(),
                    cache: None,
                })
            };
            Ok(PathPipelines {
                render: entry("render"),
                fold: entry("fold"),
            })
        })?;
        let cam = &gpu.scene().camera;
        let pixels = cam.width as u64 * cam.height as u64;
        let optimal = settings.strategy == Strategy::MisOptimal;
        check_fits(device, cam.width, cam.height, optimal)?;
        // A CPU adapter (lavapipe) has no occupancy to fill, but each dispatch ends in a wait for
        // its slowest workgroup: 4 samples per dispatch rendered `gpu/images.rs`'s Veach scene
        // in 19.3 s against 23.8 s at 1 and 20.2 s at 16, the same film bit for bit (2026-12-07).
        let samples_per_dispatch = match ctx.adapter_info.device_type {
            wgpu::DeviceType::Cpu => 4,
            _ => TARGET_THREADS.div_ceil(pixels.max(1)) as u32,
        };
        let samples_per_dispatch =
            fitting_samples_per_dispatch(device, pixels, samples_per_dispatch, optimal);
        let accum = create_accumulation(device, accum_bytes(pixels, samples_per_dispatch, optimal));
        let counters = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lumis counters"),
            size: 16,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lumis params"),
            size: PARAMS_STRIDE * DISPATCHES_PER_SUBMIT as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = gpu.bind_group(&params, &accum, &counters);
        let mut r = GpuProgressive {
            gpu,
            settings,
            seed,
            spp: 0,
            pipelines,
            samples_per_dispatch,
            params,
            accum,
            counters,
            bind_group,
        };
        r.clear();
        Ok(r)
    }

    /// Samples per pixel that one dispatch renders (1 on CPU adapters and for large images).
    pub fn samples_per_dispatch(&self) -> u32 {
        self.samples_per_dispatch
    }

    /// Renders `k` samples per dispatch from now on (clamped to 1…8 and to what the device can
    /// hold) and restarts the accumulation. The image does not depend on `k`; this is for tests
    /// and measurements.
    pub fn set_samples_per_dispatch(&mut self, k: u32) {
        let ctx = self.gpu.context().clone();
        let cam = &self.gpu.scene().camera;
        let pixels = cam.width as u64 * cam.height as u64;
        let optimal = self.optimal();
        self.samples_per_dispatch = fitting_samples_per_dispatch(&ctx.device, pixels, k, optimal);
        self.grow_accumulation();
        self.clear();
    }

    /// Whether the settings are [`Strategy::MisOptimal`]'s (more planes, split dispatches).
    fn optimal(&self) -> bool {
        self.settings.strategy == Strategy::MisOptimal
    }

    /// Makes the accumulation buffer as large as the settings and samples per dispatch need.
    fn grow_accumulation(&mut self) {
        let ctx = self.gpu.context().clone();
        let cam = &self.gpu.scene().camera;
        let pixels = cam.width as u64 * cam.height as u64;
        let size = accum_bytes(pixels, self.samples_per_dispatch, self.optimal());
        if size > self.accum.size() {
            self.accum = create_accumulation(&ctx.device, size);
            self.bind_group = self
                .gpu
                .bind_group(&self.params, &self.accum, &self.counters);
        }
    }

    fn clear(&mut self) {
        let mut encoder = self
            .gpu
            .context()
            .device
            .create_command_encoder(&Default::default());
        encoder.clear_buffer(&self.accum, 0, None);
        encoder.clear_buffer(&self.counters, 0, None);
        self.gpu.context().queue.submit([encoder.finish()]);
        self.spp = 0;
    }

    /// The scene.
    pub fn scene(&self) -> &Arc<Scene> {
        self.gpu.scene()
    }

    /// The settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The device.
    pub fn context(&self) -> &Arc<GpuContext> {
        self.gpu.context()
    }

    /// Samples per pixel accumulated so far.
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// Drops the accumulation and starts over with new settings (same scene and seed). The
    /// program does not depend on the settings (the sampler too is a parameter), so nothing is
    /// recompiled. [`GpuError::TooLarge`] (and nothing changed) where the settings need more
    /// memory than a binding holds ([`Strategy::MisOptimal`]'s planes).
    pub fn restart(&mut self, settings: Settings) -> Result<(), GpuError> {
        let ctx = self.gpu.context().clone();
        let cam = &self.gpu.scene().camera;
        let pixels = cam.width as u64 * cam.height as u64;
        let optimal = settings.strategy == Strategy::MisOptimal;
        check_fits(&ctx.device, cam.width, cam.height, optimal)?;
        self.samples_per_dispatch =
            fitting_samples_per_dispatch(&ctx.device, pixels, self.samples_per_dispatch, optimal);
        self.settings = settings;
        self.grow_accumulation();
        self.clear();
        Ok(())
    }

    /// Renders `n` more samples per pixel and waits for them. Always `true` (the CPU's `false`
    /// means cancelled; a GPU pass is not cancellable once submitted).
    pub fn render_pass(&mut self, n: u32) -> bool {
        let ctx = self.gpu.context().clone();
        let cam = &self.gpu.scene().camera;
        let groups = (cam.width.div_ceil(TILE), cam.height.div_ceil(TILE));
        let mut done = 0;
        while done < n {
            // One parameter slot per dispatch; each dispatch takes up to k samples.
            let mut slots = Vec::new();
            let mut layers = Vec::new();
            while done < n && layers.len() < DISPATCHES_PER_SUBMIT as usize {
                let mut k = (n - done).min(self.samples_per_dispatch);
                if self.optimal() {
                    // No dispatch runs across the start of a stage (its α comes from the samples
                    // before it).
                    k = k.min(next_stage_start(self.spp + done) - (self.spp + done));
                }
                let mut p: GpuParams = self.gpu.params(&self.settings, self.seed, self.spp + done);
                p.samples_per_dispatch = k;
                slots.resize(PARAMS_STRIDE as usize * layers.len(), 0u8);
                slots.extend_from_slice(bytemuck::bytes_of(&p));
                layers.push(k);
                done += k;
            }
            ctx.queue.write_buffer(&self.params, 0, &slots);
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("lumis samples"),
                    timestamp_writes: None,
                });
                for (i, &k) in layers.iter().enumerate() {
                    pass.set_bind_group(0, &self.bind_group, &[(PARAMS_STRIDE * i as u64) as u32]);
                    pass.set_pipeline(&self.pipelines.render);
                    pass.dispatch_workgroups(groups.0, groups.1, k);
                    if k > 1 {
                        pass.set_pipeline(&self.pipelines.fold);
                        pass.dispatch_workgroups(groups.0, groups.1, 1);
                    }
                }
            }
            ctx.queue.submit([encoder.finish()]);
        }
        // Wait, so that timings mean something and a following `film` sees the samples.
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        self.spp += n;
        true
    }

    /// Where the accumulation lives, for display without readback.
    pub fn accumulation(&self) -> AccumulationView<'_> {
        let cam = &self.gpu.scene().camera;
        AccumulationView {
            buffer: &self.accum,
            mean_offset: 0,
            plane_size: cam.width as u64 * cam.height as u64 * 16,
            width: cam.width,
            height: cam.height,
            spp: self.spp,
        }
    }

    /// Reads the accumulation back into a [`Film`] (the CPU's sums, in f64), so every CPU metric
    /// and statistical test applies.
    pub fn film(&self) -> Result<Film, GpuError> {
        let ctx = self.gpu.context();
        let cam = &self.gpu.scene().camera;
        let (w, h) = (cam.width, cam.height);
        let pixels = (w * h) as usize;
        let bytes = ctx.read_buffer(&self.accum, 3 * pixels as u64 * 16)?;
        let planes: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
        let counters = ctx.read_buffer(&self.counters, 16)?;
        let nonfinite = bytemuck::cast_slice::<u8, u32>(&counters)[0] as u64;
        let n = self.spp as f64;
        let n_even = self.spp.div_ceil(2) as f64;
        let mut film = Film::new(w, h);
        film.spp = self.spp;
        film.nonfinite = nonfinite;
        for (i, px) in film.pixels.iter_mut().enumerate() {
            let (mean, m2, even) = (planes[i], planes[pixels + i], planes[2 * pixels + i]);
            *px = PixelSums {
                sum: std::array::from_fn(|c| mean[c] as f64 * n),
                sum_sq: std::array::from_fn(|c| m2[c] as f64 + n * (mean[c] as f64).powi(2)),
                sum_even: std::array::from_fn(|c| even[c] as f64 * n_even),
            };
        }
        Ok(film)
    }
}

/// Planes of [`Strategy::MisOptimal`]'s state (`OPT_PLANES` in `gpu/film.wgsl`).
const OPTIMAL_PLANES: u64 = 5;

/// Bytes of the accumulation buffer: three planes of `vec4<f32>` per pixel, mis-optimal's
/// [`OPTIMAL_PLANES`] (`optimal`), and scratch planes when a dispatch renders more than one
/// sample: one per sample (four with mis-optimal's moments).
fn accum_bytes(pixels: u64, samples_per_dispatch: u32, optimal: bool) -> u64 {
    let per_sample = if optimal { 4 } else { 1 };
    let scratch = if samples_per_dispatch > 1 {
        per_sample * samples_per_dispatch as u64
    } else {
        0
    };
    let state = if optimal { OPTIMAL_PLANES } else { 0 };
    (3 + state + scratch) * pixels * 16
}

/// [`GpuError::TooLarge`] where one sample per dispatch does not fit a storage binding.
fn check_fits(
    device: &wgpu::Device,
    width: u32,
    height: u32,
    optimal: bool,
) -> Result<(), GpuError> {
    let bytes = accum_bytes(width as u64 * height as u64, 1, optimal);
    let max = device.limits().max_storage_buffer_binding_size;
    if bytes > max {
        let why = if optimal {
            " (mis-optimal keeps 128 bytes per pixel)"
        } else {
            ""
        };
        return Err(GpuError::TooLarge(format!(
            "the {width}x{height} accumulation buffer takes {bytes} bytes, more than the device's \
             {max}-byte storage binding{why}"
        )));
    }
    Ok(())
}

/// The first sample after `s` where a mis-optimal stage starts.
fn next_stage_start(s: u32) -> u32 {
    if s < FIRST_STAGE {
        FIRST_STAGE
    } else {
        stage_start(s).saturating_mul(2)
    }
}

/// `k` clamped to 1…[`MAX_SAMPLES_PER_DISPATCH`] and to what one storage binding can hold.
fn fitting_samples_per_dispatch(device: &wgpu::Device, pixels: u64, k: u32, optimal: bool) -> u32 {
    let max_size = device.limits().max_storage_buffer_binding_size;
    let mut k = k.clamp(1, MAX_SAMPLES_PER_DISPATCH);
    while k > 1 && accum_bytes(pixels, k, optimal) > max_size {
        k -= 1;
    }
    k
}

fn create_accumulation(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("lumis accumulation"),
        size,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_SRC
            | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::scene::{LightTag, MaterialTag, Records, ShapeTag};
    use crate::scene::parse_scene;

    /// A diffuse box lit by a quad light, small enough to render in a moment.
    fn scene() -> Arc<Scene> {
        let json = r#"{
          "camera": {"from": [0, 1, -3], "to": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 60, "width": 8, "height": 8},
          "materials": {"d": {"type": "diffuse", "albedo": [0.6, 0.6, 0.6]}},
          "shapes": [
            {"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0], "material": "d"},
            {"type": "quad", "corner": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 3, 0], "material": "d"},
            {"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [5, 5, 5]}
          ]
        }"#;
        Arc::new(Scene::from_desc(&parse_scene(json).unwrap()).unwrap())
    }

    /// Non-finite samples of a 2 spp render of `scene()` with `corrupt` applied to its records.
    fn nonfinite(ctx: &Arc<GpuContext>, corrupt: impl FnOnce(&mut Records)) -> u64 {
        nonfinite_of(scene(), ctx, corrupt)
    }

    /// [`nonfinite`] for `scene`.
    fn nonfinite_of(
        scene: Arc<Scene>,
        ctx: &Arc<GpuContext>,
        corrupt: impl FnOnce(&mut Records),
    ) -> u64 {
        let mut records = Records::of(&scene);
        corrupt(&mut records);
        let gpu = GpuScene::upload(ctx.clone(), scene, false, records).unwrap();
        let mut r = GpuProgressive::from_scene(gpu, Settings::default(), 1).unwrap();
        r.render_pass(2);
        r.film().unwrap().nonfinite
    }

    /// A record with a tag no WGSL `switch` knows makes its samples NaN, which the film counts,
    /// instead of contributing nothing unnoticed.
    #[test]
    fn unknown_tags_are_counted_as_nonfinite_samples() {
        let Some(ctx) = GpuContext::for_tests() else {
            return;
        };
        assert_eq!(nonfinite(&ctx, |_| {}), 0);
        let bad_material = MaterialTag::ALL.len() as u32;
        let bad_light = LightTag::ALL.len() as u32;
        let bad_shape = f32::from_bits(ShapeTag::ALL.len() as u32);
        let pixels = 64;
        // Every camera ray meets the floor or the wall (material 0).
        let n = nonfinite(&ctx, |r| r.materials[0].h[0] = bad_material);
        assert!(n > pixels, "material: {n}");
        // Light sampling from every lit point picks the one light.
        let n = nonfinite(&ctx, |r| r.lights[0].h[0] = bad_light);
        assert!(n > pixels / 2, "light: {n}");
        // The floor's first triangle.
        let n = nonfinite(&ctx, |r| r.prims[0].a[3] = bad_shape);
        assert!(n > 0, "shape: {n}");
    }

    /// The same for texture records: an unknown kind, wrap mode or channel in the textures of a
    /// conductor's reflectance and α (a 2×2 bitmap) makes the samples that read them NaN.
    #[test]
    fn unknown_texture_tags_are_counted_as_nonfinite_samples() {
        use crate::gpu::scene::{ChannelTag, TextureTag, WrapTag};
        use crate::materials::textured::MaterialTextures;
        use crate::textures::{BitmapOptions, BitmapTexture, Channel, Texture, WrapMode};
        let Some(ctx) = GpuContext::for_tests() else {
            return;
        };
        let json = r#"{
          "camera": {"from": [0, 1, -3], "to": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 60, "width": 8, "height": 8},
          "materials": {"m": {"type": "conductor", "reflectance": [0.6, 0.6, 0.6], "alpha": 0.3}},
          "shapes": [
            {"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0], "material": "m"},
            {"type": "quad", "corner": [-2, 0, 2], "edge_u": [4, 0, 0], "edge_v": [0, 3, 0], "material": "m"},
            {"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [5, 5, 5]}
          ]
        }"#;
        let mut scene = Scene::from_desc(&parse_scene(json).unwrap()).unwrap();
        let image = Arc::new(crate::image_io::Image {
            width: 2,
            height: 2,
            data: vec![glam::Vec3::new(0.2, 0.4, 0.6); 4],
        });
        let bitmap = |channel| {
            let options = BitmapOptions {
                wrap: WrapMode::Mirror,
                channel,
                ..BitmapOptions::default()
            };
            Some(Texture::Bitmap(BitmapTexture::new(image.clone(), options)))
        };
        scene.material_textures[0] = Some(MaterialTextures {
            reflectance: bitmap(Channel::Luminance),
            alpha: bitmap(Channel::G),
            ..Default::default()
        });
        let scene = Arc::new(scene);
        let pixels = 64;
        assert_eq!(nonfinite_of(scene.clone(), &ctx, |_| {}), 0);
        // Record 0 is the reflectance's, record 1 the α's (4 vec4 each from `textures`).
        let bad = |n: usize| f32::from_bits(n as u32);
        let at = |r: &Records, record: usize, k: usize| (r.textures as usize + 4 * record, k);
        for (what, record, k, tag) in [
            ("kind", 0, 0, bad(TextureTag::ALL.len())),
            ("wrap", 0, 1, bad(WrapTag::ALL.len())),
            ("channel", 1, 2, bad(ChannelTag::ALL.len())),
        ] {
            let n = nonfinite_of(scene.clone(), &ctx, |r| {
                let (i, k) = at(r, record, k);
                r.vertex_data[i][k] = tag;
            });
            assert!(n > pixels, "texture {what}: {n}");
        }
    }
}
