//! A glTF material of metallic 0.5 converges to the average of the metallic-1 and metallic-0
//! images of the same file. Until issue 44 that material was a mix of a conductor and a plastic
//! (issue 17, item 3, `materials/mix.rs`); it is now glTF's own `gltf_pbr`
//! (`materials/gltf_pbr.rs`), whose BRDF is linear in the metallic,
//! (1 − m)·dielectric + m·metal, so the same test holds. The scene: a rough (roughness 0.5, α
//! 0.25) coloured floor lit by an emitting glTF quad above it (so the glossy metal and the
//! diffuse-looking dielectric differ strongly across the image), opened as a model file
//! ([`lumis::scene::load_scene`]) and rendered at 48 × 36. The floor cannot see itself, so a path
//! meets the floor a second time only through the light's own reflection (a black metal: only
//! Schlick's grazing (1 − V·H)⁵ of its rough lobe), where the image would be
//! `((f_a + f_b)/2)²` and not `(f_a² + f_b²)/2`; with the conductor of the old mapping that
//! reflection was 0, now it is small enough that the test's blocks pass.
//!
//! Test: the block z-test (8 × 8 blocks, family-wise α = 0.01, Šidák-corrected over blocks and
//! channels) of the mix against `(A + B)/2`, with variance `(var A + var B)/4`; seeds 1, 2, 3,
//! 256 samples per pixel. Power: the same test must reject a mix of metallic 0.6 against the 0.5
//! average (seed 4): a 10-point error in the weight, 0.1·(A − B) per pixel, which catches a
//! metallic that is ignored, swapped (1 − m) or weighted differently at eval and sample.

mod common;

use common::{check_unbiased, render};
use lumis::integrator::Settings;
use lumis::metrics::{ImageWithVariance, block_z_test};
use lumis::scene::mesh::gltf::bytes::base64;
use lumis::scene::{Scene, load_scene};
use serde_json::json;
use std::path::PathBuf;
use std::sync::Arc;

const SPP: u32 = 256;

