//! Tests of PLY triangle strips: the winding and restart rules on the triangle level, then whole
//! files in the three encodings through the reader (fixtures from `ply_tests.rs`).

use super::super::tests::{ENCODINGS, V, fixture, put, tag, test_dir};
use super::*;

/// The triangles of one index list, read as a strip element reads it (−1 restarts).
fn triangles_of(list: &[i64]) -> Vec<[u32; 3]> {
    let mut out = Vec::new();
    for strip in list.split(|&i| i == -1) {
        let strip: Vec<u32> = strip.iter().map(|&i| i as u32).collect();
        strip_triangles(&strip, &mut out);
    }
    out
}

#[test]
fn odd_triangles_swap_their_first_two_vertices() {
    assert_eq!(
        triangles_of(&[0, 1, 2, 3, 4]),
        vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]
    );
}

/// Catches counting only the kept triangles for the alternation: after three degenerate
/// triangles (k = 1, 2, 3) the next is k = 4, even, not the second kept one (odd).
#[test]
fn degenerate_triangles_are_skipped_but_count_for_the_alternation() {
    assert_eq!(
        triangles_of(&[0, 1, 2, 2, 2, 3, 4]),
        vec![[0, 1, 2], [2, 3, 4]]
    );
    // An index repeated one apart is degenerate too.
    assert_eq!(triangles_of(&[0, 1, 0, 2]), vec![[0, 1, 2]]);
}

/// Catches a restart that keeps the strip's alternation: the first strip has an odd number of
/// triangles, so a carried-over parity would swap the second strip's first triangle.
#[test]
fn minus_one_restarts_the_strip_and_short_strips_give_nothing() {
    assert_eq!(
        triangles_of(&[0, 1, 2, 3, 4, -1, 5, 6, 7, -1, 8, 9, -1, -1, 1]),
        vec![[0, 1, 2], [2, 1, 3], [2, 3, 4], [5, 6, 7]]
    );
}

/// A grid of `columns` × `rows` vertices in the plane z = 0 (vertex `r * columns + c` at
/// (c, r)), as a PLY vertex header and rows.
fn grid(columns: u32, rows: u32) -> (String, Vec<Vec<V>>) {
    let header = format!(
        "element vertex {}\nproperty float x\nproperty float y\nproperty float z\n",
        columns * rows
    );
    let vertices = (0..rows)
        .flat_map(|r| (0..columns).map(move |c| vec![V::F(c as f32), V::F(r as f32), V::F(0.0)]))
        .collect();
    (header, vertices)
}

/// The zigzag strip over rows `r` and `r + 1` of a grid `columns` wide.
fn zigzag(columns: u32, r: u32) -> Vec<i32> {
    (0..columns)
        .flat_map(|c| [r * columns + c, (r + 1) * columns + c])
        .map(|i| i as i32)
        .collect()
}

/// Reads `tristrips` rows (each a list of indices, with the given length type) after `grid`.
fn read_strips_file(
    e: Encoding,
    name: &str,
    (vertex_header, vertices): &(String, Vec<Vec<V>>),
    len: &str,
    lists: &[Vec<i32>],
) -> Result<MeshData, MeshError> {
    let header = format!(
        "{vertex_header}element tristrips {}\nproperty list {len} int vertex_indices\n",
        lists.len()
    );
    let mut rows = vertices.clone();
    for list in lists {
        let n = list.len();
        let mut row = vec![match len {
            "uchar" => V::U8(n as u8),
            "ushort" => V::U16(n as u16),
            "int" => V::I32(n as i32),
            _ => V::U32(n as u32),
        }];
        row.extend(list.iter().map(|&i| V::I32(i)));
        rows.push(row);
    }
    load(&put(name, &fixture(e, &header, &rows)))
}

fn normal(mesh: &MeshData, t: [u32; 3]) -> Vec3 {
    let p = t.map(|i| mesh.positions[i as usize]);
    (p[1] - p[0]).cross(p[2] - p[0]).normalize()
}

