//! Helpers of the parity tests (the WGSL twins against their Rust modules on the same inputs):
//! the parity scene, running a snippet, random inputs and the shared tolerances.

use super::{Compare, build, context};
use glam::{Vec2, Vec3};
use lumis::gpu::GpuScene;
use lumis::gpu::kernel::run_snippet;
use lumis::integrator::Settings;
use lumis::materials::Material;
use lumis::rng::Rng;
use lumis::sampling;
use serde_json::json;
use std::sync::Arc;

/// Every material kind and variant, every light kind, more than 4 primitives (so the BVH is on).
pub const PARITY_SCENE: &str = r#"{
  "camera": {"from": [0, 2, -6], "to": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 50, "width": 8, "height": 8},
  "background": [0.2, 0.3, 0.4],
  "materials": {
    "diffuse": {"type": "diffuse", "albedo": [0.7, 0.5, 0.3]},
    "gold": {"type": "conductor", "alpha": 0.2, "eta": [0.143, 0.374, 1.442], "k": [3.983, 2.385, 1.603]},
    "tinted_copper": {"type": "conductor", "alpha": 0.25, "eta": [0.2, 0.92, 1.1], "k": [3.9, 2.45, 2.14], "specular": [0.9, 0.7, 0.5]},
    "tint": {"type": "conductor", "alpha": 0.6, "reflectance": [0.9, 0.6, 0.3]},
    "mirror": {"type": "conductor", "alpha": 0.0, "reflectance": [0.95, 0.95, 0.95]},
    "beckmann": {"type": "conductor", "alpha": 0.3, "distribution": "beckmann", "reflectance": [0.8, 0.9, 0.7]},
    "plastic_rough": {"type": "plastic", "albedo": [0.2, 0.6, 0.3], "alpha": 0.3, "ior": 1.5},
    "plastic_sharp": {"type": "plastic", "albedo": [0.8, 0.2, 0.1], "alpha": 0.02, "ior": 1.8, "specular": [0.9, 0.8, 0.7]},
    "plastic_smooth": {"type": "plastic", "albedo": [0.3, 0.3, 0.9], "alpha": 0.0, "ior": 1.4},
    "mitsuba_smooth": {"type": "plastic", "model": "mitsuba", "albedo": [0.6, 0.45, 0.3], "alpha": 0.0, "ior": 1.49, "nonlinear": true},
    "mitsuba_beckmann": {"type": "plastic", "model": "mitsuba", "distribution": "beckmann", "albedo": [0.8, 0.5, 0.2], "alpha": 0.15, "ior": 1.5},
    "mitsuba_ggx": {"type": "plastic", "model": "mitsuba", "albedo": [0.1, 0.3, 0.6], "alpha": 0.3, "ior": 1.3, "specular": [0.8, 0.9, 1.0], "nonlinear": true}
  },
  "shapes": [
    {"type": "quad", "corner": [-4, 0, -4], "edge_u": [0, 0, 8], "edge_v": [8, 0, 0], "material": "diffuse"},
    {"type": "box", "min": [-0.5, 0, -0.5], "max": [0.5, 1, 0.5], "rotate_y_deg": 25, "translate": [1, 0.01, 1], "material": "gold"},
    {"type": "sphere", "center": [-1.2, 0.6, 0.4], "radius": 0.6, "material": "plastic_rough"},
    {"type": "disk", "center": [0, 1.2, 2], "normal": [0, 0, -1], "radius": 0.7, "material": "tint"},
    {"type": "triangles", "positions": [[-2, 3, -1], [-1, 3, 0], [-2, 3, 0.5]], "indices": [[0, 1, 2]], "emission": [8, 6, 4]},
    {"type": "polygon", "vertices": [[0.0, 3.6, 1.8], [-0.205725, 3.6, 1.283156], [-0.760845, 3.6, 1.247214], [-0.33287, 3.6, 0.891844], [-0.470228, 3.6, 0.352786], [-0.0, 3.6, 0.65], [0.470228, 3.6, 0.352786], [0.33287, 3.6, 0.891844], [0.760845, 3.6, 1.247214], [0.205725, 3.6, 1.283156]], "emission": [5, 5, 5]},
    {"type": "quad", "corner": [1.5, 3, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [4, 6, 9]},
    {"type": "quad", "corner": [-3, 2, 2], "edge_u": [1, 0.2, 0], "edge_v": [0.5, 0, 1], "emission": [3, 3, 3]},
    {"type": "disk", "center": [2.5, 2, 3], "normal": [-0.3, -0.2, -1], "radius": 0.4, "emission": [10, 6, 10]},
    {"type": "sphere", "center": [2.2, 0.3, -1.0], "radius": 0.3, "emission": [6, 10, 6]},
    {"type": "sphere", "center": [0.0, 2.5, -0.5], "radius": 0.2, "material": "mirror"},
    {"type": "sphere", "center": [-2.5, 0.4, -1.5], "radius": 0.4, "material": "plastic_sharp"},
    {"type": "sphere", "center": [0.5, 0.3, -2.0], "radius": 0.3, "material": "plastic_smooth"},
    {"type": "sphere", "center": [-0.6, 0.25, -2.4], "radius": 0.25, "material": "beckmann"},
    {"type": "sphere", "center": [1.6, 0.25, -2.4], "radius": 0.25, "material": "mitsuba_smooth"},
    {"type": "sphere", "center": [-1.6, 0.25, -3.0], "radius": 0.25, "material": "mitsuba_beckmann"},
    {"type": "sphere", "center": [1.0, 0.2, -3.0], "radius": 0.2, "material": "mitsuba_ggx"},
    {"type": "sphere", "center": [2.0, 0.2, -3.4], "radius": 0.2, "material": "tinted_copper"}
  ],
  "lights": [
    {"type": "point", "position": [0.5, 2.5, 0.5], "intensity": [3, 2, 1]},
    {"type": "spot", "from": [-1, 3, -1], "to": [0, 0, 0], "intensity": [9, 8, 7], "cutoff_angle_deg": 35, "beam_width_deg": 20},
    {"type": "directional", "direction": [0.3, -1, 0.2], "irradiance": [1, 1.5, 2]},
    {"type": "projector", "from": [1, 3, -2], "to": [0, 0, 0.5], "fov_deg": 50, "irradiance": [2, 3, 4], "scale": 1.5}
  ]
}"#;

