//! `mesh_attribute` textures in the scene format: binding to the meshes that carry them, the
//! located errors, and the value a hit reads through the built scene (vertex attributes
//! interpolated, face attributes per face past a dropped degenerate face).

use crate::geometry::Ray;
use crate::materials::Material;
use crate::scene::Scene;
use crate::scene::parse::parse_scene_value_in;
use crate::textures::Texture;
use glam::{Vec2, Vec3};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// This test's own scratch folder (tests run in parallel).
fn folder(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "lumis-parse-mesh-attribute-{}-{test}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// An ASCII PLY of a unit square in the plane z = 0 (vertices (0,0), (1,0), (1,1), (0,1)) made
/// of a degenerate face and two triangles, with `vertex_color` (r g b), `vertex_rough` and
/// `face_color` (color_0..2): vertex i's colour is `COLORS[i]`, its roughness `0.1·(i+1)`, face
/// k's colour `FACES[k]`.
fn write_square(dir: &Path) {
    let mut ply = String::from(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nproperty float r\nproperty float g\nproperty float b\n\
         property float rough_0\nelement face 3\nproperty list uchar int vertex_indices\n\
         property float color_0\nproperty float color_1\nproperty float color_2\nend_header\n",
    );
    for (i, (p, c)) in [[0, 0], [1, 0], [1, 1], [0, 1]]
        .iter()
        .zip(COLORS)
        .enumerate()
    {
        ply += &format!(
            "{} {} 0 {} {} {} {}\n",
            p[0],
            p[1],
            c[0],
            c[1],
            c[2],
            0.1 * (i + 1) as f32
        );
    }
    for (f, c) in [[0, 0, 1], [0, 1, 2], [0, 2, 3]].iter().zip(FACES) {
        ply += &format!("3 {} {} {} {} {} {}\n", f[0], f[1], f[2], c[0], c[1], c[2]);
    }
    std::fs::write(dir.join("square.ply"), ply).unwrap();
}

const COLORS: [[f32; 3]; 4] = [
    [0.1, 0.2, 0.3],
    [0.9, 0.1, 0.1],
    [0.2, 0.8, 0.4],
    [0.5, 0.5, 0.9],
];
const FACES: [[f32; 3]; 3] = [[0.3, 0.3, 0.3], [0.7, 0.2, 0.1], [0.1, 0.6, 0.9]];

/// A scene looking down -z at the square (`material` on it), with `extra` merged into the root.
fn scene(material: Value, extra: Value) -> Value {
    let mut s = json!({
        "camera": {"from": [0.5, 0.5, 3], "to": [0.5, 0.5, 0], "up": [0, 1, 0], "vfov_deg": 30,
                   "width": 8, "height": 8},
        "materials": {"m": material, "white": {"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
        "shapes": [
            {"type": "mesh", "file": "square.ply", "material": "m"},
            {"type": "quad", "corner": [-1, -1, 2], "edge_u": [2, 0, 0], "edge_v": [0, 2, 0],
             "emission": [1, 1, 1]}
        ]
    });
    if let (Some(root), Some(more)) = (s.as_object_mut(), extra.as_object()) {
        for (k, v) in more {
            root.insert(k.clone(), v.clone());
        }
    }
    s
}

fn diffuse_of(name: &str) -> Value {
    json!({"type": "diffuse", "albedo": {"type": "mesh_attribute", "name": name}})
}

#[track_caller]
fn expect_err(s: &Value, dir: &Path, path: &str, fragments: &[&str]) {
    let e = parse_scene_value_in(s, dir).unwrap_err();
    assert_eq!(e.path, path, "wrong path in: {e}");
    for f in fragments {
        assert!(e.message.contains(f), "expected {f:?} in: {e}");
    }
}

/// The albedo the built scene shades with where a ray down -z meets the square at `(x, y)`.
fn albedo_at(scene: &Scene, x: f32, y: f32) -> Vec3 {
    let hit = scene
        .accel
        .intersect(&Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z))
        .expect("the ray meets the square");
    let prim = &scene.accel.primitives()[hit.prim as usize];
    match &*scene.material_at(&hit, prim.material, false) {
        Material::Diffuse(d) => d.albedo,
        other => panic!("not a diffuse: {other:?}"),
    }
}

/// The mesh's vertex i.
fn vertex(i: usize) -> Vec3 {
    Vec3::from(COLORS[i])
}

#[test]
fn vertex_attributes_interpolate_and_face_attributes_follow_their_face() {
    let dir = folder("values");
    write_square(&dir);
    let desc = parse_scene_value_in(&scene(diffuse_of("vertex_color"), json!({})), &dir).unwrap();
    assert_eq!(desc.mesh_attributes, ["vertex_color"]);
    let Some(Texture::MeshAttribute(t)) = desc.materials[0]
        .textures
        .albedo
        .as_ref()
        .map(|t| &t.texture)
    else {
        panic!("no mesh attribute texture")
    };
    assert_eq!(t.slot, 0);
    let mean = (vertex(0) + vertex(1) + vertex(2) + vertex(3)) / 4.0;
    assert!((t.mean - mean).length() < 1e-6, "{} vs {mean}", t.mean);
    assert_eq!(t.max, Vec3::new(0.9, 0.8, 0.9));
    // The stand-in constant is the mean, and the scene format round-trips.
    let again = parse_scene_value_in(&desc.to_json(), &dir).unwrap();
    assert_eq!(again.materials, desc.materials);

    let s = Scene::from_desc(&desc).unwrap();
    // Face 1 is (0, 1, 2): at (0.75, 0.25) the barycentrics are b1 = 0.5, b2 = 0.25.
    let want = 0.25 * vertex(0) + 0.5 * vertex(1) + 0.25 * vertex(2);
    assert!((albedo_at(&s, 0.75, 0.25) - want).length() < 1e-5);
    // Face 2 is (0, 2, 3): at (0.25, 0.5), b1 = 0.25, b2 = 0.5.
    let want = 0.5 * vertex(0) + 0.25 * vertex(2) + 0.25 * vertex(3);
    assert!((albedo_at(&s, 0.25, 0.5) - want).length() < 1e-5);

    // Per face, past the degenerate face 0 (dropped from the scene with its value).
    let desc = parse_scene_value_in(&scene(diffuse_of("face_color"), json!({})), &dir).unwrap();
    let s = Scene::from_desc(&desc).unwrap();
    assert_eq!(albedo_at(&s, 0.75, 0.25), Vec3::from(FACES[1]));
    assert_eq!(albedo_at(&s, 0.25, 0.5), Vec3::from(FACES[2]));

    // A scale multiplies; a one-component attribute in a scalar slot reads its component.
    let m = json!({"type": "conductor", "reflectance": [0.9, 0.9, 0.9],
                   "alpha": {"type": "mesh_attribute", "name": "vertex_rough", "scale": 0.5}});
    let desc = parse_scene_value_in(&scene(m, json!({})), &dir).unwrap();
    let s = Scene::from_desc(&desc).unwrap();
    let hit = s
        .accel
        .intersect(&Ray::new(Vec3::new(0.75, 0.25, 1.0), -Vec3::Z))
        .unwrap();
    let prim = &s.accel.primitives()[hit.prim as usize];
    let Material::Conductor(c) = &*s.material_at(&hit, prim.material, false) else {
        panic!("not a conductor")
    };
    let want = 0.5 * (0.25 * 0.1 + 0.5 * 0.2 + 0.25 * 0.3);
    assert!(
        (c.microfacet.alpha_u - want).abs() < 1e-6,
        "{}",
        c.microfacet.alpha_u
    );
    assert_eq!(hit.b, Vec2::new(0.5, 0.25));
}

#[test]
fn what_cannot_be_read_is_one_located_error() {
    let dir = folder("errors");
    write_square(&dir);
    let m = |name: &str| diffuse_of(name);
    // Not an attribute's name, an attribute the mesh lacks, a shape that is not a mesh.
    expect_err(
        &scene(m("color"), json!({})),
        &dir,
        "materials.m.albedo.name",
        &["vertex_ or face_"],
    );
    expect_err(
        &scene(m("vertex_uv"), json!({})),
        &dir,
        "materials.m.albedo",
        &[
            "vertex_uv",
            "shapes[0]",
            "vertex_color, vertex_rough, face_color",
        ],
    );
    let mut on_quad = scene(m("vertex_color"), json!({}));
    on_quad["shapes"][1]["material"] = json!("m");
    on_quad["shapes"][1]
        .as_object_mut()
        .unwrap()
        .remove("emission");
    expect_err(
        &on_quad,
        &dir,
        "materials.m.albedo",
        &["shapes[1]", "not a mesh"],
    );
    // Three components in a scalar slot; values out of the slot's range once scaled.
    let alpha = json!({"type": "conductor", "reflectance": [0.9, 0.9, 0.9],
                       "alpha": {"type": "mesh_attribute", "name": "vertex_color"}});
    expect_err(
        &scene(alpha, json!({})),
        &dir,
        "materials.m.alpha",
        &["3 components", "scalar"],
    );
    let bright = json!({"type": "diffuse",
                        "albedo": {"type": "mesh_attribute", "name": "face_color", "scale": 2}});
    expect_err(
        &scene(bright, json!({})),
        &dir,
        "materials.m.albedo",
        &["kept triangle 0", "outside [0, 1]"],
    );
    let nan = json!({"type": "diffuse",
                     "albedo": {"type": "mesh_attribute", "name": "face_color", "scale": 1e99}});
    expect_err(
        &scene(nan, json!({})),
        &dir,
        "materials.m.albedo.scale",
        &["single precision"],
    );
    // A bump map has no gradient of it; a spot light has no mesh.
    let bump = json!({"type": "diffuse", "albedo": [0.5, 0.5, 0.5],
                      "bump_map": {"texture": {"type": "mesh_attribute", "name": "vertex_rough"}}});
    expect_err(
        &scene(bump, json!({})),
        &dir,
        "materials.m.bump_map.texture.type",
        &["gradient"],
    );
    let spot = json!({"lights": [{"type": "spot", "from": [0, 2, 0], "to": [0, 0, 0],
        "up": [0, 0, 1], "intensity": [1, 1, 1], "cutoff_angle_deg": 40, "texture": {"type": "mesh_attribute", "name": "vertex_color"}}]});
    expect_err(
        &scene(m("vertex_color"), spot),
        &dir,
        "lights[0].texture",
        &["needs a mesh"],
    );
}
