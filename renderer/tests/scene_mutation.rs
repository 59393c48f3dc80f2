//! Bad input never panics (issue 7, item 3): a property-based test that mutates every valid scene
//! shipped with the project and feeds the result to the parser, the builder and the renderer.
//!
//! Each case takes one of the valid scenes (`tests/data/scenes/*.json`, `assets/*.json`), applies
//! one to four structural mutations to its JSON value (dropped keys, values of the wrong type,
//! huge, tiny, negative and zero numbers, non-finite numbers as strings, empty and padded arrays,
//! duplicated vertices, degenerate polygons, triangles, quads, disks, spheres and boxes, broken
//! cameras, unknown material references and keys, deeply nested junk) and then, sometimes, one
//! textual mutation of the serialised file (truncation, byte flips, a number literal replaced by
//! `1e999`, `NaN`, `Infinity` …). The outcome must be one of:
//!
//! * an error whose message is a single line naming where the problem is (a JSON path, or a line
//!   and column for text that is not JSON);
//! * a scene that renders 2 samples per pixel of an image of at most 8×8 pixels at depth ≤ 4 with
//!   the case's strategy and light-sampling method, with no non-finite sample and finite pixels.
//!
//! A panic anywhere is caught and reported with the mutated scene and a backtrace. The runner is
//! seeded, so every run tries the same cases; `SCENE_MUTATION_CASES` overrides the number, and
//! `SCENE_MUTATION_EXPLORE=1` runs them all and lists each kind of failure once instead of
//! stopping (and shrinking) at the first.

use glam::DVec3;
use lumis::engine::Progressive;
use lumis::integrator::{Heuristic, Settings, Strategy as Estimator};
use lumis::lights::LightSampling;
use lumis::scene::{Scene, SceneError, parse_scene_in, parse_scene_value_in};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use serde_json::{Map, Number, Value, json};
use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{self, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Cases per run: about 12 s in release mode on 2 cores (a fifth of them render).
const CASES: u32 = 20000;

/// Numbers that have broken parsers and renderers before: zeros of both signs, subnormals, the
/// edges of f32 and f64, values just around the format's limits.
const SPECIAL: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1.0000001,
    0.9999999,
    180.0,
    179.99999999,
    1e-320,
    -1e-320,
    1e-300,
    1e-38,
    1e-30,
    1e-12,
    1e-7,
    1e7,
    16384.0,
    16385.0,
    2147483648.0,
    4294967296.0,
    1e12,
    3.4e38,
    3.5e38,
    -3.5e38,
    1e100,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    f64::EPSILON,
];

/// Replacements for a number literal in the text: JSON cannot write a non-finite number, so these
/// are the ways a file tries to (plus literals JSON forbids).
const LITERALS: &[&str] = &[
    "1e999",
    "-1e999",
    "1e-999",
    "NaN",
    "nan",
    "Infinity",
    "-Infinity",
    "inf",
    "0x10",
    "01",
    "1.",
    ".5",
    "+1",
    "1e",
    "--1",
    "\"1\"",
    "18446744073709551616",
    "-9223372036854775809",
];

