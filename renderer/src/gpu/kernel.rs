//! Runs a WGSL snippet on many inputs against the uploaded scene: the GPU half of the parity
//! tests (`renderer/tests/gpu/parity.rs`), which call each WGSL function with the same random inputs as
//! its Rust twin and compare the results.
//!
//! The snippet is the body of a compute kernel with the whole library in scope (every module, as
//! [`Features::all`] but with the scene's BVH choice, CWBVH or BVH2) and the scene bound as group
//! 0. It reads its item's inputs with `inp(k)` (the k-th `vec4f`) and writes results with
//! `outp(k, v)`.
#![cfg(any(test, feature = "testing"))]

use super::GpuError;
use super::prelude::{self, Constant};
use super::scene::{GpuParams, GpuScene, PARAMS_STRIDE};
use super::shader::{Features, create_module, library_source_with};
use crate::integrator::Settings;
use wgpu::util::DeviceExt;

/// Items per workgroup of the snippet kernel.
const GROUP: u32 = 64;

/// Runs `body` once per item: `inputs` holds `in_stride` vec4s per item; the result holds
/// `out_stride` vec4s per item. Group 0 is `gpu`'s scene with the parameters of `settings` and
/// seed 0, so snippets can also trace rays and sample lights.
pub fn run_snippet(
    gpu: &GpuScene,
    settings: &Settings,
    body: &str,
    inputs: &[[f32; 4]],
    in_stride: usize,
    out_stride: usize,
) -> Result<Vec<[f32; 4]>, GpuError> {
    let constants = prelude::constants();
    run_snippet_with(
        &constants, gpu, settings, body, inputs, in_stride, out_stride,
    )
}

