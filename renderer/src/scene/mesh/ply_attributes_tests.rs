//! Tests of the PLY reader's and writer's named attributes (Mitsuba's `vertex_*` and `face_*`
//! properties, `ply_attributes.rs`), on fixtures made value by value with `ply_tests.rs`'
//! helpers.

use super::tests::{ENCODINGS, V, fixture, put, scrambled_mesh, tag, test_dir};
use super::*;

/// The sRGB decoding (to linear) of `v / max`, as Mitsuba's converter reads an integer
/// property: written out from the sRGB definition, not the reader's function.
fn decoded(v: f64, max: f64) -> f32 {
    let s = v / max;
    let linear = if s <= 0.04045 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    };
    linear as f32
}

/// A square and a triangle with Mitsuba-style attributes: `red green blue alpha` as `uchar`
/// (`vertex_color`, 4 components), `rough_0` (`vertex_rough`), properties Mitsuba ignores
/// (`foo` without postfix, `bar_x bar_y` with two components, `baz_q`), `tint_r tint_g tint_b`
/// (`vertex_tint_color`), and `color_0 color_1 color_2` on the faces (`face_color`).
pub(super) const ATTRIBUTE_HEADER: &str = "element vertex 4\n\
property float x\nproperty float y\nproperty float z\n\
property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n\
property float rough_0\nproperty float foo\nproperty float bar_x\nproperty float bar_y\n\
property float baz_q\nproperty float tint_r\nproperty float tint_g\nproperty float tint_b\n\
element face 2\n\
property list uchar int vertex_indices\n\
property float color_0\nproperty float color_1\nproperty float color_2\n";

const ATTRIBUTE_RGBA: [[u8; 4]; 4] = [
    [0, 128, 255, 255],
    [10, 11, 12, 0],
    [200, 100, 50, 7],
    [1, 2, 3, 4],
];
const ATTRIBUTE_FACE_COLORS: [[f32; 3]; 2] = [[0.1, 0.2, 0.3], [1.5, -1.0, 0.0]];

pub(super) fn attribute_rows() -> Vec<Vec<V>> {
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut rows: Vec<Vec<V>> = (0..4)
        .map(|i| {
            let [r, g, b, a] = ATTRIBUTE_RGBA[i];
            vec![
                V::F(square[i][0]),
                V::F(square[i][1]),
                V::F(0.0),
                V::U8(r),
                V::U8(g),
                V::U8(b),
                V::U8(a),
                V::F(0.25 * i as f32),
                V::F(9.0),
                V::F(1.0),
                V::F(2.0),
                V::F(3.0),
                V::F(0.1 * i as f32),
                V::F(0.5),
                V::F(-2.0),
            ]
        })
        .collect();
    let [c0, c1] = ATTRIBUTE_FACE_COLORS;
    rows.push(vec![
        V::U8(4),
        V::I32(0),
        V::I32(1),
        V::I32(2),
        V::I32(3),
        V::F(c0[0]),
        V::F(c0[1]),
        V::F(c0[2]),
    ]);
    rows.push(vec![
        V::U8(3),
        V::I32(3),
        V::I32(2),
        V::I32(1),
        V::F(c1[0]),
        V::F(c1[1]),
        V::F(c1[2]),
    ]);
    rows
}

#[test]
fn attributes_are_read_and_named_as_mitsuba_does() {
    let attribute = |name: &str, dim: u8, values: Vec<Vec3>| MeshAttribute {
        name: name.into(),
        dim,
        values,
    };
    let [c0, c1] = ATTRIBUTE_FACE_COLORS.map(Vec3::from_array);
    let expected = vec![
        // The alpha (the fourth component) is dropped from the values; `uchar` is read as
        // stored (Mitsuba 3.9.1 normalizes every integer type but `uchar`).
        attribute(
            "vertex_color",
            4,
            ATTRIBUTE_RGBA
                .iter()
                .map(|c| Vec3::new(c[0].into(), c[1].into(), c[2].into()))
                .collect(),
        ),
        attribute(
            "vertex_rough",
            1,
            (0..4).map(|i| Vec3::splat(0.25 * i as f32)).collect(),
        ),
        attribute(
            "vertex_tint_color",
            3,
            (0..4)
                .map(|i| Vec3::new(0.1 * i as f32, 0.5, -2.0))
                .collect(),
        ),
        // The square's value once per triangle of its fan.
        attribute("face_color", 3, vec![c0, c0, c1]),
    ];
    assert_eq!(expected[0].values[0], Vec3::new(0.0, 128.0, 255.0));
    for e in ENCODINGS {
        let path = put(
            &format!("attributes_{}.ply", tag(e)),
            &fixture(e, ATTRIBUTE_HEADER, &attribute_rows()),
        );
        let mesh = load(&path).unwrap();
        assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3], [3, 2, 1]], "{e:?}");
        assert_eq!(mesh.attributes, expected, "{e:?}");
    }
}