/// One structural change to a scene's JSON value; `Index`es pick among the candidates present.
#[derive(Clone, Debug)]
enum Mutation {
    /// Removes a key of an object or an element of an array.
    Drop(Index),
    /// Replaces any value with junk.
    Replace(Index, Value),
    /// Replaces a number with a special value, or scales it.
    Number(Index, f64, bool),
    /// Duplicates an element of an array in place (duplicated vertices, repeated indices).
    Duplicate(Index, Index),
    /// Empties an array or object.
    Empty(Index),
    /// Copies one 3-number array over another (`to = from`, parallel edges, coincident vertices).
    CopyVec3(Index, Index),
    /// Adds a key that the format does not know, holding junk.
    AddKey(Index, String, Value),
    /// A degeneracy chosen for the shape's type, with a parameter.
    Degenerate(Index, u8, f64),
    /// A broken camera.
    Camera(u8, f64),
    /// Points a shape at a material that does not exist, or renames a material.
    Material(Index, bool),
    /// Sets a number inside one section (`materials`, `shapes`, `camera`) to the magnitude of a
    /// special value: extreme but often valid parameters (η = 1e30, α = 1e-30, radius = 3e38).
    Within(&'static str, Index, f64),
    /// Scales the whole scene (every position and length) by a factor: valid at any scale the
    /// numbers allow.
    ScaleScene(f64),
    /// Scales every emission and the background by a factor.
    ScaleEmission(f64),
}

/// One change to the serialised text.
#[derive(Clone, Debug)]
enum TextMutation {
    /// The text as serialised.
    None,
    /// Cuts the file at a byte (possibly inside a UTF-8 sequence: then it is cut before it).
    Truncate(Index),
    /// XORs bytes (invalid UTF-8 is read lossily, as a file read would fail on it anyway).
    Flip(Vec<(Index, u8)>),
    /// Replaces one number literal.
    Literal(Index, &'static str),
}

/// A whole test case.
#[derive(Clone, Debug)]
struct Case {
    scene: Index,
    mutations: Vec<Mutation>,
    text: TextMutation,
    estimator: u8,
    solid_angle: bool,
}

/// Where a value sits in the tree.
#[derive(Clone, Debug)]
enum Seg {
    Key(String),
    Index(usize),
}

fn special() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => proptest::sample::select(SPECIAL),
        1 => any::<f64>().prop_filter("finite", |x| x.is_finite()),
        1 => -10.0..10.0f64,
    ]
}

/// A JSON number, or the string a script would write for a non-finite one.
fn number(x: f64) -> Value {
    Number::from_f64(x)
        .map(Value::Number)
        .unwrap_or_else(|| Value::String(x.to_string()))
}

/// Values of the wrong type, odd numbers, and nested junk up to ~200 levels deep (past
/// serde_json's recursion limit of 128).
fn junk() -> impl Strategy<Value = Value> {
    let leaf = prop_oneof![
        Just(Value::Null),
        any::<bool>().prop_map(Value::Bool),
        special().prop_map(number),
        proptest::sample::select(
            &[
                "", "NaN", "Infinity", "-inf", "1e999", "white", "sphere", "a\nb", "\u{0}", "é",
            ][..]
        )
        .prop_map(|s| Value::String(s.to_owned())),
        (0usize..5).prop_map(|n| json!(vec![0.5; n])),
        Just(json!({})),
        Just(json!([[0, 0, 0], [1, 0, 0], [0, 1, 0]])),
        Just(json!([[0, 1, 2]])),
    ];
    let nested = leaf.clone().prop_recursive(3, 16, 4, |inner| {
        prop_oneof![
            proptest::collection::vec(inner.clone(), 0..4).prop_map(Value::Array),
            proptest::collection::btree_map("[a-z_]{1,8}", inner, 0..4)
                .prop_map(|m| Value::Object(m.into_iter().collect())),
        ]
    });
    let deep = (1usize..200, any::<bool>()).prop_map(|(depth, arrays)| {
        (0..depth).fold(json!(1), |v, _| {
            if arrays {
                json!([v])
            } else {
                json!({ "type": v })
            }
        })
    });
    prop_oneof![6 => leaf, 3 => nested, 1 => deep]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let key = prop_oneof![
        proptest::sample::select(
            &[
                "type",
                "material",
                "emission",
                "radius",
                "normal",
                "vertices",
                "indices",
                "lights",
                "albedo",
                "alpha",
                "ior",
                "two_sided",
                "comment",
                "name",
                "",
                "max_depth",
            ][..]
        )
        .prop_map(str::to_owned),
        "[a-z\n]{1,6}",
    ];
    prop_oneof![
        3 => any::<Index>().prop_map(Mutation::Drop),
        3 => (any::<Index>(), junk()).prop_map(|(i, v)| Mutation::Replace(i, v)),
        5 => (any::<Index>(), special(), any::<bool>())
            .prop_map(|(i, x, scale)| Mutation::Number(i, x, scale)),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::Duplicate(a, b)),
        1 => any::<Index>().prop_map(Mutation::Empty),
        2 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::CopyVec3(a, b)),
        1 => (any::<Index>(), key, junk()).prop_map(|(i, k, v)| Mutation::AddKey(i, k, v)),
        6 => (any::<Index>(), any::<u8>(), special())
            .prop_map(|(i, k, x)| Mutation::Degenerate(i, k, x)),
        2 => (any::<u8>(), special()).prop_map(|(k, x)| Mutation::Camera(k, x)),
        1 => (any::<Index>(), any::<bool>()).prop_map(|(i, r)| Mutation::Material(i, r)),
        4 => (
            proptest::sample::select(&["materials", "shapes", "camera"][..]),
            any::<Index>(),
            special()
        )
            .prop_map(|(section, i, x)| Mutation::Within(section, i, x)),
        3 => (-40..=38i32).prop_map(|e| Mutation::ScaleScene(10f64.powi(e))),
        2 => (-40..=38i32).prop_map(|e| Mutation::ScaleEmission(10f64.powi(e))),
    ]
}

