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

/// Asserts that JSON `text` is rejected at exactly `path` with a message containing every
/// string of `fragments` (for problems a `Value` cannot hold: syntax, `1e999`, bare `NaN`).
#[track_caller]
fn expect_text_err(text: &str, path: &str, fragments: &[&str]) {
    let e = parse_scene(text).unwrap_err();
    assert_eq!(e.path, path, "wrong path in: {e}");
    for fragment in fragments {
        assert!(
            e.message.contains(fragment),
            "expected {fragment:?} in: {e}"
        );
    }
    assert!(!e.to_string().contains('\n'), "not one line: {e}");
}

/// The base scene as text with the first occurrence of `from` replaced by `to`.
fn base_text_with(from: &str, to: &str) -> String {
    let text = base().to_string();
    assert!(text.contains(from), "{from:?} not in the base scene");
    text.replacen(from, to, 1)
}

/// One case per rule of the Errors section of `docs/scene-format.md`, in its order, each with
/// the JSON path and the problem the message must name. Variants of most rules are tested next to
/// their parser (`parse*.rs`); this is the audit that none is missing.
#[test]
fn every_errors_section_rule_names_path_and_problem() {
    // bad JSON: syntax errors name the value being read, the line and the column.
    expect_text_err(
        "{\"camera\": {\"from\": [0, 1,, 0]}}",
        "camera.from[2]",
        &["JSON syntax error", "line 1 column 27"],
    );
    let text = base().to_string();
    let cut = text.find("\"vertices\"").unwrap() + 20;
    expect_text_err(
        &text[..cut],
        "shapes[1].vertices[1]",
        &["EOF while parsing", "line 1 column"],
    );
    expect_text_err(
        &base_text_with("\"max_depth\":8", "\"max_depth\":8,\"max_depth\":9"),
        "max_depth",
        &["duplicate key `max_depth`"],
    );
    expect_text_err(
        &base_text_with(
            "\"metal\":{",
            "\"white\":{\"type\":\"diffuse\",\"albedo\":[0,0,0]},\"metal\":{",
        ),
        "materials.white",
        &["duplicate key `white`"],
    );

    // unknown key (root, camera, material, shape).
    let mut s = base();
    s["shape"] = json!([]);
    expect_err(&s, "shape", "unknown key `shape`");
    let mut s = base();
    s["camera"]["aperture"] = json!(0.1);
    expect_err(&s, "camera.aperture", "unknown key `aperture`");
    let mut s = base();
    s["materials"]["white"]["color"] = json!([1, 1, 1]);
    expect_err(&s, "materials.white.color", "unknown key `color`");
    let s = with(
        4,
        json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "radius2": 1}),
    );
    expect_err(&s, "shapes[4].radius2", "unknown key `radius2`");

    // unknown material name, also when none is defined.
    let s = with(
        4,
        json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "Copper"}),
    );
    expect_err(&s, "shapes[4].material", "unknown material `Copper`");
    let mut s = base();
    s.as_object_mut().unwrap().remove("materials");
    expect_err(
        &s,
        "shapes[0].material",
        "unknown material `white` (no materials are defined)",
    );

    // wrong array length: too short, too long, empty, for vectors and triangle indices.
    let mut s = base();
    s["background"] = json!([0.1, 0.1, 0.1, 1.0]);
    expect_err(&s, "background", "expected 3 numbers, found 4");
    let s = with(5, json!({"type": "box", "min": [], "max": [1, 1, 1]}));
    expect_err(&s, "shapes[5].min", "expected 3 numbers, found 0");
    let s = with(
        4,
        json!({"type": "sphere", "center": [0, 0, 0], "radius": 1, "emission": [1, 1]}),
    );
    expect_err(&s, "shapes[4].emission", "expected 3 numbers, found 2");
    let mut s = base();
    s["shapes"][2]["indices"][3] = json!([1, 2]);
    expect_err(
        &s,
        "shapes[2].indices[3]",
        "expected 3 vertex indices, found 2",
    );

    // NaN and infinities: JSON has no literal for them, so they arrive as an overflowing number,
    // a bare word (a syntax error) or a string.
    expect_text_err(
        &base_text_with(
            "\"radius\":0.5,\"type\":\"sphere\"",
            "\"radius\":1e999,\"type\":\"sphere\"",
        ),
        "shapes[4].radius",
        &["number out of range"],
    );
    expect_text_err(
        &base_text_with("\"from\":[0,1,-4]", "\"from\":[-1e400,1,-4]"),
        "camera.from[0]",
        &["number out of range"],
    );
    expect_text_err(
        &base_text_with("\"emission\":[4,4,4]", "\"emission\":[4,NaN,4]"),
        "shapes[1].emission[1]",
        &["JSON syntax error"],
    );
    expect_text_err(
        &base_text_with("\"vfov_deg\":40", "\"vfov_deg\":Infinity"),
        "camera.vfov_deg",
        &["JSON syntax error"],
    );
    let s = with(
        4,
        json!({"type": "sphere", "center": [0, 0, 0], "radius": "NaN"}),
    );
    expect_err(&s, "shapes[4].radius", "expected a number, found a string");
    let mut s = base();
    s["materials"]["white"]["albedo"][2] = json!("Infinity");
    expect_err(
        &s,
        "materials.white.albedo[2]",
        "expected a number, found a string",
    );

    // negative radius (and zero: a radius must be positive).
    let s = with(
        4,
        json!({"type": "sphere", "center": [0, 0, 0], "radius": -1}),
    );
    expect_err(&s, "shapes[4].radius", "radius must be positive, found -1");
    let s = with(
        3,
        json!({"type": "disk", "center": [0, 0, 0], "normal": [0, 1, 0], "radius": 0}),
    );
    expect_err(&s, "shapes[3].radius", "radius must be positive, found 0");

    // albedo outside [0, 1].
    let mut s = base();
    s["materials"]["white"]["albedo"] = json!([0.5, 0.5, 1.0001]);
    expect_err(&s, "materials.white.albedo[2]", "is outside [0, 1]");
    let mut s = base();
    s["materials"]["plastic"]["albedo"] = json!([-0.5, 0.5, 0.5]);
    expect_err(&s, "materials.plastic.albedo[0]", "is outside [0, 1]");

    // non-planar, self-intersecting or zero-area polygon.
    let poly = |v: Value| {
        with(
            1,
            json!({"type": "polygon", "vertices": v, "emission": [1, 1, 1]}),
        )
    };
    let bent = json!([[0, 0, 0], [2, 0, 0], [2, 2, 0.5], [0, 2, 0]]);
    expect_err(&poly(bent), "shapes[1].vertices", "not planar");
    let crossed = json!([[0, 0, 0], [2, 0, 0], [0, 2, 0], [2, 2, 0]]);
    expect_err(
        &poly(crossed),
        "shapes[1].vertices",
        "not simple: edge 1 and edge 3",
    );
    let flat = json!([[0, 0, 0], [1, 0, 0], [3, 0, 0], [2, 0, 0]]);
    expect_err(&poly(flat), "shapes[1].vertices", "zero area");
    let tiny = json!([[0, 0, 0], [1, 0, 0], [0.5, 1e-12, 0]]);
    expect_err(&poly(tiny), "shapes[1].vertices", "zero area");

    // a degenerate triangle that is an emitter (a non-emitter's is dropped with a warning).
    let tris = |idx: Value, emission: [f64; 3]| {
        let pos = json!([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.5, 0, 0]]);
        with(
            2,
            json!({"type": "triangles", "positions": pos, "indices": idx, "emission": emission}),
        )
    };
    expect_err(
        &tris(json!([[0, 1, 2], [0, 3, 1]]), [1.0; 3]),
        "shapes[2].indices[1]",
        "zero area",
    );
    expect_err(
        &tris(json!([[2, 2, 2]]), [0.0, 0.0, 1.0]),
        "shapes[2].indices[0]",
        "zero area",
    );
    let d = parse_scene_value(&tris(json!([[0, 1, 2], [0, 3, 1]]), [0.0; 3])).unwrap();
    assert_eq!(
        d.warnings,
        ["shapes[2].indices: dropped 1 zero-area triangle(s): [1]"]
    );

    // a zero-length normal.
    let s = with(
        3,
        json!({"type": "disk", "center": [0, 0, 0], "normal": [0, 0, 0], "radius": 1}),
    );
    expect_err(&s, "shapes[3].normal", "zero-length normal");
    let s = with(
        3,
        json!({"type": "disk", "center": [0, 0, 0], "normal": [0, -0.0, 0], "radius": 1}),
    );
    expect_err(&s, "shapes[3].normal", "zero-length normal");

    // a camera with `from == to` or `up` parallel to the view direction.
    let mut s = base();
    s["camera"]["to"] = s["camera"]["from"].clone();
    expect_err(&s, "camera.to", "`to` equals `from`");
    let mut s = base();
    s["camera"]["up"] = json!([0, 0, -3]);
    expect_err(&s, "camera.up", "parallel to the view direction");
}

