//! Tests of the PLY reader and writer. The fixtures are made here value by value (text for
//! ASCII, bytes for the binary encodings), independently of `write`; ply-rs reads the same
//! fixtures as a second opinion.

use super::attributes_tests::{ATTRIBUTE_HEADER, attribute_rows};
use super::*;
use std::path::PathBuf;

/// A per-process folder for the test files.
pub(crate) fn test_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-mesh-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A deterministic mesh of `vertices` random points and `triangles` random index triples
/// (every vertex used, in no particular order), with random normals and texture coordinates
/// where asked.
pub(crate) fn scrambled_mesh(
    vertices: usize,
    triangles: usize,
    normals: bool,
    uvs: bool,
) -> MeshData {
    let mut state = 0x9e37_79b9_7f4a_7c15u64 ^ (vertices * 31 + triangles) as u64;
    let mut next = move || {
        // SplitMix64.
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let mut unit = move || (next() >> 40) as f32 / (1u64 << 24) as f32 * 2.0 - 1.0;
    let mut v3 = |s: f32| Vec3::new(unit() * s, unit() * s, unit() * s);
    let positions: Vec<Vec3> = (0..vertices).map(|_| v3(10.0)).collect();
    let normals = normals.then(|| (0..vertices).map(|_| v3(1.0)).collect());
    let uvs = uvs.then(|| {
        (0..vertices)
            .map(|_| {
                let v = v3(2.0);
                Vec2::new(v.x, v.y)
            })
            .collect()
    });
    let n = vertices as u64;
    let mut k = 0u64;
    let indices = (0..triangles)
        .map(|_| {
            // A stride walk covers every vertex before repeating one.
            let mut t = [0u32; 3];
            for i in &mut t {
                *i = ((k * 7919 + 13) % n) as u32;
                k += 1;
            }
            t
        })
        .collect();
    MeshData {
        positions,
        indices,
        normals,
        uvs,
        attributes: Vec::new(),
    }
}

/// Writes `bytes` to `name` in the test folder.
pub(super) fn put(name: &str, bytes: &[u8]) -> PathBuf {
    let path = test_dir().join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// One value of a fixture, with its PLY type.
#[derive(Clone, Copy, Debug)]
pub(super) enum V {
    I8(i8),
    U8(u8),
    I16(i16),
    U16(u16),
    I32(i32),
    U32(u32),
    F(f32),
    D(f64),
}

/// A file of `header` (without `ply`/`format`/`end_header`) and `rows` (one element each).
pub(super) fn fixture(encoding: Encoding, header: &str, rows: &[Vec<V>]) -> Vec<u8> {
    let format = match encoding {
        Encoding::Ascii => "ascii",
        Encoding::BinaryLittleEndian => "binary_little_endian",
        Encoding::BinaryBigEndian => "binary_big_endian",
    };
    let mut out = format!("ply\nformat {format} 1.0\n{header}end_header\n").into_bytes();
    let big = encoding == Encoding::BinaryBigEndian;
    macro_rules! bytes {
        ($v:expr) => {
            if big {
                $v.to_be_bytes().to_vec()
            } else {
                $v.to_le_bytes().to_vec()
            }
        };
    }
    for row in rows {
        if encoding == Encoding::Ascii {
            let words: Vec<String> = row
                .iter()
                .map(|v| match *v {
                    V::I8(x) => x.to_string(),
                    V::U8(x) => x.to_string(),
                    V::I16(x) => x.to_string(),
                    V::U16(x) => x.to_string(),
                    V::I32(x) => x.to_string(),
                    V::U32(x) => x.to_string(),
                    V::F(x) => x.to_string(),
                    V::D(x) => x.to_string(),
                })
                .collect();
            out.extend(words.join(" ").bytes());
            out.push(b'\n');
        } else {
            for v in row {
                out.extend(match *v {
                    V::I8(x) => bytes!(x),
                    V::U8(x) => bytes!(x),
                    V::I16(x) => bytes!(x),
                    V::U16(x) => bytes!(x),
                    V::I32(x) => bytes!(x),
                    V::U32(x) => bytes!(x),
                    V::F(x) => bytes!(x),
                    V::D(x) => bytes!(x),
                });
            }
        }
    }
    out
}

pub(super) const ENCODINGS: [Encoding; 3] = [
    Encoding::Ascii,
    Encoding::BinaryLittleEndian,
    Encoding::BinaryBigEndian,
];

pub(super) fn tag(e: Encoding) -> &'static str {
    match e {
        Encoding::Ascii => "ascii",
        Encoding::BinaryLittleEndian => "le",
        Encoding::BinaryBigEndian => "be",
    }
}

/// The pentagon fixture's header: properties out of order, a colour between them, `s t` as the
/// texture coordinates, a face property before the index list, an `edge` element with a list
/// after the faces (all to be skipped).
const RICH_HEADER: &str = "comment a pentagon and a triangle\n\
element vertex 6\n\
property float z\nproperty uchar red\nproperty float x\nproperty float y\n\
property float nx\nproperty float ny\nproperty float nz\nproperty float s\nproperty float t\n\
element face 2\n\
property uchar flags\nproperty list uchar int vertex_indices\n\
element edge 1\n\
property int vertex1\nproperty list ushort float junk\n";

/// Six vertices (a regular-ish pentagon at z = 0.25 and an apex), their normals and (s, t).
fn rich_vertices() -> Vec<[f32; 8]> {
    // [x, y, z, nx, ny, nz, s, t]
    vec![
        [1.0, 0.0, 0.25, 0.0, 0.0, 1.0, 1.0, 0.5],
        [0.309, 0.951, 0.25, 0.0, 0.0, 1.0, 0.6545, 0.9755],
        [-0.809, 0.5878, 0.25, 0.0, 0.1, 1.0, 0.0955, 0.7939],
        [-0.809, -0.5878, 0.25, 0.0, 0.0, 1.0, 0.0955, 0.2061],
        [0.309, -0.951, 0.25, -0.2, 0.0, 1.0, 0.6545, 0.0245],
        [0.0, 0.0, 1.5e-3, 0.3333, -0.5, 0.8, 0.5, 0.5],
    ]
}

fn rich_rows() -> Vec<Vec<V>> {
    let mut rows: Vec<Vec<V>> = rich_vertices()
        .iter()
        .enumerate()
        .map(|(i, v)| {
            vec![
                V::F(v[2]),
                V::U8(200 + i as u8),
                V::F(v[0]),
                V::F(v[1]),
                V::F(v[3]),
                V::F(v[4]),
                V::F(v[5]),
                V::F(v[6]),
                V::F(v[7]),
            ]
        })
        .collect();
    rows.push(vec![
        V::U8(7),
        V::U8(5),
        V::I32(0),
        V::I32(1),
        V::I32(2),
        V::I32(3),
        V::I32(4),
    ]);
    rows.push(vec![V::U8(0), V::U8(3), V::I32(0), V::I32(4), V::I32(5)]);
    rows.push(vec![V::I32(3), V::U16(2), V::F(0.5), V::F(-1.0)]);
    rows
}

/// What the rich fixture must read as: the pentagon fanned from vertex 0, then the triangle.
fn rich_expected() -> MeshData {
    let v = rich_vertices();
    MeshData {
        positions: v.iter().map(|v| Vec3::new(v[0], v[1], v[2])).collect(),
        indices: vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]],
        normals: Some(v.iter().map(|v| Vec3::new(v[3], v[4], v[5])).collect()),
        uvs: Some(v.iter().map(|v| Vec2::new(v[6], v[7])).collect()),
        attributes: Vec::new(),
    }
}

