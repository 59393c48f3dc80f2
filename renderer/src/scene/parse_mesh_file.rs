//! The `mesh` shape (scene format Version 2): a triangle mesh read from a file (`scene/mesh/`),
//! placed by `to_world`, checked once here for every front end.

use super::desc::GeometryDesc;
use super::error::SceneError;
use super::mesh::{MeshData, normals};
use super::parse_mesh::{dropped_list, has_zero_area};
use super::parse_texture::TextureLoader;
use super::walk::{Obj, array, integer, number};
use glam::{DMat3, DMat4, DVec3, DVec4};
use std::path::Path;
use std::sync::Arc;

/// A transform whose 3×3 part has |det| below this fraction of the product of its column lengths
/// is singular for all practical purposes (normals could not be transformed).
const SINGULAR: f64 = 1e-12;

/// A `mesh` shape: the file (relative to `folder`; a mesh `loader` holds in memory first),
/// `to_world`, `face_normals`, `recompute_normals` (for a file without vertex normals, compute
/// them as Mitsuba does, [`crate::scene::mesh::normals`], unless `face_normals`). Zero-area
/// triangles (after `to_world`) are an error when the shape emits (`emits`), otherwise dropped
/// with a warning.
pub(crate) fn mesh(
    obj: &Obj,
    folder: &Path,
    loader: &mut TextureLoader,
    emits: bool,
    warnings: &mut Vec<String>,
) -> Result<GeometryDesc, SceneError> {
    let file_path = obj.at("file");
    let name = obj.string("file")?;
    if name.is_empty() {
        return Err(SceneError::new(file_path, "the file name is empty"));
    }
    let to_world = match obj.get("to_world") {
        None => DMat4::IDENTITY,
        Some(v) => matrix(v, &obj.at("to_world"))?,
    };
    let face_normals = obj.opt_bool("face_normals")?.unwrap_or(false);
    let recompute = obj.opt_bool("recompute_normals")?.unwrap_or(false);
    // Which mesh of a file that holds several (Mitsuba's `.serialized`).
    let shape_index = match obj.get("shape_index") {
        None => 0,
        Some(v) => integer(v, &obj.at("shape_index"), 0, u32::MAX as i64)? as u32,
    };
    let file = folder.join(name);
    let serialized = file
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("serialized"));
    if shape_index != 0 && !serialized {
        return Err(SceneError::new(
            obj.at("shape_index"),
            "only a .serialized file holds several meshes",
        ));
    }
    let data = match loader.take_mesh(&file) {
        Some(data) => Arc::new(data),
        None => loader.mesh(&file, shape_index, &file_path)?,
    };

    let world: Vec<DVec3> = data
        .positions
        .iter()
        .map(|p| to_world.transform_point3(p.as_dvec3()))
        .collect();
    if let Some(i) = world.iter().position(|p| !p.is_finite()) {
        return Err(SceneError::new(
            &file_path,
            format!(
                "{}: vertex {i} is not finite after to_world",
                file.display()
            ),
        ));
    }
    let mut kept = Vec::with_capacity(data.indices.len());
    let mut dropped = Vec::new();
    for (t, idx) in data.indices.iter().enumerate() {
        if !has_zero_area(idx.map(|i| world[i as usize])) {
            kept.push(*idx);
        } else if emits {
            // A zero-area light has an infinite area-sampling pdf: refuse rather than guess.
            return Err(SceneError::new(
                &file_path,
                format!(
                    "{}: triangle {t} {idx:?} has zero area, which is not allowed in an emitting shape",
                    file.display()
                ),
            ));
        } else {
            dropped.push(t);
        }
    }
    if !dropped.is_empty() {
        let list = dropped_list(&dropped, |t| t.to_string());
        warnings.push(format!("{file_path}: {}: {list}", file.display()));
    }
    if kept.is_empty() {
        warnings.push(format!(
            "{file_path}: {}: the mesh has no triangles",
            file.display()
        ));
    }
    let recompute_normals = recompute && !face_normals && data.normals.is_none();
    let normals = match recompute_normals {
        true => {
            let (world_normals, _) = normals::angle_weighted(&world, &kept);
            // Stored in the file's coordinates like a file's normals: the inverse of the
            // normal matrix (the inverse transpose) is the transpose of to_world's linear part.
            let back = DMat3::from_mat4(to_world).transpose();
            Some(
                world_normals
                    .iter()
                    .map(|n| (back * *n).as_vec3())
                    .collect(),
            )
        }
        false => None,
    };
    // A file read once serves every shape that places it unchanged (instances).
    if dropped.is_empty() && normals.is_none() {
        return Ok(GeometryDesc::Mesh {
            file,
            shape_index,
            to_world,
            face_normals,
            recompute_normals,
            mesh: data,
        });
    }
    let normals = normals.or_else(|| data.normals.clone());
    // Face attributes follow the kept triangles.
    let mut attributes = data.attributes.clone();
    if !dropped.is_empty() {
        for a in attributes
            .iter_mut()
            .filter(|a| a.kind() == super::mesh::AttributeKind::Face)
        {
            let mut k = 0;
            a.values.retain(|_| {
                k += 1;
                dropped.binary_search(&(k - 1)).is_err()
            });
        }
    }
    Ok(GeometryDesc::Mesh {
        file,
        shape_index,
        to_world,
        face_normals,
        recompute_normals,
        mesh: Arc::new(MeshData {
            positions: data.positions.clone(),
            indices: kept,
            normals,
            uvs: data.uvs.clone(),
            attributes,
        }),
    })
}

