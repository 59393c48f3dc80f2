//! Reader of glTF 2.0 mesh files: `.gltf` (JSON with external or `data:` URI buffers) and `.glb`
//! (the binary container, its BIN chunk as buffer 0). Every triangle primitive of the default
//! scene, placed by its node transforms, is merged into one [`MeshData`].
//!
//! The rules, in the order they apply:
//! - **Extensions**: an entry of `extensionsRequired` is an error naming it (Draco and meshopt
//!   compression are the usual ones), except the extensions `materials::HANDLED` that a model
//!   scene reads (materials, lights). Optional extensions are ignored here.
//! - **Scene**: `scene` if the file names one, else scene 0, else (no scenes) every root node.
//! - **Transforms**: a node's `matrix`, or T·R·S from `translation`/`rotation`/`scale`, composed
//!   parent × child down the hierarchy (which must be a tree). Positions go through the full
//!   matrix (one it takes beyond `f32` is an error); normals through the inverse transpose of
//!   its 3×3 part, then are renormalised (one that a singular matrix flattens to zero stays
//!   zero). A matrix with negative determinant swaps two indices of each triangle, so the
//!   right-hand rule still gives the side the file means. Skins, morph targets and `EXT_mesh_gpu_instancing` are not applied (the rest pose).
//! - **Modes**: TRIANGLES; TRIANGLE_STRIP and TRIANGLE_FAN are converted to triangles by the
//!   spec's vertex order (their zero-area joins, triangles with a repeated index, are dropped).
//!   POINTS and LINES* primitives are skipped silently (lumis renders surfaces and has no
//!   warnings channel); a scene with no triangles at all is an error that says so.
//! - **Attributes**: POSITION and NORMAL as FLOAT VEC3, TEXCOORD_0 as FLOAT or normalised
//!   UNSIGNED_BYTE/UNSIGNED_SHORT VEC2 (`v` down from the top, as stored); indices UNSIGNED_BYTE,
//!   SHORT or INT (none: 0..n). Sparse accessors are applied. Normals (texture coordinates) are
//!   kept only if every merged primitive has them, else dropped for the whole mesh, which is
//!   then shaded flat (untextured): one mesh is shaded one way.
//! - **Buffers**: only those the placed primitives use are read, so a missing animation or image
//!   buffer does not stop the mesh. POSITION's `min`/`max` (required by the spec, unused here)
//!   may be absent.
//!
//! Every error names the file and a position: `buffer 1`, `accessor 3`, `accessor 1 element 7`,
//! `mesh 0 primitive 2`, `node 4`, `glb header`, `glb chunk 1`, or the JSON paths of the `gltf`
//! crate's validation.

#[path = "gltf_buffers.rs"]
mod buffers;
#[cfg(any(test, feature = "testing"))]
#[path = "gltf_bytes.rs"]
pub mod bytes;
#[path = "gltf_lights.rs"]
pub mod lights;
#[path = "gltf_materials.rs"]
pub mod materials;
#[path = "gltf_model.rs"]
pub mod model;

use super::{MeshData, MeshError, check};
use ::gltf::accessor::{Accessor, DataType, Dimensions};
use ::gltf::buffer::View;
use ::gltf::json;
use ::gltf::mesh::{Mode, Semantic};
use ::gltf::{Document, Primitive};
use buffers::load_buffers;
use glam::{Mat3, Mat4, Quat, Vec2, Vec3};
use std::path::Path;

/// Reads `path` as a `.gltf` or `.glb` file (told apart by the `glTF` magic, not the name).
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::at(path, "", e))?;
    load_bytes(path, &bytes)
}