#[test]
fn all_three_encodings_read_the_same_mesh() {
    for e in ENCODINGS {
        let path = put(
            &format!("rich_{}.ply", tag(e)),
            &fixture(e, RICH_HEADER, &rich_rows()),
        );
        assert_eq!(load(&path).unwrap(), rich_expected(), "{e:?}");
    }
}

#[test]
fn a_quad_is_two_triangles_and_attributes_are_optional() {
    let header = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                  element face 1\nproperty list uchar uint vertex_index\n";
    let quad = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut rows: Vec<Vec<V>> = quad
        .iter()
        .map(|p| vec![V::F(p[0]), V::F(p[1]), V::F(0.0)])
        .collect();
    rows.push(vec![V::U8(4), V::U32(0), V::U32(1), V::U32(2), V::U32(3)]);
    for e in ENCODINGS {
        let mesh = load(&put(
            &format!("quad_{}.ply", tag(e)),
            &fixture(e, header, &rows),
        ))
        .unwrap();
        assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]], "{e:?}");
        assert_eq!(mesh.positions[2], Vec3::new(1.0, 1.0, 0.0));
        assert_eq!((mesh.normals, mesh.uvs), (None, None), "{e:?}");
    }
}

#[test]
fn double_positions_and_every_texture_coordinate_naming_are_read() {
    // Literal names, not `UV_NAMES`: the test must not follow a change to the reader's list.
    for [u, v] in [
        ["u", "v"],
        ["s", "t"],
        ["texture_u", "texture_v"],
        ["texture_s", "texture_t"],
    ] {
        let header = format!(
            "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
             property double {u}\nproperty float {v}\n\
             element face 1\nproperty list uchar int vertex_indices\n"
        );
        let rows = vec![
            vec![V::D(0.1), V::D(-2.5e-7), V::D(3.0), V::D(0.3), V::F(0.7)],
            vec![
                V::D(1.0 / 3.0),
                V::D(1e30),
                V::D(-0.0),
                V::D(1.0),
                V::F(0.0),
            ],
            vec![
                V::D(7.0),
                V::D(8.0),
                V::D(9.123456789012),
                V::D(0.0),
                V::F(1.0),
            ],
            vec![V::U8(3), V::I32(2), V::I32(1), V::I32(0)],
        ];
        let expected = MeshData {
            positions: vec![
                Vec3::new(0.1, -2.5e-7, 3.0),
                Vec3::new((1.0f64 / 3.0) as f32, 1e30, -0.0),
                Vec3::new(7.0, 8.0, 9.123456789012f64 as f32),
            ],
            indices: vec![[2, 1, 0]],
            normals: None,
            uvs: Some(vec![
                Vec2::new(0.3, 0.7),
                Vec2::new(1.0, 0.0),
                Vec2::new(0.0, 1.0),
            ]),
            attributes: Vec::new(),
        };
        for e in ENCODINGS {
            let path = put(
                &format!("double_{u}_{}.ply", tag(e)),
                &fixture(e, &header, &rows),
            );
            assert_eq!(load(&path).unwrap(), expected, "{u}/{v} {e:?}");
        }
    }
}

