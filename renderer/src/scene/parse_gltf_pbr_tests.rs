//! The `gltf_pbr` material's keys, glTF's defaults, and its errors.

use crate::materials::gltf_pbr::GltfParam;
use crate::scene::desc::{GltfPbrDesc, MaterialDesc};
use crate::scene::parse::parse_scene_value;
use crate::scene::tests::{base, expect_err};
use glam::DVec3;
use serde_json::{Value, json};

const PATH: &str = "materials.white";

/// The base scene with material "white" (index 3) replaced by `value`.
fn with(value: Value) -> Value {
    let mut s = base();
    s["materials"]["white"] = value;
    s
}

/// Catches a default that is not glTF's (base colour 1, metallic 1, roughness 1, ior 1.5).
#[test]
fn defaults_are_gltfs() {
    let d = parse_scene_value(&with(json!({"type": "gltf_pbr"}))).unwrap();
    let m = &d.materials[3];
    let MaterialDesc::GltfPbr(p) = &m.material else {
        panic!("{:?}", m.material)
    };
    assert_eq!(p.base_color, DVec3::ONE);
    assert_eq!(p.scalars, [1.0, 1.0]);
    assert_eq!(p.ior, 1.5);
    assert_eq!((p.specular, p.specular_color), (1.0, DVec3::ONE));
    assert_eq!(*p, GltfPbrDesc::default());
    assert!(m.two_sided && !m.material.transmits());
}

/// Catches a key read into the wrong field or not written back.
#[test]
fn every_key_is_read_and_written_back() {
    let v = json!({
        "type": "gltf_pbr", "base_color": [0.8, 0.4, 0.2], "roughness": 0.3, "metallic": 0.6,
        "ior": 1.33, "two_sided": false, "specular": 0.25, "specular_color": [2, 0.5, 0],
    });
    let d = parse_scene_value(&with(v)).unwrap();
    let MaterialDesc::GltfPbr(p) = &d.materials[3].material else {
        panic!()
    };
    assert_eq!(p.scalars, [0.3, 0.6]);
    let m = p.material();
    assert_eq!((m.roughness, m.metallic, m.ior), (0.3, 0.6, 1.33));
    assert_eq!(m.specular, 0.25);
    assert_eq!(m.specular_color, glam::Vec3::new(2.0, 0.5, 0.0));
    assert_eq!(m.base_color, glam::Vec3::new(0.8, 0.4, 0.2));
    assert!(!d.materials[3].two_sided);
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

/// A roughness or metallic texture lands in its slot (`GltfParam::ALL`'s order), its mean
/// standing in; a bitmap's channel is how glTF's metallicRoughnessTexture is read.
#[test]
fn textures_fill_their_slots() {
    let checker = |a: f64, b: f64| json!({"type": "checkerboard", "color0": a, "color1": b});
    let d = parse_scene_value(&with(json!({
        "type": "gltf_pbr", "metallic": checker(0.2, 0.6),
        "base_color": {"type": "checkerboard", "color0": [1, 0, 0], "color1": [0, 0, 1]},
    })))
    .unwrap();
    let m = &d.materials[3];
    let MaterialDesc::GltfPbr(p) = &m.material else {
        panic!()
    };
    let metallic = GltfParam::Metallic as usize;
    for (k, slot) in m.textures.principled.iter().enumerate() {
        assert_eq!(slot.is_some(), k == metallic, "slot {k}");
    }
    assert!((p.scalars[metallic] - 0.4).abs() < 1e-6);
    assert_eq!(p.scalars[GltfParam::Roughness as usize], 1.0);
    assert_eq!(p.base_color, DVec3::new(0.5, 0.0, 0.5));
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

/// Each bad value is one error at its JSON path.
#[test]
fn bad_input_is_one_located_error() {
    for param in GltfParam::ALL {
        for bad in [1.5, -0.1] {
            let s = with(json!({"type": "gltf_pbr", param.name(): bad}));
            expect_err(&s, &format!("{PATH}.{}", param.name()), "[0, 1]");
        }
    }
    for bad in [0.99, 0.0, -2.0] {
        let s = with(json!({"type": "gltf_pbr", "ior": bad}));
        expect_err(&s, &format!("{PATH}.ior"), "≥ 1");
    }
    let s = with(json!({"type": "gltf_pbr", "base_color": [0.5, 1.5, 0.5]}));
    expect_err(&s, &format!("{PATH}.base_color[1]"), "[0, 1]");
    for bad in [1.5, -0.5] {
        let s = with(json!({"type": "gltf_pbr", "specular": bad}));
        expect_err(&s, &format!("{PATH}.specular"), "[0, 1]");
    }
    let s = with(json!({"type": "gltf_pbr", "specular_color": [1, -0.5, 1]}));
    expect_err(
        &s,
        &format!("{PATH}.specular_color[1]"),
        "finite number ≥ 0",
    );
    let s = with(json!({"type": "gltf_pbr", "alpha": 0.5}));
    expect_err(&s, &format!("{PATH}.alpha"), "unknown key `alpha`");
    let tex = json!({"type": "checkerboard", "color0": 0.5, "color1": 2.5});
    let s = with(json!({"type": "gltf_pbr", "roughness": tex}));
    expect_err(&s, &format!("{PATH}.roughness.color1"), "[0, 1]");
}
