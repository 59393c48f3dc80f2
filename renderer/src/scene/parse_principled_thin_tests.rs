//! The `principled_thin` material's keys, Mitsuba's defaults, and its errors.

use crate::materials::principled_thin::{ThinParam, ThinRates};
use crate::scene::desc::{MaterialDesc, PrincipledThinDesc};
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

#[test]
fn defaults_are_mitsubas() {
    let d = parse_scene_value(&with(json!({"type": "principled_thin"}))).unwrap();
    let MaterialDesc::PrincipledThin(p) = &d.materials[3].material else {
        panic!("{:?}", d.materials[3].material)
    };
    assert_eq!(p.base_color, DVec3::splat(0.5));
    let mut scalars = [0.0; 9];
    scalars[ThinParam::Roughness as usize] = 0.5;
    scalars[ThinParam::Eta as usize] = 1.5;
    assert_eq!(p.scalars, scalars);
    assert_eq!(p.rates, [1.0; 4]);
    assert_eq!(*p, PrincipledThinDesc::default());
    assert!(d.materials[3].material.transmits());
}

#[test]
fn every_key_is_read_and_written_back() {
    let mut v = json!({"type": "principled_thin", "base_color": [0.8, 0.4, 0.2]});
    for (k, param) in ThinParam::ALL.into_iter().enumerate() {
        v[param.name()] = json!(0.05 * (k + 1) as f64);
    }
    for (k, key) in ThinRates::KEYS.into_iter().enumerate() {
        v[key] = json!(0.5 + k as f64);
    }
    let d = parse_scene_value(&with(v)).unwrap();
    let MaterialDesc::PrincipledThin(p) = &d.materials[3].material else {
        panic!()
    };
    for (k, x) in p.scalars.iter().enumerate() {
        assert_eq!(*x, 0.05 * (k + 1) as f64);
    }
    assert_eq!(p.rates, [0.5, 1.5, 2.5, 3.5]);
    let m = p.material();
    assert_eq!((m.diff_trans, m.eta), (0.4, 0.45));
    assert_eq!(m.rates.diffuse_transmission, 3.5);
    assert_eq!(m.base_color, glam::Vec3::new(0.8, 0.4, 0.2));
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

/// Each scalar texture lands in its slot (the thin's own order) with its own range: a diff_trans
/// texture up to 2 and an eta texture above 1 are accepted; their means stand in.
#[test]
fn textures_fill_their_slots_with_their_ranges() {
    let checker = |a: f64, b: f64| json!({"type": "checkerboard", "color0": a, "color1": b});
    let d = parse_scene_value(&with(json!({
        "type": "principled_thin", "diff_trans": checker(0.4, 1.6), "eta": checker(1.2, 1.8),
        "base_color": {"type": "checkerboard", "color0": [1, 0, 0], "color1": [0, 0, 1]},
    })))
    .unwrap();
    let m = &d.materials[3];
    let MaterialDesc::PrincipledThin(p) = &m.material else {
        panic!()
    };
    let (dt, eta) = (ThinParam::DiffTrans as usize, ThinParam::Eta as usize);
    for (k, slot) in m.textures.principled.iter().enumerate() {
        assert_eq!(slot.is_some(), k == dt || k == eta, "slot {k}");
    }
    assert!((p.scalars[dt] - 1.0).abs() < 1e-6 && (p.scalars[eta] - 1.5).abs() < 1e-6);
    assert_eq!(p.base_color, DVec3::new(0.5, 0.0, 0.5));
    let back = parse_scene_value(&d.to_json()).unwrap();
    assert_eq!(back.materials[3], d.materials[3]);
}

#[test]
fn bad_input_is_one_located_error() {
    for param in ThinParam::ALL {
        let (lo, hi) = param.range();
        let s = with(json!({"type": "principled_thin", param.name(): hi as f64 + 0.5}));
        expect_err(&s, &format!("{PATH}.{}", param.name()), "must");
        let s = with(json!({"type": "principled_thin", param.name(): lo as f64 - 0.1}));
        expect_err(&s, &format!("{PATH}.{}", param.name()), "must");
    }
    let s = with(json!({"type": "principled_thin", "eta": 0.0}));
    expect_err(&s, &format!("{PATH}.eta"), "positive");
    let s = with(json!({"type": "principled_thin", "two_sided": true}));
    expect_err(&s, &format!("{PATH}.two_sided"), "same from both sides");
    let s = with(json!({"type": "principled_thin", "metallic": 0.5}));
    expect_err(&s, &format!("{PATH}.metallic"), "unknown key `metallic`");
    let s = with(json!({"type": "principled_thin", "diffuse_transmittance_sampling_rate": -1}));
    expect_err(
        &s,
        &format!("{PATH}.diffuse_transmittance_sampling_rate"),
        "finite number ≥ 0",
    );
    let tex = json!({"type": "checkerboard", "color0": 0.5, "color1": 2.5});
    let s = with(json!({"type": "principled_thin", "diff_trans": tex}));
    expect_err(&s, &format!("{PATH}.diff_trans.color1"), "[0, 2]");
}