#[test]
fn every_integer_type_works_for_list_lengths_and_indices() {
    type Make = fn(i64) -> V;
    let types: [(&str, Make); 6] = [
        ("char", |i| V::I8(i as i8)),
        ("uchar", |i| V::U8(i as u8)),
        ("short", |i| V::I16(i as i16)),
        ("ushort", |i| V::U16(i as u16)),
        ("int", |i| V::I32(i as i32)),
        ("uint", |i| V::U32(i as u32)),
    ];
    for (len_name, len) in types {
        for (item_name, item) in types {
            let header = format!(
                "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
                 element face 1\nproperty list {len_name} {item_name} vertex_indices\n"
            );
            let mut rows: Vec<Vec<V>> = (0..4)
                .map(|i| vec![V::F(i as f32), V::F(1.0), V::F(2.0)])
                .collect();
            rows.push(vec![len(4), item(3), item(2), item(1), item(0)]);
            for e in ENCODINGS {
                let name = format!("types_{len_name}_{item_name}_{}.ply", tag(e));
                let mesh = load(&put(&name, &fixture(e, &header, &rows))).unwrap();
                assert_eq!(mesh.indices, vec![[3, 2, 1], [3, 1, 0]], "{name}");
            }
        }
    }
}

/// Writes the rich fixture with `edit` applied to its rows and returns the error message.
fn rich_error(e: Encoding, name: &str, edit: impl Fn(&mut Vec<Vec<V>>)) -> (PathBuf, String) {
    let mut rows = rich_rows();
    edit(&mut rows);
    let path = put(name, &fixture(e, RICH_HEADER, &rows));
    let err = load(&path).expect_err(name).0;
    (path, err)
}

