//! [`GpuProgressive`]: the GPU twin of [`crate::engine::Progressive`].
//!
//! One dispatch per sample pass (one sample per pixel), all passes of a `render_pass` call in one
//! submission; per-sample parameters sit in one uniform buffer at 256-byte dynamic offsets. The
//! accumulation stays on the GPU in f32: the running mean, Welford's M2 and the mean of the
//! even-numbered samples, from which [`GpuProgressive::film`] rebuilds the CPU's Σx, Σx² and
//! even-sample sums (Welford's update keeps the variance accurate where plain f32 sums of x²
//! would cancel).

use super::scene_buffers::{GpuParams, GpuScene, PARAMS_STRIDE};
use super::shader::{create_module, path_tracer_source};
use super::{GpuContext, GpuError};
use crate::engine::{Film, PixelSums};
use crate::integrator::Settings;
use crate::scene::Scene;
use std::sync::Arc;

/// Sample passes recorded per submission (the uniform buffer holds this many parameter slots).
const PASSES_PER_SUBMIT: u32 = 64;

/// The workgroup of the render kernel (`@workgroup_size(8, 8, 1)` in `path.wgsl`).
const TILE: u32 = 8;

/// Where the accumulated image lives on the GPU, for showing it without a readback.
#[derive(Clone, Copy, Debug)]
pub struct AccumulationView<'a> {
    /// The buffer: three planes of `width·height` `vec4<f32>` (16 bytes each, row-major, row 0 at
    /// the top): the running mean (the image, rgb + unused w), Welford's M2, and the mean of the
    /// even-numbered samples.
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
    pipeline: wgpu::ComputePipeline,
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
        let gpu = GpuScene::with_bvh2(ctx.clone(), scene, bvh2)?;
        let device = &ctx.device;
        let source = path_tracer_source(&gpu.features())?;
        let pipeline = ctx.pipeline(&source, || {
            let module = create_module(device, "lumis path tracer", &source)?;
            let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("lumis path tracer"),
                bind_group_layouts: &[Some(gpu.layout())],
                immediate_size: 0,
            });
            Ok(
                device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("lumis path tracer"),
                    layout: Some(&layout),
                    module: &module,
                    entry_point: Some("render"),
                    compilation_options: Default::default(),
                    cache: None,
                }),
            )
        })?;
        let cam = &gpu.scene().camera;
        let pixels = cam.width as u64 * cam.height as u64;
        let accum_size = 3 * pixels * 16;
        if accum_size > device.limits().max_storage_buffer_binding_size {
            return Err(GpuError::TooLarge(format!(
                "the {}x{} accumulation buffer takes {accum_size} bytes",
                cam.width, cam.height
            )));
        }
        let accum = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lumis accumulation"),
            size: accum_size,
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
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
            size: PARAMS_STRIDE * PASSES_PER_SUBMIT as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = gpu.bind_group(&params, &accum, &counters);
        let mut r = GpuProgressive {
            gpu,
            settings,
            seed,
            spp: 0,
            pipeline,
            params,
            accum,
            counters,
            bind_group,
        };
        r.clear();
        Ok(r)
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
    /// program does not depend on the settings, so nothing is recompiled.
    pub fn restart(&mut self, settings: Settings) {
        self.settings = settings;
        self.clear();
    }

    /// Renders `n` more samples per pixel and waits for them. Always `true` (the CPU's `false`
    /// means cancelled; a GPU pass is not cancellable once submitted).
    pub fn render_pass(&mut self, n: u32) -> bool {
        let ctx = self.gpu.context().clone();
        let cam = &self.gpu.scene().camera;
        let groups = (cam.width.div_ceil(TILE), cam.height.div_ceil(TILE));
        let mut done = 0;
        while done < n {
            let count = (n - done).min(PASSES_PER_SUBMIT);
            let mut slots = vec![0u8; (PARAMS_STRIDE * count as u64) as usize];
            for i in 0..count {
                let p: GpuParams = self
                    .gpu
                    .params(&self.settings, self.seed, self.spp + done + i);
                let at = (PARAMS_STRIDE * i as u64) as usize;
                slots[at..at + size_of::<GpuParams>()].copy_from_slice(bytemuck::bytes_of(&p));
            }
            ctx.queue.write_buffer(&self.params, 0, &slots);
            let mut encoder = ctx.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("lumis samples"),
                    timestamp_writes: None,
                });
                pass.set_pipeline(&self.pipeline);
                for i in 0..count {
                    pass.set_bind_group(0, &self.bind_group, &[(PARAMS_STRIDE * i as u64) as u32]);
                    pass.dispatch_workgroups(groups.0, groups.1, 1);
                }
            }
            ctx.queue.submit([encoder.finish()]);
            done += count;
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
        let bytes = ctx.read_buffer(&self.accum, self.accum.size())?;
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