/// Reads the `.gltf` or `.glb` file `bytes` as [`load`] reads a file; `path` names it in errors
/// and its folder is where external buffers (relative `uri`s) are looked for. The entry point of
/// the fuzz target `mesh_gltf`.
pub fn load_bytes(path: &Path, bytes: &[u8]) -> Result<MeshData, MeshError> {
    let glb = bytes.starts_with(b"glTF");
    let (json_bytes, bin) = if glb {
        split_glb(path, bytes)?
    } else {
        (bytes, None)
    };
    let document = parse_document(path, json_bytes)?;
    let (placements, ..) = placements(path, &document)?;
    let mut needed = vec![false; document.buffers().len()];
    mark_geometry_buffers(&placements, &mut needed);
    let buffers = load_buffers(path, &document, &needed, glb, bin)?;
    let slices: Vec<&[u8]> = buffers.iter().map(|b| &b[..]).collect();

    let mut merged = Merged::default();
    let mut skipped = 0;
    for place in &placements {
        if !read_primitive(path, &slices, place, &mut merged)? {
            skipped += 1;
        }
    }
    if merged.mesh.indices.is_empty() {
        return Err(no_triangles(path, placements.len(), skipped));
    }
    let mesh = merged.finish();
    check(path, &mesh)?;
    Ok(mesh)
}

/// The error for a default scene without triangles.
fn no_triangles(path: &Path, placed: usize, skipped: usize) -> MeshError {
    MeshError::at(
        path,
        "",
        format!(
            "no triangles in the default scene ({placed} primitives placed, {skipped} of them \
             POINTS or LINES, which lumis skips)"
        ),
    )
}

/// GLB chunk types (little-endian `JSON` and `BIN\0`).
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

/// Splits a `.glb` into its JSON chunk and its BIN chunk, if any. Parsed here rather than by
/// the `gltf` crate, whose header arithmetic can underflow on a bad length.
fn split_glb<'a>(file: &Path, bytes: &'a [u8]) -> Result<(&'a [u8], Option<&'a [u8]>), MeshError> {
    let header = |m: String| MeshError::at(file, "glb header", m);
    if bytes.len() < 12 {
        return Err(header(format!(
            "the file has {} bytes, fewer than the 12-byte header",
            bytes.len()
        )));
    }
    let version = le_u32(&bytes[4..8]);
    if version != 2 {
        return Err(header(format!("version {version} (lumis reads glTF 2.0)")));
    }
    let length = le_u32(&bytes[8..12]) as usize;
    if length > bytes.len() {
        return Err(header(format!(
            "length {length} but the file has {} bytes",
            bytes.len()
        )));
    }
    let (mut json, mut bin) = (None, None);
    let (mut offset, mut chunk) = (12usize, 0usize);
    while offset < length {
        let at = |m: String| MeshError::at(file, &format!("glb chunk {chunk}"), m);
        if length - offset < 8 {
            return Err(at(format!(
                "truncated chunk header at byte {offset} ({length} bytes)"
            )));
        }
        let size = le_u32(&bytes[offset..offset + 4]) as usize;
        let kind = le_u32(&bytes[offset + 4..offset + 8]);
        let start = offset + 8;
        if size > length - start {
            return Err(at(format!(
                "{size} bytes from byte {start} run past the end of the file ({length} bytes)"
            )));
        }
        let data = &bytes[start..start + size];
        match (chunk, kind) {
            (0, CHUNK_JSON) => json = Some(data),
            (0, _) => return Err(at(format!("type {kind:#010x}, but the first must be JSON"))),
            (1, CHUNK_BIN) => bin = Some(data),
            // Other chunks are for extensions; the spec says to ignore unknown ones.
            _ => {}
        }
        offset = start + size;
        chunk += 1;
    }
    let json = json.ok_or_else(|| header("no JSON chunk".to_string()))?;
    Ok((json, bin))
}

fn le_u32(b: &[u8]) -> u32 {
    u32::from_le_bytes([b[0], b[1], b[2], b[3]])
}