#[test]
fn a_bad_index_names_the_face() {
    for e in ENCODINGS {
        let (path, err) = rich_error(e, &format!("bad_index_{}.ply", tag(e)), |r| {
            r[7][4] = V::I32(900)
        });
        let line = |n: usize| {
            if e == Encoding::Ascii {
                format!(" (line {n})")
            } else {
                String::new()
            }
        };
        assert_eq!(
            err,
            format!(
                "{} element face 1{}: index 900 out of range (6 vertices)",
                path.display(),
                line(28)
            )
        );
        let (path, err) = rich_error(e, &format!("neg_index_{}.ply", tag(e)), |r| {
            r[6][3] = V::I32(-1)
        });
        assert_eq!(
            err,
            format!(
                "{} element face 0{}: index -1 out of range (6 vertices)",
                path.display(),
                line(27)
            )
        );
    }
}

#[test]
fn a_non_finite_vertex_names_the_vertex_and_property() {
    for e in ENCODINGS {
        let t = tag(e);
        let line = |n: usize| {
            if e == Encoding::Ascii {
                format!(" (line {n})")
            } else {
                String::new()
            }
        };
        let (path, err) = rich_error(e, &format!("nan_{t}.ply"), |r| r[3][2] = V::F(f32::NAN));
        assert_eq!(
            err,
            format!("{} element vertex 3{}: x is NaN", path.display(), line(24))
        );
        let (_, err) = rich_error(e, &format!("inf_{t}.ply"), |r| {
            r[0][0] = V::F(f32::NEG_INFINITY)
        });
        assert!(
            err.ends_with(&format!("element vertex 0{}: z is infinite", line(21))),
            "{err}"
        );
        let (_, err) = rich_error(e, &format!("nan_normal_{t}.ply"), |r| {
            r[5][5] = V::F(f32::NAN)
        });
        assert!(
            err.ends_with(&format!("element vertex 5{}: ny is NaN", line(26))),
            "{err}"
        );
        let (_, err) = rich_error(e, &format!("inf_uv_{t}.ply"), |r| {
            r[1][8] = V::F(f32::INFINITY)
        });
        assert!(
            err.ends_with(&format!("element vertex 1{}: t is infinite", line(22))),
            "{err}"
        );
    }
    let header = "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n\
                  element face 0\nproperty list uchar int vertex_indices\n";
    let rows = vec![vec![V::D(0.0), V::D(0.0), V::D(1e300)]];
    let path = put(
        "huge.ply",
        &fixture(Encoding::BinaryLittleEndian, header, &rows),
    );
    // No faces is checked before the payload; with a face the huge z is reached.
    assert!(
        load(&path)
            .unwrap_err()
            .0
            .ends_with("element face: no faces")
    );
    let header = header.replace("face 0", "face 1");
    let mut rows = rows;
    rows.push(vec![V::U8(3), V::I32(0), V::I32(0), V::I32(0)]);
    let path = put(
        "huge.ply",
        &fixture(Encoding::BinaryLittleEndian, &header, &rows),
    );
    assert_eq!(
        load(&path).unwrap_err().0,
        format!(
            "{} element vertex 0: z = 1e300 is beyond single precision",
            path.display()
        )
    );
}

