//! Tests of the glTF reader on small files built here (`gltf_test_asset.rs`).

use super::load;
use super::test_asset::*;
use crate::scene::mesh::MeshData;
use glam::{Vec2, Vec3};
use serde_json::json;
use std::path::Path;

/// The error of loading `path`, without the leading file name (which every message must have).
fn error(path: &Path) -> String {
    let message = load(path).expect_err("the file must be rejected").0;
    let name = path.display().to_string();
    message
        .strip_prefix(&name)
        .unwrap_or_else(|| panic!("'{message}' does not start with the file name '{name}'"))
        .to_string()
}

fn quad_mesh() -> MeshData {
    MeshData {
        positions: QUAD.iter().map(|&p| Vec3::from(p)).collect(),
        indices: vec![[0, 1, 2], [0, 2, 3]],
        normals: Some(vec![Vec3::Z; 4]),
        uvs: Some(QUAD_UV.iter().map(|&t| Vec2::from(t)).collect()),
        attributes: Vec::new(),
    }
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-5
}

/// The right-hand-rule normal of triangle `t`.
fn face_normal(m: &MeshData, t: usize) -> Vec3 {
    let [a, b, c] = m.indices[t].map(|i| m.positions[i as usize]);
    (b - a).cross(c - a).normalize()
}

#[test]
fn quad_reads_positions_normals_uvs_and_indices() {
    let dir = Dir::new("quad");
    let path = quad(U16).write_glb(&dir, "quad.glb");
    assert_eq!(load(&path).unwrap(), quad_mesh());
}

#[test]
fn external_embedded_and_glb_give_the_same_mesh() {
    let dir = Dir::new("containers");
    let a = quad(U16);
    let external = a.write_external(&dir, "ext.gltf", "my quad.bin", "my%20quad.bin");
    let octet = a.write_embedded(&dir, "octet.gltf", "application/octet-stream");
    let buffer = a.write_embedded(&dir, "buffer.gltf", "application/gltf-buffer");
    let binary = a.write_glb(&dir, "bin.glb");
    for path in [external, octet, buffer, binary] {
        assert_eq!(load(&path).unwrap(), quad_mesh(), "{}", path.display());
    }
}

#[test]
fn u8_u16_u32_indices_and_no_indices_agree() {
    let dir = Dir::new("index_types");
    for (k, component) in [U8, U16, U32].into_iter().enumerate() {
        let path = quad(component).write_glb(&dir, &format!("q{k}.glb"));
        assert_eq!(
            load(&path).unwrap(),
            quad_mesh(),
            "component type {component}"
        );
    }
    // Non-indexed: the vertices in order, three per triangle.
    let mut a = Asset::default();
    let corners: Vec<[f32; 3]> = QUAD_TRIS.iter().map(|&i| QUAD[i as usize]).collect();
    let pos = a.vec3(&corners);
    let mesh = a.mesh(vec![primitive(pos, None, None, None)]);
    a.node(json!({ "mesh": mesh }));
    let m = load(&a.write_glb(&dir, "flat.glb")).unwrap();
    assert_eq!(m.indices, vec![[0, 1, 2], [3, 4, 5]]);
    assert_eq!(m.positions.len(), 6);
    assert_eq!((m.normals, m.uvs), (None, None));
}

