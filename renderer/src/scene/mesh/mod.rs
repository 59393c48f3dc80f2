//! Triangle meshes from files (scene format Version 2's `mesh` shape): one reader per format,
//! each turning its file into the same [`MeshData`], with errors that name the file and the
//! position in it (a line, an element, an accessor). Which reader runs is decided by the file's
//! extension ([`load_mesh`]); the scene front end (`parse_shapes.rs`) applies `to_world` and the
//! validation every mesh shares (finite positions, in-range indices, degenerate triangles).

pub mod gltf;
pub mod obj;
pub mod ply;

use glam::{Vec2, Vec3};
use std::path::Path;

/// A triangle mesh as a file holds it, in the file's own coordinates (glTF: with its node
/// transforms applied, all primitives of the default scene merged).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as indices into `positions`, in the file's winding (the right-hand rule gives
    /// the geometric normal). Polygons of an OBJ are fanned from their first vertex.
    pub indices: Vec<[u32; 3]>,
    /// One normal per vertex (not necessarily unit), if the file has them for every vertex.
    pub normals: Option<Vec<Vec3>>,
    /// One texture coordinate per vertex, if the file has them for every vertex; `v` as the file
    /// stores it (OBJ and PLY: up from the bottom of the image; glTF: down from the top).
    pub uvs: Option<Vec<Vec2>>,
}

/// A mesh file that cannot be read: the message names the file and, where the format has one,
/// the position of the problem (`bunny.obj line 17: face index 4021 out of range`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct MeshError(pub String);

impl MeshError {
    /// An error about `file`, at `position` if not empty (`line 17`, `element face 3`,
    /// `accessor 2`).
    pub fn at(file: &Path, position: &str, message: impl std::fmt::Display) -> MeshError {
        let name = file.display();
        if position.is_empty() {
            MeshError(format!("{name}: {message}"))
        } else {
            MeshError(format!("{name} {position}: {message}"))
        }
    }
}

/// The file extensions [`load_mesh`] reads (lower case).
pub const MESH_EXTENSIONS: [&str; 4] = ["obj", "ply", "gltf", "glb"];

/// Reads the mesh in `path`, by extension: `.obj`, `.ply`, `.gltf` or `.glb` (case-insensitive).
pub fn load_mesh(path: &Path) -> Result<MeshData, MeshError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "obj" => obj::load(path),
        "ply" => ply::load(path),
        "gltf" | "glb" => gltf::load(path),
        other => Err(MeshError::at(
            path,
            "",
            format!("unsupported mesh format '.{other}' (use .obj, .ply, .gltf or .glb)"),
        )),
    }
}

/// Checks what every reader guarantees: indices in range, `normals`/`uvs` one per vertex; the
/// error names `file`. Readers call this last, so the front end can rely on it.
pub(crate) fn check(file: &Path, mesh: &MeshData) -> Result<(), MeshError> {
    let n = mesh.positions.len();
    if let Some((t, tri)) = mesh
        .indices
        .iter()
        .enumerate()
        .find(|(_, tri)| tri.iter().any(|&i| i as usize >= n))
    {
        return Err(MeshError::at(
            file,
            &format!("triangle {t}"),
            format!("index {:?} out of range ({n} vertices)", tri),
        ));
    }
    for (what, len) in [
        ("normals", mesh.normals.as_ref().map(Vec::len)),
        ("texture coordinates", mesh.uvs.as_ref().map(Vec::len)),
    ] {
        if let Some(len) = len
            && len != n
        {
            return Err(MeshError::at(
                file,
                "",
                format!("{len} {what} for {n} vertices"),
            ));
        }
    }
    Ok(())
}