#[test]
fn a_truncated_file_names_the_element_it_ends_in() {
    for e in [Encoding::BinaryLittleEndian, Encoding::BinaryBigEndian] {
        let bytes = fixture(e, RICH_HEADER, &rich_rows());
        let header_len = bytes
            .windows(11)
            .position(|w| w == b"end_header\n")
            .unwrap()
            + 11;
        // Vertices are 33 bytes, the pentagon face 22, the triangle 14, the edge 14.
        for (cut, position) in [
            (header_len, "element vertex 0"),
            (header_len + 2 * 33 + 5, "element vertex 2"),
            (header_len + 6 * 33 + 22 + 3, "element face 1"),
            (bytes.len() - 1, "element edge 0"),
        ] {
            let path = put(&format!("cut_{}.ply", tag(e)), &bytes[..cut]);
            assert_eq!(
                load(&path).unwrap_err().0,
                format!(
                    "{} {position}: truncated: the file ends before this element is complete",
                    path.display()
                )
            );
        }
    }
    let text = fixture(Encoding::Ascii, RICH_HEADER, &rich_rows());
    let cut = text.len() - "3 2 0.5 -1\n".len() - "0 3 0 4 5\n".len();
    let path = put("cut_ascii.ply", &text[..cut]);
    assert_eq!(
        load(&path).unwrap_err().0,
        format!(
            "{} element face 1 (line 28): truncated: the file ends before this element",
            path.display()
        )
    );
}

/// The error for a file made of `text`.
fn text_error(name: &str, text: &str) -> String {
    let path = put(name, text.as_bytes());
    let err = load(&path).expect_err(name).0;
    let prefix = format!("{}", path.display());
    assert!(err.starts_with(&prefix), "{err}");
    err[prefix.len()..].to_owned()
}

const XYZ: &str = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
const FACES: &str = "element face 1\nproperty list uchar int vertex_indices\n";
const DATA: &str = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

fn ascii(header: &str, data: &str) -> String {
    format!("ply\nformat ascii 1.0\n{header}end_header\n{data}")
}

#[test]
fn structural_errors_are_named() {
    let cases: Vec<(String, &str)> = vec![
        (String::new(), " header line 1: empty file"),
        (
            "PK\x03\x04junk".into(),
            " header line 1: not a PLY file (it does not start with 'ply')",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 3\n".into(),
            " header line 4: the file ends before end_header",
        ),
        (
            "ply\nelement vertex 1\nend_header\n".into(),
            " header: no format line",
        ),
        (
            "ply\nformat ascii 1.0\nproperty float x\n".into(),
            " header line 3: property before any element",
        ),
        (
            "ply\nformat text 1.0\n".into(),
            " header line 2: unknown format 'text' (ascii, binary_little_endian or binary_big_endian)",
        ),
        (
            ascii(&XYZ.replace("float y", "float16 y"), DATA),
            " header line 5: unknown type 'float16'",
        ),
        (
            ascii(
                &XYZ.replace("vertex 3", "vertex 99999999999999999999999"),
                DATA,
            ),
            " header line 3: element count '99999999999999999999999' is not a whole number",
        ),
        (
            ascii(&XYZ.replace("vertex 3", "vertex -3"), DATA),
            " header line 3: element count '-3' is not a whole number",
        ),
        (
            ascii(&format!("{XYZ}property float x\n{FACES}"), DATA),
            " header line 7: a second property 'x' in element 'vertex'",
        ),
        (
            ascii(&format!("{XYZ}{FACES}{FACES}"), DATA),
            " header line 9: a second element 'face'",
        ),
        (
            ascii(
                &format!("{XYZ}element face 1\nproperty list float int vertex_indices\n"),
                DATA,
            ),
            " header line 8: a list's length must have an integer type",
        ),
        (
            ascii(&format!("{XYZ}frobnicate 3\n{FACES}"), DATA),
            " header line 7: unknown header keyword 'frobnicate'",
        ),
        (ascii(FACES, "3 0 1 2\n"), ": no vertex element"),
        (
            ascii(XYZ, "0 0 0\n1 0 0\n0 1 0\n"),
            ": no face or tristrips element (a point cloud has no surface to render)",
        ),
        (
            ascii(
                &format!("{}{FACES}", XYZ.replace("float y", "float why")),
                DATA,
            ),
            " element vertex: no scalar property 'y'",
        ),
        (
            ascii(
                &format!("{XYZ}element face 1\nproperty list uchar int corners\n"),
                DATA,
            ),
            " element face: no property 'vertex_indices' (or 'vertex_index')",
        ),
        (
            ascii(
                &format!("{XYZ}element face 1\nproperty list uchar float vertex_indices\n"),
                DATA,
            ),
            " element face: the vertex index list must have an integer type",
        ),
        (
            ascii(
                &format!("{XYZ}element face 1\nproperty int vertex_indices\n"),
                DATA,
            ),
            " element face: the vertex indices must be a list",
        ),
        (
            ascii(
                &format!("{XYZ}{}", FACES.replace("face 1", "face 0")),
                "0 0 0\n1 0 0\n0 1 0\n",
            ),
            " element face: no faces",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
            " element face 0 (line 13): 2 vertices (a face needs at least 3)",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0\n0 1 0\n3 0 1 2\n"),
            " element vertex 1 (line 11): too few values on the line",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0 0 7\n0 1 0\n3 0 1 2\n"),
            " element vertex 1 (line 11): too many values on the line",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n"),
            " element vertex 2 (line 12): 'one' is not a value of type float",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"),
            " element face 0 (line 13): '1.5' is not a value of type int",
        ),
        (
            ascii(&format!("{XYZ}{FACES}"), "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"),
            " element face 0 (line 13): '300' is not a value of type uchar",
        ),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        assert_eq!(
            text_error(&format!("structural_{i}.ply"), text),
            *expected,
            "case {i}"
        );
    }
}

