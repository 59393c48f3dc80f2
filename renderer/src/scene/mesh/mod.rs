//! Triangle meshes from files (scene format Version 2's `mesh` shape): one reader per format,
//! each turning its file into the same [`MeshData`], with errors that name the file and the
//! position in it (a line, an element, an accessor). Which reader runs is decided by the file's
//! extension ([`load_mesh`]); the scene front end (`parse_shapes.rs`) applies `to_world` and the
//! validation every mesh shares (finite positions, in-range indices, degenerate triangles).

pub mod gltf;
pub mod normals;
pub mod obj;
pub mod obj_materials;
pub mod ply;
pub mod serialized;
// A generated test mesh (the scale tests and `examples/make_mesh`): only with `testing`.
#[cfg(any(test, feature = "testing"))]
pub mod uv_sphere;

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
    /// One texture coordinate per vertex, if the file has them for every vertex, with `v = 0` at
    /// the image's top row as textures index it: glTF and PLY values as stored, OBJ's `v`
    /// flipped to `1 − v` (what Mitsuba 3 does with each format).
    pub uvs: Option<Vec<Vec2>>,
    /// The file's named vertex and face attributes (Mitsuba's PLY attributes: `vertex_color`,
    /// `face_color`, `vertex_<prefix>`, …), in file order; empty for the other formats.
    pub attributes: Vec<MeshAttribute>,
}

/// Whether a [`MeshAttribute`] has a value per vertex or per face.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AttributeKind {
    /// One value per vertex, interpolated by a hit's barycentrics (name `vertex_…`).
    Vertex,
    /// One value per face, constant over it (name `face_…`).
    Face,
}

/// A named per-vertex or per-face attribute of a mesh, as Mitsuba 3.9.1's `Mesh::add_attribute`
/// holds it, read by the `mesh_attribute` texture.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshAttribute {
    /// Mitsuba's name, which starts with `vertex_` or `face_` ([`MeshAttribute::kind`]).
    pub name: String,
    /// Its number of components: 1 or 3 (Mitsuba also keeps 4, `r g b a`, which its texture
    /// cannot evaluate; the front end refuses a texture that names one).
    pub dim: u8,
    /// One value per vertex (`vertex_…`) or per triangle of [`MeshData::indices`] (`face_…`: a
    /// polygon's value repeated for each triangle of its fan). One component is stored in all
    /// three (`x = y = z`); the fourth of a 4-component attribute is dropped.
    pub values: Vec<Vec3>,
}

impl MeshAttribute {
    /// Per vertex or per face, by the name's prefix.
    pub fn kind(&self) -> AttributeKind {
        if self.name.starts_with("face_") {
            AttributeKind::Face
        } else {
            AttributeKind::Vertex
        }
    }
}

/// A mesh file that cannot be read: the message names the file and, where the format has one,
/// the position of the problem (`bunny.obj line 17: face index 4021 out of range`).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct MeshError(pub String);

impl MeshError {
    /// An error about `file`, at `position` if not empty (`line 17`, `element face 3`,
    /// `accessor 2`). Always one line (see `one_line`), whatever the message quotes.
    pub fn at(file: &Path, position: &str, message: impl std::fmt::Display) -> MeshError {
        let name = file.display();
        let text = if position.is_empty() {
            format!("{name}: {message}")
        } else {
            format!("{name} {position}: {message}")
        };
        MeshError(one_line(text))
    }
}

/// `text` with every character that can break a line escaped as Rust writes it (`\u{b}`):
/// control characters other than tab, and Unicode's line and paragraph separators. Messages
/// quote the file's own words (an unknown keyword, a token, a `uri`), which may hold any of
/// them, and a splitting rule that stops at ASCII whitespace does not stop at U+000B or U+2028.
fn one_line(text: String) -> String {
    let breaks = |c: char| (c.is_control() && c != '\t') || matches!(c, '\u{2028}' | '\u{2029}');
    if !text.contains(breaks) {
        return text;
    }
    text.chars()
        .map(|c| {
            if breaks(c) {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

/// The file extensions [`load_mesh`] reads (lower case).
pub const MESH_EXTENSIONS: [&str; 5] = ["obj", "ply", "gltf", "glb", "serialized"];

/// Reads the mesh in `path`, by extension: `.obj`, `.ply`, `.gltf`, `.glb` or `.serialized`
/// (its first mesh; case-insensitive).
pub fn load_mesh(path: &Path) -> Result<MeshData, MeshError> {
    load_mesh_index(path, 0)
}

/// [`load_mesh`] for mesh `shape_index` of a file that holds several (Mitsuba's `.serialized`);
/// for the other formats, which hold one mesh, `shape_index` must be 0.
pub fn load_mesh_index(path: &Path, shape_index: u32) -> Result<MeshData, MeshError> {
    let ext = extension(path);
    if shape_index != 0 && ext != "serialized" {
        return Err(MeshError::at(
            path,
            "",
            format!("shape_index {shape_index}: only .serialized files hold several meshes"),
        ));
    }
    match ext.as_str() {
        "obj" => obj::load(path),
        "ply" => ply::load(path),
        "gltf" | "glb" => gltf::load(path),
        "serialized" => serialized::load(path, shape_index),
        other => Err(unsupported(path, other)),
    }
}

/// Reads the mesh file `bytes` as [`load_mesh`] reads the file `path`, choosing the reader by
/// the extension of `path`, which also names the file in errors (and, for `.gltf`, is where
/// external buffers are looked for). For tests and tools that hold the bytes already.
pub fn load_mesh_bytes(path: &Path, bytes: &[u8]) -> Result<MeshData, MeshError> {
    match extension(path).as_str() {
        "obj" => obj::load_bytes(path, bytes),
        "ply" => ply::load_bytes(path, bytes),
        "gltf" | "glb" => gltf::load_bytes(path, bytes),
        "serialized" => serialized::load_bytes(path, bytes, 0),
        other => Err(unsupported(path, other)),
    }
}

/// The lower-case extension of `path` ("" if none).
fn extension(path: &Path) -> String {
    path.extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase()
}

/// The error for an extension no reader takes.
fn unsupported(path: &Path, ext: &str) -> MeshError {
    MeshError::at(
        path,
        "",
        format!("unsupported mesh format '.{ext}' (use .obj, .ply, .gltf, .glb or .serialized)"),
    )
}

/// Checks what every reader guarantees: indices in range, `normals`/`uvs` one per vertex; the
/// error names `file`. Readers call this last, so the front end can rely on it; public so that
/// the mutation test and the fuzz targets can hold the readers to it.
pub fn check(file: &Path, mesh: &MeshData) -> Result<(), MeshError> {
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
    for a in &mesh.attributes {
        let (want, per) = match a.kind() {
            AttributeKind::Vertex => (n, "vertices"),
            AttributeKind::Face => (mesh.indices.len(), "triangles"),
        };
        if a.values.len() != want {
            return Err(MeshError::at(
                file,
                "",
                format!(
                    "attribute '{}' has {} values for {want} {per}",
                    a.name,
                    a.values.len()
                ),
            ));
        }
    }
    Ok(())
}
