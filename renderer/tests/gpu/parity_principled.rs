//! Parity of the principled's WGSL twin (`materials/principled.wgsl`, `materials/gtr1.wgsl`) with
//! `materials/principled.rs`: eval, pdf and sampling of principled BSDFs that exercise every lobe
//! and both sides, at random direction pairs (seed 19).

use crate::gpu_common;
use gpu_common::parity::*;
use gpu_common::*;
use serde_json::json;

/// The principled BSDFs compared, as the scene format writes them.
fn configs() -> Vec<serde_json::Value> {
    vec![
        json!({"type": "principled"}),
        json!({"type": "principled", "base_color": [0.9, 0.6, 0.3], "metallic": 0.8,
               "roughness": 0.35, "anisotropic": 0.7, "spec_tint": 0.5}),
        json!({"type": "principled", "base_color": [0.8, 0.2, 0.15], "roughness": 0.2,
               "specular": 0.7, "spec_tint": 0.4, "sheen": 0.8, "sheen_tint": 0.6,
               "clearcoat": 0.8, "clearcoat_gloss": 0.5, "flatness": 0.4}),
        json!({"type": "principled", "base_color": [0.8, 0.9, 1.0], "spec_trans": 0.9, "eta": 1.5,
               "roughness": 0.3, "metallic": 0.05, "sheen": 0.3}),
        json!({"type": "principled", "base_color": [0.2, 0.6, 0.9], "spec_trans": 1.0, "eta": 0.8,
               "roughness": 0.5, "clearcoat": 0.5, "main_specular_sampling_rate": 0.5,
               "clearcoat_sampling_rate": 3, "diffuse_reflectance_sampling_rate": 2}),
    ]
}

/// eval, pdf and sampling against the CPU (`gpu_common::parity::materials_match`, seed 19).
#[test]
fn principled_matches() {
    materials_match("principled", &configs(), 19, 1000);
}

/// Programs with a principled that does not transmit (alone: no transmission code; beside a thin
/// sheet: transmission code without refraction) compile and render what the CPU renders from
/// the same seed, in every strategy (relMSE below the same-seed check's 1e-6).
#[test]
fn reflection_only_principled_programs_render_as_the_cpu() {
    if context().is_none() {
        return;
    }
    for with_sheet in [false, true] {
        let mut materials = serde_json::Map::new();
        let mut shapes = Vec::new();
        for (i, c) in configs().into_iter().take(3).enumerate() {
            materials.insert(format!("p{i}"), c);
            shapes.push(json!({"type": "sphere", "center": [i as f64 - 1.0, 0.4, 0], "radius": 0.4, "material": format!("p{i}")}));
        }
        materials.insert(
            "floor".into(),
            json!({"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}),
        );
        shapes.push(json!({"type": "quad", "corner": [-3, 0, -3], "edge_u": [0, 0, 6], "edge_v": [6, 0, 0], "material": "floor"}));
        shapes.push(json!({"type": "quad", "corner": [-0.5, 2.5, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1], "emission": [8, 8, 8]}));
        if with_sheet {
            materials.insert(
                "sheet".into(),
                json!({"type": "thin_dielectric", "ior": 1.5}),
            );
            shapes.push(json!({"type": "quad", "corner": [-1.5, 0, -1], "edge_u": [3, 0, 0], "edge_v": [0, 1.2, 0], "material": "sheet"}));
        }
        let desc = json!({
            "camera": {"from": [0, 1.2, -4], "to": [0, 0.4, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": 32, "height": 24},
            "background": [0.2, 0.2, 0.25],
            "materials": materials,
            "shapes": shapes
        });
        let scene = build(&desc.to_string());
        assert_eq!(scene.has_transmission(), with_sheet);
        for strategy in crate::common::STRATEGIES {
            let what = format!("principled without transmission, sheet {with_sheet}, {strategy:?}");
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
}