/// Found by `renderer/tests/mesh_mutations/`: the header splits at ASCII whitespace, which U+000B,
/// U+0085 and U+2028 are not, so a quoted keyword or value carried the line break into the
/// message.
#[test]
fn quoted_line_breaks_are_escaped() {
    let cases = [
        (
            "ply\nformat ascii 1.0\nelem\u{b}ent vertex 3\nend_header\n".to_string(),
            r" header line 3: unknown header keyword 'elem\u{b}ent'",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty fl\u{2028}oat x\n".to_string(),
            r" header line 4: unknown type 'fl\u{2028}oat'",
        ),
        (
            ascii(
                &format!("{XYZ}{FACES}"),
                "0 0 0\u{85}\n1 0 0\n0 1 0\n3 0 1 2\n",
            ),
            r" element vertex 0 (line 10): '0\u{85}' is not a value of type float",
        ),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        assert_eq!(text_error(&format!("breaks_{i}.ply"), text), *expected);
    }
}

#[test]
fn ascii_is_lenient_where_the_format_allows() {
    // Blank lines, CRLF line ends, tabs, trailing spaces, `.5`, `1E0`, an element count with
    // leading zeros, sized type names.
    let text = "ply\r\nformat ascii 1.0\r\nelement vertex 003\r\nproperty float32 x\r\n\
                property float64 y\r\nproperty float z\r\nelement face 1\r\n\
                property list uint8 int32 vertex_indices\r\nend_header\r\n\
                \r\n.5\t0 0  \r\n1E0 0 0\r\n\r\n0 1 -0\r\n3 0 1 2\r\n";
    let mesh = load(&put("lenient.ply", text.as_bytes())).unwrap();
    assert_eq!(
        mesh.positions,
        vec![Vec3::new(0.5, 0.0, 0.0), Vec3::X, Vec3::new(0.0, 1.0, -0.0)]
    );
    assert_eq!(mesh.indices, vec![[0, 1, 2]]);
}

#[test]
fn a_huge_declared_count_is_an_error_not_an_allocation() {
    let header = "element vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n\
                  element face 4000000000\nproperty list uchar int vertex_indices\n";
    for e in ENCODINGS {
        let bytes = fixture(e, header, &[vec![V::F(1.0), V::F(2.0), V::F(3.0)]]);
        let err = load(&put(&format!("huge_count_{}.ply", tag(e)), &bytes))
            .unwrap_err()
            .0;
        assert!(
            err.contains("element vertex 1") && err.contains("truncated"),
            "{err}"
        );
    }
}

