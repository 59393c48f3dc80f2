//! Tests of the OBJ reader and writer, on small files written here.

use super::*;
use crate::scene::mesh::ply::tests::{scrambled_mesh, test_dir};
use std::path::PathBuf;

/// Writes `text` to `name` in the test folder.
fn put(name: &str, text: &str) -> PathBuf {
    let path = test_dir().join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn read(name: &str, text: &str) -> MeshData {
    load(&put(name, text)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The error for `text`, without the file name in front.
fn error(name: &str, text: &str) -> String {
    let path = put(name, text);
    let err = load(&path).expect_err(name).0;
    let prefix = path.display().to_string();
    assert!(err.starts_with(&prefix), "{err}");
    err[prefix.len()..].to_owned()
}

const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

fn square() -> Vec<Vec3> {
    vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y]
}

#[test]
fn a_quad_is_two_triangles_fanned_from_its_first_vertex() {
    let mesh = read("quad.obj", &format!("{SQUARE}f 1 2 3 4\n"));
    assert_eq!(
        mesh,
        MeshData {
            positions: square(),
            indices: vec![[0, 1, 2], [0, 2, 3]],
            normals: None,
            uvs: None,
            attributes: Vec::new(),
        }
    );
}

#[test]
fn a_pentagon_is_fanned() {
    let mesh = read(
        "pentagon.obj",
        "v 1 0 0\nv 0.3 0.95 0\nv -0.8 0.6 0\nv -0.8 -0.6 0\nv 0.3 -0.95 0\nf 1 2 3 4 5\n",
    );
    assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3], [0, 3, 4]]);
    assert_eq!(mesh.positions[3], Vec3::new(-0.8, -0.6, 0.0));
}

#[test]
fn normals_and_uvs_are_read_and_split_vertices() {
    let text = format!(
        "{SQUARE}vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\nvn 0 0.5 1\n\
         f 1/1/1 2/2/1 3/3/1\nf 1/1/2 3/3/2 4/4/2\n"
    );
    let mesh = read("attributes.obj", &text);
    let (n1, n2) = (Vec3::Z, Vec3::new(0.0, 0.5, 1.0));
    let p = square();
    assert_eq!(
        mesh,
        MeshData {
            // Vertices 1 and 3 appear with two normals: two vertices each.
            positions: vec![p[0], p[1], p[2], p[0], p[2], p[3]],
            indices: vec![[0, 1, 2], [3, 4, 5]],
            normals: Some(vec![n1, n1, n1, n2, n2, n2]),
            // v flipped to the image-row convention: (u, 1 − v).
            uvs: Some(vec![
                Vec2::Y,
                Vec2::ONE,
                Vec2::X,
                Vec2::Y,
                Vec2::X,
                Vec2::ZERO
            ]),
            attributes: Vec::new(),
        }
    );
    // `v//vn` gives normals without texture coordinates.
    let mesh = read(
        "normals_only.obj",
        &format!("{SQUARE}vn 0 0 1\nf 1//1 2//1 3//1 4//1\n"),
    );
    assert_eq!(mesh.normals, Some(vec![Vec3::Z; 4]));
    assert_eq!(mesh.uvs, None);
}

#[test]
fn an_attribute_missing_on_some_faces_is_dropped() {
    let text = format!(
        "{SQUARE}vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1//1 3//1 4//1\n"
    );
    let mesh = read("partial_uv.obj", &text);
    assert_eq!(mesh.uvs, None);
    assert_eq!(mesh.normals, Some(vec![Vec3::Z; 6]));
    assert_eq!(mesh.indices, vec![[0, 1, 2], [3, 4, 5]]);
    // Missing in a whole group of its own, too.
    let text = format!("{SQUARE}vn 0 0 1\ng a\nf 1//1 2//1 3//1\ng b\nf 1 3 4\n");
    let mesh = read("partial_normal.obj", &text);
    assert_eq!((mesh.normals, mesh.indices.len()), (None, 2));
}

#[test]
fn negative_indices_count_back_from_the_line() {
    let mesh = read("relative.obj", &format!("{SQUARE}f -4 -3 -2 -1\n"));
    assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.positions, square());
    // Interleaved: each face refers to the vertices just before it.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvn 0 0 1\nf -3/-1/-1 -2/-1/-1 -1/-1/-1\n\
                v 5 0 0\nv 6 0 0\nv 5 1 0\nvt 0.25 0.75\nvn 0 1 0\nf -3/-1/-1 -2/-1/-1 -1/-1/-1\n";
    let mesh = read("relative_interleaved.obj", text);
    assert_eq!(
        mesh.positions[3..],
        [
            Vec3::new(5.0, 0.0, 0.0),
            Vec3::new(6.0, 0.0, 0.0),
            Vec3::new(5.0, 1.0, 0.0)
        ]
    );
    assert_eq!(
        mesh.normals.unwrap()[..],
        [Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Y, Vec3::Y, Vec3::Y]
    );
    assert_eq!(mesh.uvs.unwrap()[3], Vec2::new(0.25, 0.25));
    assert_eq!(mesh.indices, vec![[0, 1, 2], [3, 4, 5]]);
}