/// Type errors of the containers, which no rule above names but every rule relies on.
#[test]
fn containers_of_the_wrong_type_are_named() {
    let cases = [
        (
            "materials",
            json!([]),
            "materials",
            "expected an object, found an array",
        ),
        (
            "camera",
            json!(null),
            "camera",
            "expected an object, found null",
        ),
        (
            "shapes",
            json!("none"),
            "shapes",
            "expected an array, found a string",
        ),
        (
            "background",
            json!(0.1),
            "background",
            "expected an array of 3 numbers, found a number",
        ),
        (
            "max_depth",
            json!("8"),
            "max_depth",
            "expected a number, found a string",
        ),
        (
            "name",
            json!(["x"]),
            "name",
            "expected a string, found an array",
        ),
    ];
    for (key, value, path, fragment) in cases {
        let mut s = base();
        s[key] = value;
        expect_err(&s, path, fragment);
    }
    let mut s = base();
    s["shapes"][4]["type"] = json!(3);
    expect_err(&s, "shapes[4].type", "expected a string, found a number");
    s["shapes"][4]["type"] = json!("sphere");
    s["shapes"][4]["name"] = json!(false);
    expect_err(&s, "shapes[4].name", "expected a string, found a boolean");
    let mut s = base();
    s["shapes"][1]["vertices"] = json!({"0": [0, 0, 0]});
    expect_err(
        &s,
        "shapes[1].vertices",
        "expected an array, found an object",
    );
    let mut s = base();
    s["shapes"][2]["indices"][0] = json!(0);
    expect_err(
        &s,
        "shapes[2].indices[0]",
        "expected an array, found a number",
    );
    let mut s = base();
    s["materials"]["metal"]["type"] = json!(null);
    expect_err(&s, "materials.metal.type", "expected a string, found null");
}