/// Every prefix of the valid files, and every byte of them changed three ways, must give a
/// mesh or an error, never a panic; a mesh that comes back passes `check`.
#[test]
fn mutated_files_never_panic() {
    let fixtures = [
        ("rich", RICH_HEADER, rich_rows()),
        ("attributes", ATTRIBUTE_HEADER, attribute_rows()),
    ];
    for (e, (name, header, rows)) in ENCODINGS
        .into_iter()
        .flat_map(|e| fixtures.iter().map(move |f| (e, f)))
    {
        let good = fixture(e, header, rows);
        let path = PathBuf::from(format!("mutant_{name}_{}.ply", tag(e)));
        let load = |bytes: &[u8]| read(&path, bytes, bytes.len() as u64);
        let mut tried = 0;
        for cut in 0..good.len() {
            // Only the final newline of an ASCII file may go.
            let complete = e == Encoding::Ascii && cut == good.len() - 1;
            assert_eq!(
                load(&good[..cut]).is_ok(),
                complete,
                "a prefix of {cut} bytes"
            );
            tried += 1;
        }
        for i in 0..good.len() {
            for flip in [0x01u8, 0x80, 0xff] {
                let mut bad = good.clone();
                bad[i] ^= flip;
                if let Ok(mesh) = load(&bad) {
                    check(&path, &mesh).unwrap();
                }
                tried += 1;
            }
        }
        assert!(tried > 1000);
    }
}

#[test]
fn meshes_round_trip_through_the_writer() {
    let meshes = [
        scrambled_mesh(500, 900, true, true),
        scrambled_mesh(40, 60, false, true),
        scrambled_mesh(40, 60, true, false),
        scrambled_mesh(3, 1, false, false),
    ];
    for (m, mesh) in meshes.iter().enumerate() {
        for e in ENCODINGS {
            let path = test_dir().join(format!("round_trip_{m}_{}.ply", tag(e)));
            write(&path, mesh, e).unwrap();
            assert_eq!(load(&path).unwrap(), *mesh, "mesh {m} {e:?}");
        }
    }
}

/// The same fixtures through ply-rs (the general reader the workspace depends on): both readers
/// must agree, value for value.
#[test]
fn ply_rs_reads_the_fixtures_the_same() {
    use ply_rs::parser::Parser;
    use ply_rs::ply::{DefaultElement, Property as P};
    fn num(p: &P) -> f64 {
        match *p {
            P::Char(v) => v.into(),
            P::UChar(v) => v.into(),
            P::Short(v) => v.into(),
            P::UShort(v) => v.into(),
            P::Int(v) => v.into(),
            P::UInt(v) => v.into(),
            P::Float(v) => v.into(),
            P::Double(v) => v,
            _ => panic!("a list where a scalar was expected"),
        }
    }
    fn list(p: &P) -> Vec<u32> {
        match p {
            P::ListInt(v) => v.iter().map(|&i| i as u32).collect(),
            P::ListUInt(v) => v.clone(),
            _ => panic!("an unexpected list type"),
        }
    }
    for e in ENCODINGS {
        let bytes = fixture(e, RICH_HEADER, &rich_rows());
        let ply = Parser::<DefaultElement>::new()
            .read_ply(&mut bytes.as_slice())
            .unwrap();
        let vertex = &ply.payload["vertex"];
        let f = |el: &DefaultElement, a: &str, b: &str, c: &str| {
            Vec3::new(num(&el[a]) as f32, num(&el[b]) as f32, num(&el[c]) as f32)
        };
        let theirs = MeshData {
            positions: vertex.iter().map(|v| f(v, "x", "y", "z")).collect(),
            indices: ply.payload["face"]
                .iter()
                .flat_map(|face| {
                    let l = list(&face["vertex_indices"]);
                    (1..l.len() - 1).map(move |k| [l[0], l[k], l[k + 1]])
                })
                .collect(),
            normals: Some(vertex.iter().map(|v| f(v, "nx", "ny", "nz")).collect()),
            uvs: Some(
                vertex
                    .iter()
                    .map(|v| Vec2::new(num(&v["s"]) as f32, num(&v["t"]) as f32))
                    .collect(),
            ),
            attributes: Vec::new(),
        };
        let path = put(&format!("ply_rs_{}.ply", tag(e)), &bytes);
        assert_eq!(load(&path).unwrap(), theirs, "{e:?}");
    }
}