#[test]
fn float_rgb_and_signed_integer_attributes_around_the_index_list() {
    // `r g b` floats as stored; `k_1 k_2 k_3` (short) on both sides of the index list, which is
    // reserved and so does not end the run: `face_k`, normalized by 32767 (also -32768, to
    // below -1) and sRGB-decoded.
    let header = "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n\
                  property float r\nproperty float g\nproperty float b\n\
                  element face 2\nproperty short k_1\nproperty list uchar uint vertex_index\n\
                  property short k_2\nproperty short k_3\n";
    let mut rows: Vec<Vec<V>> = (0..4)
        .map(|i| {
            let f = i as f32;
            vec![
                V::D(f64::from(i % 2)),
                V::D(f64::from(i / 2)),
                V::D(0.0),
                V::F(0.5 * f),
                V::F(2.0),
                V::F(-0.25 * f),
            ]
        })
        .collect();
    rows.push(vec![
        V::I16(-32768),
        V::U8(3),
        V::U32(0),
        V::U32(1),
        V::U32(2),
        V::I16(0),
        V::I16(32767),
    ]);
    rows.push(vec![
        V::I16(1000),
        V::U8(4),
        V::U32(0),
        V::U32(1),
        V::U32(3),
        V::U32(2),
        V::I16(-1),
        V::I16(20000),
    ]);
    let k1 = Vec3::new(
        decoded(1000.0, 32767.0),
        decoded(-1.0, 32767.0),
        decoded(20000.0, 32767.0),
    );
    let expected = vec![
        MeshAttribute {
            name: "vertex_color".into(),
            dim: 3,
            values: (0..4)
                .map(|i| Vec3::new(0.5 * i as f32, 2.0, -0.25 * i as f32))
                .collect(),
        },
        MeshAttribute {
            name: "face_k".into(),
            dim: 3,
            values: vec![
                Vec3::new((-32768.0 / 32767.0 / 12.92) as f32, 0.0, 1.0),
                k1,
                k1,
            ],
        },
    ];
    for e in ENCODINGS {
        let path = put(
            &format!("rgb_short_{}.ply", tag(e)),
            &fixture(e, header, &rows),
        );
        let mesh = load(&path).unwrap();
        assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 1, 3], [0, 3, 2]], "{e:?}");
        assert_eq!(mesh.attributes, expected, "{e:?}");
    }
}

/// Attributes as names and property indices.
type Sources = Vec<(String, Vec<usize>)>;

/// `attribute_sources` over a vertex element of float properties named `names` (`list NAME`:
/// a list).
fn sources_of(names: &[&str]) -> Sources {
    let property = |n: &&str| match n.strip_prefix("list ") {
        Some(name) => Property {
            name: name.into(),
            kind: Kind::List {
                len: Scalar::U8,
                item: Scalar::I32,
            },
        },
        None => Property {
            name: (*n).into(),
            kind: Kind::Scalar(Scalar::F32),
        },
    };
    let element = Element {
        name: "vertex".into(),
        count: 1,
        properties: names.iter().map(property).collect(),
    };
    attribute_sources(&element, AttributeKind::Vertex)
        .into_iter()
        .map(|s| (s.name, s.properties))
        .collect()
}

