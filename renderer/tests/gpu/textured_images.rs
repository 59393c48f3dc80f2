//! A textured scene rendered on the GPU agrees with the CPU's render (issue 17, item 7; the
//! lookups, material resolution and texture coordinates are compared function by function in
//! `renderer/tests/gpu/parity_textures.rs`). The scene has every textured slot the GPU mirrors, on every
//! shape kind that has its own texture coordinates: a checkerboard albedo on a diffuse floor
//! (quad), a bitmap albedo with black texels on a smooth-coated plastic sphere (where the base is
//! black the material is a pure mirror: no light sampling there), a bitmap reflectance and a
//! bitmap α (channel g, some texels 0: mirrors) on a conductor box, a checkerboard α (0 or 0.3)
//! on a glass sphere and a bitmap albedo on a diffuse disk, under a quad light and a constant sky.
//! Every texture has a transform that breaks its symmetries, so a flipped axis changes the image.
//!
//! Two checks: the block z-test of `renderer/tests/gpu/images.rs` (8×8 blocks of the 64×64 image,
//! family-wise α = 0.01, both films' variances; 32 spp each, GPU seeds 4100 + i, CPU 5100 + i)
//! with light sampling and with MIS, and the same random streams giving the CPU's image up to
//! rounding with every strategy (seed 11, 4 spp: at most 1 pixel in 1000 diverged, relMSE <
//! 1e-5, the bound of `renderer/tests/gpu/parity_mesh.rs`).

use crate::gpu_common;
use glam::Vec3;
use gpu_common::images::{cpu_render, decide_gpu_vs_cpu, gpu_render};
use lumis::image_io::Image;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::rng::Rng;
use lumis::scene::{Scene, parse_scene};
use std::path::Path;
use std::sync::Arc;

/// A `w × h` linear EXR of texels drawn by `texel` from a fixed stream.
fn write_exr(path: &Path, w: u32, h: u32, mut texel: impl FnMut(u32, &mut Rng) -> Vec3) {
    let mut r = Rng::new(17, 80, w * h);
    let data = (0..w * h).map(|i| texel(i, &mut r)).collect();
    Image {
        width: w,
        height: h,
        data,
    }
    .write(path, 0.0)
    .unwrap();
}

/// The textured scene of the module doc, `size` pixels square.
fn textured_scene(size: u32) -> Arc<Scene> {
    let dir = std::env::temp_dir().join(format!("lumis-gpu-tex-img-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (albedo, rough) = (dir.join("albedo.exr"), dir.join("rough.exr"));
    // Every fifth texel black (a plastic with no smooth part there), the others in [0.05, 0.9].
    write_exr(&albedo, 8, 6, |i, r| {
        let c = Vec3::new(r.next_f32(), r.next_f32(), r.next_f32()) * 0.85 + 0.05;
        if i % 5 == 0 { Vec3::ZERO } else { c }
    });
    // Green (the α read) 0 in every other texel, else in [0.1, 0.5].
    write_exr(&rough, 4, 4, |i, r| {
        let g = if i % 2 == 0 {
            0.0
        } else {
            0.1 + 0.4 * r.next_f32()
        };
        Vec3::new(r.next_f32(), g, r.next_f32())
    });
    let (a, g) = (albedo.display(), rough.display());
    let json = format!(
        r#"{{
  "camera": {{"from": [0, 1.6, -4.2], "to": [0, 0.5, 0.5], "up": [0, 1, 0], "vfov_deg": 45, "width": {size}, "height": {size}}},
  "background": [0.2, 0.22, 0.25],
  "materials": {{
    "floor": {{"type": "diffuse", "albedo": {{"type": "checkerboard", "color0": [0.75, 0.65, 0.3],
               "color1": [0.1, 0.25, 0.5], "uv_scale": [3, 5], "uv_offset": [0.1, 0.27]}}}},
    "wood": {{"type": "plastic", "alpha": 0, "albedo": {{"type": "bitmap", "file": "{a}",
              "wrap": "mirror", "uv_scale": [2, 1.5]}}}},
    "metal": {{"type": "conductor", "reflectance": {{"type": "bitmap", "file": "{a}"}},
               "alpha": {{"type": "bitmap", "file": "{g}", "channel": "g", "wrap": "clamp",
                          "uv_scale": [1.5, 1.5], "uv_offset": [-0.2, 0]}}}},
    "glass": {{"type": "dielectric", "ior": 1.5, "alpha": {{"type": "checkerboard", "color0": 0,
               "color1": 0.3, "uv_scale": [4, 2]}}}},
    "disc": {{"type": "diffuse", "albedo": {{"type": "bitmap", "file": "{a}", "wrap": "clamp",
              "uv_offset": [-0.2, 0.1]}}}}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "floor"}},
    {{"type": "sphere", "center": [-1.2, 0.55, 0.2], "radius": 0.55, "material": "wood"}},
    {{"type": "box", "min": [-0.45, 0, -0.45], "max": [0.45, 0.9, 0.45], "rotate_y_deg": 25,
      "translate": [0.1, 0, 0.9], "material": "metal"}},
    {{"type": "sphere", "center": [1.2, 0.5, -0.1], "radius": 0.5, "material": "glass"}},
    {{"type": "disk", "center": [0, 1.3, 2.2], "normal": [0, -0.2, -1], "radius": 1.0, "material": "disc"}},
    {{"type": "quad", "corner": [-1, 3, -1], "edge_u": [2, 0, 0], "edge_v": [0, 0, 2], "emission": [5, 5, 5]}}
  ]
}}"#
    );
    let scene = Scene::from_desc(&parse_scene(&json).unwrap_or_else(|e| panic!("{e}")))
        .unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(scene.material_textures.iter().flatten().count(), 5);
    Arc::new(scene)
}

