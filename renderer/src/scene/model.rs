//! A model file opened on its own (`lumis render bunny.ply`): the mesh becomes a scene with a
//! default material, a camera framing its bounding box and, since an OBJ or PLY file has no
//! lights, a constant white environment so that the image is never black. Everything then goes
//! through the JSON front end, so the model gets exactly the checks of a `mesh` shape.

use super::desc::SceneDesc;
use super::error::SceneError;
use super::mesh::MESH_EXTENSIONS;
use super::parse::parse_scene_value_in;
use glam::Vec3;
use serde_json::json;
use std::path::Path;

/// Vertical field of view of the automatic camera, degrees.
const VFOV_DEG: f64 = 40.0;
/// Image size of a model scene.
const SIZE: (u32, u32) = (640, 480);
/// Albedo of the default material.
const ALBEDO: f64 = 0.8;
/// Radiance of the default environment.
const ENVIRONMENT: f64 = 1.0;

/// Whether `path` names a mesh file rather than a JSON scene (by extension).
pub fn is_model_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

/// The scene of a model file: the mesh (diffuse, albedo 0.8, its vertex normals as shading
/// normals where it has them), a constant environment of radiance 1, and a camera 20° above the bounding box's
/// centre, looking at it along +z from −z, at the distance where the bounding sphere fills the
/// 40° field of view (with 10% margin).
pub fn model_scene(path: &Path) -> Result<SceneDesc, SceneError> {
    let file = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| SceneError::new("", "the model file has no name").in_file(path))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let data = super::mesh::load_mesh(path).map_err(|e| SceneError::new("", e.to_string()))?;
    let (lo, hi) = data
        .positions
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
            (a.min(*p), b.max(*p))
        });
    if data.indices.is_empty() || !lo.is_finite() || !hi.is_finite() {
        return Err(SceneError::new("", "the model has no triangles").in_file(path));
    }
    let centre = (0.5 * (lo + hi)).as_dvec3();
    let radius = (0.5 * (hi - lo).length() as f64).max(1e-6);
    let distance = 1.1 * radius / (0.5 * VFOV_DEG.to_radians()).sin();
    let elevation = 20f64.to_radians();
    let from = centre + distance * glam::DVec3::new(0.0, elevation.sin(), -elevation.cos());
    let scene = json!({
        "comment": format!("the model {file} on its own (lumis' defaults, scene/model.rs)"),
        "camera": {
            "from": from.to_array(), "to": centre.to_array(), "up": [0, 1, 0],
            "vfov_deg": VFOV_DEG, "width": SIZE.0, "height": SIZE.1,
        },
        "background": [ENVIRONMENT, ENVIRONMENT, ENVIRONMENT],
        "materials": {"model": {"type": "diffuse", "albedo": [ALBEDO, ALBEDO, ALBEDO]}},
        "shapes": [{"type": "mesh", "file": file, "material": "model"}],
    });
    parse_scene_value_in(&scene, folder).map_err(|e| e.in_file(path))
}
