//! A model file opened on its own: the OBJ/PLY defaults, the camera on the model's front, a
//! glTF file's camera, its primitives as shapes, the studio and the rule that lets a file's
//! emitters light it (issue 43).

use super::{ModelOptions, model_scene, model_scene_with};
use crate::engine::Progressive;
use crate::integrator::Settings;
use crate::scene::Scene;
use crate::scene::desc::{BackgroundDesc, GeometryDesc, MaterialDesc, ProjectionDesc, SceneDesc};
use crate::scene::mesh::gltf::test_asset::*;
use glam::DVec3;
use serde_json::json;
use std::path::Path;
use std::sync::Arc;

const NO_STUDIO: ModelOptions = ModelOptions { studio: false };

/// The model's scene without the studio.
fn plain(path: &Path) -> SceneDesc {
    model_scene_with(path, NO_STUDIO).unwrap_or_else(|e| panic!("{e}"))
}

fn close(a: DVec3, b: DVec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

#[test]
fn an_obj_file_gets_the_diffuse_default_and_the_automatic_camera() {
    let dir = Dir::new("model-obj");
    let path = dir.file("tri.obj");
    std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    let d = plain(&path);
    assert_eq!(d.materials.len(), 1);
    assert_eq!(
        d.materials[0].material,
        MaterialDesc::Diffuse {
            albedo: DVec3::splat(0.8)
        }
    );
    assert_eq!(d.background, BackgroundDesc::Constant(DVec3::ONE));
    assert!(close(d.camera.to, DVec3::new(0.5, 0.5, 0.0)));
    // On the front (+z, glTF's convention for every format), 20° up.
    let view = (d.camera.to - d.camera.from).normalize();
    let want = DVec3::new(0.0, -20f64.to_radians().sin(), -20f64.to_radians().cos());
    assert!(close(view, want), "{view}");
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

/// glTF's orthographic camera is lumis' (Mitsuba's) orthographic camera: a film of
/// `2·xmag × 2·ymag` world units, 640 pixels wide at that aspect ratio; bad values are named.
#[test]
fn an_orthographic_camera_is_orthographic_and_a_bad_one_is_named() {
    let dir = Dir::new("model-ortho");
    let a = with_camera(json!({"type": "orthographic",
        "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 10}}));
    let d = model_scene(&a.write_glb(&dir, "o.glb")).unwrap();
    assert_eq!(
        d.camera.projection,
        ProjectionDesc::Orthographic {
            view_size: [4.0, 2.0]
        }
    );
    assert_eq!((d.camera.width, d.camera.height), (640, 320));
    assert!(close(d.camera.from, DVec3::new(1.0, 2.0, 3.0)));
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let a = with_camera(json!({"type": "orthographic",
        "orthographic": {"xmag": 0, "ymag": 1, "znear": 0.1, "zfar": 10}}));
    let e = model_scene(&a.write_glb(&dir, "o0.glb")).unwrap_err();
    assert_eq!(e.path, "cameras[0].orthographic.xmag", "{e}");
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
    let d = plain(&path);
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

/// The studio: a grey ground just under the model facing up, its own material, and the studio
/// map as the environment, handed over in memory under the model's name.
#[test]
fn the_studio_adds_a_ground_under_the_model_and_its_map() {
    let dir = Dir::new("model-studio");
    let path = dir.file("tri.obj");
    std::fs::write(&path, "v 0 1 0\nv 1 1 0\nv 0 2 1\nf 1 2 3\n").unwrap();
    let d = model_scene(&path).unwrap();
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    let ground = d.shapes.last().unwrap();
    let GeometryDesc::Quad {
        corner,
        edge_u,
        edge_v,
    } = ground.geometry
    else {
        panic!("{:?}", ground.geometry)
    };
    assert!(
        corner.y < 1.0 && corner.y > 0.99,
        "just under y = 1: {corner}"
    );
    assert!(edge_u.cross(edge_v).normalize().y > 0.999, "facing up");
    let material = &d.materials[ground.material.unwrap()];
    assert_eq!(material.name, super::studio::GROUND_MATERIAL);
    let BackgroundDesc::Envmap(env) = &d.background else {
        panic!("{:?}", d.background)
    };
    assert!(env.file.ends_with("tri.obj#studio.exr"), "{:?}", env.file);
    assert_eq!(*env.image, super::studio::studio_map());
    Scene::from_desc(&d).unwrap();
}

/// The file's name is printed once, by whoever prints the warning: a model's warnings name
/// neither the file nor the generated scene's JSON paths.
#[test]
fn a_models_warnings_do_not_repeat_its_name() {
    let dir = Dir::new("model-warning");
    let path = dir.file("sliver.obj");
    std::fs::write(
        &path,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n",
    )
    .unwrap();
    let d = model_scene(&path).unwrap();
    assert_eq!(d.warnings, ["dropped 1 zero-area triangle(s): 1"]);
}

/// A glTF asset of quads, each `(corners, material)`, with `materials`.
fn quads_asset(quads: &[([[f32; 3]; 4], usize)], materials: serde_json::Value) -> Asset {
    let mut a = Asset::default();
    let mut primitives = Vec::new();
    for (corners, material) in quads {
        let pos = a.vec3(corners);
        let idx = a.indices(&QUAD_TRIS, U16);
        let mut p = primitive(pos, None, None, Some(idx));
        p["material"] = json!(material);
        primitives.push(p);
    }
    let mesh = a.mesh(primitives);
    a.node(json!({ "mesh": mesh }));
    a.root.insert("materials".into(), materials);
    a
}

/// The grey two-sided material of the test assets, and an emitter of `strength`.
fn materials(strength: f64) -> serde_json::Value {
    json!([
        {"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
            "roughnessFactor": 1}, "doubleSided": true},
        {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
            "emissiveFactor": [1, 1, 1],
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}},
    ])
}

/// The camera sees a model's front: of two walls, one at z = +½ (material 0) and one at
/// z = −½ (material 1), the automatic camera's central ray meets the front one (it looked from
/// −z, and met the back one, before issue 43).
#[test]
fn the_automatic_camera_sees_the_front() {
    let dir = Dir::new("model-front");
    let wall = |z: f32| {
        [
            [-1.0, -1.0, z],
            [1.0, -1.0, z],
            [1.0, 1.0, z],
            [-1.0, 1.0, z],
        ]
    };
    let a = quads_asset(&[(wall(0.5), 0), (wall(-0.5), 1)], materials(0.5));
    let d = model_scene(&a.write_glb(&dir, "walls.glb")).unwrap();
    let scene = Scene::from_desc(&d).unwrap();
    let ray = scene.camera.ray(320.0, 240.0);
    let hit = scene
        .intersect(&ray)
        .expect("the centre ray meets the model");
    assert!((hit.p.z - 0.5).abs() < 1e-4, "met {:?}", hit.p);
}

/// A box of five walls, open towards +z, with a light under its ceiling (`strength`).
fn open_box(strength: f64) -> Asset {
    let (l, h) = (-0.5f32, 0.5f32);
    let walls = [
        [[l, l, l], [h, l, l], [h, h, l], [l, h, l]], // back (z = −½)
        [[l, l, l], [l, l, h], [l, h, h], [l, h, l]], // left
        [[h, l, l], [h, h, l], [h, h, h], [h, l, h]], // right
        [[l, l, l], [h, l, l], [h, l, h], [l, l, h]], // floor
        [[l, h, l], [l, h, h], [h, h, h], [h, h, l]], // ceiling
    ];
    // Facing down: (e1 × e2).y < 0 for these corners.
    let light = [
        [-0.2, 0.45, -0.2],
        [0.2, 0.45, -0.2],
        [0.2, 0.45, 0.2],
        [-0.2, 0.45, 0.2],
    ];
    let mut quads: Vec<_> = walls.iter().map(|w| (*w, 0)).collect();
    quads.push((light, 1));
    quads_asset(&quads, materials(strength))
}

/// The mean of the film's `r × r` central pixels (luminance).
fn centre_mean(p: &Progressive, r: u32) -> f32 {
    let f = p.film();
    let mean = f.mean();
    let (cx, cy) = (f.width / 2, f.height / 2);
    let mut sum = 0.0;
    for y in cy - r / 2..cy + r / 2 {
        for x in cx - r / 2..cx + r / 2 {
            sum += crate::math::luminance(mean[(y * f.width + x) as usize]);
        }
    }
    sum / (r * r) as f32
}

/// Renders `d` at `w × h`, `spp` samples, on the CPU.
fn render_small(mut d: SceneDesc, w: u32, h: u32, spp: u32) -> Progressive {
    (d.camera.width, d.camera.height) = (w, h);
    let scene = Arc::new(Scene::from_desc(&d).unwrap());
    let mut p = Progressive::new(scene, Settings::default(), 1);
    assert!(p.render_pass(spp));
    assert_eq!(p.film().nonfinite, 0);
    p
}

/// A box open to the front with a bright light inside (a Cornell box as Blender exports it):
/// its emitters carry most of the power, so there is no environment, and the camera on the
/// front shows the lit inside. Before issue 43 the camera looked from −z, at the outside of the
/// back wall, black without an environment (the centre's mean was 0). With the studio and
/// without.
#[test]
fn a_box_open_to_the_front_with_a_light_inside_shows_its_inside() {
    let dir = Dir::new("model-box");
    let path = open_box(60.0).write_glb(&dir, "box.glb");
    for options in [ModelOptions::default(), NO_STUDIO] {
        let d = model_scene_with(&path, options).unwrap();
        assert_eq!(
            d.background,
            BackgroundDesc::Constant(DVec3::ZERO),
            "{options:?}"
        );
        let scene = Scene::from_desc(&d).unwrap();
        let hit = scene.intersect(&scene.camera.ray(320.0, 240.0)).unwrap();
        assert!((hit.p.z + 0.5).abs() < 1e-4, "the back wall: {:?}", hit.p);
        let p = render_small(d, 32, 24, 16);
        let centre = centre_mean(&p, 6);
        // The inner back wall (albedo 0.8) under the light: irradiance of order L·A/d² = 60 ·
        // 0.16 / 0.5 ≈ 19, radiance ≈ 0.8 · 19/π ≈ 5; far above 0.1 whatever the geometry's
        // cosines.
        assert!(centre > 0.1, "{options:?}: {centre}");
    }
}

/// An emissive label (small, as bright as the sky) keeps the environment; the same label a
/// thousand times brighter outweighs it and the scene is lit by the label alone. The
/// threshold is the rule's: emitted flux against the environment's into the bounding box.
#[test]
fn an_emissive_label_keeps_the_sky_and_a_lamp_does_not() {
    let dir = Dir::new("model-label");
    let body = [
        [-0.5, -0.5, 0.0],
        [0.5, -0.5, 0.0],
        [0.5, 0.5, 0.0],
        [-0.5, 0.5, 0.0],
    ];
    let label = [
        [-0.1, -0.05, 0.01],
        [0.1, -0.05, 0.01],
        [0.1, 0.05, 0.01],
        [-0.1, 0.05, 0.01],
    ];
    for (strength, lit_by_its_label) in [(1.0, false), (1000.0, true)] {
        let a = quads_asset(&[(body, 0), (label, 1)], materials(strength));
        let path = a.write_glb(&dir, &format!("label{strength}.glb"));
        for options in [ModelOptions::default(), NO_STUDIO] {
            let d = model_scene_with(&path, options).unwrap();
            let black = d.background == BackgroundDesc::Constant(DVec3::ZERO);
            assert_eq!(black, lit_by_its_label, "strength {strength}, {options:?}");
        }
    }
}

/// An OBJ file with a `.mtl`: a shape per material used (named `mtl NAME`), faces without one
/// on the default material, `Ke` as the shape's emission, the `.mtl`'s warnings kept.
#[test]
fn an_obj_file_gets_its_mtl_materials_one_shape_each() {
    let dir = Dir::new("model-mtl");
    let path = dir.file("two.obj");
    std::fs::write(
        &path,
        "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n\
         usemtl Red\nf 1 2 3\nusemtl Lamp\nf 1 3 4\nusemtl Nowhere\nf 1 2 5\n",
    )
    .unwrap();
    std::fs::write(
        dir.file("two.mtl"),
        "newmtl Red\nKd 0.8 0.1 0.1\nnewmtl Lamp\nKd 0 0 0\nKe 2 2 2\n",
    )
    .unwrap();
    let d = plain(&path);
    let names: Vec<&str> = d
        .shapes
        .iter()
        .map(|s| d.materials[s.material.unwrap()].name.as_str())
        .collect();
    assert_eq!(names, ["mtl Red", "mtl Lamp", "model"]);
    assert_eq!(
        d.materials[d.shapes[0].material.unwrap()].material,
        MaterialDesc::Diffuse {
            albedo: DVec3::new(0.8, 0.1, 0.1)
        }
    );
    assert_eq!(d.shapes[1].emission, DVec3::splat(2.0));
    assert_eq!(d.shapes[0].emission, DVec3::ZERO);
    assert_eq!(d.warnings.len(), 1, "{:?}", d.warnings);
    assert!(d.warnings[0].contains("'Nowhere'"), "{:?}", d.warnings);
    Scene::from_desc(&d).unwrap();
}
