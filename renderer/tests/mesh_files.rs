//! The `mesh` shape (issue 17) end to end: the same triangles written as an inline `triangles`
//! shape and as OBJ, ASCII PLY, binary PLY, glTF with an embedded buffer and GLB files render the
//! same image, bit for bit (same seed, every strategy), as a reflector and as an emitter, and
//! placed by `to_world`. What this catches: a reader that loses, reorders, re-winds or perturbs a
//! triangle, a wrong `to_world` (row- vs column-major, the translation), lights missing from
//! emitting meshes, and files not found next to the scene.

mod common;

use common::{STRATEGIES, render};
use glam::Vec3;
use lumis::integrator::Settings;
use lumis::scene::Scene;
use lumis::scene::mesh::gltf::bytes::{base64, glb};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// An octahedron with outward (right-hand-rule) faces; exact in f32.
fn octahedron() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let p = vec![
        Vec3::new(0.5, 0.0, 0.0),
        Vec3::new(-0.5, 0.0, 0.0),
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(0.0, 0.0, 0.5),
        Vec3::new(0.0, 0.0, -0.5),
    ];
    let (px, nx, py, ny, pz, nz) = (0, 1, 2, 3, 4, 5);
    let t = vec![
        [px, py, pz],
        [py, nx, pz],
        [nx, ny, pz],
        [ny, px, pz],
        [py, px, nz],
        [nx, py, nz],
        [ny, nx, nz],
        [px, ny, nz],
    ];
    (p, t)
}

fn scratch() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-mesh-files-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write_obj(path: &Path, p: &[Vec3], t: &[[u32; 3]]) {
    let mut s = String::from("# octahedron\n");
    for v in p {
        s += &format!("v {} {} {}\n", v.x, v.y, v.z);
    }
    for f in t {
        s += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(path, s).unwrap();
}

fn write_ply_ascii(path: &Path, p: &[Vec3], t: &[[u32; 3]]) {
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        p.len(),
        t.len()
    );
    for v in p {
        s += &format!("{} {} {}\n", v.x, v.y, v.z);
    }
    for f in t {
        s += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    std::fs::write(path, s).unwrap();
}

fn write_ply_binary(path: &Path, p: &[Vec3], t: &[[u32; 3]]) {
    let mut b = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement face {}\n\
         property list uchar uint vertex_indices\nend_header\n",
        p.len(),
        t.len()
    )
    .into_bytes();
    for v in p {
        for c in v.to_array() {
            b.extend(c.to_le_bytes());
        }
    }
    for f in t {
        b.push(3);
        for i in f {
            b.extend(i.to_le_bytes());
        }
    }
    std::fs::write(path, b).unwrap();
}

/// The buffer of a glTF file: positions (f32 × 3) then u32 indices.
fn gltf_buffer(p: &[Vec3], t: &[[u32; 3]]) -> Vec<u8> {
    let mut b = Vec::new();
    for v in p {
        for c in v.to_array() {
            b.extend(c.to_le_bytes());
        }
    }
    for f in t {
        for i in f {
            b.extend(i.to_le_bytes());
        }
    }
    b
}

/// The glTF JSON for [`gltf_buffer`]; `uri` is the buffer's URI, or none in a GLB.
fn gltf_json(p: &[Vec3], t: &[[u32; 3]], uri: Option<String>) -> String {
    let pos_len = p.len() * 12;
    let idx_len = t.len() * 12;
    let (lo, hi) = p
        .iter()
        .fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let uri = uri
        .map(|u| format!(r#""uri": "{u}", "#))
        .unwrap_or_default();
    format!(
        r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"mesh": 0}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
  "buffers": [{{{uri}"byteLength": {}}}],
  "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": {pos_len}}},
                  {{"buffer": 0, "byteOffset": {pos_len}, "byteLength": {idx_len}}}],
  "accessors": [{{"bufferView": 0, "componentType": 5126, "count": {}, "type": "VEC3",
                  "min": [{}, {}, {}], "max": [{}, {}, {}]}},
                {{"bufferView": 1, "componentType": 5125, "count": {}, "type": "SCALAR"}}]}}"#,
        pos_len + idx_len,
        p.len(),
        lo.x,
        lo.y,
        lo.z,
        hi.x,
        hi.y,
        hi.z,
        t.len() * 3
    )
}

