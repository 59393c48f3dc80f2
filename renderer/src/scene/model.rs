//! A model file opened on its own (`lumis render bunny.ply`): the mesh becomes a scene with a
//! camera on the model's front, lit so that its shape shows (`model_studio.rs`: the studio, and
//! the rule by which the file's own emitters may light it instead). A PLY file gets one diffuse
//! material, an OBJ file its `.mtl` materials (`mesh/obj_materials.rs`), a glTF file its
//! materials, emission and camera (`model_gltf.rs`).
//! Everything then goes through the JSON front end, so the model gets exactly the checks of a
//! scene file: meshes and images already in memory (a glTF file's primitives and images, the
//! studio's map) are handed to it under names such as `model.glb#nodes[0]
//! meshes[0].primitives[1]`, `model.glb#images[2]` and `model.glb#studio.exr`.
//!
//! **Conventions** (every format): +y is up and the model's front faces +z (glTF's rule; OBJ
//! and PLY files follow it by the same convention, as most exporters write them).

use super::desc::{BackgroundDesc, SceneDesc};
use super::error::SceneError;
use super::mesh::MESH_EXTENSIONS;
use super::mesh::obj_materials::load_obj_model;
use super::model_studio as studio;
use super::parse::parse_scene_value_preloaded;
use super::parse_texture::Preloaded;
use glam::{DVec3, Vec3};
use serde_json::{Map, Value, json};
use std::path::Path;
use std::sync::Arc;

/// Vertical field of view of the automatic camera, degrees.
const VFOV_DEG: f64 = 40.0;
/// Image size of a model scene (a glTF camera's aspect ratio keeps the width).
pub(super) const SIZE: (u32, u32) = (640, 480);
/// Albedo of the default material.
const ALBEDO: f64 = 0.8;
/// The default material's name (an OBJ's `.mtl` materials are `mtl NAME`).
const DEFAULT_MATERIAL: &str = "model";
/// Radiance of the environment without the studio.
const ENVIRONMENT: f64 = 1.0;
/// The automatic camera's elevation above the bounding box's centre, degrees.
const ELEVATION_DEG: f64 = 20.0;

/// How a model opened on its own is shown.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModelOptions {
    /// The studio (ground and studio map, `model_studio.rs`); off, a white environment of
    /// radiance 1 (`--no-studio`).
    pub studio: bool,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions { studio: true }
    }
}

/// Whether `path` names a mesh file rather than a JSON scene (by extension).
pub fn is_model_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MESH_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

/// The scene of a model file with the default options (the studio).
pub fn model_scene(path: &Path) -> Result<SceneDesc, SceneError> {
    model_scene_with(path, ModelOptions::default())
}

/// The scene of a model file. PLY: the mesh (diffuse, albedo 0.8, its vertex normals as shading
/// normals where it has them); OBJ: a mesh per `.mtl` material it uses (docs/scene-format.md,
/// "OBJ materials"); either seen by the automatic camera, lit as `options` and the rule in
/// `model_studio.rs` say. glTF: as docs/scene-format.md, "glTF materials", says.
pub fn model_scene_with(path: &Path, options: ModelOptions) -> Result<SceneDesc, SceneError> {
    let file = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| SceneError::new("", "the model file has no name").in_file(path))?;
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let model = if matches!(ext.to_ascii_lowercase().as_str(), "gltf" | "glb") {
        super::model_gltf::gltf_model(path, file)?
    } else {
        mesh_model(path, file)?
    };
    finish(path, file, model, options)
}

/// A model's own content, before it is lit: what each format's reader makes of its file.
pub(super) struct ModelParts {
    /// The camera (scene-format JSON).
    pub camera: Value,
    /// Materials by name.
    pub materials: Map<String, Value>,
    /// `mesh` shapes, each naming its file as `file` or `file#part` (a preloaded mesh).
    pub shapes: Vec<Value>,
    /// Meshes and images in memory.
    pub preloaded: Preloaded,
    /// The model's bounding box.
    pub bounds: (DVec3, DVec3),
    /// Warnings, without the file's name (whoever prints them names it once).
    pub warnings: Vec<String>,
    /// The `lights` (a glTF file's `KHR_lights_punctual`).
    pub lights: Vec<Value>,
}