/// Parses and validates the JSON, in an order that keeps the `gltf` crate from panicking: its
/// wrappers unwrap what validation checked, and one validation hook indexes the POSITION accessor
/// before bounds are known.
fn parse_document(file: &Path, json_bytes: &[u8]) -> Result<Document, MeshError> {
    // Some writers pad the GLB JSON chunk with zeros instead of spaces.
    let end = json_bytes
        .iter()
        .rposition(|&b| b != 0)
        .map_or(0, |i| i + 1);
    let root = json::Root::from_slice(&json_bytes[..end])
        .map_err(|e| MeshError::at(file, "", format!("invalid glTF JSON: {e}")))?;

    // The material extensions lumis reads leave the geometry as it is, required or not.
    let unsupported: Vec<&str> = root
        .extensions_required
        .iter()
        .map(String::as_str)
        .filter(|e| !materials::HANDLED.contains(e))
        .collect();
    if !unsupported.is_empty() {
        let names = unsupported.join(", ");
        let compressed = unsupported
            .iter()
            .any(|&e| e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression");
        let hint = if compressed {
            " (compressed geometry: export the file without compression)"
        } else {
            ""
        };
        return Err(MeshError::at(
            file,
            "",
            format!("requires glTF extension {names}, which lumis does not support{hint}"),
        ));
    }

    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let position = json::validation::Checked::Valid(json::mesh::Semantic::Positions);
            if let Some(index) = prim.attributes.get(&position)
                && index.value() >= root.accessors.len()
            {
                return Err(MeshError::at(
                    file,
                    &format!("mesh {m} primitive {p}"),
                    format!(
                        "POSITION accessor {} does not exist ({} accessors)",
                        index.value(),
                        root.accessors.len()
                    ),
                ));
            }
        }
    }

    use json::validation::Validate;
    let mut errors = Vec::new();
    root.validate(
        &root,
        json::Path::new,
        &mut |path: &dyn Fn() -> json::Path, error: json::validation::Error| {
            let path = path().to_string();
            // POSITION's bounds are a spec formality lumis does not use; exporters omit them.
            let bounds =
                path.ends_with("[\"POSITION\"].min") || path.ends_with("[\"POSITION\"].max");
            // The crate knows no extension of its own; the check above kept lumis' ones only.
            let required = path.starts_with("extensionsRequired[")
                && matches!(error, json::validation::Error::Unsupported);
            if required {
                return;
            }
            if !(bounds && matches!(error, json::validation::Error::Missing)) {
                errors.push(format!("{path}: {error}"));
            }
        },
    );
    if !errors.is_empty() {
        let more = errors.len().saturating_sub(5);
        errors.truncate(5);
        let mut message = format!("invalid glTF: {}", errors.join("; "));
        if more > 0 {
            message += &format!("; and {more} more");
        }
        return Err(MeshError::at(file, "", message));
    }
    Ok(Document::from_json_without_validation(root))
}

/// One mesh primitive as the scene places it, with its glTF material (`None`: the default
/// material), which only [`model::load_model`] reads.
struct Placement<'a> {
    /// The node that places it.
    node: usize,
    mesh: usize,
    primitive: Primitive<'a>,
    world: Mat4,
    material: Option<usize>,
}

/// A camera or light node's index and world matrix.
type NodePlacement = (usize, Mat4);
/// What [`placements`] finds: primitives, the camera, the lights.
type Placed<'a> = (
    Vec<Placement<'a>>,
    Option<NodePlacement>,
    Vec<NodePlacement>,
);

