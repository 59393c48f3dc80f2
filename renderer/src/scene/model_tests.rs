//! A model file opened on its own: the OBJ/PLY defaults, a glTF file's camera, and its
//! primitives as shapes.

use super::model_scene;
use crate::scene::Scene;
use crate::scene::desc::{BackgroundDesc, GeometryDesc, MaterialDesc};
use crate::scene::mesh::gltf::test_asset::*;
use glam::DVec3;
use serde_json::json;

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

#[test]
fn an_obj_file_gets_the_diffuse_default_and_the_automatic_camera() {
    let dir = Dir::new("model-obj");
    let path = dir.file("tri.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let d = model_scene(&path).unwrap();
    assert_eq!(d.materials.len(), 1);
    assert_eq!(
        d.materials[0].material,
        MaterialDesc::Diffuse {
            albedo: DVec3::splat(0.8)
        }
    );
    assert_eq!(d.background, BackgroundDesc::Constant(DVec3::ONE));
    assert!(close(d.camera.to, DVec3::new(0.5, 0.5, 0.0)));
    assert_eq!(
        (
            d.camera.width,
            d.camera.height,
            d.camera.vfov_deg().unwrap()
        ),
        (640, 480, 40.0)
    );
}

/// A quad, and a camera node: translated to (1, 2, 3), turned 90° about +y (so it looks along
/// −x), with `camera`.
fn with_camera(camera: serde_json::Value) -> Asset {
    let mut a = quad(U16);
    let s = std::f32::consts::FRAC_1_SQRT_2;
    a.node(json!({"camera": 0, "translation": [1, 2, 3], "rotation": [0, s, 0, s]}));
    a.root.insert("cameras".into(), json!([camera]));
    a
}

#[test]
fn the_first_perspective_camera_is_used() {
    let dir = Dir::new("model-camera");
    let a = with_camera(json!({"type": "perspective",
        "perspective": {"yfov": 0.5, "aspectRatio": 2.0, "znear": 0.1}}));
    let d = model_scene(&a.write_glb(&dir, "c.glb")).unwrap();
    let c = &d.camera;
    assert!(close(c.from, DVec3::new(1.0, 2.0, 3.0)), "{:?}", c.from);
    let forward = (c.to - c.from).normalize();
    assert!(
        close(forward, DVec3::NEG_X),
        "looks along its −z, turned: {forward:?}"
    );
    assert!(close(c.up.normalize(), DVec3::Y));
    assert!((c.vfov_deg().unwrap() - (0.5f32 as f64).to_degrees()).abs() < 1e-9);
    assert_eq!(
        (c.width, c.height),
        (640, 320),
        "aspect ratio 2 at 640 pixels wide"
    );
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);

    let a = with_camera(json!({"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}}));
    let d = model_scene(&a.write_glb(&dir, "c2.glb")).unwrap();
    assert_eq!(
        (d.camera.width, d.camera.height),
        (640, 480),
        "no aspect ratio: the default"
    );

    // Depth first in the default scene's order: the camera on node 2, listed first, wins.
    let mut a =
        with_camera(json!({"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}}));
    a.node(json!({"camera": 1, "translation": [0, 0, 9]}));
    a.root.insert(
        "cameras".into(),
        json!([{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}},
               {"type": "perspective", "perspective": {"yfov": 0.25, "znear": 0.1}}]),
    );
    a.scenes = Some(json!([{"nodes": [0, 2, 1]}]));
    let d = model_scene(&a.write_glb(&dir, "c3.glb")).unwrap();
    assert!(close(d.camera.from, DVec3::new(0.0, 0.0, 9.0)));
    assert!((d.camera.vfov_deg().unwrap() - (0.25f32 as f64).to_degrees()).abs() < 1e-9);
}

#[test]
fn an_orthographic_camera_warns_and_a_bad_one_is_named() {
    let dir = Dir::new("model-ortho");
    let auto = model_scene(&quad(U16).write_glb(&dir, "plain.glb"))
        .unwrap()
        .camera;
    let a = with_camera(json!({"type": "orthographic",
        "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}));
    let d = model_scene(&a.write_glb(&dir, "o.glb")).unwrap();
    assert_eq!(d.camera, auto, "the automatic camera");
    assert_eq!(d.warnings.len(), 1);
    assert!(
        d.warnings[0].contains("cameras[0] (on nodes[1]) is orthographic"),
        "{:?}",
        d.warnings
    );
    let a = with_camera(json!({"type": "perspective", "perspective": {"yfov": 4.0, "znear": 0.1}}));
    let e = model_scene(&a.write_glb(&dir, "bad.glb")).unwrap_err();
    assert_eq!(e.path, "cameras[0].perspective.yfov");
    assert!(e.to_string().contains("bad.glb"), "{e}");
    let mut a =
        with_camera(json!({"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.1}}));
    a.nodes[1]["scale"] = json!([1, 0, 0]);
    let e = model_scene(&a.write_glb(&dir, "flat.glb")).unwrap_err();
    assert_eq!(e.path, "nodes[1]", "{e}");
}

/// Each placed primitive is one `mesh` shape with its own attributes: a primitive without
/// normals does not take them from another (the JSON `mesh` shape, one mesh, drops them for
/// all), and the scene builds and renders from memory, not from the file.
#[test]
fn each_primitive_is_a_shape_with_its_own_attributes() {
    let dir = Dir::new("model-parts");
    let mut a = quad(U16);
    let pos = a.vec3(&QUAD.map(|p| [p[0] + 2.0, p[1], p[2]]));
    let idx = a.indices(&QUAD_TRIS, U16);
    let mesh = a.mesh(vec![primitive(pos, None, None, Some(idx))]);
    a.node(json!({ "mesh": mesh }));
    let path = a.write_glb(&dir, "two.glb");
    let d = model_scene(&path).unwrap();
    assert_eq!(d.shapes.len(), 2);
    let meshes: Vec<_> = d
        .shapes
        .iter()
        .map(|s| match &s.geometry {
            GeometryDesc::Mesh { file, mesh, .. } => (file.clone(), mesh.clone()),
            g => panic!("{g:?}"),
        })
        .collect();
    assert!(
        meshes[0]
            .0
            .ends_with("two.glb#nodes[0] meshes[0].primitives[0]")
    );
    assert!(meshes[0].1.normals.is_some() && meshes[0].1.uvs.is_some());
    assert!(meshes[1].1.normals.is_none());
    assert_eq!(meshes[1].1.positions[0], glam::Vec3::new(2.0, 0.0, 0.0));
    let merged = crate::scene::mesh::gltf::load(&path).unwrap();
    assert!(merged.normals.is_none(), "the merged mesh has none");
    std::fs::remove_file(&path).unwrap();
    let scene = Scene::from_desc(&d).unwrap();
    assert_eq!(scene.accel.primitives().len(), 4);
}
