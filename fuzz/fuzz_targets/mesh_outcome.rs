//! What the mesh fuzz targets hold a reader's result to, as `renderer/tests/mesh_mutations.rs` does: a
//! mesh passes `mesh::check` and has at least one triangle and only finite values; an error
//! starts with the file's name and is one line (no character that breaks a line).

use lumis::scene::mesh::{MeshData, MeshError, check};
use std::path::Path;

/// Panics (a crash for libFuzzer) if `result` breaks a promise of the readers.
pub fn judge(path: &Path, result: Result<MeshData, MeshError>) {
    match result {
        Ok(mesh) => {
            check(path, &mesh).expect("a loaded mesh passes check");
            assert!(!mesh.indices.is_empty(), "a mesh without triangles");
            assert!(
                mesh.positions.iter().all(|p| p.is_finite()),
                "non-finite position"
            );
            assert!(
                mesh.normals.iter().flatten().all(|n| n.is_finite()),
                "non-finite normal"
            );
            assert!(
                mesh.uvs.iter().flatten().all(|t| t.is_finite()),
                "non-finite texture coordinate"
            );
        }
        Err(MeshError(message)) => {
            let name = path.display().to_string();
            assert!(message.starts_with(&name), "file not named: {message:?}");
            let breaks = [
                '\n', '\r', '\u{b}', '\u{c}', '\u{85}', '\u{2028}', '\u{2029}',
            ];
            assert!(!message.contains(breaks), "not one line: {message:?}");
        }
    }
}
