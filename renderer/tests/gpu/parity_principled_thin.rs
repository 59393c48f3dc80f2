//! Parity of the thin principled's WGSL twin (`materials/principled_thin.wgsl`) with
//! `materials/principled_thin.rs`: eval, pdf and sampling of thin principled BSDFs that exercise
//! every lobe and both sides, at random direction pairs (seed 23); and a program with a thin
//! principled and no principled (which still takes the principled's helpers) renders as the CPU.

use crate::gpu_common;
use gpu_common::parity::*;
use gpu_common::*;
use serde_json::json;

/// The thin principled BSDFs compared, as the scene format writes them.
fn configs() -> Vec<serde_json::Value> {
    vec![
        json!({"type": "principled_thin"}),
        json!({"type": "principled_thin", "base_color": [0.3, 0.7, 0.2], "diff_trans": 1.2,
               "spec_trans": 0.3, "roughness": 0.4, "sheen": 0.5, "sheen_tint": 0.5}),
        json!({"type": "principled_thin", "base_color": [0.9, 0.85, 0.7], "spec_trans": 0.8,
               "eta": 1.5, "roughness": 0.2, "spec_tint": 0.5, "anisotropic": 0.6}),
        json!({"type": "principled_thin", "base_color": [0.7, 0.35, 0.2], "spec_trans": 0.5,
               "diff_trans": 0.5, "flatness": 0.5, "eta": 0.8, "roughness": 0.35,
               "specular_reflectance_sampling_rate": 0.5,
               "specular_transmittance_sampling_rate": 2,
               "diffuse_reflectance_sampling_rate": 3,
               "diffuse_transmittance_sampling_rate": 0.7}),
    ]
}

/// eval, pdf and sampling against the CPU (`gpu_common::parity::materials_match`, seed 23).
#[test]
fn principled_thin_matches() {
    materials_match("thin principled", &configs(), 23, 1000);
}

/// A program with thin principled materials and no other principled (it takes the principled's
/// helpers, `gpu/shader.rs`) compiles and renders what the CPU renders from the same seed, in
/// every strategy (relMSE below the same-seed check's 1e-6).
#[test]
fn thin_principled_program_renders_as_the_cpu() {
    if context().is_none() {
        return;
    }
    let mut materials = serde_json::Map::new();
    let mut shapes = Vec::new();
    for (i, c) in configs().into_iter().enumerate() {
        materials.insert(format!("p{i}"), c);
        shapes.push(json!({"type": "sphere", "center": [i as f64 - 1.5, 0.4, 0], "radius": 0.4, "material": format!("p{i}")}));
    }
    shapes.push(json!({"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "p0"}));
    shapes.push(json!({"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [8, 8, 8]}));
    let desc = json!({
        "camera": {"from": [0, 1.2, -4], "to": [0, 0.4, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 32, "height": 24},
        "background": [0.2, 0.2, 0.25],
        "materials": materials,
        "shapes": shapes
    });
    let scene = build(&desc.to_string());
    assert!(scene.has_transmission());
    for strategy in crate::common::STRATEGIES {
        let what = format!("thin principled, {strategy:?}");
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
