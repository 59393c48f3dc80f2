//! The scene flattened into GPU storage buffers, with layouts the WGSL records mirror (see the
//! comments at the top of `shape.wgsl`, `material.wgsl`, `light.wgsl` and `bvh.wgsl`).
//!
//! Primitives are uploaded in the BVH's leaf order, which is the order of
//! [`crate::geometry::Accel::primitives`], so the obvhs CWBVH nodes go up byte for byte and a hit's
//! primitive index means the same on both sides. The optional BVH2 ([`GpuScene::with_bvh2`]) is
//! built over that same list and reaches it through its `primitive_indices`, so its hits index the
//! same primitives.

use super::shader::Features;
use super::{GpuContext, GpuError};
use crate::geometry::Shape;
use crate::geometry::primitive::NONE;
use crate::integrator::{Heuristic, Settings, Strategy};
use crate::lights::{Light, LightSampling};
use crate::materials::{ConductorFresnel, Material};
use crate::scene::Scene;
use bytemuck::{Pod, Zeroable};
use std::sync::Arc;
use wgpu::util::DeviceExt;

/// A primitive record (`Prim` in `shape.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuPrim {
    a: [f32; 4],
    b: [f32; 4],
    c: [f32; 4],
    d: [f32; 4],
}

/// A material record (`Material` in `material.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuMaterial {
    h: [u32; 4],
    a: [f32; 4],
    b: [f32; 4],
    c: [f32; 4],
}

/// A light record (`Light` in `light.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
pub struct GpuLight {
    h: [u32; 4],
    a: [f32; 4],
    b: [f32; 4],
    c: [f32; 4],
    d: [f32; 4],
    le: [f32; 4],
}

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
    /// Strategy: 0 light, 1 BSDF, 2 mixture, 3 MIS.
    pub strategy: u32,
    /// Heuristic: 0 balance, 1 power.
    pub heuristic: u32,
    /// Light sampling: 0 area, 1 solid angle.
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
    /// Padding.
    pub pad: u32,
    /// Camera origin; w = tan of the half horizontal field of view.
    pub cam_origin: [f32; 4],
    /// Camera forward axis; w = tan of the half vertical field of view.
    pub cam_forward: [f32; 4],
    /// Camera right axis.
    pub cam_right: [f32; 4],
    /// Camera up axis.
    pub cam_up: [f32; 4],
}

/// Uniform slots are this far apart (the largest `min_uniform_buffer_offset_alignment` wgpu
/// allows), so one buffer holds the parameters of many dispatches.
pub const PARAMS_STRIDE: u64 = 256;

/// The scene on the GPU.
pub struct GpuScene {
    ctx: Arc<GpuContext>,
    scene: Arc<Scene>,
    features: Features,
    nodes: wgpu::Buffer,
    prims: wgpu::Buffer,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    light_tris: wgpu::Buffer,
    tables: wgpu::Buffer,
    light_cdf: u32,
    light_pmf: u32,
    layout: wgpu::BindGroupLayout,
}