/// Mitsuba 3.9.1's `find_other_fields`, traced by hand on its quirks (see `attribute_sources`).
#[test]
fn attribute_runs_follow_mitsubas_loop_and_its_quirks() {
    let one = |name: &str, p: &[usize]| vec![(name.to_owned(), p.to_vec())];
    let cases: Vec<(&[&str], Sources)> = vec![
        // The four sequences; `r g b` adds `_color`; a reserved name does not end a run.
        (
            &["a_x", "u", "a_y", "nx", "a_z"],
            one("vertex_a", &[0, 2, 4]),
        ),
        (&["a_r", "a_g", "a_b"], one("vertex_a_color", &[0, 1, 2])),
        (&["a_0", "a_1", "a_2"], one("vertex_a", &[0, 1, 2])),
        (&["a_1", "a_2", "a_3"], one("vertex_a", &[0, 1, 2])),
        (&["a_1"], one("vertex_a", &[0])),
        // A name without `_` (not reserved: `r g b a` are) or with a longer postfix ends the run.
        (&["a_x", "m", "a_y"], one("vertex_a", &[0])),
        (&["a_x", "b", "a_y", "a_z"], one("vertex_a", &[0, 2, 3])),
        (&["a_x", "a_yy", "a_z"], one("vertex_a", &[0])),
        // 2 or 4 components are dropped, and the prefix may start again.
        (&["p_x", "p_y", "k", "p_0"], one("vertex_p", &[3])),
        (&["q_r", "q_g", "q_b", "q_a"], vec![]),
        // A fifth property breaks the sequence.
        (&["w_x", "w_y", "w_z", "w_w", "w_v"], vec![]),
        // A postfix that cannot start a run is skipped.
        (&["a_q", "a_x"], one("vertex_a", &[1])),
        // A kept prefix skips what starts with it and one property more (`e_x`).
        (
            &["c_0", "d", "c_1", "cc_x", "e_x", "f_0"],
            vec![("vertex_c".into(), vec![0]), ("vertex_f".into(), vec![5])],
        ),
        // A broken sequence drops the run, skips the same way, and leaves the count at 1: a
        // lone `bar_x` then has 2 components, and `bar_x bar_z` 3, found by name (`bar_y` is
        // earlier); without `bar_y` Mitsuba fails to load the file, and lumis drops it.
        (&["foo_x", "foo_y", "foo_w", "gap", "bar_x"], vec![]),
        (
            &["foo_0", "foo_2", "gap", "bar_y", "bar_x", "bar_z"],
            one("vertex_bar", &[4, 3, 5]),
        ),
        (&["foo_0", "foo_2", "gap", "bar_x", "bar_z"], vec![]),
        // Colours: `red green blue alpha` renamed to `r g b a`, only when `r g b` is
        // incomplete; the first field named `r` wins; `alpha` beside `r g b` is ignored.
        (
            &["red", "green", "blue", "alpha"],
            one("vertex_color", &[0, 1, 2, 3]),
        ),
        (
            &["r", "red", "green", "blue"],
            one("vertex_color", &[0, 2, 3]),
        ),
        (&["r", "g", "b", "alpha", "a_0"], {
            let mut v = one("vertex_color", &[0, 1, 2]);
            v.extend(one("vertex_a", &[4]));
            v
        }),
        // `r g b` and `color_0 …` would both be `vertex_color`: Mitsuba refuses the file,
        // lumis keeps the first.
        (
            &["r", "g", "b", "color_0", "color_1", "color_2"],
            one("vertex_color", &[0, 1, 2]),
        ),
        // `s t` become `u v` (reserved) unless `u v` are there.
        (
            &["k_0", "s", "k_1", "t", "k_2"],
            one("vertex_k", &[0, 2, 4]),
        ),
        (
            &["u", "v", "k_0", "s", "k_1", "t", "k_2"],
            one("vertex_k", &[2]),
        ),
        // A list is `name.count i0 i1 i2` to Mitsuba: it ends a run.
        (&["k_0", "list k_list", "k_1"], one("vertex_k", &[0])),
    ];
    for (names, expected) in cases {
        assert_eq!(sources_of(names), expected, "{names:?}");
    }
}