fn text_mutation() -> impl Strategy<Value = TextMutation> {
    prop_oneof![
        6 => Just(TextMutation::None),
        1 => any::<Index>().prop_map(TextMutation::Truncate),
        1 => proptest::collection::vec((any::<Index>(), 1u8..), 1..4).prop_map(TextMutation::Flip),
        2 => (any::<Index>(), proptest::sample::select(LITERALS))
            .prop_map(|(i, l)| TextMutation::Literal(i, l)),
    ]
}

fn case() -> impl Strategy<Value = Case> {
    (
        any::<Index>(),
        // Mostly one mutation, so that many cases still render.
        prop_oneof![
            3 => proptest::collection::vec(mutation(), 1..2),
            2 => proptest::collection::vec(mutation(), 2..4),
        ],
        text_mutation(),
        0u8..5,
        any::<bool>(),
    )
        .prop_map(|(scene, mutations, text, estimator, solid_angle)| Case {
            scene,
            mutations,
            text,
            estimator,
            solid_angle,
        })
}

/// Paths of every value in `v` (pre-order) that satisfies `keep`.
fn paths(v: &Value, keep: &dyn Fn(&Value) -> bool) -> Vec<Vec<Seg>> {
    fn walk(v: &Value, at: &mut Vec<Seg>, keep: &dyn Fn(&Value) -> bool, out: &mut Vec<Vec<Seg>>) {
        if keep(v) {
            out.push(at.clone());
        }
        match v {
            Value::Array(items) => {
                for (i, item) in items.iter().enumerate() {
                    at.push(Seg::Index(i));
                    walk(item, at, keep, out);
                    at.pop();
                }
            }
            Value::Object(map) => {
                for (k, item) in map {
                    at.push(Seg::Key(k.clone()));
                    walk(item, at, keep, out);
                    at.pop();
                }
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    walk(v, &mut Vec::new(), keep, &mut out);
    out
}

fn get_mut<'a>(mut v: &'a mut Value, path: &[Seg]) -> &'a mut Value {
    for seg in path {
        v = match seg {
            Seg::Key(k) => &mut v[k.as_str()],
            Seg::Index(i) => &mut v[*i],
        };
    }
    v
}

/// The value at a random path among those satisfying `keep`, if any.
fn pick<'a>(v: &'a mut Value, i: &Index, keep: &dyn Fn(&Value) -> bool) -> Option<&'a mut Value> {
    let all = paths(v, keep);
    if all.is_empty() {
        return None;
    }
    let path = all[i.index(all.len())].clone();
    Some(get_mut(v, &path))
}

fn is_vec3(v: &Value) -> bool {
    v.as_array()
        .is_some_and(|a| a.len() == 3 && a.iter().all(Value::is_number))
}

fn vec3_of(v: &Value) -> Option<DVec3> {
    let a = v.as_array()?;
    (a.len() == 3).then_some(())?;
    Some(DVec3::new(a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?))
}

fn vec3_json(p: DVec3) -> Value {
    Value::Array(vec![number(p.x), number(p.y), number(p.z)])
}

