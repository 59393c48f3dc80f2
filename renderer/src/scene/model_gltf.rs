//! A glTF file opened on its own (`scene/model.rs`): one `mesh` shape per placed primitive with
//! its material and emission (mapped by `mesh/gltf_materials.rs`), and the file's camera or the
//! automatic one.

use super::error::SceneError;
use super::mesh::gltf::model::{CameraNode, CameraProjection, Model, load_model};
use super::model::{ModelParts, SIZE, auto_camera, bounds};
use super::parse::MAX_IMAGE_SIZE;
use super::parse_texture::Preloaded;
use glam::Vec3;
use serde_json::{Value, json};
use std::path::Path;

/// The parts of the glTF file `path` (named `file`).
pub(super) fn gltf_model(path: &Path, file: &str) -> Result<ModelParts, SceneError> {
    let Model {
        primitives,
        materials,
        camera,
        lights,
    } = load_model(path).map_err(|e| SceneError::new("", e.to_string()))?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut ignored = materials.ignored;
    ignored.extend(lights.ignored);
    let mut warnings = Vec::new();
    let mut preloaded = Preloaded::default();
    let all = || {
        primitives
            .iter()
            .flat_map(|p| p.mesh.positions.iter().copied())
    };
    let (lo, hi) = bounds(all());
    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let camera = match camera {
        Some(c) => gltf_camera(path, &c, radius)?,
        None => auto_camera(path, (lo, hi), &mut all())?,
    };

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

    let mut seen = std::collections::HashSet::new();
    ignored.retain(|i| seen.insert(i.clone()));
    if !ignored.is_empty() {
        warnings.push(format!(
            "glTF features lumis does not render: {}",
            ignored.join(", ")
        ));
    }
    Ok(ModelParts {
        camera,
        materials: materials.json,
        shapes,
        preloaded,
        bounds: (lo, hi),
        warnings,
        lights: lights.json,
    })
}

/// The scene camera of a glTF camera node, placed by the node's world matrix (it looks along
/// its local −z with +y up). Perspective: `yfov`, and `aspectRatio` as 640 pixels wide (640 ×
/// 480 without one). Orthographic: a film of `2·xmag × 2·ymag` (glTF's magnifications are half
/// the view's width and height), 640 pixels wide. Clip planes are not read. `radius` (the
/// model's) places `to`.
fn gltf_camera(path: &Path, c: &CameraNode, radius: f64) -> Result<Value, SceneError> {
    let at = format!("cameras[{}]", c.camera);
    let err = |at: String, m: String| SceneError::new(at, m).in_file(path);
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
    let height_at = |aspect: f64| {
        let h = (SIZE.0 as f64 / aspect).round();
        h.clamp(1.0, MAX_IMAGE_SIZE as f64) as u32
    };
    let frame = |width: u32, height: u32| {
        json!({
            "from": from.to_array(), "to": to.to_array(), "up": up.to_array(),
            "width": width, "height": height,
        })
    };
    match c.projection {
        CameraProjection::Perspective { yfov, aspect } => {
            let vfov_deg = (yfov as f64).to_degrees();
            if !(vfov_deg > 0.0 && vfov_deg < 180.0) {
                let m = format!("{yfov} radians is outside (0, π)");
                return Err(err(format!("{at}.perspective.yfov"), m));
            }
            let (width, height) = match aspect {
                None => SIZE,
                Some(a) if a > 0.0 && a.is_finite() => (SIZE.0, height_at(a as f64)),
                Some(a) => {
                    let m = format!("{a} must be positive");
                    return Err(err(format!("{at}.perspective.aspectRatio"), m));
                }
            };
            let mut camera = frame(width, height);
            camera["vfov_deg"] = json!(vfov_deg);
            Ok(camera)
        }
        CameraProjection::Orthographic { xmag, ymag } => {
            for (key, v) in [("xmag", xmag), ("ymag", ymag)] {
                if !(v > 0.0 && v.is_finite()) {
                    let m = format!("{v} must be positive");
                    return Err(err(format!("{at}.orthographic.{key}"), m));
                }
            }
            let (w, h) = (2.0 * xmag as f64, 2.0 * ymag as f64);
            let mut camera = frame(SIZE.0, height_at(w / h));
            camera["type"] = json!("orthographic");
            camera["view_size"] = json!([w, h]);
            Ok(camera)
        }
    }
}

#[cfg(test)]
#[path = "model_gltf_tests.rs"]
mod tests;
