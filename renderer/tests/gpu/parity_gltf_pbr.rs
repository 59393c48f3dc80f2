//! Parity of glTF's metallic-roughness material's WGSL twin (`materials/gltf_pbr.wgsl`) with
//! `materials/gltf_pbr.rs`: eval, pdf and sampling of materials across its parameters at random
//! direction pairs (seed 44), `KHR_materials_specular`'s weight and colour among them; and a
//! program with it and nothing else that samples GGX (its roughness and metallic textured, the
//! base colour too) renders as the CPU.

use crate::gpu_common;
use gpu_common::parity::*;
use gpu_common::*;
use serde_json::json;

/// The glTF materials compared, as the scene format writes them.
fn configs() -> Vec<serde_json::Value> {
    vec![
        json!({"type": "gltf_pbr"}),
        json!({"type": "gltf_pbr", "base_color": [0.8, 0.3, 0.1], "metallic": 0, "roughness": 0.5}),
        json!({"type": "gltf_pbr", "base_color": [0.9, 0.6, 0.2], "metallic": 0.4,
               "roughness": 0.25, "ior": 1.8}),
        json!({"type": "gltf_pbr", "base_color": [0.5, 0.5, 0.5], "metallic": 0,
               "roughness": 0.7, "ior": 1.0}),
        json!({"type": "gltf_pbr", "base_color": [0.95, 0.64, 0.54], "roughness": 0.05}),
        json!({"type": "gltf_pbr", "base_color": [0.6, 0.6, 0.3], "metallic": 0.2,
               "roughness": 0.4, "specular": 0.5, "specular_color": [1.5, 0.5, 20]}),
    ]
}

/// eval, pdf and sampling against the CPU (`gpu_common::parity::materials_match`, seed 44; it
/// reflects only, so no sample may cross the surface).
#[test]
fn gltf_pbr_matches() {
    materials_match("glTF PBR", &configs(), 44, 0);
}

/// A program with glTF materials (textured roughness, metallic and base colour among them) and
/// no other rough material compiles and renders what the CPU renders from the same seed, in
/// every strategy (relMSE below the same-seed check's 1e-6).
#[test]
fn gltf_pbr_program_renders_as_the_cpu() {
    if context().is_none() {
        return;
    }
    let checker = |a: f64, b: f64| json!({"type": "checkerboard", "color0": a, "color1": b, "uv_scale": [4, 4]});
    let mut configs = configs();
    configs.push(json!({"type": "gltf_pbr", "roughness": checker(0.2, 0.8),
        "metallic": checker(0.0, 1.0), "two_sided": false,
        "base_color": {"type": "checkerboard", "color0": [0.9, 0.2, 0.1], "color1": [0.1, 0.5, 0.9]}}));
    let mut materials = serde_json::Map::new();
    let mut shapes = Vec::new();
    for (i, c) in configs.into_iter().enumerate() {
        materials.insert(format!("p{i}"), c);
        shapes.push(json!({"type": "sphere", "center": [0.9 * i as f64 - 2.7, 0.4, 0], "radius": 0.4, "material": format!("p{i}")}));
    }
    // The textured one (the last) on the floor too.
    shapes.push(json!({"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "p6"}));
    shapes.push(json!({"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [8, 8, 8]}));
    let desc = json!({
        "camera": {"from": [0, 1.2, -5], "to": [0, 0.4, 0], "up": [0, 1, 0], "vfov_deg": 50, "width": 32, "height": 24},
        "background": [0.2, 0.2, 0.25],
        "materials": materials,
        "shapes": shapes
    });
    let scene = build(&desc.to_string());
    assert!(!scene.has_transmission());
    for strategy in crate::common::STRATEGIES {
        let what = format!("glTF PBR, {strategy:?}");
        let settings = lumis::integrator::Settings {
            strategy,
            ..Default::default()
        };
        let r = gpu_common::images::same_seed_check(&what, &scene, settings).expect("a GPU");
        if let Err(e) = r {
            panic!("{e}");
        }
    }
}
