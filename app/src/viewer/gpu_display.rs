//! Showing a GPU lane without a round trip through the CPU: a compute shader
//! (`gpu_display.wgsl`, the twin of [`super::tonemap::srgb8`]) reads the running mean straight
//! from the render's accumulation buffer and writes a texture on the window's own wgpu device,
//! which egui then draws. The render thread renders on that same device (see
//! [`lumis::gpu::GpuContext::from_device`]), so a frame costs one small dispatch, not a readback.

use eframe::egui_wgpu;
use eframe::wgpu;
use std::sync::Arc;

/// A GPU render's image as the render thread publishes it: where its mean lives and how much
/// has been accumulated (a cheap handle; the buffer is shared, not copied).
#[derive(Clone, Debug)]
pub struct LiveImage {
    /// The accumulation buffer; its first `width·height` `vec4<f32>` are the running mean.
    pub buffer: wgpu::Buffer,
    /// Bytes of the mean plane.
    pub plane_size: u64,
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// Samples per pixel in the buffer when published.
    pub spp: u32,
}

/// The display pipeline: accumulation buffer → exposure → sRGB bytes in an `Rgba8Unorm`
/// storage texture (egui expects textures holding sRGB-encoded bytes).
pub struct DisplayKernel {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
}

/// The uniform block of `gpu_display.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct DisplayParams {
    width: u32,
    height: u32,
    gain: f32,
    pad: u32,
}

/// The workgroup of `display_main`.
const TILE: u32 = 8;

impl DisplayKernel {
    /// Compiles the display shader on `device`.
    pub fn new(device: &wgpu::Device) -> DisplayKernel {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("lumis display"),
            source: wgpu::ShaderSource::Wgsl(include_str!("gpu_display.wgsl").into()),
        });
        let storage = |binding, ty| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty,
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lumis display"),
            entries: &[
                storage(
                    0,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                ),
                storage(
                    1,
                    wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                ),
                storage(
                    2,
                    wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: wgpu::TextureFormat::Rgba8Unorm,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                ),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("lumis display"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("lumis display"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("display_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        DisplayKernel { pipeline, layout }
    }

    /// A texture the kernel can write and egui can draw, `width`×`height`.
    pub fn target(device: &wgpu::Device, width: u32, height: u32) -> wgpu::Texture {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("lumis display target"),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    }

    /// Writes the display pixels of `image` at `gain` into `target` (same size), on `queue`
    /// after whatever render passes were submitted before.
    pub fn run(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        image: &LiveImage,
        gain: f32,
        target: &wgpu::Texture,
    ) {
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("lumis display params"),
            size: size_of::<DisplayParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(
            &params,
            0,
            bytemuck::bytes_of(&DisplayParams {
                width: image.width,
                height: image.height,
                gain,
                pad: 0,
            }),
        );
        let view = target.create_view(&Default::default());
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("lumis display"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                        buffer: &image.buffer,
                        offset: 0,
                        size: wgpu::BufferSize::new(image.plane_size),
                    }),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(&view),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("lumis display"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            pass.dispatch_workgroups(image.width.div_ceil(TILE), image.height.div_ceil(TILE), 1);
        }
        queue.submit([encoder.finish()]);
    }
}

/// As the CPU lanes' textures (`textures::PANE_SAMPLING`): nearest when magnified, so that a
/// zoomed pane shows single pixels, linear when minified.
fn pane_sampler() -> wgpu::SamplerDescriptor<'static> {
    wgpu::SamplerDescriptor {
        label: Some("lumis pane"),
        mag_filter: wgpu::FilterMode::Nearest,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    }
}

/// One lane's texture and what it last showed.
struct Slot {
    texture: wgpu::Texture,
    id: egui::TextureId,
    shown: Option<(wgpu::Buffer, u32, u32)>,
}

/// The window's display of GPU lanes: the kernel, and per lane a texture registered with
/// egui's renderer, refreshed only when the lane has new samples or the exposure changed.
pub struct GpuDisplay {
    device: wgpu::Device,
    queue: wgpu::Queue,
    renderer: Arc<egui::mutex::RwLock<egui_wgpu::Renderer>>,
    kernel: DisplayKernel,
    slots: Vec<Slot>,
}

impl GpuDisplay {
    /// The display on the window's device.
    pub fn new(state: &egui_wgpu::RenderState) -> GpuDisplay {
        GpuDisplay {
            device: state.device.clone(),
            queue: state.queue.clone(),
            renderer: state.renderer.clone(),
            kernel: DisplayKernel::new(&state.device),
            slots: Vec::new(),
        }
    }