/// An OBJ or PLY file's parts: one diffuse mesh (an OBJ: a mesh per `.mtl` material,
/// `mesh/obj_materials.rs`), the automatic camera.
fn mesh_model(path: &Path, file: &str) -> Result<ModelParts, SceneError> {
    let is_obj = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("obj"));
    let (groups, obj_materials, warnings) = if is_obj {
        let m = load_obj_model(path).map_err(|e| SceneError::new("", e.to_string()))?;
        let groups = m.groups.into_iter().map(|g| (g.mesh, g.material)).collect();
        (groups, m.materials, m.warnings)
    } else {
        let data = super::mesh::load_mesh(path).map_err(|e| SceneError::new("", e.to_string()))?;
        (vec![(data, None)], Vec::new(), Vec::new())
    };
    if groups.iter().all(|(mesh, _)| mesh.indices.is_empty()) {
        return Err(SceneError::new("", "the model has no triangles").in_file(path));
    }
    let all = || groups.iter().flat_map(|(m, _)| m.positions.iter().copied());
    let bounds = bounds(all());
    let camera = auto_camera(path, bounds, &mut all())?;
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut preloaded = Preloaded::default();
    let mut materials = Map::new();
    let mut shapes = Vec::new();
    let single = groups.len() == 1 && groups[0].1.is_none();
    for (mesh, material) in groups {
        let (part, key, emission) = match material {
            None => {
                let default = json!({"type": "diffuse", "albedo": [ALBEDO, ALBEDO, ALBEDO]});
                materials.insert(DEFAULT_MATERIAL.into(), default);
                ("no material".to_owned(), DEFAULT_MATERIAL.to_owned(), None)
            }
            Some(k) => {
                let m = &obj_materials[k];
                let key = format!("mtl {}", m.name);
                materials.insert(key.clone(), m.json.clone());
                (format!("usemtl {}", m.name), key, m.emission)
            }
        };
        // One mesh without materials keeps the file's own name (warnings say nothing more).
        let name = match single {
            true => file.to_owned(),
            false => format!("{file}#{part}"),
        };
        let mut shape = json!({"type": "mesh", "file": name, "material": key});
        if let Some(e) = emission {
            shape["emission"] = json!(e);
        }
        preloaded.meshes.insert(folder.join(&name), mesh);
        shapes.push(shape);
    }
    Ok(ModelParts {
        camera,
        materials,
        shapes,
        preloaded,
        bounds,
        warnings,
        lights: Vec::new(),
    })
}

