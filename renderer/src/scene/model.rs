//! A model file opened on its own (`lumis render bunny.ply`): the mesh becomes a scene with a
//! camera framing its bounding box and a constant white environment, so that the image is never
//! black. An OBJ or PLY file gets one diffuse material; a glTF file keeps its materials (mapped
//! by `mesh/gltf_materials.rs`), its emission (then without the environment) and its first
//! camera. Everything then goes through the JSON front end, so the model gets exactly the checks
//! of a scene file: a glTF file's primitives and decoded images are handed to it in memory,
//! under names such as `model.glb#nodes[0] meshes[0].primitives[1]` and `model.glb#images[2]`.

use super::desc::SceneDesc;
use super::error::SceneError;
use super::mesh::MESH_EXTENSIONS;
use super::mesh::gltf::model::{CameraNode, Model, load_model};
use super::parse::{MAX_IMAGE_SIZE, parse_scene_value_in, parse_scene_value_preloaded};
use super::parse_texture::Preloaded;
use glam::{DVec3, Vec3};
use serde_json::{Value, json};
use std::path::Path;

/// Vertical field of view of the automatic camera, degrees.
const VFOV_DEG: f64 = 40.0;
/// Image size of a model scene (a glTF camera's aspect ratio keeps the width).
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

/// The scene of a model file. OBJ and PLY: the mesh (diffuse, albedo 0.8, its vertex normals as
/// shading normals where it has them) under a constant environment of radiance 1, seen by the
/// automatic camera: 20° above the bounding box's centre, looking at it along +z from −z, at the
/// distance where the bounding sphere fills the 40° field of view (with 10% margin). glTF: as
/// docs/scene-format.md, "glTF materials", says.
pub fn model_scene(path: &Path) -> Result<SceneDesc, SceneError> {
    let file = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| SceneError::new("", "the model file has no name").in_file(path))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    if matches!(ext.to_ascii_lowercase().as_str(), "gltf" | "glb") {
        return gltf_scene(path, file, folder);
    }
    let data = super::mesh::load_mesh(path).map_err(|e| SceneError::new("", e.to_string()))?;
    if data.indices.is_empty() {
        return Err(SceneError::new("", "the model has no triangles").in_file(path));
    }
    let camera = auto_camera(path, &data.positions)?;
    let scene = json!({
        "comment": format!("the model {file} on its own (lumis' defaults, scene/model.rs)"),
        "camera": camera,
        "background": [ENVIRONMENT, ENVIRONMENT, ENVIRONMENT],
        "materials": {"model": {"type": "diffuse", "albedo": [ALBEDO, ALBEDO, ALBEDO]}},
        "shapes": [{"type": "mesh", "file": file, "material": "model"}],
    });
    parse_scene_value_in(&scene, folder).map_err(|e| e.in_file(path))
}

/// The automatic camera of a model with these vertices (see [`model_scene`]).
fn auto_camera(path: &Path, positions: &[Vec3]) -> Result<Value, SceneError> {
    let (lo, hi) = bounds(positions);
    if !lo.is_finite() || !hi.is_finite() {
        return Err(SceneError::new("", "the model has no triangles").in_file(path));
    }
    let centre = 0.5 * (lo + hi);
    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let distance = 1.1 * radius / (0.5 * VFOV_DEG.to_radians()).sin();
    let elevation = 20f64.to_radians();
    let from = centre + distance * DVec3::new(0.0, elevation.sin(), -elevation.cos());
    Ok(json!({
        "from": from.to_array(), "to": centre.to_array(), "up": [0, 1, 0],
        "vfov_deg": VFOV_DEG, "width": SIZE.0, "height": SIZE.1,
    }))
}

/// The bounding box of `positions` (infinite when empty).
fn bounds(positions: &[Vec3]) -> (DVec3, DVec3) {
    let (lo, hi) = positions
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
            (a.min(*p), b.max(*p))
        });
    (lo.as_dvec3(), hi.as_dvec3())
}