fn write_gltf_embedded(path: &Path, p: &[Vec3], t: &[[u32; 3]]) {
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64(&gltf_buffer(p, t))
    );
    std::fs::write(path, gltf_json(p, t, Some(uri))).unwrap();
}

fn write_glb(path: &Path, p: &[Vec3], t: &[[u32; 3]]) {
    let bin = gltf_buffer(p, t);
    std::fs::write(path, glb(&gltf_json(p, t, None), Some(&bin))).unwrap();
}

/// A floor, a small quad light and the octahedron (`shape`: its JSON), saved as `name` in the
/// scratch folder; `emits` makes the octahedron a light too.
fn scene_with(name: &str, shape: &str) -> Arc<Scene> {
    let text = format!(
        r#"{{
  "camera": {{"from": [0, 1.2, -2.5], "to": [0, 0.3, 0], "up": [0, 1, 0], "vfov_deg": 45,
              "width": 24, "height": 24}},
  "max_depth": 4,
  "materials": {{"floor": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
                 "metal": {{"type": "conductor", "alpha": 0.2, "reflectance": [0.9, 0.6, 0.3]}}}},
  "shapes": [
    {{"type": "quad", "corner": [-2, 0, -2], "edge_u": [0, 0, 4], "edge_v": [4, 0, 0],
      "material": "floor"}},
    {{"type": "quad", "corner": [-0.3, 2, -0.3], "edge_u": [0.6, 0, 0], "edge_v": [0, 0, 0.6],
      "emission": [6, 6, 6]}},
    {shape}
  ]
}}"#
    );
    let path = scratch().join(name);
    std::fs::write(&path, text).unwrap();
    Arc::new(Scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

/// The inline `triangles` shape, translated by `offset` (exact in f32 for the offsets used).
fn inline(p: &[Vec3], t: &[[u32; 3]], offset: Vec3, extra: &str) -> String {
    let positions: Vec<String> = p
        .iter()
        .map(|v| {
            let w = *v + offset;
            format!("[{}, {}, {}]", w.x, w.y, w.z)
        })
        .collect();
    let indices: Vec<String> = t.iter().map(|f| format!("{f:?}")).collect();
    format!(
        r#"{{"type": "triangles", "positions": [{}], "indices": [{}], {extra}}}"#,
        positions.join(", "),
        indices.join(", ")
    )
}

fn images(scene: &Arc<Scene>) -> Vec<Vec<u32>> {
    STRATEGIES
        .into_iter()
        .enumerate()
        .map(|(s, strategy)| {
            let settings = Settings {
                strategy,
                ..Settings::default()
            };
            render(scene, settings, 8, 90 + s as u32)
                .film()
                .mean()
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect()
        })
        .collect()
}

#[test]
fn every_format_renders_the_inline_triangles_image() {
    let (p, t) = octahedron();
    let dir = scratch();
    write_obj(&dir.join("octa.obj"), &p, &t);
    write_ply_ascii(&dir.join("octa_ascii.ply"), &p, &t);
    write_ply_binary(&dir.join("octa_binary.ply"), &p, &t);
    write_gltf_embedded(&dir.join("octa.gltf"), &p, &t);
    write_glb(&dir.join("octa.glb"), &p, &t);
    let offset = Vec3::new(0.25, 0.5, 0.125);
    let to_world =
        r#""to_world": [[1, 0, 0, 0.25], [0, 1, 0, 0.5], [0, 0, 1, 0.125], [0, 0, 0, 1]]"#;
    for (material, emits) in [
        (r#""material": "metal""#, false),
        (r#""emission": [2, 1, 0.5]"#, true),
    ] {
        let reference = scene_with("inline.json", &inline(&p, &t, offset, material));
        assert_eq!(reference.lights.len(), 1 + if emits { 8 } else { 0 });
        let expected = images(&reference);
        for file in [
            "octa.obj",
            "octa_ascii.ply",
            "octa_binary.ply",
            "octa.gltf",
            "octa.glb",
        ] {
            let shape = format!(r#"{{"type": "mesh", "file": "{file}", {to_world}, {material}}}"#);
            let scene = scene_with("mesh.json", &shape);
            assert_eq!(scene.lights.len(), reference.lights.len(), "{file}");
            assert_eq!(
                scene.accel.primitives().len(),
                reference.accel.primitives().len(),
                "{file}"
            );
            assert!(
                images(&scene) == expected,
                "{file} (emits: {emits}): images differ"
            );
        }
    }
}

/// The scene keeps a mesh's vertex attributes per vertex, normals in world space (the inverse
/// transpose of `to_world`, unit length) and UVs as read; `face_normals` drops the normals; every
/// kept triangle's `attr` finds its own vertices, also after a dropped zero-area triangle.
#[test]
fn mesh_attributes_reach_the_scene_in_world_space() {
    use glam::Vec2;
    use lumis::geometry::mesh_attributes::HAS_NORMALS;
    use lumis::geometry::primitive::NONE;
    use lumis::scene::mesh::MeshData;
    let dir = scratch();
    let mesh = MeshData {
        positions: vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
        ],
        // The second triangle has zero area and is dropped.
        indices: vec![[0, 3, 4], [0, 1, 2], [1, 3, 2]],
        normals: Some(vec![
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::Z,
            Vec3::new(0.0, 1.0, 1.0),
            Vec3::Z,
            Vec3::Z,
        ]),
        uvs: Some(
            (0..5)
                .map(|i| Vec2::new(i as f32 * 0.1, 1.0 - i as f32 * 0.2))
                .collect(),
        ),
        attributes: Vec::new(),
    };
    lumis::scene::mesh::ply::write(
        &dir.join("attr.ply"),
        &mesh,
        lumis::scene::mesh::ply::Encoding::Ascii,
    )
    .unwrap();
    // Scale x by 2: a normal (nx, ny, nz) becomes (nx/2, ny, nz), normalised.
    let to_world = r#""to_world": [[2, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]"#;
    for face_normals in [false, true] {
        let shape = format!(
            r#"{{"type": "mesh", "file": "attr.ply", "face_normals": {face_normals}, {to_world}}}"#
        );
        let scene = scene_with("attr.json", &shape);
        let a = &scene.attributes;
        assert_eq!(a.has_normals(), !face_normals);
        let prims: Vec<_> = scene
            .accel
            .primitives()
            .iter()
            // The two quads come first: their corner UVs are meshes 0 and 1.
            .filter(|p| p.attr != NONE && a.triangles[p.attr as usize].mesh == 2)
            .collect();
        assert_eq!(a.meshes.len(), 3);
        assert_eq!(prims.len(), 2, "the zero-area triangle is dropped");
        for p in prims {
            let t = a.triangles[p.attr as usize];
            let m = a.meshes[t.mesh as usize];
            assert_eq!(m.flags & HAS_NORMALS != 0, !face_normals);
            let lumis::geometry::Shape::Triangle { v, .. } = p.shape else {
                unreachable!()
            };
            for (k, &i) in t.v.iter().enumerate() {
                // The vertex in the file whose world position is this corner.
                let file_p = mesh.positions[i as usize];
                assert_eq!(v[k], Vec3::new(2.0 * file_p.x + 1.0, file_p.y, file_p.z));
                assert_eq!(
                    a.uvs[(m.uv_base + i) as usize],
                    mesh.uvs.as_ref().unwrap()[i as usize]
                );
                if !face_normals {
                    let n = mesh.normals.as_ref().unwrap()[i as usize];
                    let expected = Vec3::new(n.x / 2.0, n.y, n.z).normalize();
                    let got = a.normals[(m.normal_base + i) as usize];
                    assert!((got - expected).length() < 1e-6, "{got} vs {expected}");
                }
            }
        }
    }
}