#[test]
fn objects_groups_and_materials_merge_into_one_mesh() {
    let text = format!(
        "mtllib missing.mtl\n{SQUARE}o first\nusemtl red\nf 1 2 3\ng second\nusemtl blue\nf 1 3 4\n\
         usemtl\ns 1\nf 4 3 2\n"
    );
    // Without the bare `usemtl` no rewrite happens: tobj itself sees the materials.
    let plain = read("groups_plain.obj", &text.replace("usemtl\ns 1", "s 1"));
    assert_eq!(plain.indices.len(), 3);
    // tobj alone fails on a tab after `usemtl`.
    let tab = read("usemtl_tab.obj", &format!("{SQUARE}usemtl\tred\nf 1 2 3\n"));
    assert_eq!(tab.indices.len(), 1);
    let mesh = read("groups.obj", &text);
    let p = square();
    assert_eq!(mesh.indices.len(), 3);
    let corners: Vec<[Vec3; 3]> = mesh
        .indices
        .iter()
        .map(|t| t.map(|i| mesh.positions[i as usize]))
        .collect();
    assert_eq!(
        corners,
        vec![[p[0], p[1], p[2]], [p[0], p[2], p[3]], [p[3], p[2], p[1]]]
    );
}

#[test]
fn constructs_tobj_mishandles_are_read_correctly() {
    // Polylines add no triangles; a colour on some vertices only, a one-number `vt` (v = 0), a
    // `w` that divides, `usemtl` with a tab, CRLF line ends and a comment that is not UTF-8 are
    // all fine.
    let mut bytes = b"# caf\xe9\r\nv 0 0 0 1 0 0\r\nv 2 0 0 2\r\nv 1 1 0\r\nv 0 1 0\r\n".to_vec();
    bytes.extend(b"vt 0.5\r\nvt 1 0.25 0\r\nvt 0 1\r\nl 1 2 3 4\r\nl 1 2\r\nusemtl\tred\r\n");
    bytes.extend(b"f 1/1 2/2 3/3\r\n");
    let path = test_dir().join("quirks.obj");
    std::fs::write(&path, &bytes).unwrap();
    let mesh = load(&path).unwrap();
    assert_eq!(
        mesh,
        MeshData {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)],
            indices: vec![[0, 1, 2]],
            normals: None,
            uvs: Some(vec![Vec2::new(0.5, 1.0), Vec2::new(1.0, 0.75), Vec2::ZERO]),
            attributes: Vec::new(),
        }
    );
}

#[test]
fn the_issue_example_names_file_line_and_count() {
    // A face on line 17 pointing past the 3000 vertices of the file (the last ones after it).
    let mut text = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    text.push_str(&"# padding\n".repeat(13));
    text.push_str("f 1 2 4021\n");
    text.push_str(&"v 0 0 1\n".repeat(2997));
    let path = put("bunny.obj", &text);
    assert_eq!(
        load(&path).unwrap_err().0,
        format!(
            "{} line 17: face index 4021 out of range (3000 vertices)",
            path.display()
        )
    );
    // A forward reference in range is fine.
    text = text.replace("f 1 2 4021", "f 1 2 3000");
    assert_eq!(read("bunny_ok.obj", &text).indices.len(), 1);
}

