//! Fuzz target: arbitrary bytes as an OBJ file, through `obj::load_bytes` (what `load_mesh` runs on
//! a `.obj` once the file is read). `mesh_outcome.rs` judges the result as
//! `renderer/tests/mesh_mutations.rs` does: a mesh that passes `mesh::check` with finite values, or a
//! one-line error that names the file. Any panic (including debug assertions and integer overflow,
//! which `cargo fuzz` enables) is a crash.

#![no_main]

#[path = "mesh_outcome.rs"]
mod outcome;

use libfuzzer_sys::fuzz_target;
use lumis::scene::mesh::obj;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.obj");
    outcome::judge(path, obj::load_bytes(path, data));
});