/// Every primitive of the default scene (see the module doc) with its world matrix, depth
/// first in the file's order, and the first node on that walk with a camera, with its world
/// matrix, and every node on that walk with a `KHR_lights_punctual` light, with theirs.
fn placements<'a>(file: &Path, doc: &'a Document) -> Result<Placed<'a>, MeshError> {
    let nodes: Vec<_> = doc.nodes().collect();
    let roots: Vec<usize> = match doc.default_scene().or_else(|| doc.scenes().next()) {
        Some(scene) => scene.nodes().map(|n| n.index()).collect(),
        None => {
            let mut child = vec![false; nodes.len()];
            for node in &nodes {
                for c in node.children() {
                    child[c.index()] = true;
                }
            }
            (0..nodes.len()).filter(|&i| !child[i]).collect()
        }
    };

    let mut seen = vec![false; nodes.len()];
    let mut out = Vec::new();
    let (mut camera, mut lights) = (None, Vec::new());
    // An explicit stack: a deep chain of nodes must not overflow the call stack.
    let mut stack: Vec<(usize, Mat4)> = roots.iter().rev().map(|&i| (i, Mat4::IDENTITY)).collect();
    while let Some((index, parent)) = stack.pop() {
        let at = |m: &str| MeshError::at(file, &format!("node {index}"), m);
        if std::mem::replace(&mut seen[index], true) {
            return Err(at(
                "reached twice (the node hierarchy must be a tree: a cycle or a shared child)",
            ));
        }
        let node = &nodes[index];
        let world = parent * local_matrix(node).map_err(at)?;
        if !world.is_finite() {
            return Err(at("transform is not finite (composed with its parents)"));
        }
        if camera.is_none() && node.camera().is_some() {
            camera = Some((index, world));
        }
        if lights::has_light(node) {
            lights.push((index, world));
        }
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                out.push(Placement {
                    node: index,
                    mesh: mesh.index(),
                    material: primitive.material().index(),
                    primitive,
                    world,
                });
            }
        }
        let children: Vec<usize> = node.children().map(|c| c.index()).collect();
        stack.extend(children.into_iter().rev().map(|c| (c, world)));
    }
    Ok((out, camera, lights))
}

/// A node's own matrix, or what is wrong with it.
fn local_matrix(node: &::gltf::Node) -> Result<Mat4, &'static str> {
    let m = match node.transform() {
        ::gltf::scene::Transform::Matrix { matrix } => Mat4::from_cols_array_2d(&matrix),
        ::gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            let q = Quat::from_array(rotation);
            // The spec asks for unit quaternions; writers round, so normalise what is not zero.
            let length = q.length();
            if length.is_nan() || length <= 1e-6 {
                return Err("rotation is not a unit quaternion (its length is 0 or not finite)");
            }
            Mat4::from_scale_rotation_translation(
                Vec3::from_array(scale),
                q.normalize(),
                Vec3::from_array(translation),
            )
        }
    };
    if m.is_finite() {
        Ok(m)
    } else {
        Err("transform is not finite")
    }
}

/// The accessors a surface primitive reads.
fn used_accessors<'a>(primitive: &Primitive<'a>) -> impl Iterator<Item = Accessor<'a>> {
    [
        primitive.get(&Semantic::Positions),
        primitive.get(&Semantic::Normals),
        primitive.get(&Semantic::TexCoords(0)),
        primitive.indices(),
    ]
    .into_iter()
    .flatten()
}

fn is_surface(mode: Mode) -> bool {
    matches!(
        mode,
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
    )
}

/// Marks, per buffer, whether the surface primitives of `placements` read it.
fn mark_geometry_buffers(placements: &[Placement], needed: &mut [bool]) {
    let mut mark = |view: View| needed[view.buffer().index()] = true;
    for place in placements.iter().filter(|p| is_surface(p.primitive.mode())) {
        for accessor in used_accessors(&place.primitive) {
            accessor.view().map(&mut mark);
            if let Some(sparse) = accessor.sparse() {
                mark(sparse.indices().view());
                mark(sparse.values().view());
            }
        }
    }
}

/// What a primitive reads an accessor as; decides the layouts accepted.
#[derive(Clone, Copy)]
enum Role {
    Position,
    Normal,
    TexCoord,
    Index,
}

impl Role {
    fn name(self) -> &'static str {
        match self {
            Role::Position => "POSITION",
            Role::Normal => "NORMAL",
            Role::TexCoord => "TEXCOORD_0",
            Role::Index => "indices",
        }
    }
}