/// The scene of a glTF file: one `mesh` shape per placed primitive with its material and
/// emission, the file's camera or the automatic one, and the white environment unless
/// something emits.
fn gltf_scene(path: &Path, file: &str, folder: &Path) -> Result<SceneDesc, SceneError> {
    let Model {
        primitives,
        materials,
        camera,
    } = load_model(path).map_err(|e| SceneError::new("", e.to_string()))?;
    let mut ignored = materials.ignored;
    let mut warnings = Vec::new();
    let mut preloaded = Preloaded::default();
    let positions: Vec<Vec3> = primitives
        .iter()
        .flat_map(|p| p.mesh.positions.iter().copied())
        .collect();
    let (lo, hi) = bounds(&positions);
    drop(positions);

    let mut shapes = Vec::new();
    for p in primitives {
        if p.mesh.indices.is_empty() {
            continue;
        }
        let (_, mapped) = materials
            .mapped
            .iter()
            .find(|(m, _)| *m == p.material)
            .expect("every material a primitive uses is mapped");
        if mapped.textured && p.mesh.uvs.is_none() {
            ignored.push(format!(
                "{}: the textures of its material (it has no TEXCOORD_0)",
                p.name
            ));
        }
        if p.has_colors {
            ignored.push(format!("{} COLOR_0", p.name));
        }
        let name = format!("{file}#{}", p.name);
        let mut shape = json!({"type": "mesh", "file": name, "material": mapped.name});
        if let Some(e) = &mapped.emission {
            shape["emission"] = e.clone();
        }
        shapes.push(shape);
        preloaded.meshes.insert(folder.join(&name), p.mesh);
    }
    for (name, raw, image) in materials.images {
        preloaded.images.insert((folder.join(name), raw), image);
    }

    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let camera = match camera {
        Some(c) => gltf_camera(path, &c, radius, &mut warnings)?,
        None => None,
    };
    let camera = match camera {
        Some(c) => c,
        None => auto_camera(path, &[lo.as_vec3(), hi.as_vec3()])?,
    };
    let emits = shapes.iter().any(|s| s.get("emission").is_some());
    let environment = if emits { 0.0 } else { ENVIRONMENT };
    let scene = json!({
        "comment": format!("the glTF file {file} on its own (scene/model.rs)"),
        "camera": camera,
        "background": [environment, environment, environment],
        "materials": materials.json,
        "shapes": shapes,
    });
    let mut desc =
        parse_scene_value_preloaded(&scene, folder, preloaded).map_err(|e| e.in_file(path))?;
    let mut seen = std::collections::HashSet::new();
    ignored.retain(|i| seen.insert(i.clone()));
    if !ignored.is_empty() {
        warnings.push(format!(
            "{}: glTF features lumis does not render: {}",
            path.display(),
            ignored.join(", ")
        ));
    }
    desc.warnings.extend(warnings);
    Ok(desc)
}

/// The scene camera of a glTF camera node: a perspective camera's `yfov`, and its
/// `aspectRatio` as 640 pixels wide (640 × 480 without one). An orthographic camera is `None`
/// with a warning (lumis' camera is a pinhole). `radius` (the model's) places `to`.
fn gltf_camera(
    path: &Path,
    c: &CameraNode,
    radius: f64,
    warnings: &mut Vec<String>,
) -> Result<Option<Value>, SceneError> {
    let at = format!("cameras[{}]", c.camera);
    let err = |at: String, m: String| SceneError::new(at, m).in_file(path);
    let Some((yfov, aspect)) = c.perspective else {
        warnings.push(format!(
            "{}: {at} (on nodes[{}]) is orthographic and lumis' camera a pinhole: the automatic \
             camera is used",
            path.display(),
            c.node
        ));
        return Ok(None);
    };
    let vfov_deg = (yfov as f64).to_degrees();
    if !(vfov_deg > 0.0 && vfov_deg < 180.0) {
        let m = format!("{yfov} radians is outside (0, π)");
        return Err(err(format!("{at}.perspective.yfov"), m));
    }
    let (width, height) = match aspect {
        None => SIZE,
        Some(a) if a > 0.0 && a.is_finite() => {
            let h = (SIZE.0 as f64 / a as f64).round();
            (SIZE.0, h.clamp(1.0, MAX_IMAGE_SIZE as f64) as u32)
        }
        Some(a) => {
            let m = format!("{a} must be positive");
            return Err(err(format!("{at}.perspective.aspectRatio"), m));
        }
    };
    // The camera looks along its local −z with +y up, placed by the node's world matrix.
    let from = c.world.transform_point3(Vec3::ZERO).as_dvec3();
    let forward = c.world.transform_vector3(Vec3::NEG_Z).as_dvec3();
    let up = c.world.transform_vector3(Vec3::Y).as_dvec3();
    let degenerate = !(forward.is_finite() && up.is_finite())
        || forward.length() == 0.0
        || forward.normalize().cross(up.normalize_or_zero()).length() < 1e-6;
    if degenerate {
        let m = format!(
            "the transform of the node of {at} flattens the camera's view direction or its up \
             vector"
        );
        return Err(err(format!("nodes[{}]", c.node), m));
    }
    let to = from + forward.normalize() * radius;
    Ok(Some(json!({
        "from": from.to_array(), "to": to.to_array(), "up": up.to_array(),
        "vfov_deg": vfov_deg, "width": width, "height": height,
    })))
}

#[cfg(test)]
#[path = "model_tests.rs"]
mod tests;