#[test]
fn node_hierarchy_composes_trs_and_matrix() {
    // Parent: T(1,2,3)·R(90° about z)·S(2); child: matrix T(0,0,5)·S(1,1,3) (column-major).
    let dir = Dir::new("hierarchy");
    let mut a = Asset::default();
    let pos = a.vec3(&[[1.0, 0.0, 0.0], [0.0, 1.0, 1.0], [0.0, 0.0, 0.0]]);
    // Not unit in the file: the reader renormalises.
    let nrm = a.vec3(&[[0.0, 1.0, 1.0]; 3]);
    let mesh = a.mesh(vec![primitive(pos, Some(nrm), None, None)]);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    a.node(
        json!({"translation": [1, 2, 3], "rotation": [0, 0, h, h], "scale": [2, 2, 2],
        "children": [1]}),
    );
    a.node(json!({"mesh": mesh,
        "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 3, 0,  0, 0, 5, 1]}));
    let m = load(&a.write_glb(&dir, "h.glb")).unwrap();
    // By hand: child (x, y, 3z + 5), then ×2, then (x, y) → (−y, x), then + (1, 2, 3).
    let expected = [
        Vec3::new(1.0, 4.0, 13.0),
        Vec3::new(-1.0, 2.0, 19.0),
        Vec3::new(1.0, 2.0, 13.0),
    ];
    for (got, want) in m.positions.iter().zip(expected) {
        assert!(close(*got, want), "{got} != {want}");
    }
    // Normal (0,1,1): inverse transpose of S(1,1,3) gives (0,1,1/3) ∥ (0,3,1); rotated: (−3,0,1).
    let want = Vec3::new(-3.0, 0.0, 1.0) / 10f32.sqrt();
    for n in m.normals.unwrap() {
        assert!(close(n, want), "{n} != {want}");
    }
    assert_eq!(m.indices, vec![[0, 1, 2]]);
}

#[test]
fn a_mesh_on_two_nodes_is_placed_twice() {
    let dir = Dir::new("instances");
    let mut a = quad(U16);
    a.node(json!({"mesh": 0, "translation": [0, 0, 2]}));
    let m = load(&a.write_glb(&dir, "i.glb")).unwrap();
    assert_eq!(m.positions.len(), 8);
    assert_eq!(m.indices[2..], [[4, 5, 6], [4, 6, 7]]);
    assert!(close(m.positions[6], Vec3::new(1.0, 1.0, 2.0)));
}

/// A tetrahedron around the origin, every face wound so its right-hand normal points out, with
/// per-corner normals equal to the face normals.
fn tetrahedron() -> Asset {
    let v = [
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    let faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for f in faces {
        let [a, b, c] = f.map(|i| Vec3::from_array(v[i]));
        let n = (b - a).cross(c - a).normalize();
        assert!(
            n.dot(a + b + c) > 0.0,
            "the test tetrahedron must be wound outward"
        );
        positions.extend([a, b, c].map(|p| p.to_array()));
        normals.extend([n.to_array(); 3]);
    }
    let mut a = Asset::default();
    let pos = a.vec3(&positions);
    let nrm = a.vec3(&normals);
    a.mesh(vec![primitive(pos, Some(nrm), None, None)]);
    a
}

#[test]
fn a_mirrored_node_keeps_normals_outward() {
    let dir = Dir::new("mirror");
    for (k, node) in [
        json!({"mesh": 0, "scale": [-1, 1, 1]}),
        json!({"mesh": 0, "scale": [2, -1, 3], "translation": [5, 0, 0]}),
        json!({"mesh": 0, "matrix": [1, 0, 0, 0,  0, 1, 0, 0,  0, 0, -1, 0,  0, 0, 0, 1]}),
    ]
    .into_iter()
    .enumerate()
    {
        let mut a = tetrahedron();
        a.node(node.clone());
        let m = load(&a.write_glb(&dir, &format!("m{k}.glb"))).unwrap();
        let centre = m.positions.iter().sum::<Vec3>() / m.positions.len() as f32;
        let normals = m.normals.as_ref().unwrap();
        for t in 0..m.indices.len() {
            let g = face_normal(&m, t);
            let [a, b, c] = m.indices[t].map(|i| m.positions[i as usize]);
            assert!(
                g.dot((a + b + c) / 3.0 - centre) > 0.0,
                "{node}: face {t} points in"
            );
            for i in m.indices[t] {
                let n = normals[i as usize];
                assert!(close(n, g), "{node}: vertex normal {n} != face normal {g}");
            }
        }
    }
}

#[test]
fn strips_and_fans_become_triangles() {
    let dir = Dir::new("strip");
    let mut a = Asset::default();
    let pos = a.vec3(&[
        [0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 0.0, 0.0],
    ]);
    // A strip of 4 triangles and one with a repeated vertex (a zero-area join, dropped).
    let strip = a.indices(&[0, 1, 2, 3, 4], U16);
    let joined = a.indices(&[0, 1, 2, 2, 3, 4], U16);
    let fan = a.indices(&[2, 0, 1, 3], U16);
    let mut prims = Vec::new();
    for (idx, mode) in [(strip, 5), (joined, 5), (fan, 6)] {
        let mut p = primitive(pos, None, None, Some(idx));
        p["mode"] = json!(mode);
        prims.push(p);
    }
    let mesh = a.mesh(prims);
    a.node(json!({ "mesh": mesh }));
    let m = load(&a.write_glb(&dir, "s.glb")).unwrap();
    // glTF: strip triangle i = {v_i, v_{i+1+i%2}, v_{i+2−i%2}}; fan i = {v_{i+1}, v_{i+2}, v_0}.
    let strip_tris = [[0, 1, 2], [1, 3, 2], [2, 3, 4]];
    // The join shifts the parity: its last triangle is wound the other way, as the file says.
    let joined_tris = [[0, 1, 2], [2, 4, 3]];
    let fan_tris = [[0, 1, 2], [1, 3, 2]];
    let mut want: Vec<[u32; 3]> = strip_tris.to_vec();
    want.extend(joined_tris.iter().map(|t| t.map(|i| i + 5)));
    want.extend(fan_tris.iter().map(|t| t.map(|i| i + 10)));
    assert_eq!(m.indices, want);
    // Strip and fan triangles keep the winding of their first: all face the same way.
    for t in [0, 1, 2, 3, 5, 6] {
        assert!(close(face_normal(&m, t), -Vec3::Z), "triangle {t}");
    }
    assert!(close(face_normal(&m, 4), Vec3::Z));
}

#[test]
fn normals_and_uvs_are_kept_only_when_every_primitive_has_them() {
    let dir = Dir::new("attributes");
    let mut a = Asset::default();
    let pos = a.vec3(&QUAD);
    let nrm = a.vec3(&[[0.0, 0.0, 1.0]; 4]);
    let uv = a.vec2(&QUAD_UV);
    let idx = a.indices(&QUAD_TRIS, U8);
    let mesh = a.mesh(vec![
        primitive(pos, Some(nrm), Some(uv), Some(idx)),
        primitive(pos, None, Some(uv), Some(idx)),
    ]);
    a.node(json!({ "mesh": mesh }));
    let m = load(&a.write_glb(&dir, "a.glb")).unwrap();
    assert_eq!(m.normals, None, "the second primitive has no normals");
    assert_eq!(m.uvs.as_ref().map(Vec::len), Some(8));
    assert_eq!(m.indices, vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]]);
}

#[test]
fn normalized_integer_uvs_and_sparse_positions_are_read() {
    let dir = Dir::new("sparse");
    let mut a = quad(U16);
    // TEXCOORD_0 as normalised u16 and u8.
    let t16: Vec<u8> = QUAD_UV
        .iter()
        .flatten()
        .flat_map(|&f| ((f * 65535.0) as u16).to_le_bytes())
        .collect();
    let v16 = a.view(&t16);
    let uv16 = a.accessor(
        json!({"bufferView": v16, "componentType": U16, "normalized": true,
        "type": "VEC2", "count": 4}),
    );
    // POSITION: the quad's base with element 2 replaced by (1, 2, 0) through a sparse entry.
    let iv = a.view(&2u8.to_le_bytes());
    let vv = a.view(
        &[1f32, 2.0, 0.0]
            .iter()
            .flat_map(|f| f.to_le_bytes())
            .collect::<Vec<_>>(),
    );
    let sparse = a.accessor(
        json!({"bufferView": 0, "componentType": FLOAT, "type": "VEC3",
        "count": 4, "min": [0, 0, 0], "max": [1, 2, 0],
        "sparse": {"count": 1, "indices": {"bufferView": iv, "componentType": U8},
                   "values": {"bufferView": vv}}}),
    );
    a.meshes[0]["primitives"][0]["attributes"]["TEXCOORD_0"] = json!(uv16);
    a.meshes[0]["primitives"][0]["attributes"]["POSITION"] = json!(sparse);
    let m = load(&a.write_glb(&dir, "s.glb")).unwrap();
    let mut want = quad_mesh();
    want.positions[2] = Vec3::new(1.0, 2.0, 0.0);
    assert_eq!(m, want);
}

#[test]
fn the_default_scene_decides_what_is_read() {
    let dir = Dir::new("scenes");
    let mut a = quad(U16);
    a.node(json!({"mesh": 0, "translation": [0, 0, 7]}));
    a.scenes = Some(json!([{"nodes": [0]}, {"nodes": [1]}]));
    let first = load(&a.write_glb(&dir, "none.glb")).unwrap();
    assert_eq!(first.positions[0], Vec3::ZERO, "no `scene`: scene 0");
    a.scene = Some(1);
    let second = load(&a.write_glb(&dir, "one.glb")).unwrap();
    assert_eq!(second.positions[0], Vec3::new(0.0, 0.0, 7.0), "`scene`: 1");
    a.scenes = Some(json!([]));
    a.scene = None;
    let roots = load(&a.write_glb(&dir, "roots.glb")).unwrap();
    assert_eq!(roots.positions.len(), 8, "no scenes: every root node");
}

#[test]
fn points_and_lines_are_skipped_and_alone_they_are_an_error() {
    let dir = Dir::new("lines");
    let mut a = quad(U16);
    let mut line = primitive(0, None, None, None);
    line["mode"] = json!(1);
    let mut points = primitive(0, None, None, None);
    points["mode"] = json!(0);
    a.meshes[0]["primitives"]
        .as_array_mut()
        .unwrap()
        .extend([line.clone(), points]);
    assert_eq!(load(&a.write_glb(&dir, "mixed.glb")).unwrap(), quad_mesh());
    a.meshes[0]["primitives"] = json!([line]);
    let e = error(&a.write_glb(&dir, "only.glb"));
    assert!(
        e.starts_with(
            ": no triangles in the default scene (1 primitives placed, 1 of them POINTS or LINES"
        ),
        "{e}"
    );
}

#[test]
fn position_bounds_may_be_missing_and_unused_buffers_are_not_read() {
    let dir = Dir::new("lenient");
    let mut a = quad(U16);
    let acc = a.accessors[0].as_object_mut().unwrap();
    acc.remove("min");
    acc.remove("max");
    a.root.insert(
        "buffers".into(),
        json!([{"byteLength": a.bin.len()},
        {"byteLength": 10, "uri": "animation.bin"}]),
    );
    assert_eq!(load(&a.write_glb(&dir, "l.glb")).unwrap(), quad_mesh());
}

// ---- errors -------------------------------------------------------------------------------

#[test]
fn missing_or_short_buffers_are_named() {
    let dir = Dir::new("buffers");
    let a = quad(U16);
    let path = dir.file("missing.gltf");
    std::fs::write(&path, a.json(Some("data.bin".into())).to_string()).unwrap();
    let e = error(&path);
    assert!(e.starts_with(" buffer 0: cannot read 'data.bin': "), "{e}");

    std::fs::write(dir.file("short.bin"), &a.bin[..a.bin.len() - 4]).unwrap();
    std::fs::write(&path, a.json(Some("short.bin".into())).to_string()).unwrap();
    let n = a.bin.len();
    assert_eq!(
        error(&path),
        format!(
            " buffer 0: 'short.bin' has {} bytes, fewer than its byteLength {n}",
            n - 4
        )
    );

    let glb_path = dir.file("nobin.glb");
    std::fs::write(&glb_path, glb(&a.json(None).to_string(), None)).unwrap();
    assert_eq!(
        error(&glb_path),
        " buffer 0: has no uri and the .glb has no BIN chunk"
    );

    std::fs::write(&path, a.json(None).to_string()).unwrap();
    assert!(error(&path).starts_with(" buffer 0: has no uri (only buffer 0 of a .glb"));

    std::fs::write(
        &path,
        a.json(Some("http://example.com/a.bin".into())).to_string(),
    )
    .unwrap();
    assert!(
        error(&path).contains("unsupported scheme 'http'"),
        "{}",
        error(&path)
    );

    let uri = format!("data:application/octet-stream,{}", "abc");
    std::fs::write(&path, a.json(Some(uri)).to_string()).unwrap();
    assert!(error(&path).contains("is not base64"));
    let uri = format!("data:application/octet-stream;base64,!{}", base64(&a.bin));
    std::fs::write(&path, a.json(Some(uri)).to_string()).unwrap();
    assert!(error(&path).starts_with(" buffer 0: data URI: invalid base64 character '!'"));
}

#[test]
fn out_of_range_accessors_and_views_are_named() {
    let dir = Dir::new("ranges");
    // The position accessor reads one element past its view.
    let mut a = quad(U16);
    a.accessors[0]["count"] = json!(5);
    a.accessors[1]["count"] = json!(5);
    a.accessors[2]["count"] = json!(5);
    assert_eq!(
        error(&a.write_glb(&dir, "acc.glb")),
        " accessor 0: 5 elements of 12 bytes (stride 12) from byte 0 run past the end of buffer \
         view 0 (48 bytes)"
    );
    // The view runs past the buffer.
    let mut a = quad(U16);
    let n = a.bin.len();
    a.views[3]["byteLength"] = json!(100);
    assert_eq!(
        error(&a.write_glb(&dir, "view.glb")),
        format!(
            " accessor 3: buffer view 3 (bytes 128..+100) runs past the end of buffer 0 ({n} bytes)"
        )
    );
    // A stride smaller than the element, a zero count, an offset beyond any size.
    let mut a = quad(U16);
    a.views[0]["byteStride"] = json!(8);
    assert!(
        error(&a.write_glb(&dir, "stride.glb"))
            .contains("byteStride 8 is smaller than the 12-byte element")
    );
    let mut a = quad(U16);
    a.accessors[3]["count"] = json!(0);
    assert_eq!(
        error(&a.write_glb(&dir, "zero.glb")),
        " accessor 3: count is 0"
    );
    let mut a = quad(U16);
    a.accessors[0]["byteOffset"] = json!(u64::MAX - 4);
    assert!(error(&a.write_glb(&dir, "huge.glb")).starts_with(" accessor 0: 4 elements"));
}

#[test]
fn bad_indices_and_non_finite_values_are_named() {
    let dir = Dir::new("values");
    let mut a = Asset::default();
    let pos = a.vec3(&QUAD);
    let good = a.indices(&QUAD_TRIS, U8);
    let idx = a.indices(&[0, 1, 2, 0, 2, 900], U16);
    let mesh = a.mesh(vec![
        primitive(pos, None, None, Some(good)),
        primitive(pos, None, None, Some(idx)),
    ]);
    a.node(json!({ "mesh": mesh }));
    assert_eq!(
        error(&a.write_glb(&dir, "index.glb")),
        " mesh 0 primitive 1: index 900 out of range (4 vertices)"
    );

    for (k, bad, what) in [(0, f32::NAN, "NaN"), (1, f32::INFINITY, "infinite")] {
        let mut a = Asset::default();
        let mut p = QUAD;
        p[2][1] = bad;
        let pos = a.vec3(&p);
        let mesh = a.mesh(vec![primitive(pos, None, None, None)]);
        a.node(json!({ "mesh": mesh }));
        assert_eq!(
            error(&a.write_glb(&dir, &format!("nan{k}.glb"))),
            format!(" accessor 0 element 2: position is {what}")
        );
    }
    let mut a = quad(U16);
    let bad = a.vec3(&[
        [0.0, 0.0, 1.0],
        [0.0, f32::NAN, 1.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, 1.0],
    ]);
    a.meshes[0]["primitives"][0]["attributes"]["NORMAL"] = json!(bad);
    assert_eq!(
        error(&a.write_glb(&dir, "nrm.glb")),
        format!(" accessor {bad} element 1: normal is NaN")
    );

    // Not a multiple of 3, mismatched attribute counts, a wrong component type.
    let mut a = quad(U16);
    a.accessors[3]["count"] = json!(5);
    assert_eq!(
        error(&a.write_glb(&dir, "three.glb")),
        " mesh 0 primitive 0: 5 vertices in TRIANGLES mode is not a multiple of 3"
    );
    let mut a = quad(U16);
    a.accessors[2]["count"] = json!(3);
    assert_eq!(
        error(&a.write_glb(&dir, "count.glb")),
        " mesh 0 primitive 0: TEXCOORD_0 has 3 elements but POSITION has 4"
    );
    let mut a = quad(U16);
    a.accessors[0]["componentType"] = json!(U16);
    assert!(
        error(&a.write_glb(&dir, "type.glb"))
            .starts_with(" accessor 0: POSITION must be FLOAT VEC3, found Vec3 of U16")
    );
    let mut a = quad(U16);
    a.accessors[3]["componentType"] = json!(FLOAT);
    assert!(
        error(&a.write_glb(&dir, "ftype.glb")).starts_with(" accessor 3: indices must be SCALAR")
    );
}

/// Found by `renderer/tests/mesh_mutations/`: f32::MAX is a finite position and 2 a finite scale, but
/// the placed position was infinite and loaded.
#[test]
fn a_position_that_its_transform_overflows_is_named() {
    let dir = Dir::new("overflow");
    let mut a = Asset::default();
    let mut p = QUAD;
    p[3][0] = f32::MAX;
    let pos = a.vec3(&p);
    let idx = a.indices(&QUAD_TRIS, U8);
    let mesh = a.mesh(vec![primitive(pos, None, None, Some(idx))]);
    a.node(json!({ "children": [1], "scale": [2.0, 2.0, 2.0] }));
    a.node(json!({ "mesh": mesh }));
    let e = error(&a.write_glb(&dir, "overflow.glb"));
    assert_eq!(
        e,
        " accessor 0 element 3: position overflows single precision under the transform of \
         node 1 (with its parents)"
    );
    // At the edge but not beyond: still read.
    a.nodes[0]["scale"] = json!([1.0, 1.0, 1.0]);
    let mesh = load(&a.write_glb(&dir, "edge.glb")).unwrap();
    assert_eq!(mesh.positions[3].x, f32::MAX);
}

/// Found by `renderer/tests/mesh_mutations/` (in PLY files): a message quotes the file, and a JSON
/// string may hold a newline or U+2028, which must not break the message's line.
#[test]
fn quoted_line_breaks_are_escaped() {
    let dir = Dir::new("one_line");
    let a = quad(U16);
    let path = dir.file("breaks.gltf");
    std::fs::write(
        &path,
        a.json(Some("a\nb\u{2028}c\u{b}d.bin".into())).to_string(),
    )
    .unwrap();
    let e = error(&path);
    assert!(
        e.starts_with(r" buffer 0: cannot read 'a\nb\u{2028}c\u{b}d.bin': "),
        "{e}"
    );
}

#[test]
fn bad_sparse_accessors_are_named() {
    let dir = Dir::new("bad_sparse");
    for (k, indices, want) in [
        (
            0,
            [3u8, 1],
            "sparse index 1 (entry 1) is not above the one before it",
        ),
        (
            1,
            [1u8, 9],
            "sparse index 9 (entry 1) out of range (4 elements)",
        ),
    ] {
        let mut a = quad(U16);
        let iv = a.view(&indices);
        let vv = a.view(&[0u8; 24]);
        a.accessors[0]["sparse"] = json!({"count": 2,
            "indices": {"bufferView": iv, "componentType": U8}, "values": {"bufferView": vv}});
        assert_eq!(
            error(&a.write_glb(&dir, &format!("s{k}.glb"))),
            format!(" accessor 0: {want}")
        );
    }
    let mut a = quad(U16);
    let iv = a.view(&[0u8, 1]);
    let vv = a.view(&[0u8; 12]);
    a.accessors[0]["sparse"] = json!({"count": 2,
        "indices": {"bufferView": iv, "componentType": U8}, "values": {"bufferView": vv}});
    assert!(
        error(&a.write_glb(&dir, "short.glb"))
            .starts_with(" accessor 0: sparse values: 2 elements of 12 bytes")
    );
}

#[test]
fn required_extensions_are_named() {
    let dir = Dir::new("extensions");
    for (k, names) in [
        vec!["KHR_draco_mesh_compression"],
        vec!["EXT_meshopt_compression", "KHR_mesh_quantization"],
        vec!["EXT_texture_webp"],
    ]
    .into_iter()
    .enumerate()
    {
        let mut a = quad(U16);
        a.root.insert("extensionsRequired".into(), json!(names));
        a.root.insert("extensionsUsed".into(), json!(names));
        let e = error(&a.write_glb(&dir, &format!("e{k}.glb")));
        assert!(
            e.starts_with(&format!(
                ": requires glTF extension {}, which lumis does not support",
                names.join(", ")
            )),
            "{e}"
        );
        assert_eq!(e.contains("compressed geometry"), k < 2, "{e}");
    }
}

#[test]
fn bad_glb_containers_are_named() {
    let dir = Dir::new("glb");
    let good = quad(U16);
    let bytes = glb(&good.json(None).to_string(), Some(&good.bin));
    let cases: Vec<(Vec<u8>, String)> = vec![
        (
            b"glTF\x02\0\0".to_vec(),
            " glb header: the file has 7 bytes, fewer than the 12-byte header".into(),
        ),
        (
            {
                let mut b = bytes.clone();
                b[4] = 1;
                b
            },
            " glb header: version 1 (lumis reads glTF 2.0)".into(),
        ),
        (
            bytes[..bytes.len() - 4].to_vec(),
            format!(
                " glb header: length {} but the file has {} bytes",
                bytes.len(),
                bytes.len() - 4
            ),
        ),
        (
            {
                let mut b = bytes.clone();
                b[12] = 0xff;
                b[13] = 0xff;
                b
            },
            " glb chunk 0: 65535 bytes from byte 20 run past the end of the file".into(),
        ),
        (
            {
                let mut b = bytes.clone();
                b[16..20].copy_from_slice(b"BIN\0");
                b
            },
            " glb chunk 0: type 0x004e4942, but the first must be JSON".into(),
        ),
        (
            {
                let mut b = bytes[..14].to_vec();
                b[8..12].copy_from_slice(&14u32.to_le_bytes());
                b
            },
            " glb chunk 0: truncated chunk header at byte 12 (14 bytes)".into(),
        ),
    ];
    for (k, (bytes, want)) in cases.into_iter().enumerate() {
        let path = dir.file(&format!("g{k}.glb"));
        std::fs::write(&path, bytes).unwrap();
        let e = error(&path);
        assert!(e.starts_with(&want), "case {k}: {e}");
    }
}

#[test]
fn invalid_json_and_invalid_gltf_are_named_with_their_paths() {
    let dir = Dir::new("json");
    let path = dir.file("bad.gltf");
    std::fs::write(&path, "{ \"asset\": ").unwrap();
    assert!(
        error(&path).starts_with(": invalid glTF JSON: EOF while parsing"),
        "{}",
        error(&path)
    );

    let a = quad(U16);
    let mut j = a.json(Some(format!(
        "data:application/octet-stream;base64,{}",
        base64(&a.bin)
    )));
    j["meshes"][0]["primitives"][0]["indices"] = json!(42);
    j["meshes"][0]["primitives"][0]["mode"] = json!(99);
    std::fs::write(&path, j.to_string()).unwrap();
    let e = error(&path);
    assert!(e.contains("invalid glTF: "), "{e}");
    assert!(
        e.contains("meshes[0].primitives[0].indices: Index out of bounds"),
        "{e}"
    );
    assert!(
        e.contains("meshes[0].primitives[0].mode: Invalid value"),
        "{e}"
    );

    // The `gltf` crate's own validation would index this accessor and panic.
    j["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(77);
    std::fs::write(&path, j.to_string()).unwrap();
    assert_eq!(
        error(&path),
        " mesh 0 primitive 0: POSITION accessor 77 does not exist (4 accessors)"
    );
}

#[test]
fn bad_node_hierarchies_are_named() {
    let dir = Dir::new("nodes");
    let mut a = quad(U16);
    a.node(json!({"children": [2]}));
    a.node(json!({"children": [1], "mesh": 0}));
    a.scenes = Some(json!([{"nodes": [0, 1]}]));
    assert!(error(&a.write_glb(&dir, "cycle.glb")).starts_with(" node 1: reached twice"));
    let mut a = quad(U16);
    a.nodes[0]["scale"] = json!([1e30, 1, 1]);
    a.node(json!({"children": [0], "scale": [1e30, 1, 1]}));
    assert_eq!(
        error(&a.write_glb(&dir, "inf.glb")),
        " node 0: transform is not finite (composed with its parents)"
    );
    let mut a = quad(U16);
    a.nodes[0]["rotation"] = json!([0, 0, 0, 0]);
    assert!(
        error(&a.write_glb(&dir, "rot.glb"))
            .starts_with(" node 0: rotation is not a unit quaternion")
    );
}

#[test]
fn a_missing_file_is_named() {
    let path = std::env::temp_dir().join("lumis-gltf-test-no-such-file.glb");
    assert!(error(&path).starts_with(": "));
}

#[test]
fn base64_decodes_with_and_without_padding() {
    for n in 0..10 {
        let bytes: Vec<u8> = (0..n).map(|i| (i * 37 + 5) as u8).collect();
        let text = base64(&bytes);
        assert_eq!(super::buffers::decode_base64(&text).unwrap(), bytes);
        assert_eq!(
            super::buffers::decode_base64(text.trim_end_matches('=')).unwrap(),
            bytes
        );
    }
    assert!(super::buffers::decode_base64("QUJDR").is_err());
}