/// The parity scene on the CPU and uploaded to the shared device; `None` where GPU tests are
/// skipped.
pub fn parity_scene() -> Option<(Arc<lumis::scene::Scene>, GpuScene)> {
    let ctx = context()?;
    let scene = build(PARITY_SCENE);
    let gpu = GpuScene::new(ctx, scene.clone()).expect("upload");
    Some((scene, gpu))
}

/// Runs `body` on `inputs` (`in_stride` vec4 per item) and returns `out_stride` vec4 per item.
pub fn run(
    gpu: &GpuScene,
    body: &str,
    inputs: &[[f32; 4]],
    in_stride: usize,
    out_stride: usize,
) -> Vec<[f32; 4]> {
    run_snippet(
        gpu,
        &Settings::default(),
        body,
        inputs,
        in_stride,
        out_stride,
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// A random unit vector.
pub fn unit(r: &mut Rng) -> Vec3 {
    sampling::sample_uniform_sphere(r.next_2d())
}

/// One in `per` of the values compared so far.
pub fn c_allowance(c: &Compare, per: usize) -> usize {
    c.n / per
}

/// `v` and `w` as one vec4 of a snippet's input.
pub fn f4(v: Vec3, w: f32) -> [f32; 4] {
    [v.x, v.y, v.z, w]
}

/// Random inputs per comparison.
pub const N: usize = 8192;

/// How closely the GPU's and the CPU's sampled light directions agree where the geometry is
/// well conditioned, in radians (measured on an NVIDIA H100: ~4e-6).
pub const DIRECTION_AGREEMENT: f32 = 1e-5;

/// A small scene for snippets that read only their inputs.
pub const ANY_SCENE: &str = r#"{
  "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
  "materials": {"d": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
  "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "d"}]
}"#;

/// [`ANY_SCENE`] uploaded to the shared device; `None` where GPU tests are skipped.
pub fn any_scene_gpu() -> Option<GpuScene> {
    Some(GpuScene::new(context()?, build(ANY_SCENE)).expect("upload"))
}

/// A unit direction at a random cosine in (−1, 1) (or (0, 1) where `upper`), random azimuth.
fn direction(r: &mut Rng, upper: bool) -> Vec3 {
    let z = if upper {
        r.next_f32().max(1e-3)
    } else {
        2.0 * r.next_f32() - 1.0
    };
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * r.next_f32();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

/// Parity of the materials of `configs` (scene-format material objects) with their WGSL twins:
/// eval and pdf at random pairs (seed `seed`; the viewer on either side of a transmitting one),
/// and the sample drawn with the same random numbers: direction, weight, pdf and η'. Tolerances:
/// 2e-4 relative, with an absolute floor of 1e-7 of each value's largest magnitude over the test
/// (the CPU may sum a refraction's half vector in f64, the GPU in f32: in a lobe's far tail,
/// where that sum nearly cancels, the two differ by more than any relative bound, on values 1e7
/// below the peak). A sample whose lobe choice or validity sits within 1e-4 of a boundary is left
/// out and counted (at most 1 in 500); more than half the samples must be compared, more than
/// `min_crossings` of them crossing the surface (0: a reflection-only material, none may).
pub fn materials_match(what: &str, configs: &[serde_json::Value], seed: u32, min_crossings: usize) {
    let Some(ctx) = context() else {
        return;
    };
    let mut materials = serde_json::Map::new();
    for (i, c) in configs.iter().enumerate() {
        materials.insert(format!("p{i}"), c.clone());
    }
    let desc = json!({
        "camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 4, "height": 4},
        "materials": materials,
        "shapes": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "p0"}]
    });
    let scene = build(&desc.to_string());
    let list: Vec<(Material, usize)> = (0..configs.len())
        .map(|i| {
            let index = scene
                .material_names
                .iter()
                .position(|n| *n == format!("p{i}"))
                .unwrap();
            (scene.materials[index].clone(), index)
        })
        .collect();
    let gpu = GpuScene::new(ctx, scene).expect("upload");
    let mut r = Rng::new(seed, 0, 0);
    let items = 4 * N;
    let mut inputs = Vec::with_capacity(3 * items);
    for k in 0..items {
        let (m, index) = &list[k % list.len()];
        let wo = direction(&mut r, !m.transmits());
        let wi = direction(&mut r, false);
        inputs.push([wo.x, wo.y, wo.z, *index as f32]);
        inputs.push([wi.x, wi.y, wi.z, k as f32]);
        inputs.push([r.next_f32(), r.next_f32(), r.next_f32(), 0.0]);
    }
    let out = run(
        &gpu,
        "let m = materials[u32(inp(0u).w)]; let wo = inp(0u).xyz; let wi = inp(1u).xyz;
         let u = inp(2u);
         outp(0u, vec4f(material_eval(m, wo, wi), material_pdf(m, wo, wi)));
         let s = material_sample(m, wo, u.x, u.yz);
         outp(1u, vec4f(s.wi, select(-1.0, s.pdf, s.ok)));
         outp(2u, vec4f(s.weight, s.eta));",
        &inputs,
        3,
        3,
    );
    let scale = |f: &dyn Fn(&[[f32; 4]]) -> f32| out.chunks(3).map(f).fold(0.0f32, f32::max);
    let eval_scale = scale(&|o| o[0][..3].iter().fold(0.0f32, |a, b| a.max(b.abs())));
    let pdf_scale = scale(&|o| o[0][3].abs());
    let mut eval = Compare::new(&format!("{what} eval"), 2e-4, 1e-7 * eval_scale);
    let mut pdf = Compare::new(&format!("{what} pdf"), 2e-4, 1e-7 * pdf_scale);
    let mut sample = Compare::new(&format!("{what} sample"), 2e-4, 1e-5);
    let (mut sampled, mut ambiguous, mut none) = (0, 0, 0);
    let mut crossings = 0;
    for (i, o) in inputs.chunks(3).zip(out.chunks(3)) {
        let k = i[1][3] as usize;
        let m = &list[k % list.len()].0;
        let wo = Vec3::from_slice(&i[0][..3]);
        let wi = Vec3::from_slice(&i[1][..3]);
        let what = format!("{m:?} wo {wo} wi {wi}");
        let f = m.eval(wo, wi);
        for c in 0..3 {
            eval.scalar(o[0][c], f[c], &what);
        }
        pdf.scalar(o[0][3], m.pdf(wo, wi), &what);
        let (u_lobe, u) = (i[2][0], Vec2::new(i[2][1], i[2][2]));
        let s = m.sample(wo, u_lobe, u);
        let gpu_ok = o[1][3] >= 0.0;
        match s {
            Some(s) if gpu_ok => {
                sampled += 1;
                crossings += usize::from(s.wi.z * wo.z < 0.0);
                let what = format!("{what} u {u_lobe} {u}");
                for (g, w) in o[1][..3].iter().zip(s.wi.to_array()) {
                    sample.scalar(*g, w, &format!("wi, {what}"));
                }
                // Weights and pdfs as relative quantities.
                let mut rel = Compare::new("", 2e-4, 0.0);
                rel.scalar(o[1][3], s.pdf, &what);
                for (g, w) in o[2][..3].iter().zip(s.weight.to_array()) {
                    rel.scalar(*g, w, &what);
                }
                rel.scalar(o[2][3], s.eta, &what);
                if rel.bad > 0 {
                    ambiguous += 1;
                }
            }
            None if !gpu_ok => none += 1,
            // One side's lobe choice or validity test fell the other way.
            _ => ambiguous += 1,
        }
    }
    eprintln!(
        "{what}: {sampled} samples compared ({crossings} crossing the surface), {none} \
         refused by both, {ambiguous} different (a lobe boundary, a validity edge or a weight \
         beyond 2e-4)"
    );
    let crossings_ok = match min_crossings {
        0 => crossings == 0,
        n => crossings > n,
    };
    assert!(sampled > items / 2 && crossings_ok, "{sampled} {crossings}");
    assert!(ambiguous < items / 500, "{ambiguous} of {items}");
    eval.finish(0);
    pdf.finish(0);
    sample.finish(0);
}