/// The model's scene: its parts, lit (the studio or the white environment, unless its emitters
/// carry most of the power: `model_studio.rs`), through the JSON front end.
fn finish(
    path: &Path,
    file: &str,
    parts: ModelParts,
    options: ModelOptions,
) -> Result<SceneDesc, SceneError> {
    let ModelParts {
        camera,
        mut materials,
        mut shapes,
        mut preloaded,
        bounds: (lo, hi),
        warnings,
        lights,
    } = parts;
    let folder = path.parent().unwrap_or(Path::new(""));
    let model_shapes: Vec<String> = shapes
        .iter()
        .map(|s| s["file"].as_str().unwrap_or_default().to_owned())
        .collect();
    let (background, mean) = if options.studio {
        let (ground, ground_material) = studio::ground(lo, hi);
        // No model material has this name: glTF's are `materials[k] …` or `default material…`,
        // an OBJ's `mtl …` or `model`, a PLY's `model`.
        let replaced = materials.insert(studio::GROUND_MATERIAL.into(), ground_material);
        debug_assert!(replaced.is_none(), "a model material named like the ground");
        shapes.push(ground);
        let map = studio::studio_map();
        let mean = studio::mean_luminance(&map);
        let name = format!("{file}#studio.exr");
        preloaded
            .images
            .insert((folder.join(&name), true), Arc::new(map));
        (json!({ "envmap": name }), mean)
    } else {
        (json!([ENVIRONMENT, ENVIRONMENT, ENVIRONMENT]), ENVIRONMENT)
    };
    let scene = json!({
        "comment": format!("the model {file} on its own (scene/model.rs)"),
        "camera": camera,
        "background": background,
        "materials": materials,
        "shapes": shapes,
        "lights": lights,
    });
    let mut desc =
        parse_scene_value_preloaded(&scene, folder, preloaded).map_err(|e| e.in_file(path))?;
    if studio::emitted_flux(&desc, lo, hi) > studio::environment_flux(mean, lo, hi) {
        desc.background = BackgroundDesc::Constant(DVec3::ZERO);
    }
    // The front end's warnings name the generated scene's JSON paths and the file again; the
    // user knows neither: keep the part of the model they are about (a glTF primitive).
    for w in &mut desc.warnings {
        for (i, name) in model_shapes.iter().enumerate() {
            let prefix = format!("shapes[{i}].file: {}: ", folder.join(name).display());
            if let Some(rest) = w.strip_prefix(&prefix) {
                *w = match name.split_once('#') {
                    Some((_, part)) => format!("{part}: {rest}"),
                    None => rest.to_owned(),
                };
                break;
            }
        }
    }
    desc.warnings.extend(warnings);
    Ok(desc)
}

/// The automatic camera of a model with this bounding box and these vertices: on the front side
/// (+z), 20° above the box's centre, looking at it, at the least distance where every vertex
/// falls inside the middle 90% of the 40° (vertical) field of view of the 640 × 480 image, and
/// in front of the camera (a tight fit: the bounding sphere, or the box's corners, leave long
/// and sparse models small in the frame).
pub(super) fn auto_camera(
    path: &Path,
    (lo, hi): (DVec3, DVec3),
    vertices: &mut dyn Iterator<Item = Vec3>,
) -> Result<Value, SceneError> {
    if !lo.is_finite() || !hi.is_finite() {
        return Err(SceneError::new("", "the model has no triangles").in_file(path));
    }
    let centre = 0.5 * (lo + hi);
    let radius = (0.5 * (hi - lo).length()).max(1e-6);
    let elevation = ELEVATION_DEG.to_radians();
    let back = DVec3::new(0.0, elevation.sin(), elevation.cos());
    let right = DVec3::Y.cross(back).normalize();
    let up = back.cross(right);
    let tan_y = 0.9 * (0.5 * VFOV_DEG.to_radians()).tan();
    let tan_x = tan_y * SIZE.0 as f64 / SIZE.1 as f64;
    let mut distance = 1e-3 * radius;
    for v in vertices {
        let offset = v.as_dvec3() - centre;
        // Its depth in front of a camera at `centre + distance·back` is `distance − toward`.
        let toward = offset.dot(back);
        let fit_x = offset.dot(right).abs() / tan_x + toward;
        let fit_y = offset.dot(up).abs() / tan_y + toward;
        distance = distance.max(fit_x).max(fit_y).max(toward + 1e-3 * radius);
    }
    let from = centre + distance * back;
    Ok(json!({
        "from": from.to_array(), "to": centre.to_array(), "up": [0, 1, 0],
        "vfov_deg": VFOV_DEG, "width": SIZE.0, "height": SIZE.1,
    }))
}

/// The bounding box of `positions` (infinite when empty).
pub(super) fn bounds(positions: impl IntoIterator<Item = Vec3>) -> (DVec3, DVec3) {
    let (lo, hi) = positions
        .into_iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), p| {
            (a.min(p), b.max(p))
        });
    (lo.as_dvec3(), hi.as_dvec3())
}

#[cfg(test)]
#[path = "model_tests.rs"]
mod tests;
