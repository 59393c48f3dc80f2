//! The `principled` material's keys, Mitsuba's defaults and rules, and its errors.

use crate::materials::principled::{PrincipledParam, eta_from_specular};
use crate::scene::desc::{MaterialDesc, PrincipledDesc};
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

fn principled(value: Value) -> (PrincipledDesc, bool) {
    let d = parse_scene_value(&with(value)).unwrap_or_else(|e| panic!("{e}"));
    let m = &d.materials[3];
    let MaterialDesc::Principled(p) = &m.material else {
        panic!("{:?}", m.material)
    };
    (p.clone(), m.two_sided)
}

#[test]
fn defaults_are_mitsubas() {
    let (p, two_sided) = principled(json!({"type": "principled"}));
    assert_eq!(p.base_color, DVec3::splat(0.5));
    let mut scalars = [0.0; 10];
    scalars[PrincipledParam::Roughness as usize] = 0.5;
    assert_eq!(p.scalars, scalars);
    assert_eq!(p.eta, eta_from_specular(0.5) as f64);
    assert_eq!(p.eta, 1.5, "2/(1 − √0.04) − 1");
    assert_eq!(p.rates, [1.0; 3]);
    assert!(!p.transmission && two_sided);
    assert_eq!(p, PrincipledDesc::default());
}

#[test]
fn every_key_is_read_and_written_back() {
    let mut v = json!({
        "type": "principled", "base_color": [0.8, 0.4, 0.2], "eta": 1.33,
        "main_specular_sampling_rate": 0.5, "clearcoat_sampling_rate": 3,
        "diffuse_reflectance_sampling_rate": 2,
    });
    for (k, param) in PrincipledParam::ALL.into_iter().enumerate() {
        v[param.name()] = json!(0.05 * (k + 1) as f64);
    }
    let d = parse_scene_value(&with(v)).unwrap();
    let MaterialDesc::Principled(p) = &d.materials[3].material else {
        panic!()
    };
    for (k, x) in p.scalars.iter().enumerate() {
        assert_eq!(*x, 0.05 * (k + 1) as f64);
    }
    assert_eq!((p.eta, p.rates), (1.33, [0.5, 3.0, 2.0]));
    assert!(p.transmission, "spec_trans 0.2");
    let m = p.material();
    assert_eq!(m.clearcoat_gloss, 0.5);
    assert_eq!(m.base_color, glam::Vec3::new(0.8, 0.4, 0.2));
    // The description writes back what it read (eta, not specular).
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

/// Mitsuba's flag: `spec_trans` a texture or a number other than 0 turns transmission on, and
/// with it η = 1 becomes 1.001 and specular 0 becomes 1e-3; without, they stay.
#[test]
fn transmission_follows_mitsubas_flag() {
    let (p, _) = principled(json!({"type": "principled", "spec_trans": 0.0}));
    assert!(!p.transmission);
    let checker = json!({"type": "checkerboard", "color0": 0.0, "color1": 0.0});
    let (p, two_sided) = principled(json!({"type": "principled", "spec_trans": checker}));
    assert!(p.transmission && !two_sided, "a texture, even of zeros");
    let (p, _) = principled(json!({"type": "principled", "spec_trans": 0.5, "eta": 1.0}));
    assert_eq!(p.eta, 1.001f32 as f64);
    let (p, _) = principled(json!({"type": "principled", "eta": 1.0}));
    assert_eq!(p.eta, 1.0);
    let (p, _) = principled(json!({"type": "principled", "spec_trans": 0.5, "specular": 0.0}));
    assert_eq!(p.eta, eta_from_specular(1e-3) as f64);
    let (p, _) = principled(json!({"type": "principled", "specular": 0.0}));
    assert_eq!(p.eta, 1.0);
}

#[test]
fn textures_fill_their_slots_and_stand_in_by_their_mean() {
    let checker = |a: f64, b: f64| json!({"type": "checkerboard", "color0": a, "color1": b});
    let d = parse_scene_value(&with(json!({
        "type": "principled", "roughness": checker(0.2, 0.6),
        "base_color": {"type": "checkerboard", "color0": [1, 0, 0], "color1": [0, 0, 1]},
    })))
    .unwrap();
    let m = &d.materials[3];
    let MaterialDesc::Principled(p) = &m.material else {
        panic!()
    };
    assert!(m.textures.albedo.is_some() && m.textures.principled[0].is_some());
    assert!(m.textures.principled[1..].iter().all(Option::is_none));
    // Texture means are f32.
    assert!((p.scalars[0] - 0.4).abs() < 1e-7, "{}", p.scalars[0]);
    assert_eq!(p.base_color, DVec3::new(0.5, 0.0, 0.5));
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

#[test]
fn bad_input_is_one_located_error() {
    let s = with(json!({"type": "principled", "eta": 1.5, "specular": 0.5}));
    expect_err(
        &s,
        &format!("{PATH}.specular"),
        "give eta or specular, not both",
    );
    for bad in [0.0, -1.0, 10.5] {
        let s = with(json!({"type": "principled", "eta": bad}));
        expect_err(
            &s,
            &format!("{PATH}.eta"),
            "must be positive and at most 10",
        );
    }
    for bad in [-0.1, 1.5] {
        let s = with(json!({"type": "principled", "specular": bad}));
        expect_err(&s, &format!("{PATH}.specular"), "outside [0, 1]");
        for param in PrincipledParam::ALL {
            let s = with(json!({"type": "principled", param.name(): bad}));
            expect_err(&s, &format!("{PATH}.{}", param.name()), "outside [0, 1]");
        }
    }
    let s = with(json!({"type": "principled", "base_color": [1.2, 0, 0]}));
    expect_err(&s, &format!("{PATH}.base_color[0]"), "outside [0, 1]");
    let s = with(json!({"type": "principled", "clearcoat_sampling_rate": -1}));
    expect_err(
        &s,
        &format!("{PATH}.clearcoat_sampling_rate"),
        "finite number ≥ 0",
    );
    let s = with(json!({"type": "principled", "spec_trans": 0.3, "two_sided": true}));
    expect_err(&s, &format!("{PATH}.two_sided"), "never two-sided");
    let s = with(json!({"type": "principled", "albedo": [1, 1, 1]}));
    expect_err(&s, &format!("{PATH}.albedo"), "unknown key `albedo`");
    let tex = json!({"type": "checkerboard", "color0": 0.5, "color1": 1.5});
    let s = with(json!({"type": "principled", "metallic": tex}));
    expect_err(
        &s,
        &format!("{PATH}.metallic.color1"),
        "principled parameter",
    );
}
