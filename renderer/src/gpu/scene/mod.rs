//! [`GpuScene`]: the scene flattened into GPU storage buffers, one record encoder per kind
//! ([`materials`], [`lights`], [`shapes`], [`attributes`], [`textures`], [`bvh`]) whose layouts
//! the WGSL records mirror, the environment map and the bitmaps' texels as textures ([`envmap`],
//! [`textures`]), and the per-dispatch uniform ([`params`]). Each kind's tags are a
//! `#[repr(u32)]` enum next to its encoder, which the generated WGSL prelude (`gpu/prelude.rs`)
//! names for the shaders.
//! WGSL twin: `gpu/bindings.wgsl` (the bind group this module creates).
//!
//! Primitives are uploaded in the BVH's leaf order, which is the order of
//! [`crate::geometry::Accel::primitives`], so the obvhs CWBVH nodes go up byte for byte and a hit's
//! primitive index means the same on both sides. The optional BVH2 ([`GpuScene::with_bvh2`]) is
//! built over that same list and reaches it through its `primitive_indices`, so its hits index the
//! same primitives.

pub mod attributes;
pub mod bvh;
pub mod envmap;
pub mod lights;
pub mod materials;
pub mod params;
pub mod shapes;
pub mod textures;

pub use attributes::AttrOffsets;
pub use bvh::{BVH2_STACK_SIZE, CWBVH_STACK_SIZE};
pub use lights::{GpuLight, LightTag};
pub use materials::{DistributionTag, FresnelTag, GpuMaterial, MaterialTag};
pub use params::{
    CameraTag, FilterTag, GpuParams, HeuristicTag, LightSamplingTag, LightSelectionTag,
    PARAMS_STRIDE, SamplerTag, StrategyTag,
};
pub use shapes::{GpuPrim, ShapeTag};
pub use textures::{ChannelTag, TextureTag, WrapTag};

use super::shader::Features;
use super::{GpuContext, GpuError};
use crate::lights::Light;
use crate::scene::Scene;
use envmap::EnvmapTexels;
use std::sync::Arc;
use textures::TextureTexels;
use wgpu::util::DeviceExt;

/// The scene on the GPU.
pub struct GpuScene {
    ctx: Arc<GpuContext>,
    scene: Arc<Scene>,
    features: Features,
    nodes: wgpu::Buffer,
    prims: wgpu::Buffer,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    vertex_data: wgpu::Buffer,
    tables: wgpu::Buffer,
    /// The environment map's texels (a 1×1 placeholder without one), kept with its view.
    _envmap: wgpu::Texture,
    envmap_view: wgpu::TextureView,
    /// The bitmaps' texels (a 1×1 placeholder without any), kept with its view.
    _texels: wgpu::Texture,
    texels_view: wgpu::TextureView,
    light_cdf: u32,
    light_pmf: u32,
    light_bvh: u32,
    attr: AttrOffsets,
    textures: u32,
    layout: wgpu::BindGroupLayout,
}

/// Every record of a scene but the BVH nodes, as the storage buffers will hold them.
pub(crate) struct Records {
    pub(crate) prims: Vec<GpuPrim>,
    pub(crate) materials: Vec<GpuMaterial>,
    pub(crate) lights: Vec<GpuLight>,
    /// Polygon lights' triangles, then the mesh vertex attributes at `attr`, then the texture
    /// records at `textures`.
    pub(crate) vertex_data: Vec<[f32; 4]>,
    /// In a scene with masks first the opacity record of each material (`materials/mask.wgsl`),
    /// then coat albedo tables, an environment map's sampling tables, the light-selection CDF
    /// and pmf.
    pub(crate) tables: Vec<f32>,
    pub(crate) light_cdf: u32,
    pub(crate) light_pmf: u32,
    /// Offset of the light BVH in `tables`, or `NONE`.
    pub(crate) light_bvh: u32,
    /// Where the attribute arrays start in `vertex_data`.
    pub(crate) attr: AttrOffsets,
    /// Where the texture records start in `vertex_data`.
    pub(crate) textures: u32,
    /// The bitmaps' texels.
    pub(crate) texels: TextureTexels,
    /// What to call each texture record in an error.
    pub(crate) texture_names: Vec<String>,
    /// The environment map's texels, if the scene has one (at most one: its background).
    pub(crate) envmap: Option<EnvmapTexels>,
}