/// Checks that the `gltf` crate's reader can read `accessor` as `role` and stays inside the
/// buffers: the layout the reader assumes (it has `unreachable!` and `debug_assert!` for the
/// others), `count` ≥ 1, every byte range, sparse indices ascending and in range.
fn check_accessor(
    file: &Path,
    accessor: &Accessor,
    buffers: &[&[u8]],
    role: Role,
) -> Result<(), MeshError> {
    let at = |m: String| MeshError::at(file, &format!("accessor {}", accessor.index()), m);
    let (ty, dims, norm) = (
        accessor.data_type(),
        accessor.dimensions(),
        accessor.normalized(),
    );
    let layout_ok = match role {
        Role::Position | Role::Normal => ty == DataType::F32 && dims == Dimensions::Vec3,
        Role::TexCoord => {
            dims == Dimensions::Vec2
                && (ty == DataType::F32 || (norm && matches!(ty, DataType::U8 | DataType::U16)))
        }
        Role::Index => {
            dims == Dimensions::Scalar
                && !norm
                && matches!(ty, DataType::U8 | DataType::U16 | DataType::U32)
        }
    };
    if !layout_ok {
        let expected = match role {
            Role::Position | Role::Normal => "FLOAT VEC3",
            Role::TexCoord => "VEC2 of FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT",
            Role::Index => "SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT",
        };
        let normalized = if norm { " normalized" } else { "" };
        return Err(at(format!(
            "{} must be {expected}, found {dims:?} of {ty:?}{normalized} (quantized \
             geometry, KHR_mesh_quantization, is not supported)",
            role.name()
        )));
    }
    let count = accessor.count();
    if count == 0 {
        return Err(at("count is 0".into()));
    }
    let element = accessor.size();
    if let Some(view) = accessor.view() {
        check_range(buffers, &view, accessor.offset(), count, element).map_err(at)?;
    }
    if let Some(sparse) = accessor.sparse() {
        let n = sparse.count();
        if n == 0 || n > count {
            return Err(at(format!(
                "sparse count {n} is not in 1..={count} (the accessor's count)"
            )));
        }
        let indices = sparse.indices();
        let index_size = indices.index_type().size();
        let iview = indices.view();
        check_range(buffers, &iview, indices.offset(), n, index_size)
            .map_err(|m| at(format!("sparse indices: {m}")))?;
        let values = sparse.values();
        check_range(buffers, &values.view(), values.offset(), n, element)
            .map_err(|m| at(format!("sparse values: {m}")))?;
        // The reader silently drops indices that are not strictly ascending or out of range.
        let stride = iview.stride().unwrap_or(index_size);
        let base = iview.offset() + indices.offset();
        let data = buffers[iview.buffer().index()];
        let mut previous = None;
        for k in 0..n {
            let b = &data[base + k * stride..][..index_size];
            let i = match index_size {
                1 => b[0] as usize,
                2 => u16::from_le_bytes([b[0], b[1]]) as usize,
                _ => le_u32(b) as usize,
            };
            if i >= count {
                return Err(at(format!(
                    "sparse index {i} (entry {k}) out of range ({count} elements)"
                )));
            }
            if previous.is_some_and(|p| i <= p) {
                return Err(at(format!(
                    "sparse index {i} (entry {k}) is not above the one before it"
                )));
            }
            previous = Some(i);
        }
    }
    Ok(())
}

/// Checks that `count` elements of `element` bytes from `offset` in `view` (at its stride, as
/// the reader steps) lie inside the view, and the view inside its buffer's declared length.
fn check_range(
    buffers: &[&[u8]],
    view: &View,
    offset: usize,
    count: usize,
    element: usize,
) -> Result<(), String> {
    let buffer = view.buffer();
    let declared = buffer.length().min(buffers[buffer.index()].len());
    let view_end = view.offset().checked_add(view.length());
    if view_end.is_none_or(|end| end > declared) {
        return Err(format!(
            "buffer view {} (bytes {}..+{}) runs past the end of buffer {} ({declared} bytes)",
            view.index(),
            view.offset(),
            view.length(),
            buffer.index()
        ));
    }
    let stride = view.stride().unwrap_or(element);
    if stride < element {
        return Err(format!(
            "buffer view {}: byteStride {stride} is smaller than the {element}-byte element",
            view.index()
        ));
    }
    let end = stride
        .checked_mul(count - 1)
        .and_then(|s| s.checked_add(element))
        .and_then(|s| s.checked_add(offset));
    if end.is_none_or(|end| end > view.length()) {
        return Err(format!(
            "{count} elements of {element} bytes (stride {stride}) from byte {offset} run past \
             the end of buffer view {} ({} bytes)",
            view.index(),
            view.length()
        ));
    }
    Ok(())
}