/// Keys and names from the file are quoted in messages; a newline in one must not break the
/// one-line error.
#[test]
fn messages_stay_on_one_line() {
    let mut s = base();
    s["camera"]["a\nb"] = json!(1);
    let e = parse_scene_value(&s).unwrap_err();
    assert_eq!(e.to_string(), format!("camera.\"a\\nb\": {}", e.message));
    assert!(e.message.starts_with("unknown key `a\\nb`"), "{e}");
    // Keys that are empty or hold path punctuation are quoted, so a path is never empty.
    let mut s = base();
    s[""] = json!(1);
    expect_err(&s, "\"\"", "unknown key ``");
    let mut s = base();
    s["materials"]["red.metal"] = json!({"type": "diffuse", "albedo": [2, 0, 0]});
    expect_err(&s, "materials.\"red.metal\".albedo[0]", "outside [0, 1]");
    let s = with(
        4,
        json!({"type": "sphere\r\n", "center": [0, 0, 0], "radius": 1}),
    );
    let e = parse_scene_value(&s).unwrap_err();
    assert!(!e.to_string().contains(['\r', '\n']), "{e}");
    let e = parse_scene("{\"camera\u{2028}\": [}").unwrap_err();
    assert!(!e.to_string().contains('\u{2028}'), "{e}");
}