/// [`run_snippet`] with the prelude written from `constants` (a test's altered table).
pub(crate) fn run_snippet_with(
    constants: &[Constant],
    gpu: &GpuScene,
    settings: &Settings,
    body: &str,
    inputs: &[[f32; 4]],
    in_stride: usize,
    out_stride: usize,
) -> Result<Vec<[f32; 4]>, GpuError> {
    assert!(in_stride > 0 && inputs.len().is_multiple_of(in_stride));
    let items = (inputs.len() / in_stride) as u32;
    let kernel = format!(
        "@group(1) @binding(0) var<storage, read> kernel_in: array<vec4f>;\n\
         @group(1) @binding(1) var<storage, read_write> kernel_out: array<vec4f>;\n\
         var<private> item: u32;\n\
         fn inp(k: u32) -> vec4f {{ return kernel_in[item * {in_stride}u + k]; }}\n\
         fn outp(k: u32, v: vec4f) {{ kernel_out[item * {out_stride}u + k] = v; }}\n\
         @compute @workgroup_size({GROUP})\n\
         fn main(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
             item = gid.x + gid.y * {GROUP}u * 65535u;\n\
             if item >= {items}u {{ return; }}\n\
             {body}\n\
         }}\n"
    );
    // Everything on but what the scene's data layout decides: its BVH, and whether `tables`
    // starts with the opacity records (`materials/mask.wgsl`).
    let features = Features {
        use_bvh: gpu.features().use_bvh,
        bvh2: gpu.features().bvh2,
        has_masks: gpu.features().has_masks,
        ..Features::all()
    };
    let source = library_source_with(constants, &features, &kernel)?;
    let ctx = gpu.context();
    let device = &ctx.device;
    let module = create_module(device, "lumis snippet", &source)?;
    let io_entry = super::scene::storage_layout_entry;
    let io_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("lumis snippet io"),
        entries: &[io_entry(0, true), io_entry(1, false)],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("lumis snippet"),
        bind_group_layouts: &[Some(gpu.layout()), Some(&io_layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("lumis snippet"),
        layout: Some(&layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });

    let params: GpuParams = gpu.params(settings, 0, 0);
    let mut slot = vec![0u8; PARAMS_STRIDE as usize];
    slot[..size_of::<GpuParams>()].copy_from_slice(bytemuck::bytes_of(&params));
    let init = |label: &str, bytes: &[u8], usage: wgpu::BufferUsages| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytes,
            usage,
        })
    };
    let params = init("lumis snippet params", &slot, wgpu::BufferUsages::UNIFORM);
    let storage = wgpu::BufferUsages::STORAGE;
    let accum = init("lumis snippet accum", &[0u8; 64], storage);
    let counters = init("lumis snippet counters", &[0u8; 16], storage);
    let scene_group = gpu.bind_group(&params, &accum, &counters);
    let input = init("lumis snippet in", bytemuck::cast_slice(inputs), storage);
    let out_size = (items as u64 * out_stride as u64 * 16).max(16);
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("lumis snippet out"),
        size: out_size,
        usage: storage | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let io_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("lumis snippet io"),
        layout: &io_layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &scene_group, &[0]);
        pass.set_bind_group(1, &io_group, &[]);
        let groups = items.div_ceil(GROUP);
        pass.dispatch_workgroups(groups.min(65535), groups.div_ceil(65535), 1);
    }
    ctx.queue.submit([encoder.finish()]);
    let bytes = ctx.read_buffer(&output, out_size)?;
    let mut out: Vec<[f32; 4]> = bytemuck::cast_slice(&bytes).to_vec();
    out.truncate(items as usize * out_stride);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gpu::GpuContext;
    use crate::gpu::prelude::Value;
    use crate::scene::{Scene, parse_scene};
    use std::sync::Arc;

    /// A scene with a plastic, for snippets that read materials.
    fn plastic_scene(ctx: Arc<GpuContext>) -> GpuScene {
        let json = r#"{
          "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
          "materials": {"p": {"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.3, "ior": 1.5}},
          "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "p"}]
        }"#;
        let scene = Scene::from_desc(&parse_scene(json).unwrap()).unwrap();
        GpuScene::new(ctx, Arc::new(scene)).unwrap()
    }

    /// A constant changed on the Rust side is what the shader computes with: the prelude is the
    /// only definition (a module's own copy would fail to compile as a redefinition).
    #[test]
    fn a_changed_rust_constant_reaches_the_shader() {
        let Some(ctx) = GpuContext::for_tests() else {
            return;
        };
        let gpu = plastic_scene(ctx);
        let body = "let m = materials[0];
             outp(0u, vec4f(SMOOTH_ALPHA, f32(E_TABLE_SIZE), f32(MATERIAL_PLASTIC), f32(m.h.x)));
             outp(1u, vec4f(select(0.0, 1.0, ggx_is_smooth(0.2)), coat_node_mu(1u), material_pdf(m, vec3f(0.0, 0.0, 1.0), vec3f(0.0, 0.0, 1.0)), 0.0));";
        let run = |constants: &[Constant]| {
            run_snippet_with(
                constants,
                &gpu,
                &Settings::default(),
                body,
                &[[0.0; 4]],
                1,
                2,
            )
            .unwrap()
        };
        let normal = run(&prelude::constants());
        assert_eq!(normal[0], [1e-3, 64.0, 2.0, 2.0]);
        assert_eq!(normal[1][0], 0.0);
        assert!(normal[1][2] > 0.0, "{normal:?}");
        // SMOOTH_ALPHA 0.25 makes α = 0.2 smooth, a 4-node table moves node 1 to (1/3)³, and a
        // renumbered MATERIAL_PLASTIC no longer matches the record's tag (which the encoder
        // wrote from the unchanged Rust enum), so the material is unknown: NaN.
        let changed: Vec<Constant> = prelude::constants()
            .into_iter()
            .map(|c| Constant {
                value: match c.name {
                    "SMOOTH_ALPHA" => Value::F32(0.25),
                    "E_TABLE_SIZE" => Value::U32(4),
                    // A tag no material has (the switches need distinct cases).
                    "MATERIAL_PLASTIC" => Value::U32(100),
                    _ => c.value,
                },
                ..c
            })
            .collect();
        let out = run(&changed);
        assert_eq!(out[0], [0.25, 4.0, 100.0, 2.0]);
        assert_eq!(out[1][0], 1.0);
        let t = 1.0f32 / 3.0;
        assert_eq!(out[1][1], t * t * t);
        assert!(out[1][2].is_nan(), "{out:?}");
    }
}