/// `to_world`: 4 rows of 4 finite numbers, row-major, an affine transform (last row
/// `[0, 0, 0, 1]`) that is invertible.
fn matrix(v: &serde_json::Value, path: &str) -> Result<DMat4, SceneError> {
    let rows = array(v, path)?;
    if rows.len() != 4 {
        return Err(SceneError::new(
            path,
            format!("expected 4 rows, found {}", rows.len()),
        ));
    }
    let mut m = [[0.0f64; 4]; 4];
    for (r, row) in rows.iter().enumerate() {
        let rpath = format!("{path}[{r}]");
        let items = array(row, &rpath)?;
        if items.len() != 4 {
            return Err(SceneError::new(
                rpath,
                format!("expected 4 numbers, found {}", items.len()),
            ));
        }
        for (c, item) in items.iter().enumerate() {
            m[r][c] = number(item, &format!("{rpath}[{c}]"))?;
        }
    }
    if m[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(SceneError::new(
            format!("{path}[3]"),
            "the last row must be [0, 0, 0, 1] (affine transforms only)",
        ));
    }
    // glam is column-major: the file's rows are the matrix's rows.
    let mat = DMat4::from_cols_array_2d(&m).transpose();
    let cols = [mat.x_axis, mat.y_axis, mat.z_axis].map(|c: DVec4| c.truncate().length());
    let det = glam::DMat3::from_mat4(mat).determinant();
    // Finite entries give a finite determinant, so `<=` also covers every singular case.
    if det.abs() <= SINGULAR * cols[0] * cols[1] * cols[2] {
        return Err(SceneError::new(
            path,
            format!("the matrix is not invertible (determinant {det:e})"),
        ));
    }
    Ok(mat)
}

#[cfg(test)]
mod tests {
    use super::super::tests::{expect_err, with};
    use serde_json::json;

    fn mesh(extra: serde_json::Value) -> serde_json::Value {
        let mut m = json!({"type": "mesh", "file": "no_such_mesh.obj"});
        for (k, v) in extra.as_object().unwrap() {
            m[k] = v.clone();
        }
        with(0, m)
    }

    #[test]
    fn bad_mesh_shapes_name_the_key() {
        expect_err(&mesh(json!({})), "shapes[0].file", "no_such_mesh.obj");
        expect_err(&mesh(json!({"file": ""})), "shapes[0].file", "empty");
        expect_err(
            &mesh(json!({"file": "bunny.stl"})),
            "shapes[0].file",
            "unsupported mesh format '.stl'",
        );
        expect_err(&mesh(json!({"file": 7})), "shapes[0].file", "a string");
        expect_err(
            &mesh(json!({"face_normals": 1})),
            "shapes[0].face_normals",
            "true or false",
        );
        expect_err(&mesh(json!({"scale": 2})), "shapes[0].scale", "unknown key");
        let id = json!([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]);
        let mut m = id.clone();
        m[3] = json!([0, 0, 1, 1]);
        expect_err(
            &mesh(json!({"to_world": m})),
            "shapes[0].to_world[3]",
            "affine",
        );
        expect_err(
            &mesh(json!({"to_world": [[1, 0, 0, 0]]})),
            "shapes[0].to_world",
            "expected 4 rows",
        );
        let mut m = id.clone();
        m[1] = json!([0, 1, 0]);
        expect_err(
            &mesh(json!({"to_world": m})),
            "shapes[0].to_world[1]",
            "expected 4 numbers",
        );
        let mut m = id.clone();
        m[2][2] = json!("x");
        expect_err(
            &mesh(json!({"to_world": m})),
            "shapes[0].to_world[2][2]",
            "",
        );
        let mut m = id.clone();
        m[2] = json!([1, 0, 0, 0]);
        expect_err(
            &mesh(json!({"to_world": m})),
            "shapes[0].to_world",
            "not invertible",
        );
        // A valid matrix gets as far as the missing file.
        let mut m = id;
        m[0][3] = json!(5);
        expect_err(
            &mesh(json!({"to_world": m})),
            "shapes[0].file",
            "no_such_mesh.obj",
        );
    }
}