fn apply(scene: &mut Value, m: &Mutation) {
    match m {
        Mutation::Drop(i) => {
            // Pick a container with something in it and drop one of its members.
            let non_empty = |v: &Value| match v {
                Value::Array(a) => !a.is_empty(),
                Value::Object(o) => !o.is_empty(),
                _ => false,
            };
            if let Some(c) = pick(scene, i, &non_empty) {
                match c {
                    Value::Array(a) => {
                        a.remove(i.index(a.len()));
                    }
                    Value::Object(o) => {
                        let key = o.keys().nth(i.index(o.len())).cloned().unwrap_or_default();
                        o.remove(&key);
                    }
                    _ => {}
                }
            }
        }
        Mutation::Replace(i, junk) => {
            if let Some(v) = pick(scene, i, &|_| true) {
                *v = junk.clone();
            }
        }
        Mutation::Number(i, x, scale) => {
            if let Some(v) = pick(scene, i, &Value::is_number) {
                let old = v.as_f64().unwrap_or(0.0);
                *v = number(if *scale { old * x } else { *x });
            }
        }
        Mutation::Duplicate(i, j) => {
            if let Some(Value::Array(a)) =
                pick(scene, i, &|v| v.as_array().is_some_and(|a| !a.is_empty()))
            {
                let k = j.index(a.len());
                let item = a[k].clone();
                a.insert(k, item);
            }
        }
        Mutation::Empty(i) => {
            if let Some(v) = pick(scene, i, &|v| v.is_array() || v.is_object()) {
                *v = if v.is_array() { json!([]) } else { json!({}) };
            }
        }
        Mutation::CopyVec3(i, j) => {
            let all = paths(scene, &is_vec3);
            if !all.is_empty() {
                let from = get_mut(scene, &all[i.index(all.len())]).clone();
                *get_mut(scene, &all[j.index(all.len())]) = from;
            }
        }
        Mutation::AddKey(i, key, junk) => {
            if let Some(Value::Object(o)) = pick(scene, i, &Value::is_object) {
                o.insert(key.clone(), junk.clone());
            }
        }
        Mutation::Degenerate(i, kind, x) => {
            if let Some(Value::Array(shapes)) = scene.get_mut("shapes")
                && !shapes.is_empty()
            {
                let k = i.index(shapes.len());
                degenerate(&mut shapes[k], *kind, *x);
            }
        }
        Mutation::Camera(kind, x) => {
            if let Some(cam) = scene.get_mut("camera").and_then(Value::as_object_mut) {
                camera(cam, *kind, *x);
            }
        }
        Mutation::Within(section, i, x) => {
            if let Some(part) = scene.get_mut(*section)
                && let Some(v) = pick(part, i, &Value::is_number)
            {
                *v = number(x.abs());
            }
        }
        Mutation::ScaleScene(factor) => scale_keys(scene, LENGTHS, *factor, false),
        Mutation::ScaleEmission(factor) => {
            scale_keys(scene, &["emission", "background"], *factor, false)
        }
        Mutation::Material(i, rename) => {
            if *rename {
                if let Some(Value::Object(mats)) = scene.get_mut("materials")
                    && !mats.is_empty()
                {
                    let key = mats
                        .keys()
                        .nth(i.index(mats.len()))
                        .cloned()
                        .unwrap_or_default();
                    if let Some(m) = mats.remove(&key) {
                        mats.insert(format!("{key}_renamed"), m);
                    }
                }
            } else if let Some(Value::Array(shapes)) = scene.get_mut("shapes")
                && let n = shapes.len()
                && n > 0
                && let Some(shape) = shapes[i.index(n)].as_object_mut()
            {
                shape.insert("material".into(), json!("no_such_material"));
            }
        }
    }
}

/// Keys whose values are positions or lengths, which scale with the scene.
const LENGTHS: &[&str] = &[
    "from",
    "to",
    "corner",
    "edge_u",
    "edge_v",
    "vertices",
    "positions",
    "center",
    "radius",
    "min",
    "max",
    "translate",
];

/// Multiplies every number under the keys in `keys` by `factor`.
fn scale_keys(v: &mut Value, keys: &[&str], factor: f64, inside: bool) {
    match v {
        Value::Number(n) if inside => *v = number(n.as_f64().unwrap_or(0.0) * factor),
        Value::Array(items) => items
            .iter_mut()
            .for_each(|item| scale_keys(item, keys, factor, inside)),
        Value::Object(map) => {
            for (k, item) in map.iter_mut() {
                scale_keys(item, keys, factor, inside || keys.contains(&k.as_str()));
            }
        }
        _ => {}
    }
}