impl Records {
    /// Encodes every record of `scene`.
    pub(crate) fn of(scene: &Scene) -> Records {
        let mut tables = Vec::new();
        let mut vertex_data = Vec::new();
        let prims = shapes::encode(scene);
        let scene_textures = textures::encode(scene);
        // At offset 0, where `materials/mask.wgsl` reads it (empty without masks).
        tables.extend(scene_textures.opacity.iter().map(|&id| bits(id)));
        let materials = materials::encode(
            scene,
            &mut tables,
            &scene_textures.slots,
            &scene_textures.mix_weights,
            &scene_textures.normal_maps,
            &scene_textures.principled,
        );
        let lights = lights::encode(
            scene,
            &mut vertex_data,
            &mut tables,
            &scene_textures.emission,
        );
        let (light_cdf, light_pmf) = lights::selection(scene, &mut tables);
        let light_bvh = scene
            .light_bvh
            .as_ref()
            .map_or(crate::geometry::primitive::NONE, |b| {
                b.append_tables(&mut tables)
            });
        let attr = attributes::encode(&scene.attributes, &mut vertex_data);
        let textures = vertex_data.len() as u32;
        vertex_data.extend_from_slice(&scene_textures.records);
        let mut maps = scene.lights.iter().filter_map(|l| match l {
            Light::Envmap(e) => Some(EnvmapTexels::of(e)),
            _ => None,
        });
        let envmap = maps.next();
        // One texture binding: the scene builder makes at most one map, the background.
        assert!(maps.next().is_none(), "a scene with two environment maps");
        Records {
            prims,
            materials,
            lights,
            vertex_data,
            tables,
            light_cdf,
            light_pmf,
            light_bvh,
            attr,
            textures,
            texels: scene_textures.texels,
            texture_names: scene_textures.names,
            envmap,
        }
    }
}