/// The rule that matters for rendering: every triangle of the strips over a planar grid faces
/// the way the first does (a wrong alternation flips every other one; a parity carried over a
/// restart flips the second strip, whose predecessor has an odd number of triangles), in every
/// encoding and with every usual list-length type. One strip is split by −1, the next joined
/// by degenerate triangles (`…, 7, 7, 4, 4, 8, …`), the last is an element of its own.
#[test]
fn strips_over_a_plane_all_face_the_same_way_in_every_encoding() {
    let g = grid(4, 4);
    // Rows 0–1 in two strips of 5 and 4 vertices: 3 and 2 triangles, the second from k = 0.
    let mut first = zigzag(4, 0)[..5].to_vec();
    first.push(-1);
    first.extend(&zigzag(4, 0)[4..]);
    // Rows 1–2 joined to the second by repeats: four degenerate triangles, then the strip at
    // an even k.
    let mut joined = first.clone();
    joined.extend([7, 4]);
    joined.extend(zigzag(4, 1));
    let lists = vec![joined, zigzag(4, 2)];
    for e in ENCODINGS {
        for len in ["uchar", "ushort", "int", "uint"] {
            let name = format!("strips_plane_{}_{len}.ply", tag(e));
            let mesh = read_strips_file(e, &name, &g, len, &lists).unwrap();
            // 3 + 2 from the split strip, 6 from the joined rows, 6 from the last element.
            assert_eq!(mesh.indices.len(), 17, "{name}");
            let first = normal(&mesh, mesh.indices[0]);
            assert_eq!(first, -Vec3::Z, "{name}");
            for (k, &t) in mesh.indices.iter().enumerate() {
                assert_eq!(normal(&mesh, t), first, "{name} triangle {k} {t:?}");
            }
            assert_eq!(mesh.indices[3], [2, 6, 3], "{name}: the strip after −1");
            assert_eq!(mesh.indices[5], [4, 8, 5], "{name}: the joined strip");
            assert_eq!(mesh.indices[11], [8, 12, 9], "{name}: the last element");
        }
    }
}

/// Catches a strip that continues from one element into the next (which would add triangles
/// across the two lists).
#[test]
fn each_element_starts_a_strip_of_its_own() {
    let mesh = read_strips_file(
        Encoding::Ascii,
        "strips_rows.ply",
        &grid(3, 2),
        "uchar",
        &[vec![0, 3], vec![1, 4, 2, 5]],
    )
    .unwrap();
    assert_eq!(mesh.indices, vec![[1, 4, 2], [2, 4, 5]]);
}

/// The strip element's other properties, scalars and lists before and after the index list,
/// are skipped, and so are the extras a strip file may have (a `material` element).
#[test]
fn other_properties_of_the_strip_element_are_skipped() {
    let (vertex_header, vertices) = grid(3, 2);
    let header = format!(
        "{vertex_header}element tristrips 1\nproperty uchar flags\n\
         property list uchar float weights\nproperty list int int vertex_indices\n\
         property float red\nelement material 1\nproperty int id\n"
    );
    for e in ENCODINGS {
        let mut rows = vertices.clone();
        let mut row = vec![V::U8(7), V::U8(2), V::F(0.5), V::F(1.5), V::I32(4)];
        row.extend([0, 3, 1, 4].map(V::I32));
        row.push(V::F(0.25));
        rows.push(row);
        rows.push(vec![V::I32(3)]);
        let path = put(
            &format!("strips_extra_{}.ply", tag(e)),
            &fixture(e, &header, &rows),
        );
        let mesh = load(&path).unwrap();
        assert_eq!(mesh.indices, vec![[0, 3, 1], [1, 3, 4]], "{e:?}");
        assert!(mesh.attributes.is_empty(), "{e:?}: {:?}", mesh.attributes);
    }
}