/// Makes shape `s` degenerate in a way that suits its type; `x` is a special number.
fn degenerate(s: &mut Value, kind: u8, x: f64) {
    if !s.is_object() {
        return;
    }
    let ty = s
        .get("type")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_owned();
    // Any shape: extreme emission, a material, an odd type.
    match kind % 16 {
        0 => {
            s["emission"] = vec3_json(DVec3::splat(x.abs()));
            return;
        }
        1 => {
            s["emission"] = json!([x, 0, 0]);
            return;
        }
        _ => {}
    }
    let vec = |s: &Value, key: &str| s.get(key).and_then(vec3_of);
    match ty.as_str() {
        "sphere" | "disk" => match kind % 4 {
            0 | 1 => s["radius"] = number(x),
            2 => s["normal"] = vec3_json(DVec3::new(x, 0.0, 0.0)),
            _ => {
                if let Some(c) = vec(s, "center") {
                    s["center"] = vec3_json(c * x);
                }
            }
        },
        "quad" => {
            let (u, v) = (vec(s, "edge_u"), vec(s, "edge_v"));
            if let (Some(u), Some(v)) = (u, v) {
                match kind % 4 {
                    0 => s["edge_v"] = vec3_json(u * x),
                    1 => s["edge_u"] = vec3_json(u * x),
                    2 => s["edge_v"] = vec3_json(v + u * x * 1e-9),
                    _ => s["corner"] = vec3_json(DVec3::splat(x)),
                }
            }
        }
        "polygon" => {
            let Some(verts) = s.get("vertices").and_then(Value::as_array) else {
                return;
            };
            let mut v: Vec<DVec3> = verts.iter().filter_map(vec3_of).collect();
            if v.len() < 2 {
                return;
            }
            let n = v.len();
            match kind % 7 {
                // Collinear: every vertex on the line through the first two.
                0 => {
                    let (a, d) = (v[0], v[1] - v[0]);
                    for (j, p) in v.iter_mut().enumerate() {
                        *p = a + d * (j as f64 * if x == 0.0 { 1.0 } else { x });
                    }
                }
                // Off the plane by x.
                1 => v[n - 1].y += x,
                // Two vertices swapped: usually self-intersecting.
                2 => v.swap(0, n / 2),
                // Scaled: tiny or huge.
                3 => v.iter_mut().for_each(|p| *p *= x),
                // A repeated vertex.
                4 => v[n - 1] = v[0],
                // Reversed: valid, facing the other way.
                5 => v.reverse(),
                // Nearly coincident neighbours.
                _ => v[1] = v[0] + (v[1] - v[0]) * 1e-12,
            }
            s["vertices"] = Value::Array(v.into_iter().map(vec3_json).collect());
        }
        "triangles" => match kind % 4 {
            0 => s["indices"] = json!([[0, 0, 1]]),
            1 => s["indices"] = json!([[0, 1, 2], [2, 1, 0], [0, 1, u32::MAX]]),
            2 => {
                if let Some(p) = s.get_mut("positions").and_then(Value::as_array_mut) {
                    for (j, q) in p.iter_mut().enumerate() {
                        *q = json!([j as f64 * x, 0, 0]);
                    }
                }
            }
            _ => s["positions"] = json!([]),
        },
        "box" => match kind % 4 {
            0 => s["max"] = s.get("min").cloned().unwrap_or(Value::Null),
            1 => s["rotate_y_deg"] = number(x),
            2 => s["translate"] = vec3_json(DVec3::splat(x)),
            _ => s["min"] = vec3_json(DVec3::splat(-x.abs())),
        },
        _ => s["type"] = json!(["sphere", "polygon", "quad", "cone"][kind as usize % 4]),
    }
}

