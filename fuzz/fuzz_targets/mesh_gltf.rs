//! Fuzz target: arbitrary bytes as a glTF 2.0 file through `gltf::load_bytes`, which tells a `.glb`
//! (the `glTF` magic) from `.gltf` JSON by its content, so one target covers both entry points of
//! `load_mesh`. Buffers come from the GLB's BIN chunk or `data:` URIs; the file is named as if it
//! lay in a folder that does not exist, so a relative `uri` fails to open rather than reading
//! whatever lies beside the fuzzer. `mesh_outcome.rs` judges the result as
//! `renderer/tests/mesh_mutations.rs` does: a mesh that passes `mesh::check` with finite values, or a
//! one-line error that names the file. Any panic (including debug assertions and integer overflow,
//! which `cargo fuzz` enables) is a crash.

#![no_main]

#[path = "mesh_outcome.rs"]
mod outcome;

use libfuzzer_sys::fuzz_target;
use lumis::scene::mesh::gltf;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("/nonexistent-lumis-fuzz/fuzz.gltf");
    outcome::judge(path, gltf::load_bytes(path, data));
});