fn settings(strategy: Strategy, light_sampling: LightSampling) -> Settings {
    Settings {
        strategy,
        light_sampling,
        ..Settings::default()
    }
}

const MIS: Strategy = Strategy::Mis {
    heuristic: Heuristic::Power,
};

/// The block z-test of the module doc, with light sampling and with MIS.
#[test]
fn gpu_textured_scene_matches_the_cpu() {
    let scene = textured_scene(64);
    let mut failures = Vec::new();
    for (i, strategy) in [Strategy::Light, MIS].into_iter().enumerate() {
        let s = settings(strategy, LightSampling::SolidAngle);
        let what = format!("gpu textured scene {strategy:?} vs cpu");
        let Some(decision) = decide_gpu_vs_cpu(&what, &scene, s, 32, 4100 + i as u32, 8) else {
            return;
        };
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Same seed, same samples: the GPU's image is the CPU's up to rounding with every strategy
/// (both light-sampling methods), as the module doc says.
#[test]
fn same_seed_gives_the_cpu_image() {
    let scene = textured_scene(64);
    let pixels = (scene.camera.width * scene.camera.height) as usize;
    let mut worst = 0.0f64;
    for (i, strategy) in [
        Strategy::Light,
        Strategy::Bsdf,
        Strategy::Mixture { light_weight: 0.5 },
        MIS,
    ]
    .into_iter()
    .enumerate()
    {
        let method = [LightSampling::SolidAngle, LightSampling::Area][i % 2];
        let s = settings(strategy, method);
        let Some(gpu) = gpu_render(&scene, s, 4, 11) else {
            return;
        };
        assert_eq!(gpu.nonfinite, 0, "{strategy:?}: non-finite samples");
        let cpu = cpu_render(&scene, s, 4, 11);
        let (g, c) = (gpu.mean(), cpu.mean());
        let diverged = g
            .iter()
            .zip(&c)
            .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * (1.0 + b.max_element()))
            .count();
        let e = lumis::metrics::relmse(&g, &c);
        eprintln!("{strategy:?}: relMSE {e:.2e}, {diverged} of {pixels} pixels diverged");
        assert!(
            diverged * 1000 <= pixels,
            "{strategy:?}: {diverged} of {pixels} pixels differ from the CPU's"
        );
        worst = worst.max(e);
    }
    assert!(worst < 1e-5, "relMSE against the CPU up to {worst:e}");
}