fn camera(cam: &mut Map<String, Value>, kind: u8, x: f64) {
    let vec = |cam: &Map<String, Value>, key: &str| cam.get(key).and_then(vec3_of);
    let (from, to) = (vec(cam, "from"), vec(cam, "to"));
    match kind % 6 {
        0 => {
            if let Some(f) = from {
                cam.insert("to".into(), vec3_json(f + DVec3::splat(x * 1e-13)));
            }
        }
        1 => {
            if let (Some(f), Some(t)) = (from, to) {
                cam.insert("up".into(), vec3_json((t - f) * x));
            }
        }
        2 => {
            cam.insert("vfov_deg".into(), number(x));
        }
        3 => {
            cam.insert("width".into(), number(x));
        }
        4 => {
            if let Some(f) = from {
                cam.insert("from".into(), vec3_json(f * x));
            }
        }
        _ => {
            cam.insert("up".into(), vec3_json(DVec3::new(0.0, x, 0.0)));
        }
    }
}

fn mutate_text(text: String, m: &TextMutation) -> String {
    match m {
        TextMutation::None => text,
        TextMutation::Truncate(i) => {
            let mut cut = i.index(text.len().max(1)).min(text.len());
            while !text.is_char_boundary(cut) {
                cut -= 1;
            }
            text[..cut].to_owned()
        }
        TextMutation::Flip(flips) => {
            let mut bytes = text.into_bytes();
            if !bytes.is_empty() {
                for (i, x) in flips {
                    let k = i.index(bytes.len());
                    bytes[k] ^= x;
                }
            }
            String::from_utf8_lossy(&bytes).into_owned()
        }
        TextMutation::Literal(i, lit) => {
            // Byte ranges of number literals (outside strings).
            let b = text.as_bytes();
            let mut spans = Vec::new();
            let (mut k, mut in_str) = (0, false);
            while k < b.len() {
                let c = b[k];
                if in_str {
                    if c == b'\\' {
                        k += 1;
                    } else if c == b'"' {
                        in_str = false;
                    }
                    k += 1;
                } else if c == b'"' {
                    in_str = true;
                    k += 1;
                } else if c == b'-' || c.is_ascii_digit() {
                    let start = k;
                    while k < b.len()
                        && matches!(b[k], b'0'..=b'9' | b'-' | b'+' | b'.' | b'e' | b'E')
                    {
                        k += 1;
                    }
                    spans.push((start, k));
                } else {
                    k += 1;
                }
            }
            if spans.is_empty() {
                return text;
            }
            let (s, e) = spans[i.index(spans.len())];
            format!("{}{lit}{}", &text[..s], &text[e..])
        }
    }
}

/// The valid scenes the cases start from, with their file names and folders (which the files they
/// name, such as environment maps, are relative to).
fn seeds() -> Vec<(String, Value, PathBuf)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut files = Vec::new();
    for dir in ["tests/data/scenes", "assets"] {
        for entry in std::fs::read_dir(root.join(dir)).expect("scene directory") {
            let path = entry.expect("directory entry").path();
            if path.extension().is_some_and(|e| e == "json") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(&path).expect("read scene");
            let value: Value = serde_json::from_str(&text).expect("valid JSON");
            // The seeds must be valid, or the test would only exercise error paths.
            let folder = path
                .parent()
                .expect("a scene file has a folder")
                .to_path_buf();
            parse_scene_value_in(&value, &folder)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            let name = path
                .strip_prefix(&root)
                .unwrap_or(&path)
                .display()
                .to_string();
            (name, value, folder)
        })
        .collect()
}

/// What happened to a case.
#[derive(Debug)]
enum Outcome {
    Rejected,
    Rendered,
}

/// An error must be one line and say where: a JSON path, a line and column, or the root.
fn check_error(e: &SceneError) -> Result<(), String> {
    let text = e.to_string();
    if text.contains(['\n', '\r']) {
        return Err(format!("error is not one line: {text:?}"));
    }
    let located = !e.path.is_empty()
        || (e.message.contains(" line ") && e.message.contains(" column "))
        || e.message.contains("root");
    if !located {
        return Err(format!("error names no location: {text:?}"));
    }
    Ok(())
}