/// The renderer computes in f32: numbers beyond its range, radiance that would overflow samples,
/// and scenes too large for the BVH's costs are refused by name; tiny vectors still normalise.
#[test]
fn single_precision_limits() {
    use super::Scene;
    let mut s = base();
    s["shapes"][4]["center"][1] = json!(3.5e38);
    expect_err(
        &s,
        "shapes[4].center[1]",
        "out of range: numbers must lie within ±3.4e38",
    );
    let mut s = base();
    s["shapes"][3]["emission"] = json!([1, 2e30, 1]);
    expect_err(&s, "shapes[3].emission[1]", "radiance must be at most 1e30");
    let mut s = base();
    s["background"] = json!([1e31, 0, 0]);
    expect_err(&s, "background[0]", "radiance must be at most 1e30");
    let mut s = base();
    s["shapes"][3]["emission"] = json!([1e30, 1e30, 1e30]);
    assert!(parse_scene_value(&s).is_ok());

    // Finite numbers that make the scene too large fail in the builder, at the shape.
    let mut s = base();
    s["shapes"][4]["radius"] = json!(1e19);
    let e = Scene::from_json_str(&s.to_string())
        .err()
        .expect("too large");
    assert_eq!(e.path, "shapes[4]", "{e}");
    assert!(e.message.contains("units across; at most 1e15"), "{e}");
    s["shapes"][4]["radius"] = json!(1e10);
    assert!(Scene::from_json_str(&s.to_string()).is_ok());

    // A disk normal or camera `up` whose length underflows is still a direction.
    let mut s = base();
    s["shapes"][3]["normal"] = json!([0, -1e-300, 0]);
    s["camera"]["up"] = json!([0, 1e-300, 0]);
    let d = parse_scene_value(&s).unwrap();
    let GeometryDesc::Disk { normal, .. } = d.shapes[3].geometry else {
        panic!()
    };
    assert_eq!(normal, DVec3::new(0.0, -1.0, 0.0));
    let scene = Scene::from_desc(&d).unwrap();
    let ray = scene.camera.ray(32.0, 24.0);
    assert!(ray.d.is_finite() && ray.o.is_finite(), "{ray:?}");
    // `up` parallel to the view is caught even when its length underflows.
    s["camera"]["up"] = json!([0, 0, 1e-300]);
    expect_err(&s, "camera.up", "parallel to the view direction");
}