    /// The texture showing `image` in slot `lane` at `gain`, updated if anything changed.
    pub fn texture(&mut self, lane: usize, image: &LiveImage, gain: f32) -> egui::TextureId {
        let size = (image.width, image.height);
        let fits = self
            .slots
            .get(lane)
            .is_some_and(|s| (s.texture.width(), s.texture.height()) == size);
        if !fits {
            let texture = DisplayKernel::target(&self.device, image.width, image.height);
            let view = texture.create_view(&Default::default());
            let mut renderer = self.renderer.write();
            let slot = if let Some(old) = self.slots.get(lane) {
                renderer.update_egui_texture_from_wgpu_texture_with_sampler_options(
                    &self.device,
                    &view,
                    pane_sampler(),
                    old.id,
                );
                Slot {
                    texture,
                    id: old.id,
                    shown: None,
                }
            } else {
                let id = renderer.register_native_texture_with_sampler_options(
                    &self.device,
                    &view,
                    pane_sampler(),
                );
                Slot {
                    texture,
                    id,
                    shown: None,
                }
            };
            if lane < self.slots.len() {
                self.slots[lane] = slot;
            } else {
                self.slots.push(slot);
            }
        }
        let slot = &mut self.slots[lane];
        let key = (image.buffer.clone(), image.spp, gain.to_bits());
        if slot.shown.as_ref() != Some(&key) {
            self.kernel
                .run(&self.device, &self.queue, image, gain, &slot.texture);
            slot.shown = Some(key);
        }
        slot.id
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::viewer::tonemap::srgb8;
    use glam::Vec3;
    use lumis::gpu::GpuContext;

    /// The WGSL display and `tonemap::srgb8` agree to one unit in the last place (the GPU's
    /// float-to-unorm conversion rounds to nearest even, the CPU half up) over values across
    /// the sRGB curve's linear toe, its power segment and the clamp, at several exposures.
    #[test]
    fn display_shader_matches_srgb8() {
        if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
            eprintln!("LUMIS_SKIP_GPU_TESTS is set: skipping a GPU test");
            return;
        }
        let ctx = GpuContext::new().expect("a wgpu adapter (lavapipe without a GPU)");
        let (w, h) = (37u32, 23u32);
        let mut rng = lumis::rng::Rng::new(7, 0, 0);
        let mean: Vec<[f32; 4]> = (0..w * h)
            .map(|i| {
                let mut c = [0.0; 4];
                for x in c.iter_mut().take(3) {
                    // Log-uniform over 1e-5…10, plus exact zeros and ones.
                    *x = match i % 17 {
                        0 => 0.0,
                        1 => 1.0,
                        _ => 10f32.powf(rng.next_f32() * 6.0 - 5.0),
                    };
                }
                c
            })
            .collect();
        let buffer = wgpu::util::DeviceExt::create_buffer_init(
            &ctx.device,
            &wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytemuck::cast_slice(&mean),
                usage: wgpu::BufferUsages::STORAGE,
            },
        );
        let image = LiveImage {
            buffer,
            plane_size: (w * h * 16) as u64,
            width: w,
            height: h,
            spp: 1,
        };
        let kernel = DisplayKernel::new(&ctx.device);
        let target = DisplayKernel::target(&ctx.device, w, h);
        for exposure in [-3.0f32, 0.0, 2.5] {
            let gain = 2f32.powf(exposure);
            kernel.run(&ctx.device, &ctx.queue, &image, gain, &target);
            let got = read_texture(&ctx, &target);
            for (i, m) in mean.iter().enumerate() {
                let want = srgb8(Vec3::new(m[0], m[1], m[2]), gain);
                for c in 0..3 {
                    let d = (got[i][c] as i32 - want[c] as i32).abs();
                    assert!(
                        d <= 1,
                        "pixel {i} channel {c}: gpu {} cpu {} (exposure {exposure}, value {})",
                        got[i][c],
                        want[c],
                        m[c]
                    );
                }
                assert_eq!(got[i][3], 255);
            }
        }
    }

    /// Copies an Rgba8 texture back, rows unpadded.
    fn read_texture(ctx: &GpuContext, t: &wgpu::Texture) -> Vec<[u8; 4]> {
        let (w, h) = (t.width(), t.height());
        let row = (w * 4).div_ceil(256) * 256;
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: (row * h) as u64,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        encoder.copy_texture_to_buffer(
            t.as_image_copy(),
            wgpu::TexelCopyBufferInfo {
                buffer: &staging,
                layout: wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(row),
                    rows_per_image: Some(h),
                },
            },
            wgpu::Extent3d {
                width: w,
                height: h,
                depth_or_array_layers: 1,
            },
        );
        ctx.queue.submit([encoder.finish()]);
        let bytes = ctx.read_buffer(&staging, (row * h) as u64).unwrap();
        (0..h)
            .flat_map(|y| {
                let bytes = &bytes;
                (0..w).map(move |x| {
                    let at = (y * row + 4 * x) as usize;
                    [bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]
                })
            })
            .collect()
    }
}