/// Parses, builds and renders one mutated scene.
fn run(
    text: &str,
    value: Option<&Value>,
    folder: &std::path::Path,
    estimator: u8,
    solid_angle: bool,
) -> Result<Outcome, String> {
    let parsed = parse_scene_in(text, folder);
    // Without text mutations the value and its text must be judged alike.
    if let Some(value) = value {
        let direct = parse_scene_value_in(value, folder);
        match (&parsed, &direct) {
            (Ok(a), Ok(b)) if a != b => return Err("text and value parse differently".into()),
            // Only the text parser limits nesting (to 128, against stack overflows).
            (Err(a), _) if a.message.contains("recursion limit exceeded") => {}
            (Err(a), Err(b)) if a != b => {
                return Err(format!("text error {a} but value error {b}"));
            }
            (Ok(_), Err(e)) | (Err(e), Ok(_)) => {
                return Err(format!("only one of text and value is rejected: {e}"));
            }
            _ => {}
        }
    }
    let mut desc = match parsed {
        Ok(d) => d,
        Err(e) => return check_error(&e).map(|()| Outcome::Rejected),
    };
    // Keep renders tiny whatever the file asks for (1×16384 stays 1×8).
    desc.camera.width = desc.camera.width.min(8);
    desc.camera.height = desc.camera.height.min(8);
    let scene = match Scene::from_desc(&desc) {
        Ok(s) => s,
        Err(e) => return check_error(&e).map(|()| Outcome::Rejected),
    };
    let strategy = match estimator {
        0 => Estimator::Light,
        1 => Estimator::Bsdf,
        2 => Estimator::Mixture { light_weight: 0.5 },
        3 => Estimator::Mis {
            heuristic: Heuristic::Balance,
        },
        _ => Estimator::Mis {
            heuristic: Heuristic::Power,
        },
    };
    let settings = Settings {
        strategy,
        light_sampling: if solid_angle {
            LightSampling::SolidAngle
        } else {
            LightSampling::Area
        },
        max_depth: Some(if (1..=4).contains(&desc.max_depth) {
            desc.max_depth
        } else {
            4
        }),
        ..Settings::default()
    };
    let mut render = Progressive::new(Arc::new(scene), settings, 7);
    assert!(render.render_pass(2), "nothing cancels this render");
    let film = render.film();
    if film.nonfinite > 0 {
        return Err(format!(
            "{} non-finite samples with {settings:?}",
            film.nonfinite
        ));
    }
    if let Some(i) = film.mean().iter().position(|p| !p.is_finite()) {
        return Err(format!("pixel {i} is not finite with {settings:?}"));
    }
    Ok(Outcome::Rendered)
}

/// A panic's message and backtrace without the frames of the panic machinery and of this test's
/// harness (everything from `catch_unwind` on).
fn short_backtrace(text: &str) -> String {
    let mut out = Vec::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if line.contains("catch_unwind") {
            break;
        }
        let machinery = [
            "panicking",
            "rust_begin_unwind",
            "backtrace::",
            "Backtrace",
            "boxed.rs",
            "{closure#1}",
        ]
        .iter()
        .any(|m| line.contains(m));
        // A frame is a name line followed by an `at file:line` line.
        if lines
            .peek()
            .is_some_and(|l| l.trim_start().starts_with("at "))
        {
            let at = lines.next().unwrap_or_default();
            if !machinery && !at.contains("/rustc/") {
                out.push(line);
                out.push(at);
            }
        } else if !machinery || !line.trim_start().starts_with(char::is_numeric) {
            out.push(line);
        }
    }
    out.join("\n")
}

/// The message and backtrace of the last panic, from the hook (it may run on a worker thread).
static PANIC: Mutex<Option<String>> = Mutex::new(None);

