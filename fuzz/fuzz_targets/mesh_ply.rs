//! Fuzz target: arbitrary bytes as a PLY file (ASCII or binary, whichever its header says), through
//! `ply::load_bytes` (what `load_mesh` runs on a `.ply`; reading a file only adds the open).
//! `mesh_outcome.rs` judges the result as `renderer/tests/mesh_mutations.rs` does: a mesh that passes
//! `mesh::check` with finite values, or a one-line error that names the file. Any panic (including
//! debug assertions and integer overflow, which `cargo fuzz` enables) is a crash, and so is an
//! allocation beyond libFuzzer's `-rss_limit_mb` (a header's count must not reserve memory the file
//! cannot fill).

#![no_main]

#[path = "mesh_outcome.rs"]
mod outcome;

use libfuzzer_sys::fuzz_target;
use lumis::scene::mesh::ply;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.ply");
    outcome::judge(path, ply::load_bytes(path, data));
});
