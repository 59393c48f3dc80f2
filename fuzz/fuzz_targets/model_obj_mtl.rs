//! Fuzz target: arbitrary bytes as an OBJ file and its `.mtl` (split at the first NUL byte: the
//! OBJ before it, the `.mtl` after it, handed out for every `mtllib` name), through
//! `obj_materials::load_obj_model_bytes` (what opening an `.obj` on its own runs once the files
//! are read). Each group's mesh is judged as the other mesh targets judge theirs
//! (`mesh_outcome.rs`); every number of a mapped material is finite; an error names the file (the
//! OBJ or the `.mtl`) and is one line. Any panic is a crash.

#![no_main]

#[path = "mesh_outcome.rs"]
mod outcome;

use libfuzzer_sys::fuzz_target;
use lumis::scene::mesh::MeshError;
use lumis::scene::mesh::obj_materials::load_obj_model_bytes;
use std::path::Path;

/// Whether every number in `v` is finite (serde_json writes NaN as null).
fn finite(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Null => false,
        serde_json::Value::Number(n) => n.as_f64().is_some_and(f64::is_finite),
        serde_json::Value::Array(a) => a.iter().all(finite),
        serde_json::Value::Object(o) => o.values().all(finite),
        _ => true,
    }
}

fuzz_target!(|data: &[u8]| {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let (obj, mtl) = (&data[..split], data.get(split + 1..).unwrap_or(&[]));
    let path = Path::new("fuzz.obj");
    match load_obj_model_bytes(path, obj, &|_| Some(mtl.to_vec())) {
        Ok(model) => {
            for g in model.groups {
                outcome::judge(path, Ok(g.mesh));
            }
            for m in &model.materials {
                assert!(finite(&m.json), "a non-finite number in {}", m.json);
                assert!(
                    m.emission.is_none_or(|e| e.iter().all(|x| x.is_finite() && *x >= 0.0)),
                    "emission {:?}",
                    m.emission
                );
            }
            for w in &model.warnings {
                assert!(!w.contains(['\n', '\r']), "not one line: {w:?}");
            }
        }
        // The OBJ's errors name the OBJ; a `.mtl`'s name the file its `mtllib` names (any name,
        // `a line 2: material 'A': …`), with the line.
        Err(MeshError(message)) if !message.starts_with("fuzz.obj") => {
            assert!(message.contains(" line "), "no line: {message:?}");
            let breaks = ['\n', '\r', '\u{b}', '\u{c}', '\u{85}', '\u{2028}', '\u{2029}'];
            assert!(!message.contains(breaks), "not one line: {message:?}");
        }
        Err(e) => outcome::judge(path, Err(e)),
    }
});
