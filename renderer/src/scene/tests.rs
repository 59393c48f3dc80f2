//! Scene tests shared by the parser modules: a small valid scene to break, the error assertion,
//! and the shared example scenes.

use super::parse::{load_scene, parse_scene, parse_scene_value};
use super::{GeometryDesc, SceneDesc};
use crate::geometry::polygon::validate_polygon;
use glam::DVec3;
use serde_json::{Value, json};
use std::path::PathBuf;

/// A valid scene using every material and shape type; tests replace one part to break a rule.
pub(crate) fn base() -> Value {
    json!({
        "comment": "test scene",
        "camera": {"from": [0, 1, -4], "to": [0, 1, 0], "up": [0, 1, 0], "vfov_deg": 40,
                   "width": 64, "height": 48},
        "max_depth": 8,
        "background": [0.1, 0.1, 0.1],
        "materials": {
            "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]},
            "metal": {"type": "conductor", "alpha": 0, "reflectance": [0.9, 0.9, 0.9]},
            "copper": {"type": "conductor", "alpha": 0.1, "eta": [0.2, 0.92, 1.1],
                       "k": [3.9, 2.45, 2.14]},
            "plastic": {"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.2},
        },
        "shapes": [
            {"type": "quad", "corner": [-5, 0, -5], "edge_u": [0, 0, 10], "edge_v": [10, 0, 0],
             "material": "white"},
            {"type": "polygon", "comment": "concave L, facing down",
             "vertices": [[0, 3, 0], [0, 3, 2], [1, 3, 2], [1, 3, 1], [2, 3, 1], [2, 3, 0]],
             "emission": [4, 4, 4]},
            {"type": "triangles", "positions": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]],
             "indices": [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], "material": "metal"},
            {"type": "disk", "center": [0, 2.9, 0], "normal": [0, -2, 0], "radius": 0.5,
             "emission": [1, 1, 1]},
            {"type": "sphere", "center": [1, 1, 1], "radius": 0.5, "material": "copper"},
            {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "plastic"},
        ],
    })
}

/// The base scene with shape `i` replaced by `value`.
pub(crate) fn with(i: usize, value: Value) -> Value {
    let mut s = base();
    s["shapes"][i] = value;
    s
}

/// Asserts that `scene` is rejected at exactly `path` with a message containing `fragment`,
/// both as a value and through the text parser.
#[track_caller]
pub(crate) fn expect_err(scene: &Value, path: &str, fragment: &str) {
    for e in [
        parse_scene_value(scene).unwrap_err(),
        parse_scene(&scene.to_string()).unwrap_err(),
    ] {
        assert_eq!(e.path, path, "wrong path in: {e}");
        assert!(
            e.message.contains(fragment),
            "expected {fragment:?} in: {e}"
        );
    }
}

fn shared(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../tests/data/scenes")
        .join(name)
}

const SHARED: [&str; 4] = [
    "analytic_disk.json",
    "analytic_polygon.json",
    "seed_cornell.json",
    "veach_mis.json",
];

#[test]
fn shared_scenes_parse() {
    for name in SHARED {
        let d = load_scene(&shared(name)).unwrap_or_else(|e| panic!("{e}"));
        assert!(d.warnings.is_empty(), "{name}: {:?}", d.warnings);
        assert!(!d.shapes.is_empty());
    }
    let cornell = load_scene(&shared("seed_cornell.json")).unwrap();
    assert_eq!(
        (
            cornell.camera.width,
            cornell.max_depth,
            cornell.shapes.len()
        ),
        (256, 50, 16)
    );
    let veach = load_scene(&shared("veach_mis.json")).unwrap();
    assert_eq!(
        (veach.camera.width, veach.camera.height, veach.max_depth),
        (320, 180, -1)
    );
}

#[test]
fn seed_cornell_hexagon_is_a_valid_polygon() {
    let d = load_scene(&shared("seed_cornell.json")).unwrap();
    let GeometryDesc::Polygon { vertices } = &d.shapes[2].geometry else {
        panic!("shapes[2] is not the hexagon");
    };
    assert_eq!(validate_polygon(vertices), Ok(DVec3::new(0.0, -1.0, 0.0)));
    assert_eq!(d.shapes[2].emission, DVec3::splat(15.0));
}

#[test]
fn to_json_round_trips() {
    let mut scenes: Vec<SceneDesc> = SHARED
        .iter()
        .map(|n| load_scene(&shared(n)).unwrap())
        .collect();
    scenes.push(parse_scene_value(&base()).unwrap());
    for d in scenes {
        let json = d.to_json();
        assert_eq!(parse_scene_value(&json).unwrap(), d);
        // Through text, serde_json's default float parser (without the `float_roundtrip`
        // feature) may be 1 ulp off on 17-digit numbers, so compare to within a few ulps.
        let text = serde_json::to_string_pretty(&json).unwrap();
        assert_json_close(&parse_scene(&text).unwrap().to_json(), &json, "");
    }
}

/// Equal JSON, except that numbers may differ by a few ulps.
#[track_caller]
fn assert_json_close(a: &Value, b: &Value, path: &str) {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let (x, y) = (x.as_f64().unwrap(), y.as_f64().unwrap());
            assert!(
                (x - y).abs() <= 4.0 * f64::EPSILON * x.abs().max(y.abs()),
                "{path}: {x} vs {y}"
            );
        }
        (Value::Array(x), Value::Array(y)) => {
            assert_eq!(x.len(), y.len(), "{path}");
            for (i, (x, y)) in x.iter().zip(y).enumerate() {
                assert_json_close(x, y, &format!("{path}[{i}]"));
            }
        }
        (Value::Object(x), Value::Object(y)) => {
            assert!(x.keys().eq(y.keys()), "{path}: keys differ");
            for (k, x) in x {
                assert_json_close(x, &y[k], &format!("{path}.{k}"));
            }
        }
        _ => assert_eq!(a, b, "{path}"),
    }
}

#[test]
fn to_json_writes_non_defaults() {
    let mut s = base();
    s["materials"]["white"]["two_sided"] = json!(false);
    let j = parse_scene_value(&s).unwrap().to_json();
    assert_eq!(j["materials"]["white"]["two_sided"], json!(false));
    assert_eq!(j["materials"]["plastic"]["ior"], json!(1.5));
    assert_eq!(j["shapes"][2]["material"], json!("metal"));
    assert!(j["shapes"][0].get("emission").is_none());
    assert_eq!(j["shapes"][3]["normal"], json!([0.0, -1.0, 0.0]));
}