/// The file's errors name the element and the index; the line in ASCII.
#[test]
fn bad_indices_and_stripless_files_are_named() {
    let g = grid(3, 2);
    for e in ENCODINGS {
        let line = |n: usize| {
            if e == Encoding::Ascii {
                format!(" (line {n})")
            } else {
                String::new()
            }
        };
        let t = tag(e);
        let err = |name: &str, lists: &[Vec<i32>]| {
            let name = format!("{name}_{t}.ply");
            let error = read_strips_file(e, &name, &g, "int", lists).expect_err(&name);
            let prefix = test_dir().join(&name).display().to_string();
            assert!(error.0.starts_with(&prefix), "{error}");
            error.0[prefix.len()..].to_owned()
        };
        // 9 header lines, 6 vertices: the strips start at line 16.
        assert_eq!(
            err("strips_range", &[vec![0, 3, 1], vec![4, 6, 5]]),
            format!(
                " element tristrips 1{}: index 6 out of range (6 vertices)",
                line(17)
            )
        );
        assert_eq!(
            err("strips_minus_two", &[vec![0, 3, -2, 1]]),
            format!(
                " element tristrips 0{}: index -2 out of range (6 vertices)",
                line(16)
            )
        );
        let none = " element tristrips: no triangles (every strip has fewer than 3 vertices or \
                    only degenerate triangles)";
        assert_eq!(
            err(
                "strips_none",
                &[vec![0, 3, -1, 1, 4], vec![2, 2, 5], vec![]]
            ),
            none
        );
        assert_eq!(err("strips_empty", &[]), none);
    }
}

/// A file with both elements: the faces' triangles first, then the strips', whatever the
/// order of the elements (the strips come first here); the face attributes are dropped (they
/// have no value for the strips' triangles), the vertex attributes kept.
#[test]
fn faces_and_strips_are_read_together_faces_first() {
    let header = "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n\
                  property float weight_0\n\
                  element tristrips 1\nproperty list uchar int vertex_indices\n\
                  element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\n\
                  property uchar green\nproperty uchar blue\n";
    for e in ENCODINGS {
        let mut rows: Vec<Vec<V>> = (0..6)
            .map(|i| {
                let (x, y) = ((i % 3) as f32, (i / 3) as f32);
                vec![V::F(x), V::F(y), V::F(0.0), V::F(i as f32)]
            })
            .collect();
        rows.push(vec![V::U8(4), V::I32(1), V::I32(4), V::I32(2), V::I32(5)]);
        rows.push(vec![
            V::U8(3),
            V::I32(0),
            V::I32(1),
            V::I32(3),
            V::U8(255),
            V::U8(0),
            V::U8(0),
        ]);
        let path = put(
            &format!("strips_and_faces_{}.ply", tag(e)),
            &fixture(e, header, &rows),
        );
        let mesh = load(&path).unwrap();
        assert_eq!(mesh.indices, vec![[0, 1, 3], [1, 4, 2], [2, 4, 5]], "{e:?}");
        let names: Vec<&str> = mesh.attributes.iter().map(|a| a.name.as_str()).collect();
        assert_eq!(names, ["vertex_weight"], "{e:?}");
    }
    // With no strip triangle, the faces' attributes stay (they cover every triangle).
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                property uchar red\nproperty uchar green\nproperty uchar blue\n\
                element tristrips 1\nproperty list uchar int vertex_indices\nend_header\n\
                0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n2 0 1\n";
    let mesh = load(&put("strips_short_and_face.ply", text.as_bytes())).unwrap();
    assert_eq!(mesh.indices, vec![[0, 1, 2]]);
    assert_eq!(mesh.attributes[0].name, "face_color");
}

/// An empty `face` element beside strips is no error: the strips are the surface.
#[test]
fn an_empty_face_element_beside_strips_is_no_error() {
    let text = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
                property float z\nelement face 0\nproperty list uchar int vertex_indices\n\
                element tristrips 1\nproperty list int int vertex_indices\nend_header\n\
                0 0 0\n1 0 0\n0 1 0\n4 0 1 2 -1\n";
    let mesh = load(&put("strips_empty_faces.ply", text.as_bytes())).unwrap();
    assert_eq!(mesh.indices, vec![[0, 1, 2]]);
}