/// `camera.filter`: box by default, the gaussian's defaults (0.5, 4σ), written back by
/// `to_json`, and bad values refused at their JSON path.
#[test]
fn camera_filter_parses_round_trips_and_names_errors() {
    let with = |f: &str| {
        format!(
            r#"{{"camera": {{"from": [0,0,-5], "to": [0,0,0], "up": [0,1,0], "vfov_deg": 40, "width": 8, "height": 8{f}}}, "materials": {{}}, "shapes": []}}"#
        )
    };
    let d = parse_scene(&with("")).unwrap();
    assert_eq!(d.camera.filter, super::FilterDesc::Box);
    let d = parse_scene(&with(r#", "filter": {"type": "gaussian"}"#)).unwrap();
    assert_eq!(
        d.camera.filter,
        super::FilterDesc::Gaussian {
            stddev: 0.5,
            radius: 2.0
        }
    );
    let back = parse_scene(&d.to_json().to_string()).unwrap();
    assert_eq!(back.camera.filter, d.camera.filter);
    // The tent: Mitsuba's default radius 1, and round trip.
    let t = parse_scene(&with(r#", "filter": {"type": "tent"}"#)).unwrap();
    assert_eq!(t.camera.filter, super::FilterDesc::Tent { radius: 1.0 });
    let t = parse_scene(&with(r#", "filter": {"type": "tent", "radius": 2.5}"#)).unwrap();
    let back = parse_scene(&t.to_json().to_string()).unwrap();
    assert_eq!(back.camera.filter, super::FilterDesc::Tent { radius: 2.5 });
    // The signed filters: Mitsuba's defaults (3 lobes; B = C = ⅓), and round trips.
    for (f, want) in [
        (
            r#"{"type": "lanczos"}"#,
            super::FilterDesc::Lanczos { lobes: 3 },
        ),
        (
            r#"{"type": "lanczos", "lobes": 5}"#,
            super::FilterDesc::Lanczos { lobes: 5 },
        ),
        (
            r#"{"type": "mitchell"}"#,
            super::FilterDesc::Mitchell {
                b: 1.0 / 3.0,
                c: 1.0 / 3.0,
            },
        ),
        (
            r#"{"type": "mitchell", "b": 0.4, "c": 0.3}"#,
            super::FilterDesc::Mitchell { b: 0.4, c: 0.3 },
        ),
        (r#"{"type": "catmullrom"}"#, super::FilterDesc::CatmullRom),
    ] {
        let d = parse_scene(&with(&format!(r#", "filter": {f}"#))).unwrap();
        assert_eq!(d.camera.filter, want, "{f}");
        let back = parse_scene(&d.to_json().to_string()).unwrap();
        assert_eq!(back.camera.filter, want, "{f}");
    }
    for (f, path) in [
        (r#", "filter": {"type": "sinc"}"#, "camera.filter.type"),
        (
            r#", "filter": {"type": "lanczos", "lobes": 0}"#,
            "camera.filter.lobes",
        ),
        (
            r#", "filter": {"type": "lanczos", "lobes": 17}"#,
            "camera.filter.lobes",
        ),
        (
            r#", "filter": {"type": "lanczos", "lobes": 2.5}"#,
            "camera.filter.lobes",
        ),
        (
            r#", "filter": {"type": "mitchell", "B": 0.5}"#,
            "camera.filter.B",
        ),
        (
            r#", "filter": {"type": "catmullrom", "c": 0.5}"#,
            "camera.filter.c",
        ),
        // Negative lobes so deep that an edge pixel's filter integral is negative.
        (
            r#", "filter": {"type": "mitchell", "b": 10, "c": 0}"#,
            "camera.filter.type",
        ),
        (
            r#", "filter": {"type": "tent", "radius": 0}"#,
            "camera.filter.radius",
        ),
        (
            r#", "filter": {"type": "tent", "radius": 17}"#,
            "camera.filter.radius",
        ),
        (
            r#", "filter": {"type": "tent", "stddev": 1}"#,
            "camera.filter.stddev",
        ),
        (
            r#", "filter": {"type": "gaussian", "stddev": 0}"#,
            "camera.filter.stddev",
        ),
        (
            r#", "filter": {"type": "gaussian", "stddev": 1, "radius": 0.5}"#,
            "camera.filter.radius",
        ),
        (
            r#", "filter": {"type": "box", "radius": 1}"#,
            "camera.filter.radius",
        ),
    ] {
        let e = parse_scene(&with(f)).unwrap_err();
        assert!(e.to_string().contains(path), "{f}: {e}");
    }
}

/// A file lumis does not read is named with what lumis reads (issue 43 item 4), before it is
/// read at all: not a JSON syntax error about a file that was never JSON. A `.pbrt` file is
/// named as pbrt-v4's format. (The files need not exist: the extension decides.)
#[test]
fn unknown_file_types_name_the_formats_lumis_reads() {
    for (file, words) in [
        (
            "scenes/killeroo.pbrt",
            &["pbrt-v4", "does not read pbrt"][..],
        ),
        ("scenes/model.xyz", &["does not open '.xyz' files"][..]),
        ("scenes/model.USD", &["does not open '.USD' files"][..]),
    ] {
        let e = load_scene(std::path::Path::new(file)).unwrap_err();
        let text = e.to_string();
        assert!(text.contains(file), "{text}");
        for w in words
            .iter()
            .chain(&[".json", ".xml", ".obj", ".ply", ".gltf", ".glb"])
        {
            assert!(text.contains(w), "{w:?} not in: {text}");
        }
        assert!(!text.contains("JSON"), "{text}");
    }
    // A file without an extension is still read as JSON (and this one is missing).
    let e = load_scene(std::path::Path::new("scenes/no_extension")).unwrap_err();
    assert!(e.to_string().contains("cannot read the scene file"), "{e}");
}