fn v4(v: glam::Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

fn bits(u: u32) -> f32 {
    f32::from_bits(u)
}

/// A compute shader's storage-buffer binding `binding` (read-only or read-write), as the scene's
/// bind group and the test kernels' I/O group declare them.
pub(crate) fn storage_layout_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

impl GpuScene {
    /// Flattens and uploads `scene`, with the CWBVH. Every scene the builder makes is mirrored
    /// (textured materials and emission, mixes and a plastic's textured α since issue 17): the
    /// texture slots are destructured in `textures::slots`, so a slot added to
    /// `MaterialTextures` fails to compile there until the GPU has it. The camera's pixel filter,
    /// box or gaussian, is the kernel's too (`camera/filter.wgsl`, issue 18), so no scene is refused.
    pub fn new(ctx: Arc<GpuContext>, scene: Arc<Scene>) -> Result<GpuScene, GpuError> {
        GpuScene::with_bvh2(ctx, scene, false)
    }

    /// Flattens and uploads `scene`; with `bvh2` (and a scene large enough for a BVH) it also
    /// builds an obvhs BVH2 and the programs traverse that instead of the CWBVH
    /// ([`Features::bvh2`]), for measuring the two. The images are the same up to float rounding
    /// either way.
    pub fn with_bvh2(
        ctx: Arc<GpuContext>,
        scene: Arc<Scene>,
        bvh2: bool,
    ) -> Result<GpuScene, GpuError> {
        let records = Records::of(&scene);
        GpuScene::upload(ctx, scene, bvh2, records)
    }

    /// Uploads `records` (those of `scene`, possibly altered by a test) with `scene`'s BVH.
    pub(crate) fn upload(
        ctx: Arc<GpuContext>,
        scene: Arc<Scene>,
        bvh2: bool,
        records: Records,
    ) -> Result<GpuScene, GpuError> {
        let mut features = Features::of(&scene);
        features.bvh2 = bvh2 && features.use_bvh;
        let bvh2_rows = if features.bvh2 {
            bvh::bvh2_rows(scene.accel.primitives())?
        } else {
            Vec::new()
        };
        let nodes: &[u8] = match scene.accel.cwbvh() {
            Some(_) if features.bvh2 => bytemuck::cast_slice(&bvh2_rows),
            Some(cwbvh) => {
                bvh::check_cwbvh(cwbvh)?;
                bytemuck::cast_slice(&cwbvh.nodes)
            }
            None => &[],
        };
        let device = &ctx.device;
        let limit = device.limits().max_storage_buffer_binding_size as usize;
        textures::check_records(&records.texture_names, records.textures as usize, limit)?;
        for (what, size) in [
            ("BVH nodes", nodes.len()),
            ("primitives", records.prims.len() * size_of::<GpuPrim>()),
            (
                "light triangles, mesh vertex attributes and texture records",
                records.vertex_data.len() * size_of::<[f32; 4]>(),
            ),
            (
                if records.envmap.is_some() {
                    "tables (with the environment map's sampling tables)"
                } else {
                    "tables"
                },
                records.tables.len() * size_of::<f32>(),
            ),
        ] {
            if size > limit {
                return Err(GpuError::TooLarge(format!(
                    "{what} take {size} bytes, the device binds at most {limit}"
                )));
            }
        }
        let placeholder = EnvmapTexels::placeholder();
        let texels = records.envmap.as_ref().unwrap_or(&placeholder);
        let max = device.limits().max_texture_dimension_2d;
        if texels.width > max || texels.height > max {
            return Err(GpuError::TooLarge(format!(
                "the {}x{} environment map exceeds the device's {max}x{max} textures",
                texels.width, texels.height
            )));
        }
        let envmap = texels.upload(device, &ctx.queue);
        let envmap_view = envmap.create_view(&wgpu::TextureViewDescriptor::default());
        let texel_layout = records.texels.layout(max)?;
        let texture_texels = records.texels.upload(device, &ctx.queue, texel_layout);
        let texels_view = texture_texels.create_view(&wgpu::TextureViewDescriptor::default());
        // Bindings may not be empty: pad every buffer to at least one 16-byte element.
        let storage = |label: &str, data: &[u8]| {
            let mut bytes = data.to_vec();
            if bytes.is_empty() {
                bytes.resize(80, 0);
            }
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: &bytes,
                usage: wgpu::BufferUsages::STORAGE,
            })
        };
        let r = &records;
        let layout = Self::create_layout(device);
        Ok(GpuScene {
            nodes: storage("lumis nodes", nodes),
            prims: storage("lumis prims", bytemuck::cast_slice(&r.prims)),
            materials: storage("lumis materials", bytemuck::cast_slice(&r.materials)),
            lights: storage("lumis lights", bytemuck::cast_slice(&r.lights)),
            vertex_data: storage("lumis vertex data", bytemuck::cast_slice(&r.vertex_data)),
            tables: storage("lumis tables", bytemuck::cast_slice(&r.tables)),
            _envmap: envmap,
            envmap_view,
            _texels: texture_texels,
            texels_view,
            light_cdf: r.light_cdf,
            light_pmf: r.light_pmf,
            light_bvh: r.light_bvh,
            attr: r.attr,
            textures: r.textures,
            layout,
            features,
            scene,
            ctx,
        })
    }

    fn create_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
        let storage = storage_layout_entry;
        let mut entries = vec![wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: true,
                min_binding_size: wgpu::BufferSize::new(size_of::<GpuParams>() as u64),
            },
            count: None,
        }];
        entries.extend((1..=6).map(|b| storage(b, true)));
        entries.push(storage(7, false));
        entries.push(storage(8, false));
        // The environment map (`envmap_texels`) and the bitmaps' texels (`texture_texels`):
        // rgba32float, read with textureLoad only.
        entries.extend([9, 10].map(|binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Texture {
                sample_type: wgpu::TextureSampleType::Float { filterable: false },
                view_dimension: wgpu::TextureViewDimension::D2,
                multisampled: false,
            },
            count: None,
        }));
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("lumis scene"),
            entries: &entries,
        })
    }

    /// The context the buffers live in.
    pub fn context(&self) -> &Arc<GpuContext> {
        &self.ctx
    }

    /// The scene.
    pub fn scene(&self) -> &Arc<Scene> {
        &self.scene
    }

    /// What the scene uses (decides the specialised program).
    pub fn features(&self) -> Features {
        self.features
    }

    /// The layout of bind group 0 (`gpu/bindings.wgsl`).
    pub fn layout(&self) -> &wgpu::BindGroupLayout {
        &self.layout
    }

    /// Bind group 0 with the scene and the given parameter, accumulation and counter buffers.
    pub fn bind_group(
        &self,
        params: &wgpu::Buffer,
        accum: &wgpu::Buffer,
        counters: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        fn whole(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
            wgpu::BindGroupEntry {
                binding,
                resource: buffer.as_entire_binding(),
            }
        }
        self.ctx
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("lumis scene"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: params,
                            offset: 0,
                            size: wgpu::BufferSize::new(size_of::<GpuParams>() as u64),
                        }),
                    },
                    whole(1, &self.nodes),
                    whole(2, &self.prims),
                    whole(3, &self.materials),
                    whole(4, &self.lights),
                    whole(5, &self.vertex_data),
                    whole(6, &self.tables),
                    whole(7, accum),
                    whole(8, counters),
                    wgpu::BindGroupEntry {
                        binding: 9,
                        resource: wgpu::BindingResource::TextureView(&self.envmap_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 10,
                        resource: wgpu::BindingResource::TextureView(&self.texels_view),
                    },
                ],
            })
    }
}