/// The mesh being merged; `normals`/`uvs` become `None` at the first primitive without them.
struct Merged {
    mesh: MeshData,
    normals: Option<Vec<Vec3>>,
    uvs: Option<Vec<Vec2>>,
}

impl Merged {
    /// The mesh with the attributes every primitive had.
    fn finish(self) -> MeshData {
        MeshData {
            normals: self.normals,
            uvs: self.uvs,
            ..self.mesh
        }
    }
}

impl Default for Merged {
    fn default() -> Self {
        Merged {
            mesh: MeshData::default(),
            normals: Some(Vec::new()),
            uvs: Some(Vec::new()),
        }
    }
}

/// An error for a non-finite element, at its accessor and element.
fn check_finite(
    file: &Path,
    accessor: &Accessor,
    what: &str,
    values: impl Iterator<Item = (usize, bool, bool)>,
) -> Result<(), MeshError> {
    for (i, nan, finite) in values {
        if !finite {
            let how = if nan { "NaN" } else { "infinite" };
            return Err(MeshError::at(
                file,
                &format!("accessor {} element {i}", accessor.index()),
                format!("{what} is {how}"),
            ));
        }
    }
    Ok(())
}

/// Reads one placed primitive into `out`; `false` if its mode is skipped.
fn read_primitive(
    file: &Path,
    buffers: &[&[u8]],
    place: &Placement,
    out: &mut Merged,
) -> Result<bool, MeshError> {
    let primitive = &place.primitive;
    let mode = primitive.mode();
    if !is_surface(mode) {
        return Ok(false);
    }
    let here = format!("mesh {} primitive {}", place.mesh, primitive.index());
    let at = |m: String| MeshError::at(file, &here, m);
    let unreadable = |a: &Accessor| {
        MeshError::at(
            file,
            &format!("accessor {}", a.index()),
            "cannot be read (buffer data missing)",
        )
    };

    let pos_acc = primitive
        .get(&Semantic::Positions)
        .ok_or_else(|| at("has no POSITION".into()))?;
    check_accessor(file, &pos_acc, buffers, Role::Position)?;
    let n = pos_acc.count();
    let normal_acc = primitive.get(&Semantic::Normals);
    let uv_acc = primitive.get(&Semantic::TexCoords(0));
    for (acc, role) in [(&normal_acc, Role::Normal), (&uv_acc, Role::TexCoord)] {
        if let Some(acc) = acc {
            check_accessor(file, acc, buffers, role)?;
            if acc.count() != n {
                return Err(at(format!(
                    "{} has {} elements but POSITION has {n}",
                    role.name(),
                    acc.count()
                )));
            }
        }
    }
    if let Some(acc) = primitive.indices() {
        check_accessor(file, &acc, buffers, Role::Index)?;
    }

    let reader = primitive.reader(|b| buffers.get(b.index()).copied());
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| unreadable(&pos_acc))?
        .map(Vec3::from_array)
        .collect();
    if positions.len() != n {
        return Err(unreadable(&pos_acc));
    }
    check_finite(
        file,
        &pos_acc,
        "position",
        positions
            .iter()
            .enumerate()
            .map(|(i, p)| (i, p.is_nan(), p.is_finite())),
    )?;

    let normals = match (&normal_acc, out.normals.is_some()) {
        (Some(acc), true) => {
            let v: Vec<Vec3> = reader
                .read_normals()
                .ok_or_else(|| unreadable(acc))?
                .map(Vec3::from_array)
                .collect();
            if v.len() != n {
                return Err(unreadable(acc));
            }
            check_finite(
                file,
                acc,
                "normal",
                v.iter()
                    .enumerate()
                    .map(|(i, p)| (i, p.is_nan(), p.is_finite())),
            )?;
            Some(v)
        }
        _ => None,
    };
    let uvs = match (&uv_acc, out.uvs.is_some()) {
        (Some(acc), true) => {
            let v: Vec<Vec2> = reader
                .read_tex_coords(0)
                .ok_or_else(|| unreadable(acc))?
                .into_f32()
                .map(Vec2::from_array)
                .collect();
            if v.len() != n {
                return Err(unreadable(acc));
            }
            check_finite(
                file,
                acc,
                "texture coordinate",
                v.iter()
                    .enumerate()
                    .map(|(i, p)| (i, p.is_nan(), p.is_finite())),
            )?;
            Some(v)
        }
        _ => None,
    };

    let vertex_order: Vec<u32> = match primitive.indices() {
        Some(acc) => {
            let v: Vec<u32> = reader
                .read_indices()
                .ok_or_else(|| unreadable(&acc))?
                .into_u32()
                .collect();
            if v.len() != acc.count() {
                return Err(unreadable(&acc));
            }
            if let Some(&bad) = v.iter().find(|&&i| i as usize >= n) {
                return Err(at(format!("index {bad} out of range ({n} vertices)")));
            }
            v
        }
        None => {
            let n32 = u32::try_from(n).map_err(|_| at(format!("{n} vertices is too many")))?;
            (0..n32).collect()
        }
    };
    let mut triangles = triangles(mode, &vertex_order).map_err(at)?;

    // Placement: positions by the world matrix, normals by its inverse transpose (computed as
    // the cofactor matrix times the determinant's sign, which stays finite for a singular one).
    let base = out.mesh.positions.len();
    let base32 = u32::try_from(base + n)
        .map(|_| base as u32)
        .map_err(|_| at("the merged mesh has more than 2^32 vertices".into()))?;
    let world = place.world;
    let linear = Mat3::from_mat4(world);
    let det = linear.determinant();
    let (a, b, c) = (linear.x_axis, linear.y_axis, linear.z_axis);
    let normal_matrix = Mat3::from_cols(b.cross(c), c.cross(a), a.cross(b)) * det.signum();
    if det < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    // Finite positions and a finite matrix can still overflow (f32::MAX scaled by 2).
    let placed = positions.iter().map(|&p| world.transform_point3(p));
    if let Some(i) = placed.clone().position(|p| !p.is_finite()) {
        return Err(MeshError::at(
            file,
            &format!("accessor {} element {i}", pos_acc.index()),
            format!(
                "position overflows single precision under the transform of node {} (with \
                 its parents)",
                place.node
            ),
        ));
    }
    out.mesh.positions.extend(placed);
    out.mesh
        .indices
        .extend(triangles.iter().map(|t| t.map(|i| i + base32)));
    match (normals, &mut out.normals) {
        (Some(v), Some(all)) => {
            all.extend(v.iter().map(|&n| (normal_matrix * n).normalize_or_zero()));
        }
        _ => out.normals = None,
    }
    match (uvs, &mut out.uvs) {
        (Some(v), Some(all)) => all.extend(v),
        _ => out.uvs = None,
    }
    Ok(true)
}

/// Triangles of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN vertex sequence, in the orders the
/// glTF spec gives (strip: {v_i, v_{i+1+i%2}, v_{i+2−i%2}}; fan: {v_{i+1}, v_{i+2}, v_0}).
fn triangles(mode: Mode, v: &[u32]) -> Result<Vec<[u32; 3]>, String> {
    let degenerate = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    Ok(match mode {
        Mode::Triangles => {
            if !v.len().is_multiple_of(3) {
                return Err(format!(
                    "{} vertices in TRIANGLES mode is not a multiple of 3",
                    v.len()
                ));
            }
            v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect()
        }
        Mode::TriangleStrip => (0..v.len().saturating_sub(2))
            .map(|i| [v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]])
            .filter(|t| !degenerate(t))
            .collect(),
        Mode::TriangleFan => (0..v.len().saturating_sub(2))
            .map(|i| [v[i + 1], v[i + 2], v[0]])
            .filter(|t| !degenerate(t))
            .collect(),
        _ => Vec::new(),
    })
}

#[cfg(test)]
#[path = "gltf_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "gltf_test_asset.rs"]
pub(crate) mod test_asset;