#[test]
fn mutated_scenes_are_rejected_or_render_finite_images() {
    let seeds = seeds();
    assert!(seeds.len() >= 4, "found only {} scenes", seeds.len());
    let cases = std::env::var("SCENE_MUTATION_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES);

    let default_hook = panic::take_hook();
    panic::set_hook(Box::new(|info| {
        let bt = std::backtrace::Backtrace::force_capture();
        *PANIC.lock().unwrap_or_else(|e| e.into_inner()) = Some(format!("{info}\n{bt}"));
    }));

    let config = Config {
        cases,
        rng_algorithm: RngAlgorithm::ChaCha,
        failure_persistence: None,
        // A failure prints the mutated scene; a few shrink steps make it smaller, not all.
        max_shrink_iters: 256,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, b"lumis scene mutation, issue 7 ..");
    let mut runner = TestRunner::new_with_rng(config, rng);
    let (tried, rejected, rendered) = (AtomicU64::new(0), AtomicU64::new(0), AtomicU64::new(0));
    // SCENE_MUTATION_EXPLORE=1: run every case and list each kind of failure once, with a count
    // and an example, instead of stopping at the first (for diagnosis, not CI).
    let explore = std::env::var_os("SCENE_MUTATION_EXPLORE").is_some();
    let found = Mutex::new(BTreeMap::<String, (u64, String)>::new());
    let start = Instant::now();
    let result = runner.run(&case(), |case| {
        tried.fetch_add(1, Ordering::Relaxed);
        let (name, seed, folder) = &seeds[case.scene.index(seeds.len())];
        let mut value = seed.clone();
        for m in &case.mutations {
            apply(&mut value, m);
        }
        let text = mutate_text(value.to_string(), &case.text);
        let direct = matches!(case.text, TextMutation::None).then_some(&value);
        let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
            run(&text, direct, folder, case.estimator, case.solid_angle)
        }));
        let failure = match outcome {
            Ok(Ok(Outcome::Rejected)) => {
                rejected.fetch_add(1, Ordering::Relaxed);
                return Ok(());
            }
            Ok(Ok(Outcome::Rendered)) => {
                rendered.fetch_add(1, Ordering::Relaxed);
                return Ok(());
            }
            Ok(Err(msg)) => msg,
            Err(_) => {
                let p = PANIC.lock().unwrap_or_else(|e| e.into_inner()).take();
                format!("panic: {}", short_backtrace(&p.unwrap_or_default()))
            }
        };
        let mut how = format!("{:?} and {:?}", case.mutations, case.text);
        if how.len() > 2000 {
            how = format!("{}…", how.chars().take(2000).collect::<String>());
        }
        let report = format!("{failure}\nfrom {name} with {how}\nscene: {text}");
        if explore {
            let first = failure.lines().next().unwrap_or_default();
            let kind = match first.split_once(" non-finite samples") {
                Some((_, settings)) => format!("non-finite samples{settings}"),
                None => failure.lines().nth(1).unwrap_or(first).to_owned(),
            };
            let mut seen = found.lock().unwrap_or_else(|e| e.into_inner());
            let entry = seen.entry(kind).or_insert((0, report));
            entry.0 += 1;
            return Ok(());
        }
        Err(TestCaseError::fail(report))
    });
    let found = found.into_inner().unwrap_or_else(|e| e.into_inner());
    for (kind, (count, example)) in &found {
        let _ = writeln!(std::io::stderr(), "=== {count}× {kind}\n{example}\n");
    }
    panic::set_hook(default_hook);

    let seconds = start.elapsed().as_secs_f64();
    let (tried, rejected, rendered) = (
        tried.into_inner(),
        rejected.into_inner(),
        rendered.into_inner(),
    );
    // Straight to stderr, past the test harness's capture: the count belongs in CI's log.
    let _ = writeln!(
        std::io::stderr(),
        "scene_mutation: {cases} cases from {} scenes ({tried} runs with shrinking): {rejected} \
         rejected with a located one-line error, {rendered} rendered finite, {seconds:.1} s",
        seeds.len()
    );
    assert!(
        found.is_empty(),
        "{} kinds of failure, listed above",
        found.len()
    );
    match result {
        Ok(()) => {}
        // The reason holds the scene; the shrunk case's `Debug` would only repeat it, longer.
        Err(TestError::Fail(reason, _)) => panic!("{reason}"),
        Err(e) => panic!("{e}"),
    }
    // Both outcomes must be common, or the mutations are too weak or too strong to mean much.
    assert!(
        rendered * 10 > tried && rejected * 10 > tried,
        "{rendered} rendered, {rejected} rejected of {tried}"
    );
}
