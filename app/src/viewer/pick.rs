//! Clicking an object: a camera ray through the pixel, the scene's closest hit, and from the hit
//! primitive back to the description's material and emitting shape.

use lumis::geometry::primitive::NONE;
use lumis::scene::{GeometryDesc, Scene, SceneDesc};

/// What a click hit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Picked {
    /// Index into [`SceneDesc::materials`] (`None`: a shape without material).
    pub material: Option<usize>,
    /// Index into [`SceneDesc::shapes`] when the hit shape emits.
    pub light_shape: Option<usize>,
}

/// For each light of a scene built from `desc`, the shape it came from. Mirrors the order in
/// which `Scene::from_desc` creates lights: one per emitting shape, one per triangle of an
/// emitting mesh and one per face of an emitting box; the background, last, has no shape.
pub fn light_to_shape(desc: &SceneDesc) -> Vec<usize> {
    let mut out = Vec::new();
    for (i, s) in desc.shapes.iter().enumerate() {
        if !s.emission.cmpgt(glam::DVec3::ZERO).any() {
            continue;
        }
        let count = match &s.geometry {
            GeometryDesc::Triangles { indices, .. } => indices.len(),
            GeometryDesc::Box { .. } => 6,
            _ => 1,
        };
        out.extend(std::iter::repeat_n(i, count));
    }
    out
}

/// What the camera sees through film position (`x`, `y`) (pixels, y down), or `None` for the
/// background.
pub fn pick(scene: &Scene, desc: &SceneDesc, x: f32, y: f32) -> Option<Picked> {
    let hit = scene.accel.intersect(&scene.camera.ray(x, y))?;
    let prim = scene.accel.primitives()[hit.prim as usize];
    let material = (prim.material as usize) < desc.materials.len();
    let light_shape = if prim.light == NONE {
        None
    } else {
        light_to_shape(desc).get(prim.light as usize).copied()
    };
    Some(Picked {
        material: material.then_some(prim.material as usize),
        light_shape,
    })
}