#[test]
fn a_non_finite_attribute_value_names_the_element_and_property() {
    for e in ENCODINGS {
        let line = |n: usize| {
            if e == Encoding::Ascii {
                format!(" (line {n})")
            } else {
                String::new()
            }
        };
        let mut rows = attribute_rows();
        rows[2][7] = V::F(f32::NAN);
        let path = put(
            &format!("nan_attribute_{}.ply", tag(e)),
            &fixture(e, ATTRIBUTE_HEADER, &rows),
        );
        assert_eq!(
            load(&path).unwrap_err().0,
            format!(
                "{} element vertex 2{}: rough_0 is NaN",
                path.display(),
                line(27)
            )
        );
        let mut rows = attribute_rows();
        rows[5][5] = V::F(f32::INFINITY);
        let path = put(
            &format!("inf_attribute_{}.ply", tag(e)),
            &fixture(e, ATTRIBUTE_HEADER, &rows),
        );
        assert_eq!(
            load(&path).unwrap_err().0,
            format!(
                "{} element face 1{}: color_1 is infinite",
                path.display(),
                line(30)
            )
        );
    }
}

/// `mesh` with a colour and a one-component attribute on its vertices and faces.
fn with_attributes(mut mesh: MeshData) -> MeshData {
    let wave = |n: usize, k: f32| -> Vec<Vec3> {
        (0..n)
            .map(|i| {
                let t = i as f32 * k;
                Vec3::new(t.sin(), t.cos() * 3.0, -t)
            })
            .collect()
    };
    let (v, f) = (mesh.positions.len(), mesh.indices.len());
    mesh.attributes = vec![
        MeshAttribute {
            name: "vertex_color".into(),
            dim: 3,
            values: wave(v, 0.37),
        },
        MeshAttribute {
            name: "vertex_rough".into(),
            dim: 1,
            values: wave(v, 0.11).iter().map(|p| Vec3::splat(p.x)).collect(),
        },
        MeshAttribute {
            name: "face_color".into(),
            dim: 3,
            values: wave(f, 0.53),
        },
        MeshAttribute {
            name: "face_id".into(),
            dim: 1,
            values: (0..f).map(|i| Vec3::splat(i as f32)).collect(),
        },
    ];
    mesh
}

#[test]
fn attributes_round_trip_through_the_writer() {
    let meshes = [
        with_attributes(scrambled_mesh(40, 60, true, true)),
        with_attributes(scrambled_mesh(3, 1, false, false)),
    ];
    for (m, mesh) in meshes.iter().enumerate() {
        for e in ENCODINGS {
            let path = test_dir().join(format!("attribute_trip_{m}_{}.ply", tag(e)));
            write(&path, mesh, e).unwrap();
            assert_eq!(load(&path).unwrap(), *mesh, "mesh {m} {e:?}");
        }
    }
    // The properties the writer chose, which Mitsuba reads as the same names.
    let path = test_dir().join("attribute_trip_header.ply");
    write(&path, &meshes[1], Encoding::Ascii).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(
        text.contains(
            "property float z\nproperty float color_0\nproperty float color_1\n\
             property float color_2\nproperty float rough_0\nelement face 1\n\
             property list uchar uint vertex_indices\nproperty float color_0\n\
             property float color_1\nproperty float color_2\nproperty float id_0\nend_header\n"
        ),
        "{text}"
    );
}

#[test]
fn the_writer_refuses_attributes_that_cannot_round_trip() {
    let refused = |edit: &dyn Fn(&mut MeshAttribute)| {
        let mut mesh = with_attributes(scrambled_mesh(3, 1, false, false));
        edit(&mut mesh.attributes[0]);
        let path = test_dir().join("refused_attribute.ply");
        let err = write(&path, &mesh, Encoding::BinaryLittleEndian).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);
        err.to_string()
    };
    assert_eq!(
        refused(&|a| a.dim = 4),
        "PLY attribute 'vertex_color': 4 components (r g b a) cannot be written: the values \
         hold only 3"
    );
    assert_eq!(
        refused(&|a| a.name = "colour".into()),
        "PLY attribute 'colour': the name must start with 'vertex_' or 'face_'"
    );
    assert_eq!(
        refused(&|a| a.name = "vertex_rough".into()),
        "PLY attribute 'vertex_rough': a second attribute of that name"
    );
    assert_eq!(
        refused(&|a| {
            a.values.pop();
        }),
        "PLY attribute 'vertex_color': 2 values for 3"
    );
}