#[test]
fn bad_lines_are_named() {
    let cases = [
        (
            format!("{SQUARE}f 1 2 0\n"),
            " line 5: face index 0 (OBJ indices start at 1)",
        ),
        (
            format!("{SQUARE}f 1 2 5\n"),
            " line 5: face index 5 out of range (4 vertices)",
        ),
        (
            format!("v 0 0 0\nf -1 -2 -3\n{SQUARE}"),
            " line 2: face index -2 out of range (1 vertices before this line)",
        ),
        (
            format!("{SQUARE}vt 0 0\nf 1/1 2/2 3/1\n"),
            " line 6: face texture index 2 out of range (1 texture coordinates)",
        ),
        (
            format!("{SQUARE}f 1/1 2/1 3/1\n"),
            " line 5: face texture index 1 out of range (0 texture coordinates)",
        ),
        (
            format!("{SQUARE}vn 0 0 1\nf 1//1 2//-2 3//1\n"),
            " line 6: face normal index -2 out of range (1 normals before this line)",
        ),
        (
            format!("{SQUARE}f 1 2\n"),
            " line 5: a face needs at least 3 vertices, found 2",
        ),
        (
            format!("{SQUARE}f\n"),
            " line 5: a face needs at least 3 vertices, found 0",
        ),
        (
            format!("{SQUARE}f 1 2 3/4/5/6\n"),
            " line 5: bad vertex reference '3/4/5/6'",
        ),
        (
            format!("{SQUARE}f 1 2 /3\n"),
            " line 5: bad vertex reference '/3'",
        ),
        (
            format!("{SQUARE}f 1 2 three\n"),
            " line 5: bad vertex reference 'three'",
        ),
        (
            format!("{SQUARE}f 1 2 3.0\n"),
            " line 5: bad vertex reference '3.0'",
        ),
        (
            "v 0 0 0\nv 1 abc 0\n".into(),
            " line 2: 'abc' is not a number",
        ),
        ("v 0 0 0\nv 1 nan 0\n".into(), " line 2: y is NaN"),
        ("v 0 0 0\nv 1 0 -inf\n".into(), " line 2: z is infinite"),
        (
            "v 1e39 0 0\n".into(),
            " line 1: x = 1e39 is beyond single precision",
        ),
        (
            "v 1e30 0 0 1e-30\n".into(),
            " line 1: x / w is beyond single precision",
        ),
        ("v 1 0 0 0\n".into(), " line 1: w is 0"),
        ("v 1 0 0 NaN 0 0\n".into(), " line 1: r is NaN"),
        (
            "v 1 0\n".into(),
            " line 1: 'v' needs 3 numbers (4 with w, 6 with a colour), found 2",
        ),
        (
            "v 1 0 0 1 1\n".into(),
            " line 1: 'v' needs 3 numbers (4 with w, 6 with a colour), found 5",
        ),
        (
            format!("{SQUARE}vn 0 0\n"),
            " line 5: 'vn' needs 3 numbers, found 2",
        ),
        (
            format!("{SQUARE}vn 0 0 1 1\n"),
            " line 5: 'vn' needs 3 numbers, found 4",
        ),
        (format!("{SQUARE}vn 0 inf 1\n"), " line 5: y is infinite"),
        (
            format!("{SQUARE}vt\n"),
            " line 5: 'vt' needs 1 to 3 numbers, found 0",
        ),
        (format!("{SQUARE}vt 0.5 NaN\n"), " line 5: v is NaN"),
        (SQUARE.into(), ": no faces"),
        (format!("{SQUARE}l 1 2 3\np 1\n"), ": no faces"),
        (String::new(), ": no faces"),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        assert_eq!(
            error(&format!("bad_{i}.obj"), text),
            *expected,
            "case {i}: {text}"
        );
    }
    let missing = test_dir().join("does_not_exist.obj");
    assert!(
        load(&missing)
            .unwrap_err()
            .0
            .contains("does_not_exist.obj: cannot read: ")
    );
}

/// `mesh` with its vertices renumbered in the order its triangles first use them and unused
/// ones dropped: how an OBJ file of it reads back.
fn in_first_use_order(mesh: &MeshData) -> MeshData {
    let mut new_index = vec![u32::MAX; mesh.positions.len()];
    let mut order = Vec::new();
    let indices = mesh
        .indices
        .iter()
        .map(|t| {
            t.map(|i| {
                if new_index[i as usize] == u32::MAX {
                    new_index[i as usize] = order.len() as u32;
                    order.push(i as usize);
                }
                new_index[i as usize]
            })
        })
        .collect();
    MeshData {
        positions: order.iter().map(|&i| mesh.positions[i]).collect(),
        indices,
        normals: mesh
            .normals
            .as_ref()
            .map(|n| order.iter().map(|&i| n[i]).collect()),
        uvs: mesh
            .uvs
            .as_ref()
            .map(|n| order.iter().map(|&i| n[i]).collect()),
        attributes: Vec::new(),
    }
}

#[test]
fn meshes_round_trip_through_the_writer() {
    for (m, (normals, uvs)) in [(true, true), (false, true), (true, false), (false, false)]
        .into_iter()
        .enumerate()
    {
        let mesh = scrambled_mesh(300, 500, normals, uvs);
        let path = test_dir().join(format!("round_trip_{m}.obj"));
        write(&path, &mesh).unwrap();
        assert_eq!(load(&path).unwrap(), in_first_use_order(&mesh), "mesh {m}");
    }
}

/// Every prefix of a valid file, and every byte of it changed three ways, must give a mesh or
/// an error, never a panic; a mesh that comes back passes `check`.
#[test]
fn mutated_files_never_panic() {
    let good = format!(
        "{SQUARE}vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\ng a\nf 1/1/1 2/2/1 3/3/1\nf -4/1 -2/3 -1/2\n"
    )
    .into_bytes();
    let path = PathBuf::from("mutant.obj");
    for cut in 0..good.len() {
        if let Ok(mesh) = load_bytes(&path, &good[..cut]) {
            check(&path, &mesh).unwrap();
        }
    }
    for i in 0..good.len() {
        for flip in [0x01u8, 0x80, 0xff] {
            let mut bad = good.clone();
            bad[i] ^= flip;
            if let Ok(mesh) = load_bytes(&path, &bad) {
                check(&path, &mesh).unwrap();
            }
        }
    }
}
