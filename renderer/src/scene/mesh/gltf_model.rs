//! A glTF file read as a scene of its own (`lumis render model.glb`, [`crate::scene::model`]):
//! each placed triangle primitive as its own mesh, with the primitive's own normals and texture
//! coordinates (so that one primitive without them does not drop them for all), the lumis
//! materials of the glTF materials they use ([`super::materials`]), and the first camera of the
//! default scene. Geometry is read exactly as [`super::load`] reads it.

use super::{
    Merged, Placement, is_surface, load_buffers, mark_geometry_buffers, no_triangles,
    parse_document, placements, read_primitive, split_glb,
};
use super::{lights, materials};
use crate::scene::mesh::{MeshData, MeshError, check};
use ::gltf::mesh::Semantic;
use glam::Mat4;
use std::path::Path;

/// A glTF file read as a scene of its own ([`crate::scene::model`]): each placed triangle
/// primitive as its own mesh (so each keeps its material and its own normals and texture
/// coordinates), the materials they use, and the first camera of the default scene.
pub struct Model {
    /// The triangle primitives of the default scene, in the order [`super::load`] merges them.
    pub primitives: Vec<ModelPrimitive>,
    /// The lumis materials of the glTF materials the primitives use.
    pub materials: materials::Materials,
    /// The first node of the default scene (depth first) that has a camera.
    pub camera: Option<CameraNode>,
    /// The `KHR_lights_punctual` lights its nodes place.
    pub lights: lights::Lights,
}

/// One placed primitive of a [`Model`].
pub struct ModelPrimitive {
    /// Where it is, for names and messages: `nodes[3] meshes[0].primitives[1]`.
    pub name: String,
    /// Its glTF material (`None`: the default material).
    pub material: Option<usize>,
    /// Its triangles, placed by the node's transform, with the primitive's own attributes.
    pub mesh: MeshData,
    /// Whether it has vertex colours (`COLOR_0`), which lumis does not apply.
    pub has_colors: bool,
}

/// A camera node: the node, its camera, and the node's world matrix.
pub struct CameraNode {
    /// The node's index.
    pub node: usize,
    /// The camera's index.
    pub camera: usize,
    /// Camera to world (the camera looks along its −z with +y up).
    pub world: Mat4,
    /// The camera's projection and its parameters.
    pub projection: CameraProjection,
}

/// A glTF camera's projection, its parameters as the file has them (unchecked).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraProjection {
    /// `perspective`.
    Perspective {
        /// `yfov`, radians.
        yfov: f32,
        /// `aspectRatio`.
        aspect: Option<f32>,
    },
    /// `orthographic`.
    Orthographic {
        /// `xmag`: half the view's width.
        xmag: f32,
        /// `ymag`: half the view's height.
        ymag: f32,
    },
}

/// Reads `path` as [`super::load`] does, as a [`Model`]: the same checks and errors, and also
/// those of the materials' textures and images
/// (`materials[2].pbrMetallicRoughness.baseColorTexture`).
pub fn load_model(path: &Path) -> Result<Model, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::at(path, "", e))?;
    let glb = bytes.starts_with(b"glTF");
    let (json_bytes, bin) = if glb {
        split_glb(path, &bytes)?
    } else {
        (&bytes[..], None)
    };
    let document = parse_document(path, json_bytes)?;
    let (placements, camera, light_nodes) = placements(path, &document)?;
    let surfaces: Vec<&Placement> = placements
        .iter()
        .filter(|p| is_surface(p.primitive.mode()))
        .collect();
    let mut used: Vec<Option<usize>> = surfaces.iter().map(|p| p.material).collect();
    used.sort_unstable();
    used.dedup();
    let mut needed = vec![false; document.buffers().len()];
    mark_geometry_buffers(&placements, &mut needed);
    materials::mark_image_buffers(&document, &used, &mut needed);
    let buffers = load_buffers(path, &document, &needed, glb, bin)?;
    let slices: Vec<&[u8]> = buffers.iter().map(|b| &b[..]).collect();

    let mut primitives = Vec::with_capacity(surfaces.len());
    for place in &surfaces {
        let mut merged = Merged::default();
        read_primitive(path, &slices, place, &mut merged)?;
        let mesh = merged.finish();
        check(path, &mesh)?;
        primitives.push(ModelPrimitive {
            name: format!(
                "nodes[{}] meshes[{}].primitives[{}]",
                place.node,
                place.mesh,
                place.primitive.index()
            ),
            material: place.material,
            mesh,
            has_colors: place.primitive.get(&Semantic::Colors(0)).is_some(),
        });
    }
    if primitives.iter().all(|p| p.mesh.indices.is_empty()) {
        let skipped = placements.len() - surfaces.len();
        return Err(no_triangles(path, placements.len(), skipped));
    }
    let materials = materials::read(path, &document, &slices, &used)?;
    let lights = lights::read(path, document.as_json(), &light_nodes)?;
    let camera = camera.map(|(node, world)| {
        let cam = document
            .nodes()
            .nth(node)
            .and_then(|n| n.camera())
            .expect("a camera node found by `placements`");
        let projection = match cam.projection() {
            ::gltf::camera::Projection::Perspective(p) => CameraProjection::Perspective {
                yfov: p.yfov(),
                aspect: p.aspect_ratio(),
            },
            ::gltf::camera::Projection::Orthographic(o) => CameraProjection::Orthographic {
                xmag: o.xmag(),
                ymag: o.ymag(),
            },
        };
        CameraNode {
            node,
            camera: cam.index(),
            world,
            projection,
        }
    });
    Ok(Model {
        primitives,
        materials,
        camera,
        lights,
    })
}