fn v4(v: glam::Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

fn bits(u: u32) -> f32 {
    f32::from_bits(u)
}

/// A prefix sum in f64 normalised to end at exactly 1, rounded to f32 (the CPU's
/// `DiscreteDistribution` keeps it in f64; f32 is all the GPU has).
fn cdf(weights: &[f32]) -> Vec<f32> {
    let total: f64 = weights.iter().map(|&w| w as f64).sum();
    let mut acc = 0.0f64;
    let mut out = vec![0.0f32];
    for &w in weights {
        acc += w as f64;
        out.push((acc / total) as f32);
    }
    out
}

/// The deepest BVH2 the traversal's stack holds (`BVH2_STACK_SIZE` in `bvh2.wgsl`): near-first
/// traversal defers at most one node per level.
const BVH2_MAX_DEPTH: usize = 64;

/// Builds an obvhs BVH2 over `prims` (the CWBVH's leaf order) and packs it as `bvh2.wgsl` reads
/// it: node i as two `vec4<u32>` (min.xyz, prim_count) and (max.xyz, first), then the leaves'
/// primitive ids, four per row. A leaf's `first` becomes the word index of its ids, so the shader
/// needs no offset uniform (and the bind group layout stays the CWBVH's).
fn bvh2_rows(prims: &[crate::geometry::primitive::Primitive]) -> Result<Vec<[u32; 4]>, GpuError> {
    use obvhs::{BvhBuildParams, bvh2::builder::build_bvh2};
    let bvh = build_bvh2(
        prims,
        BvhBuildParams::medium_build(),
        &mut std::time::Duration::default(),
    );
    // Depth of the tree, iteratively (it may be deep enough to matter).
    let mut depth = 0;
    let mut todo = vec![(0usize, 1usize)];
    while let Some((i, d)) = todo.pop() {
        depth = depth.max(d);
        let n = &bvh.nodes[i];
        if n.prim_count == 0 {
            todo.push((n.first_index as usize, d + 1));
            todo.push((n.first_index as usize + 1, d + 1));
        }
    }
    if depth > BVH2_MAX_DEPTH {
        return Err(GpuError::TooLarge(format!(
            "the BVH2 is {depth} levels deep, its GPU traversal holds {BVH2_MAX_DEPTH}"
        )));
    }
    let ids_word = 8 * bvh.nodes.len() as u32;
    let mut rows = Vec::with_capacity(2 * bvh.nodes.len() + bvh.primitive_indices.len() / 4 + 1);
    for n in &bvh.nodes {
        let first = if n.prim_count == 0 {
            n.first_index
        } else {
            ids_word + n.first_index
        };
        let (lo, hi) = (n.aabb.min, n.aabb.max);
        rows.push([lo.x.to_bits(), lo.y.to_bits(), lo.z.to_bits(), n.prim_count]);
        rows.push([hi.x.to_bits(), hi.y.to_bits(), hi.z.to_bits(), first]);
    }
    for ids in bvh.primitive_indices.chunks(4) {
        let mut row = [0u32; 4];
        row[..ids.len()].copy_from_slice(ids);
        rows.push(row);
    }
    Ok(rows)
}

impl GpuScene {
    /// Flattens and uploads `scene`, with the CWBVH.
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
        let mut features = Features::of(&scene);
        features.bvh2 = bvh2 && features.use_bvh;
        let mut tables: Vec<f32> = Vec::new();

        let prims: Vec<GpuPrim> = scene
            .accel
            .primitives()
            .iter()
            .map(|p| {
                let (kind, a, b, c, d) = match p.shape {
                    Shape::Triangle { v, n } => (0u32, v[0], v[1], v[2], v4(n, 0.0)),
                    Shape::Disk(k) => (
                        1,
                        k.center,
                        glam::Vec3::ZERO,
                        glam::Vec3::ZERO,
                        v4(k.n, k.radius),
                    ),
                    Shape::Sphere(s) => (
                        2,
                        s.center,
                        glam::Vec3::ZERO,
                        glam::Vec3::ZERO,
                        [0.0, 0.0, 0.0, s.radius],
                    ),
                };
                GpuPrim {
                    a: v4(a, bits(kind)),
                    b: v4(b, bits(p.material)),
                    c: v4(c, bits(p.light)),
                    d,
                }
            })
            .collect();

        let materials: Vec<GpuMaterial> = scene
            .materials
            .iter()
            .zip(&scene.two_sided)
            .map(|(m, &two_sided)| {
                let smooth = m.has_smooth_part() as u32;
                let z = [0.0; 4];
                match m {
                    Material::Diffuse(d) => GpuMaterial {
                        h: [0, two_sided as u32, 0, smooth],
                        a: v4(d.albedo, 0.0),
                        b: z,
                        c: z,
                    },
                    Material::Conductor(c) => {
                        let (kind, a, b) = match c.fresnel {
                            ConductorFresnel::Complex { eta, k } => (0, eta, k),
                            ConductorFresnel::Tint(r) => (1, r, glam::Vec3::ZERO),
                        };
                        GpuMaterial {
                            h: [1, two_sided as u32, kind, smooth],
                            a: v4(a, 0.0),
                            b: v4(b, 0.0),
                            c: [c.alpha, 0.0, 0.0, 0.0],
                        }
                    }
                    Material::Plastic(p) => {
                        let offset = tables.len() as u32;
                        tables.extend_from_slice(p.coat().table());
                        let f0 = crate::materials::fresnel::schlick_f0_from_ior(p.ior());
                        // As `Plastic::new`: no light reaches the base of a coat that reflects all.
                        let e_avg = p.coat().average();
                        let diffuse_norm = if 1.0 - e_avg > 1e-6 {
                            1.0 / (1.0 - e_avg)
                        } else {
                            0.0
                        };
                        GpuMaterial {
                            h: [2, two_sided as u32, offset, smooth],
                            a: v4(p.albedo(), 0.0),
                            b: v4(p.specular(), 0.0),
                            c: [p.alpha(), f0, diffuse_norm, 0.0],
                        }
                    }
                }
            })
            .collect();

        let mut light_tris: Vec<[f32; 4]> = Vec::new();
        let lights: Vec<GpuLight> = scene
            .lights
            .iter()
            .map(|l| {
                let z = [0.0; 4];
                let mut g = GpuLight {
                    h: [0; 4],
                    a: z,
                    b: z,
                    c: z,
                    d: z,
                    le: z,
                };
                match l {
                    Light::Triangle(t) => {
                        g.h[0] = 0;
                        g.a = v4(t.v[0], 0.0);
                        g.b = v4(t.v[1], 0.0);
                        g.c = v4(t.v[2], 0.0);
                        g.d = v4(t.n, 0.0);
                        g.le = v4(t.le, t.area);
                    }
                    Light::Polygon(p) => {
                        let areas: Vec<f32> = p
                            .triangles
                            .iter()
                            .map(crate::geometry::triangle::triangle_area)
                            .collect();
                        let c = cdf(&areas);
                        g.h = [
                            1,
                            (light_tris.len() / 3) as u32,
                            p.triangles.len() as u32,
                            0,
                        ];
                        for (i, t) in p.triangles.iter().enumerate() {
                            light_tris.push(v4(t[0], c[i]));
                            light_tris.push(v4(t[1], c[i + 1]));
                            light_tris.push(v4(t[2], 0.0));
                        }
                        g.a = v4(p.origin, 0.0);
                        g.d = v4(p.n, 0.0);
                        g.le = v4(p.le, p.area);
                    }
                    Light::Quad(q) => {
                        g.h[0] = 2;
                        g.a = v4(q.corner, 0.0);
                        g.b = v4(q.edge_u, 0.0);
                        g.c = v4(q.edge_v, 0.0);
                        g.d = v4(q.n, 0.0);
                        g.le = v4(q.le, q.area);
                    }
                    Light::Disk(k) => {
                        g.h[0] = 3;
                        g.a = v4(k.disk.center, k.disk.radius);
                        g.d = v4(k.disk.n, 0.0);
                        g.le = v4(k.le, k.disk.area());
                    }
                    Light::Sphere(s) => {
                        g.h[0] = 4;
                        g.a = v4(s.sphere.center, s.sphere.radius);
                        g.le = v4(s.le, s.sphere.area());
                    }
                    Light::Background(b) => {
                        g.h[0] = 5;
                        g.le = v4(b.le, 0.0);
                    }
                }
                g
            })
            .collect();

        // Light selection: the CPU's power distribution, CDF and pmf side by side in the tables.
        let (light_cdf, light_pmf) = match &scene.light_sampler {
            Some(sampler) => {
                let powers: Vec<f32> = scene.lights.iter().map(|l| l.power().max(0.0)).collect();
                let c = cdf(&powers);
                let cdf_offset = tables.len() as u32;
                tables.extend_from_slice(&c);
                let pmf_offset = tables.len() as u32;
                tables.extend((0..scene.lights.len()).map(|i| sampler.pmf(i)));
                (cdf_offset, pmf_offset)
            }
            None => (NONE, NONE),
        };

        let bvh2_rows = if features.bvh2 {
            bvh2_rows(scene.accel.primitives())?
        } else {
            Vec::new()
        };
        let nodes: &[u8] = match scene.accel.cwbvh() {
            Some(_) if features.bvh2 => bytemuck::cast_slice(&bvh2_rows),
            Some(bvh) => bytemuck::cast_slice(&bvh.nodes),
            None => &[],
        };
        let device = &ctx.device;
        let limit = device.limits().max_storage_buffer_binding_size as usize;
        for (what, size) in [
            ("BVH nodes", nodes.len()),
            ("primitives", prims.len() * size_of::<GpuPrim>()),
        ] {
            if size > limit {
                return Err(GpuError::TooLarge(format!(
                    "{what} take {size} bytes, the device binds at most {limit}"
                )));
            }
        }
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
        let layout = Self::create_layout(device);
        Ok(GpuScene {
            nodes: storage("lumis nodes", nodes),
            prims: storage("lumis prims", bytemuck::cast_slice(&prims)),
            materials: storage("lumis materials", bytemuck::cast_slice(&materials)),
            lights: storage("lumis lights", bytemuck::cast_slice(&lights)),
            light_tris: storage("lumis light triangles", bytemuck::cast_slice(&light_tris)),
            tables: storage("lumis tables", bytemuck::cast_slice(&tables)),
            light_cdf,
            light_pmf,
            layout,
            features,
            scene,
            ctx,
        })
    }

    fn create_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
        let storage = |binding: u32, read_only: bool| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
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

    /// The layout of bind group 0 (`bindings.wgsl`).
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
                    whole(5, &self.light_tris),
                    whole(6, &self.tables),
                    whole(7, accum),
                    whole(8, counters),
                ],
            })
    }

    /// The uniform for sample `sample` of a render with `settings` and `seed`.
    pub fn params(&self, settings: &Settings, seed: u32, sample: u32) -> GpuParams {
        let scene = &self.scene;
        let cam = &scene.camera;
        let (forward, right, up, tan_x, tan_y) = cam.basis();
        let (strategy, heuristic, mix_weight) = match settings.strategy {
            Strategy::Light => (0, 0, 1.0),
            Strategy::Bsdf => (1, 0, 0.0),
            Strategy::Mixture { light_weight } => (2, 0, light_weight),
            Strategy::Mis { heuristic } => (
                3,
                match heuristic {
                    Heuristic::Balance => 0,
                    Heuristic::Power => 1,
                },
                0.0,
            ),
        };
        GpuParams {
            width: cam.width,
            height: cam.height,
            seed,
            sample,
            strategy,
            heuristic,
            light_sampling: match settings.light_sampling {
                LightSampling::Area => 0,
                LightSampling::SolidAngle => 1,
            },
            max_depth: settings.max_depth.unwrap_or(scene.max_depth),
            rr_depth: settings.rr_depth,
            n_lights: scene.lights.len() as u32,
            background: scene.background_light.unwrap_or(NONE),
            light_cdf: self.light_cdf,
            light_pmf: self.light_pmf,
            mix_weight,
            samples_per_dispatch: 1,
            pad: 0,
            cam_origin: v4(cam.origin, tan_x),
            cam_forward: v4(forward, tan_y),
            cam_right: v4(right, 0.0),
            cam_up: v4(up, 0.0),
        }
    }
}