/// `metallic-M.gltf` in a scratch folder: two quads (the floor in material 0 of metallic
/// `metallic`, facing up; a light in material 1, facing down) and a camera.
fn write_gltf(metallic: f64) -> PathBuf {
    let quads: [[[f32; 3]; 4]; 2] = [
        [
            [-2.0, 0.0, -1.0],
            [-2.0, 0.0, 3.0],
            [2.0, 0.0, 3.0],
            [2.0, 0.0, -1.0],
        ],
        [
            [-0.4, 1.2, 0.8],
            [0.4, 1.2, 0.8],
            [0.4, 1.2, 1.4],
            [-0.4, 1.2, 1.4],
        ],
    ];
    let mut bin = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut primitives = Vec::new();
    for (i, q) in quads.iter().enumerate() {
        let start = bin.len();
        bin.extend(q.iter().flatten().flat_map(|x| x.to_le_bytes()));
        views.push(json!({"buffer": 0, "byteOffset": start, "byteLength": 48}));
        accessors.push(
            json!({"bufferView": 2 * i, "componentType": 5126, "type": "VEC3",
            "count": 4}),
        );
        let start = bin.len();
        bin.extend([0u16, 1, 2, 0, 2, 3].iter().flat_map(|x| x.to_le_bytes()));
        bin.extend([0u8; 4]);
        views.push(json!({"buffer": 0, "byteOffset": start, "byteLength": 12}));
        accessors.push(
            json!({"bufferView": 2 * i + 1, "componentType": 5123, "type": "SCALAR",
            "count": 6}),
        );
        primitives.push(
            json!({"attributes": {"POSITION": 2 * i}, "indices": 2 * i + 1,
            "material": i}),
        );
    }
    let gltf = json!({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": bin.len(),
                     "uri": format!("data:application/octet-stream;base64,{}", base64(&bin))}],
        "bufferViews": views,
        "accessors": accessors,
        "meshes": [{"primitives": primitives}],
        "materials": [
            {"doubleSided": true, "pbrMetallicRoughness": {
                "baseColorFactor": [0.9, 0.5, 0.2, 1], "metallicFactor": metallic,
                "roughnessFactor": 0.5}},
            {"emissiveFactor": [1, 1, 1],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}},
             "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 1}},
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.01}}],
        // Turned 180° about +y (looking along +z), at z = −2.5, 0.8 up.
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0.8, -2.5],
                   "rotation": [0, 1, 0, 0]}],
        "scenes": [{"nodes": [0, 1]}],
    });
    let dir = std::env::temp_dir().join(format!("lumis-gltf-mix-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!("metallic-{metallic}.gltf"));
    std::fs::write(&path, gltf.to_string()).unwrap();
    path
}

fn scene(metallic: f64) -> Arc<Scene> {
    let path = write_gltf(metallic);
    let mut desc = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_file(&path).unwrap();
    assert!(desc.warnings.is_empty(), "{:?}", desc.warnings);
    (desc.camera.width, desc.camera.height) = (48, 36);
    // One glTF material each, no mix (the old mapping's mix of metallic 0.5 fails here).
    assert!(desc.materials.iter().all(|m| m.mix.is_none()));
    let gltf = desc
        .materials
        .iter()
        .filter(|m| matches!(m.material, lumis::scene::MaterialDesc::GltfPbr(_)));
    assert_eq!(gltf.count(), 2, "the floor's and the light's");
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

/// The block test of the material of `metallic` (rendered with `seed`) against the average of
/// the metal and the dielectric renders.
fn against_average(
    metallic: f64,
    seed: u32,
    metal: &lumis::engine::Progressive,
    plastic: &lumis::engine::Progressive,
) -> lumis::metrics::BlockTest {
    let mix = render(&scene(metallic), Settings::default(), SPP, seed);
    let (a, b) = (metal.film(), plastic.film());
    let mean: Vec<glam::Vec3> = a
        .mean()
        .iter()
        .zip(b.mean())
        .map(|(x, y)| 0.5 * (*x + y))
        .collect();
    let var: Vec<[f64; 3]> = a
        .variance_of_mean()
        .iter()
        .zip(b.variance_of_mean())
        .map(|(x, y)| [0, 1, 2].map(|c| 0.25 * (x[c] + y[c])))
        .collect();
    let film = mix.film();
    block_z_test(
        film.width,
        film.height,
        &ImageWithVariance {
            mean: &film.mean(),
            var: &film.variance_of_mean(),
        },
        &ImageWithVariance {
            mean: &mean,
            var: &var,
        },
        8,
        0.01,
    )
}

#[test]
fn metallic_half_converges_to_the_average_of_metal_and_plastic() {
    let metal = render(&scene(1.0), Settings::default(), SPP, 1);
    let plastic = render(&scene(0.0), Settings::default(), SPP, 2);
    let test = against_average(0.5, 3, &metal, &plastic);
    common::assert_unbiased("metallic 0.5 vs (metal + plastic)/2", &test);
    let wrong = against_average(0.6, 4, &metal, &plastic);
    assert!(
        check_unbiased("metallic 0.6 vs the 0.5 average (must be detected)", &wrong).is_err(),
        "the test cannot tell a 0.1 error in the weight"
    );
}

/// The GPU backend renders the glTF material (`renderer/tests/gpu/parity_gltf_pbr.rs` compares
/// it with the CPU): the scene is accepted, with its code.
#[test]
fn the_gpu_accepts_the_gltf_material() {
    let scene = scene(0.5);
    // The GPU tests' policy (renderer/tests/gpu/common): no adapter fails unless skipping is asked for.
    if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
        return;
    }
    let ctx = lumis::gpu::GpuContext::new().unwrap_or_else(|e| panic!("{e}"));
    let gpu = lumis::gpu::GpuScene::new(ctx, scene).unwrap_or_else(|e| panic!("{e}"));
    assert!(gpu.features().has_gltf_pbr, "{:?}", gpu.features());
}
