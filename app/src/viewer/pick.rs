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
            GeometryDesc::Mesh { mesh, .. } => mesh.indices.len(),
            GeometryDesc::Box { .. } => 6,
            GeometryDesc::Quad { .. }
            | GeometryDesc::Polygon { .. }
            | GeometryDesc::Disk { .. }
            | GeometryDesc::Sphere { .. } => 1,
            // The parser refuses an emitting cylinder.
            GeometryDesc::Cylinder { .. } => 0,
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

#[cfg(test)]
mod tests {
    use super::*;
    use lumis::scene::{Scene, load_scene};

    /// `light_to_shape` has one entry per light `Scene::from_desc` makes (the background aside),
    /// for every shipped scene and for an emitting mesh file (one light per triangle).
    #[test]
    fn one_shape_per_light() {
        let dir = std::env::temp_dir().join(format!("lumis-pick-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(
            dir.join("tet.obj"),
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
        )
        .unwrap();
        let mesh_scene = dir.join("mesh.json");
        std::fs::write(
            &mesh_scene,
            r#"{"camera": {"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                "width": 4, "height": 4},
               "shapes": [{"type": "mesh", "file": "tet.obj", "emission": [1, 1, 1]},
                          {"type": "sphere", "center": [3, 0, 0], "radius": 1, "emission": [1, 1, 1]}]}"#,
        )
        .unwrap();
        let assets = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets");
        let mut paths: Vec<_> = std::fs::read_dir(&assets)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
        paths.push(mesh_scene);
        for path in paths {
            let desc = load_scene(&path).unwrap();
            let scene = Scene::from_desc(&desc).unwrap();
            let shapes = light_to_shape(&desc);
            let background = scene.background_light.is_some() as usize;
            assert_eq!(
                shapes.len() + background,
                scene.lights.len(),
                "{}",
                path.display()
            );
        }
    }
}
