//! Bad mesh files never panic (issue 17, item 9): a property test that mutates small valid mesh
//! files of every format and loads them through `load_mesh_bytes` (every 16th case also from a
//! file through `load_mesh`, which must give the same result).
//!
//! The valid files are made here at test time: ASCII, binary little-endian and binary big-endian
//! PLY from `ply::write` (a 3×3 grid with normals and texture coordinates), an ASCII and a
//! big-endian PLY written by hand (quads and a pentagon, `double` and `ushort` values, a skipped
//! list and a skipped element, `vertex_index`/`s`/`t`), an OBJ from `obj::write` and one by hand
//! (`v`/`vt`/`vn`, quads and a pentagon, negative indices, groups, materials, a `w`), and a glTF
//! asset (two primitives, TRIANGLES and TRIANGLE_STRIP, one with a sparse POSITION accessor, under
//! a translated, rotated, scaled parent node) as `.gltf` with a `data:` URI buffer and as `.glb`.
//!
//! Each case applies one to four mutations, each at one of four levels, which run in this order:
//! the glTF buffer's bytes (then re-encoded, so the container stays consistent), the glTF JSON as
//! a value (a member set to a hostile value, removed, or added), the text (glTF JSON, or the
//! whole file of the other formats: a number replaced by NaN, infinity, a huge or negative value
//! or a small integer near the mesh's counts; a line duplicated or deleted; a format keyword
//! inserted), and last the file's bytes (a bit pattern flipped, truncation anywhere, bytes
//! inserted or deleted, a 1-, 2-, 4- or 8-byte value such as a NaN, `u32::MAX` or a small index
//! written over binary data in the file's byte order). The outcome must be one of:
//!
//! * a mesh that passes `mesh::check` and has only finite positions, normals and texture
//!   coordinates (every reader promises that);
//! * a `MeshError` whose message starts with the file's path and is one line.
//!
//! A panic is caught and reported with the seed file, the mutations, a backtrace and the mutated
//! bytes (escaped, and saved under the temp folder) so that it can be replayed. The runner is
//! seeded (ChaCha, seed `b"lumis mesh mutation, issue 17 .."`), so every run tries the same
//! `CASES` = 200,000 cases (6 to 14 s in release on 2 cores, as busy as they are; 500,000 ran
//! clean once as well); `MESH_MUTATION_CASES` overrides the number, and
//! `MESH_MUTATION_EXPLORE=1` runs them all and lists each kind of failure once instead of
//! stopping (and shrinking) at the first. `MESH_MUTATION_SEED_DIR=DIR` also writes the seed
//! files to `DIR/mesh_obj`, `DIR/mesh_ply` and `DIR/mesh_gltf`, the fuzz targets' corpora
//! (`fuzz/README.md`).

use lumis::scene::mesh::gltf::bytes::{self, base64};
use lumis::scene::mesh::{MeshData, MeshError, check, load_mesh, load_mesh_bytes, obj, ply};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestError, TestRng, TestRunner};
use serde_json::{Value, json};
use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// Cases per run (see the module doc for the time).
const CASES: u32 = 200_000;

// ----------------------------------------------------------------------------------------------
// The valid files.

/// A 3×3 grid of vertices (8 triangles) with normals and texture coordinates: small counts, so
/// that the small integers among the replacement numbers land on and around them.
fn grid() -> MeshData {
    let mut mesh = MeshData {
        normals: Some(Vec::new()),
        uvs: Some(Vec::new()),
        ..MeshData::default()
    };
    for j in 0..3 {
        for i in 0..3 {
            let (u, v) = (i as f32 * 0.5, j as f32 * 0.5);
            mesh.positions
                .push(glam::Vec3::new(u - 0.5, v - 0.5, 0.25 * u * v));
            mesh.normals
                .as_mut()
                .unwrap()
                .push(glam::Vec3::new(-0.1 * v, -0.1 * u, 1.0));
            mesh.uvs.as_mut().unwrap().push(glam::Vec2::new(u, v));
        }
    }
    for j in 0..2u32 {
        for i in 0..2u32 {
            let a = j * 3 + i;
            mesh.indices.push([a, a + 1, a + 4]);
            mesh.indices.push([a, a + 4, a + 3]);
        }
    }
    mesh
}

/// How a seed file is built and which levels its mutations can reach.
#[derive(Clone, Debug, PartialEq)]
enum Kind {
    /// OBJ or ASCII PLY: text all through.
    Text,
    /// Binary PLY: a text header, then data in this byte order (`true`: big-endian).
    BinaryPly { big_endian: bool },
    /// glTF: the JSON and the buffer, packed into a `.gltf` (`glb` false) or a `.glb`.
    Gltf {
        json: Value,
        bin: Vec<u8>,
        glb: bool,
    },
}

/// A valid file to start from.
struct Seed {
    name: &'static str,
    ext: &'static str,
    kind: Kind,
    /// The file (for glTF: packed from `json` and `bin` unmutated).
    bytes: Vec<u8>,
}

/// A per-process folder for the files.
fn dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-mesh-mutations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A PLY header and rows of typed values, encoded as the header's format says.
fn ply_by_hand(header: &str, rows: &[Vec<(char, f64)>], big_endian: Option<bool>) -> Vec<u8> {
    let format = match big_endian {
        None => "ascii",
        Some(false) => "binary_little_endian",
        Some(true) => "binary_big_endian",
    };
    let mut out = format!("ply\nformat {format} 1.0\n{header}end_header\n").into_bytes();
    for row in rows {
        let Some(big) = big_endian else {
            let text: Vec<String> = row.iter().map(|(_, v)| v.to_string()).collect();
            out.extend(text.join(" ").bytes());
            out.push(b'\n');
            continue;
        };
        for &(t, v) in row {
            // b: u8, h: u16, i: i32, f: f32, d: f64.
            let bytes: Vec<u8> = match (t, big) {
                ('b', _) => vec![v as u8],
                ('h', false) => (v as u16).to_le_bytes().to_vec(),
                ('h', true) => (v as u16).to_be_bytes().to_vec(),
                ('i', false) => (v as i32).to_le_bytes().to_vec(),
                ('i', true) => (v as i32).to_be_bytes().to_vec(),
                ('f', false) => (v as f32).to_le_bytes().to_vec(),
                ('f', true) => (v as f32).to_be_bytes().to_vec(),
                ('d', false) => v.to_le_bytes().to_vec(),
                ('d', true) => v.to_be_bytes().to_vec(),
                _ => unreachable!("type {t}"),
            };
            out.extend(bytes);
        }
    }
    out
}

/// A PLY with what `ply::write` does not make: polygons, mixed types, skipped data.
fn rich_ply(big_endian: Option<bool>) -> Vec<u8> {
    let header = "comment by hand\nelement vertex 6\nproperty double x\nproperty float y\n\
                  property float z\nproperty list uchar int extra\nproperty float s\n\
                  property float t\nproperty ushort flags\nelement face 2\n\
                  property list uchar int vertex_index\nproperty uchar material\n\
                  element edge 1\nproperty int vertex1\nproperty int vertex2\n";
    let mut rows = Vec::new();
    for k in 0..6 {
        let (x, y) = ((k % 3) as f64, (k / 3) as f64);
        let mut row = vec![('d', x), ('f', y), ('f', 0.5), ('b', 1.0), ('i', 7.0)];
        row.extend([('f', x / 2.0), ('f', y), ('h', k as f64)]);
        rows.push(row);
    }
    let quad = [0.0, 1.0, 4.0, 3.0];
    let mut row = vec![('b', 4.0)];
    row.extend(quad.map(|i| ('i', i)));
    row.push(('b', 0.0));
    rows.push(row);
    let pentagon = [1.0, 2.0, 5.0, 4.0, 0.0];
    let mut row = vec![('b', 5.0)];
    row.extend(pentagon.map(|i| ('i', i)));
    row.push(('b', 1.0));
    rows.push(row);
    rows.push(vec![('i', 0.0), ('i', 5.0)]);
    ply_by_hand(header, &rows, big_endian)
}

/// An OBJ with what `obj::write` does not make.
const RICH_OBJ: &str = "# by hand\nmtllib none.mtl\no grid\n\
v -1 -1 0\nv 0 -1 0\nv 1 -1 0\nv -1 0 0\nv 0 0 0.5 1\nv 1 0 0\nv -1 1 0\nv 0 1 0\nv 1 1 0\n\
vt 0 0\nvt 0.5 0\nvt 1 0\nvt 0 0.5\nvt 0.5 0.5\nvt 1 0.5\nvt 0 1\nvt 0.5 1\nvt 1 1\n\
vn 0 0 1\nvn 0 0.1 1\ng left\nusemtl red\ns 1\n\
f 1/1/1 2/2/1 5/5/2 4/4/2\nf 4/4/2 5/5/2 8/8/1 7/7/1\ng right\nusemtl blue\n\
f -8/-8/-2 -7/-7/-2 -4/-4/-1 -1/-1/-1 -5/-5/-1\nf 5/5/2 9/9/1 8/8/1\n";

/// The glTF asset: JSON (buffer 0 without a `uri`) and its buffer.
fn gltf_asset() -> (Value, Vec<u8>) {
    let mesh = grid();
    let mut bin = Vec::new();
    let view = |bin: &mut Vec<u8>, bytes: Vec<u8>| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let v = json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len()});
        bin.extend(bytes);
        v
    };
    let floats = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let p: Vec<f32> = mesh.positions.iter().flat_map(|p| p.to_array()).collect();
    let n: Vec<f32> = mesh
        .normals
        .as_ref()
        .unwrap()
        .iter()
        .flat_map(|p| p.to_array())
        .collect();
    let t: Vec<f32> = mesh
        .uvs
        .as_ref()
        .unwrap()
        .iter()
        .flat_map(|p| p.to_array())
        .collect();
    let i: Vec<u8> = mesh
        .indices
        .iter()
        .flatten()
        .flat_map(|&i| (i as u16).to_le_bytes())
        .collect();
    let mut views = vec![
        view(&mut bin, floats(&p)),
        view(&mut bin, floats(&n)),
        view(&mut bin, floats(&t)),
        view(&mut bin, i),
        // A strip over the bottom row pair, u8 indices.
        view(&mut bin, vec![0, 3, 1, 4, 2, 5]),
        // Sparse: vertex 4 moved up.
        view(&mut bin, vec![4]),
        view(&mut bin, floats(&[0.0, 0.0, 0.75])),
    ];
    views[0]["byteStride"] = json!(12);
    views[0]["target"] = json!(34962);
    let json = json!({
        "asset": {"version": "2.0", "generator": "lumis mesh_mutations"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"children": [1], "translation": [0.5, 0.0, -1.0],
             "rotation": [0.0, 0.38268343, 0.0, 0.9238795], "scale": [2.0, 2.0, 2.0]},
            {"mesh": 0, "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0,
                                    0.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]},
        ],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3,
             "material": 0},
            {"attributes": {"POSITION": 5, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 4,
             "mode": 5},
        ]}],
        "materials": [{"name": "grid"}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 9,
             "min": [-0.5, -0.5, 0.0], "max": [0.5, 0.5, 0.25]},
            {"bufferView": 1, "componentType": 5126, "type": "VEC3", "count": 9},
            {"bufferView": 2, "componentType": 5126, "type": "VEC2", "count": 9},
            {"bufferView": 3, "componentType": 5123, "type": "SCALAR", "count": 24},
            {"bufferView": 4, "componentType": 5121, "type": "SCALAR", "count": 6},
            {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 9,
             "sparse": {"count": 1,
                        "indices": {"bufferView": 5, "componentType": 5121},
                        "values": {"bufferView": 6}}},
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    (json, bin)
}

/// The `.gltf` (buffer as a data URI) or `.glb` (BIN chunk) file of `json` and `bin`, from the
/// text of `json` (already given its data URI for `.gltf`).
fn pack(json_text: &str, bin: &[u8], glb: bool) -> Vec<u8> {
    if glb {
        bytes::glb(json_text, Some(bin))
    } else {
        json_text.as_bytes().to_vec()
    }
}

/// Gives a `.gltf`'s buffer 0 its data URI (if the JSON still has a buffer 0 object).
fn embed(json: &mut Value, bin: &[u8]) {
    if let Some(buffer) = json
        .pointer_mut("/buffers/0")
        .and_then(Value::as_object_mut)
    {
        buffer.insert(
            "uri".into(),
            json!(format!(
                "data:application/octet-stream;base64,{}",
                base64(bin)
            )),
        );
    }
}

/// Every seed file; each must load as it is (checked by the test).
fn seeds() -> Vec<Seed> {
    let dir = dir();
    let mesh = grid();
    let written = |name: &str, f: &dyn Fn(&Path) -> std::io::Result<()>| {
        let path = dir.join(name);
        f(&path).unwrap();
        std::fs::read(&path).unwrap()
    };
    let mut seeds = Vec::new();
    for (name, encoding, kind) in [
        ("grid_ascii.ply", ply::Encoding::Ascii, Kind::Text),
        (
            "grid_le.ply",
            ply::Encoding::BinaryLittleEndian,
            Kind::BinaryPly { big_endian: false },
        ),
        (
            "grid_be.ply",
            ply::Encoding::BinaryBigEndian,
            Kind::BinaryPly { big_endian: true },
        ),
    ] {
        seeds.push(Seed {
            name,
            ext: "ply",
            kind,
            bytes: written(name, &|p| ply::write(p, &mesh, encoding)),
        });
    }
    seeds.push(Seed {
        name: "rich_ascii.ply",
        ext: "ply",
        kind: Kind::Text,
        bytes: rich_ply(None),
    });
    seeds.push(Seed {
        name: "rich_be.ply",
        ext: "ply",
        kind: Kind::BinaryPly { big_endian: true },
        bytes: rich_ply(Some(true)),
    });
    seeds.push(Seed {
        name: "grid.obj",
        ext: "obj",
        kind: Kind::Text,
        bytes: written("grid.obj", &|p| obj::write(p, &mesh)),
    });
    seeds.push(Seed {
        name: "rich.obj",
        ext: "obj",
        kind: Kind::Text,
        bytes: RICH_OBJ.as_bytes().to_vec(),
    });
    let (json, bin) = gltf_asset();
    for (name, ext, glb) in [("grid.gltf", "gltf", false), ("grid.glb", "glb", true)] {
        let mut j = json.clone();
        if !glb {
            embed(&mut j, &bin);
        }
        seeds.push(Seed {
            name,
            ext,
            bytes: pack(&j.to_string(), &bin, glb),
            kind: Kind::Gltf {
                json: json.clone(),
                bin: bin.clone(),
                glb,
            },
        });
    }
    seeds
}

// ----------------------------------------------------------------------------------------------
// The mutations.

/// Numbers written over number tokens in text: non-finite, beyond `f32`, beyond the integer
/// types, negative, and small counts and indices around the seeds' own (9 vertices, 8
/// triangles, 24 indices, 6 strip indices), plus tokens that are not numbers at all.
const TEXT_NUMBERS: &[&str] = &[
    "nan",
    "NaN",
    "-nan",
    "inf",
    "-inf",
    "infinity",
    "1e39",
    "-1e39",
    "3.4028236e38",
    "1e-46",
    "1e308",
    "1e309",
    "0",
    "-0",
    "-1",
    "-2",
    "-10",
    "1",
    "2",
    "3",
    "4",
    "5",
    "6",
    "7",
    "8",
    "9",
    "10",
    "12",
    "23",
    "24",
    "25",
    "255",
    "256",
    "65535",
    "65536",
    "2147483647",
    "2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "18446744073709551616",
    "99999999999999999999999",
    "0.5",
    "1.5",
    "-0.5",
    "1e",
    ".",
    "-",
    "0x10",
    "",
    "1/1",
    "//",
    "5126",
    "5125",
    "5123",
    "5121",
    "5120",
    "34962",
];

/// Values written over JSON members.
fn json_values() -> Vec<Value> {
    let mut v: Vec<Value> = [
        0i64, 1, 2, 3, 4, 5, 6, 7, 8, 9, 12, 24, 25, -1, 255, 256, 65535, 65536, 4294967295,
        4294967296,
    ]
    .iter()
    .map(|&n| json!(n))
    .collect();
    v.extend([
        json!(u64::MAX),
        json!(1e300),
        json!(-1e300),
        json!(0.5),
        json!(null),
        json!(true),
        json!(""),
        json!("x.bin"),
        json!("data:application/octet-stream;base64,"),
        json!("data:application/octet-stream;base64,AAAA"),
        json!("data:,text"),
        json!("http://example.com/a.bin"),
        json!([]),
        json!({}),
        json!([0]),
        json!([0, 0, 0]),
        json!([0, 0, 0, 0]),
        json!([1e30, 1e30, 1e30]),
        json!([1e-30, 1e-30, 1e-30]),
        json!([0.0, 0.0, 0.0, 1e30]),
        json!(vec![0.0; 16]),
        json!([1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1]),
        json!([-1.0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]),
        json!([0, 1]),
        json!([1, 0]),
        json!([0, 0]),
        json!(["KHR_draco_mesh_compression"]),
        json!(["EXT_meshopt_compression", "KHR_mesh_quantization"]),
        json!({"count": 1, "indices": {"bufferView": 5, "componentType": 5121},
               "values": {"bufferView": 6}}),
        json!({"count": 9, "indices": {"bufferView": 4, "componentType": 5121},
               "values": {"bufferView": 0}}),
        json!({"POSITION": 0}),
        json!({"POSITION": 1, "NORMAL": 0}),
        json!({"POSITION": 0, "TEXCOORD_0": 4}),
        json!({"buffer": 0, "byteLength": 4}),
        json!({"buffer": 0, "byteOffset": 4294967295u64, "byteLength": 4}),
        json!({"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 100}),
        json!({"nodes": [1, 0]}),
        json!({"mesh": 0, "children": [0]}),
    ]);
    for s in ["SCALAR", "VEC2", "VEC3", "VEC4", "MAT4"] {
        v.push(json!(s));
    }
    for n in [5120, 5121, 5122, 5123, 5124, 5125, 5126] {
        v.push(json!(n));
    }
    v
}

/// Members added to JSON objects.
const JSON_KEYS: &[&str] = &[
    "sparse",
    "byteStride",
    "mode",
    "children",
    "matrix",
    "rotation",
    "scale",
    "translation",
    "normalized",
    "extensionsRequired",
    "extensionsUsed",
    "scene",
    "scenes",
    "nodes",
    "mesh",
    "indices",
    "NORMAL",
    "TEXCOORD_0",
    "POSITION",
    "byteOffset",
    "byteLength",
    "count",
    "bufferView",
    "buffer",
    "uri",
    "min",
    "max",
    "componentType",
    "type",
];

/// Text inserted at a random place: format keywords and line structure.
const INSERTIONS: &[&str] = &[
    "\n",
    "\r\n",
    "\r",
    " ",
    "\t",
    "\0",
    "\u{b}",
    "\u{2028}",
    "\u{85}",
    "\u{ff}",
    "#",
    "/",
    "\\\n",
    "-",
    "f 1 2 3\n",
    "f -1 -2 -3\n",
    "f 1/1/1 2/2/2\n",
    "f 1//1 2//2 3//3\n",
    "f 1 1 1\n",
    "f 10 11 12\n",
    "v 1 2 3\n",
    "v 1 2 3 0\n",
    "v 1 2 3 0.5 0.5 0.5\n",
    "vt 0.5\n",
    "vn 0 0 1\n",
    "l 1 2\n",
    "p 1\n",
    "usemtl\n",
    "o\n",
    "g\n",
    "s off\n",
    "mtllib a.mtl\n",
    "ply\n",
    "format ascii 1.0\n",
    "format binary_big_endian 1.0\n",
    "element face 1\n",
    "element vertex 0\n",
    "element vertex 18446744073709551615\n",
    "property float x\n",
    "property list uchar int vertex_indices\n",
    "property list float int vertex_indices\n",
    "property list uchar float vertex_indices\n",
    "end_header\n",
    "comment\n",
    "3 0 1 2\n",
    "255 0 1 2\n",
    "glTF",
    "JSON",
    "BIN\0",
    "{}",
    "[]",
    ",",
    "\"",
    "null",
];

/// Little- or big-endian values written over binary data: NaNs, infinities, extremes, small
/// indices and counts.
const BINARY_VALUES: &[(u8, u64)] = &[
    (1, 0),
    (1, 1),
    (1, 2),
    (1, 3),
    (1, 9),
    (1, 255),
    (2, 0xffff),
    (2, 9),
    (4, 0),
    (4, 1),
    (4, 8),
    (4, 9),
    (4, 0x7fff_ffff),
    (4, 0x8000_0000),
    (4, 0xffff_ffff),
    (4, 0x7fc0_0000),           // f32 NaN
    (4, 0xffc0_0001),           // f32 NaN, sign and payload
    (4, 0x7f80_0000),           // f32 +inf
    (4, 0xff80_0000),           // f32 -inf
    (4, 0x7f7f_ffff),           // f32::MAX
    (4, 0x0000_0001),           // the smallest f32 subnormal
    (4, 0x8000_0000),           // f32 -0
    (8, 0x7ff8_0000_0000_0000), // f64 NaN
    (8, 0x7ff0_0000_0000_0000), // f64 +inf
    (8, 0x47ef_ffff_e000_0001), // f64 just beyond f32::MAX
    (8, u64::MAX),
];

/// Where a mutation applies; they run in this order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Level {
    /// The glTF buffer (falls back to `Bytes` for other formats).
    Buffer,
    /// The glTF JSON as a value (falls back to `Text`).
    Json,
    /// The glTF JSON text, or the whole file of a text format (binary PLY: the whole file too).
    Text,
    /// The file's bytes.
    Bytes,
}

/// One mutation; indices are resolved against what they mutate when they apply.
#[derive(Clone, Debug)]
enum Mutation {
    /// `byte ^= mask` (mask not 0).
    Flip(Index, u8),
    /// Cut the data at this point.
    Truncate(Index),
    /// Insert arbitrary bytes or one of `INSERTIONS`.
    Insert(Index, Result<Vec<u8>, Index>),
    /// Remove up to this many bytes.
    Delete(Index, u8),
    /// Replace the k-th number token by one of `TEXT_NUMBERS`.
    Number(Index, Index),
    /// Duplicate (`true`) or delete the k-th line.
    Line(Index, bool),
    /// Write one of `BINARY_VALUES` at this offset (of the binary part, if the file has one).
    Binary(Index, Index),
    /// JSON: set the k-th member or element (depth first) to one of `json_values()`.
    Set(Index, Index),
    /// JSON: remove the k-th member or element.
    Remove(Index),
    /// JSON: add one of `JSON_KEYS` with one of `json_values()` to the k-th object.
    Add(Index, Index, Index),
}

/// A test case: a seed file and the mutations.
#[derive(Clone, Debug)]
struct Case {
    seed: Index,
    mutations: Vec<(Level, Mutation)>,
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let i = any::<Index>;
    prop_oneof![
        3 => (i(), 1u8..=255).prop_map(|(a, m)| Mutation::Flip(a, m)),
        2 => i().prop_map(Mutation::Truncate),
        2 => (i(), prop_oneof![
            prop::collection::vec(any::<u8>(), 1..8).prop_map(Ok),
            i().prop_map(Err),
        ]).prop_map(|(a, b)| Mutation::Insert(a, b)),
        1 => (i(), 1u8..16).prop_map(|(a, n)| Mutation::Delete(a, n)),
        5 => (i(), i()).prop_map(|(a, b)| Mutation::Number(a, b)),
        2 => (i(), any::<bool>()).prop_map(|(a, d)| Mutation::Line(a, d)),
        3 => (i(), i()).prop_map(|(a, b)| Mutation::Binary(a, b)),
        4 => (i(), i()).prop_map(|(a, b)| Mutation::Set(a, b)),
        1 => i().prop_map(Mutation::Remove),
        2 => (i(), i(), i()).prop_map(|(a, b, c)| Mutation::Add(a, b, c)),
    ]
}

fn case() -> impl Strategy<Value = Case> {
    let level = prop_oneof![
        Just(Level::Buffer),
        Just(Level::Json),
        Just(Level::Text),
        Just(Level::Bytes)
    ];
    (
        any::<Index>(),
        prop::collection::vec((level, mutation()), 1..=4),
    )
        .prop_map(|(seed, mut mutations)| {
            mutations.sort_by_key(|(level, _)| *level);
            Case { seed, mutations }
        })
}

/// The byte ranges of number-like tokens in `data`.
fn number_tokens(data: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < data.len() {
        let c = data[i];
        let starts = c.is_ascii_digit()
            || (matches!(c, b'-' | b'.' | b'+') && data.get(i + 1).is_some_and(u8::is_ascii_digit));
        let after_word = i > 0 && (data[i - 1].is_ascii_alphanumeric() || data[i - 1] == b'_');
        if starts && !after_word {
            let start = i;
            i += 1;
            while i < data.len()
                && matches!(data[i], b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-')
            {
                i += 1;
            }
            out.push((start, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Applies a byte- or text-level mutation to `data`; `binary` is where binary data starts and
/// its byte order (binary PLY: after the header; a glTF buffer: all of it, little-endian).
fn mutate_bytes(data: &mut Vec<u8>, m: &Mutation, binary: Option<(usize, bool)>) {
    let len = data.len();
    match m {
        Mutation::Flip(at, mask) if len > 0 => data[at.index(len)] ^= mask,
        Mutation::Truncate(at) => data.truncate(at.index(len + 1)),
        Mutation::Insert(at, what) => {
            let bytes = match what {
                Ok(b) => b.clone(),
                Err(k) => k.get(INSERTIONS).as_bytes().to_vec(),
            };
            let at = at.index(len + 1);
            data.splice(at..at, bytes);
        }
        Mutation::Delete(at, n) if len > 0 => {
            let at = at.index(len);
            data.drain(at..(at + *n as usize).min(len));
        }
        Mutation::Number(k, value) => {
            let tokens = number_tokens(data);
            if !tokens.is_empty() {
                let (a, b) = tokens[k.index(tokens.len())];
                data.splice(a..b, value.get(TEXT_NUMBERS).bytes());
            }
        }
        Mutation::Line(k, duplicate) => {
            let starts: Vec<usize> = std::iter::once(0)
                .chain(
                    data.iter()
                        .enumerate()
                        .filter(|&(_, &c)| c == b'\n')
                        .map(|(i, _)| i + 1),
                )
                .filter(|&s| s < len)
                .collect();
            if !starts.is_empty() {
                let k = k.index(starts.len());
                let (a, b) = (starts[k], starts.get(k + 1).copied().unwrap_or(len));
                if *duplicate {
                    let line = data[a..b].to_vec();
                    data.splice(b..b, line);
                } else {
                    data.drain(a..b);
                }
            }
        }
        Mutation::Binary(at, value) => {
            let (start, big_endian) = binary.unwrap_or((0, false));
            let &(size, v) = value.get(BINARY_VALUES);
            let size = size as usize;
            if len >= start + size {
                let at = start + at.index(len - start - size + 1);
                let bytes = v.to_le_bytes();
                let mut bytes = bytes[..size].to_vec();
                if big_endian {
                    bytes.reverse();
                }
                data[at..at + size].copy_from_slice(&bytes);
            }
        }
        // JSON mutations of a seed without JSON: a byte flip instead.
        Mutation::Set(at, _) | Mutation::Remove(at) | Mutation::Add(at, _, _) if len > 0 => {
            data[at.index(len)] ^= 0x20
        }
        _ => {}
    }
}

/// The JSON pointers of every member and element of `v`, depth first, and of its objects.
fn json_paths(v: &Value, here: String, slots: &mut Vec<String>, objects: &mut Vec<String>) {
    match v {
        Value::Object(map) => {
            objects.push(here.clone());
            for (k, child) in map {
                let p = format!("{here}/{}", k.replace('~', "~0").replace('/', "~1"));
                slots.push(p.clone());
                json_paths(child, p, slots, objects);
            }
        }
        Value::Array(items) => {
            for (i, child) in items.iter().enumerate() {
                let p = format!("{here}/{i}");
                slots.push(p.clone());
                json_paths(child, p, slots, objects);
            }
        }
        _ => {}
    }
}

/// Applies a JSON-level mutation (others: nothing; they go to the text level).
fn mutate_json(json: &mut Value, m: &Mutation, values: &[Value]) -> bool {
    let (mut slots, mut objects) = (Vec::new(), Vec::new());
    json_paths(json, String::new(), &mut slots, &mut objects);
    match m {
        Mutation::Set(k, value) => {
            let p = &slots[k.index(slots.len())];
            *json.pointer_mut(p).expect("a path just listed") = value.get(values).clone();
        }
        Mutation::Remove(k) => {
            let p = &slots[k.index(slots.len())];
            let (parent, last) = p.rsplit_once('/').expect("a member path");
            match json.pointer_mut(parent).expect("a path just listed") {
                Value::Object(map) => {
                    map.remove(&last.replace("~1", "/").replace("~0", "~"));
                }
                Value::Array(items) => {
                    items.remove(last.parse::<usize>().expect("an index"));
                }
                _ => unreachable!("a parent is a container"),
            }
        }
        Mutation::Add(k, key, value) => {
            let p = &objects[k.index(objects.len())];
            if let Some(map) = json.pointer_mut(p).and_then(Value::as_object_mut) {
                map.insert((*key.get(JSON_KEYS)).into(), value.get(values).clone());
            }
        }
        _ => return false,
    }
    true
}

/// The mutated file of `case`.
fn build(seed: &Seed, case: &Case, values: &[Value]) -> Vec<u8> {
    let mut mutations = case.mutations.iter().peekable();
    let mut file = match &seed.kind {
        Kind::Gltf { json, bin, glb } => {
            let mut bin = bin.clone();
            while let Some((_, m)) = mutations.next_if(|(l, _)| *l == Level::Buffer) {
                mutate_bytes(&mut bin, m, Some((0, false)));
            }
            let mut json = json.clone();
            if !glb {
                embed(&mut json, &bin);
            }
            let mut deferred = Vec::new();
            while let Some((_, m)) = mutations.next_if(|(l, _)| *l == Level::Json) {
                if !mutate_json(&mut json, m, values) {
                    deferred.push(m);
                }
            }
            let mut text = json.to_string().into_bytes();
            for m in deferred {
                mutate_bytes(&mut text, m, None);
            }
            while let Some((_, m)) = mutations.next_if(|(l, _)| *l == Level::Text) {
                mutate_bytes(&mut text, m, None);
            }
            let text = String::from_utf8_lossy(&text);
            pack(&text, &bin, *glb)
        }
        _ => seed.bytes.clone(),
    };
    for (_, m) in mutations {
        let binary = match seed.kind {
            Kind::BinaryPly { big_endian } => {
                let end = b"end_header\n";
                let start = file
                    .windows(end.len())
                    .position(|w| w == end)
                    .map(|i| i + end.len());
                Some((start.unwrap_or(0), big_endian))
            }
            Kind::Gltf { glb: true, .. } => Some((0, false)),
            _ => None,
        };
        mutate_bytes(&mut file, m, binary);
    }
    file
}

// ----------------------------------------------------------------------------------------------
// The outcome.

/// What a mutated file did.
enum Outcome {
    Loaded,
    Rejected,
}

/// Loads `path` and judges the result; `Err` is a broken promise.
fn judge(path: &Path, result: Result<MeshData, MeshError>) -> Result<Outcome, String> {
    let name = path.display().to_string();
    match result {
        Ok(mesh) => {
            check(path, &mesh).map_err(|e| format!("loaded, but fails check: {e}"))?;
            if mesh.indices.is_empty() {
                return Err("loaded a mesh without triangles".into());
            }
            let p = mesh.positions.iter().position(|p| !p.is_finite());
            let n = mesh.normals.iter().flatten().position(|p| !p.is_finite());
            let t = mesh.uvs.iter().flatten().position(|p| !p.is_finite());
            for (what, i) in [("position", p), ("normal", n), ("texture coordinate", t)] {
                if let Some(i) = i {
                    return Err(format!("loaded, but {what} {i} is not finite"));
                }
            }
            Ok(Outcome::Loaded)
        }
        Err(MeshError(message)) => {
            if !message.starts_with(&name) {
                return Err(format!("error does not name the file: {message:?}"));
            }
            let breaks = [
                '\n', '\r', '\u{b}', '\u{c}', '\u{85}', '\u{2028}', '\u{2029}',
            ];
            if message.contains(breaks) {
                return Err(format!("error is not one line: {message:?}"));
            }
            Ok(Outcome::Rejected)
        }
    }
}

/// The message and backtrace of the last panic, from the hook.
static PANIC: Mutex<Option<String>> = Mutex::new(None);

/// The frames of a backtrace up to the test harness, without the panic machinery.
fn short_backtrace(text: &str) -> String {
    let mut out = Vec::new();
    for line in text.lines() {
        if line.contains("catch_unwind") {
            break;
        }
        if !["panicking", "rust_begin_unwind", "backtrace", "/rustc/"]
            .iter()
            .any(|m| line.contains(m))
        {
            out.push(line);
        }
    }
    out.join("\n")
}

#[test]
fn mutated_mesh_files_load_or_fail_with_a_located_one_line_error() {
    let seeds = seeds();
    let dir = dir();
    let values = json_values();
    // MESH_MUTATION_SEED_DIR=fuzz/corpus: the seeds become the fuzz targets' corpora.
    let corpus = std::env::var_os("MESH_MUTATION_SEED_DIR").map(PathBuf::from);
    // Every seed loads as it is, or the mutations start from an error.
    for seed in &seeds {
        let path = dir.join(seed.name);
        std::fs::write(&path, &seed.bytes).unwrap();
        if let Some(corpus) = &corpus {
            let target = match seed.ext {
                "glb" => "gltf",
                ext => ext,
            };
            let folder = corpus.join(format!("mesh_{target}"));
            std::fs::create_dir_all(&folder).unwrap();
            std::fs::write(folder.join(seed.name), &seed.bytes).unwrap();
        }
        let mesh = load_mesh(&path).unwrap_or_else(|e| panic!("seed {}: {e}", seed.name));
        assert!(matches!(judge(&path, Ok(mesh)), Ok(Outcome::Loaded)));
    }
    let cases = std::env::var("MESH_MUTATION_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES);

    let default_hook = panic::take_hook();
    panic::set_hook(Box::new(|info| {
        let bt = std::backtrace::Backtrace::force_capture();
        *PANIC.lock().unwrap_or_else(|e| e.into_inner()) = Some(format!("{info}\n{bt}"));
    }));
    let config = Config {
        cases,
        rng_algorithm: RngAlgorithm::ChaCha,
        failure_persistence: None,
        max_shrink_iters: 1024,
        ..Config::default()
    };
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, b"lumis mesh mutation, issue 17 ..");
    let mut runner = TestRunner::new_with_rng(config, rng);
    let explore = std::env::var_os("MESH_MUTATION_EXPLORE").is_some();
    // Per seed: loaded, rejected.
    let tally = Mutex::new(vec![(0u64, 0u64); seeds.len()]);
    let found = Mutex::new(BTreeMap::<String, (u64, String)>::new());
    let start = Instant::now();
    let case_number = std::cell::Cell::new(0u64);
    let result = runner.run(&case(), |case| {
        let s = case.seed.index(seeds.len());
        let seed = &seeds[s];
        let bytes = build(seed, &case, &values);
        let path = dir.join(format!("mutant.{}", seed.ext));
        // Mostly from memory: rewriting a file costs about a millisecond on ext4 (it flushes a
        // replaced file's blocks), far more than reading it. Every 16th case also goes through
        // the file, and both entries must agree.
        let through_file = case_number.get().is_multiple_of(16);
        case_number.set(case_number.get() + 1);
        let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
            let result = load_mesh_bytes(&path, &bytes);
            if through_file {
                std::fs::write(&path, &bytes).unwrap();
                let from_file = load_mesh(&path);
                if from_file != result {
                    return Err(format!(
                        "load_mesh gives {from_file:?} but load_mesh_bytes {result:?}"
                    ));
                }
            }
            judge(&path, result)
        }));
        let failure = match outcome {
            Ok(Ok(outcome)) => {
                let mut t = tally.lock().unwrap();
                match outcome {
                    Outcome::Loaded => t[s].0 += 1,
                    Outcome::Rejected => t[s].1 += 1,
                }
                return Ok(());
            }
            Ok(Err(m)) => m,
            Err(_) => {
                let p = PANIC.lock().unwrap_or_else(|e| e.into_inner()).take();
                format!("panic: {}", short_backtrace(&p.unwrap_or_default()))
            }
        };
        // The input, to replay: saved beside the seeds, and escaped in the report.
        let saved = dir.join(format!(
            "failure-{}.{}",
            start.elapsed().as_nanos(),
            seed.ext
        ));
        std::fs::write(&saved, &bytes).unwrap();
        let report = format!(
            "{failure}\nfrom {} with {:?}\nsaved as {}\nbytes: b\"{}\"",
            seed.name,
            case.mutations,
            saved.display(),
            bytes.escape_ascii()
        );
        if explore {
            let kind = format!(
                "{}: {}",
                seed.ext,
                failure.lines().next().unwrap_or_default()
            );
            let mut seen = found.lock().unwrap_or_else(|e| e.into_inner());
            seen.entry(kind).or_insert((0, report)).0 += 1;
            return Ok(());
        }
        Err(TestCaseError::fail(report))
    });
    panic::set_hook(default_hook);
    let found = found.into_inner().unwrap_or_else(|e| e.into_inner());
    for (kind, (count, example)) in &found {
        let _ = writeln!(std::io::stderr(), "=== {count}× {kind}\n{example}\n");
    }
    let tally = tally.into_inner().unwrap();
    let seconds = start.elapsed().as_secs_f64();
    let per_seed: Vec<String> = seeds
        .iter()
        .zip(&tally)
        .map(|(s, (l, r))| format!("{} {l}/{r}", s.name))
        .collect();
    // Straight to stderr, past the harness's capture: the counts belong in CI's log.
    let _ = writeln!(
        std::io::stderr(),
        "mesh_mutations: {cases} cases in {seconds:.1} s; loaded/rejected per seed: {}",
        per_seed.join(", ")
    );
    assert!(
        found.is_empty(),
        "{} kinds of failure, listed above",
        found.len()
    );
    match result {
        Ok(()) => {}
        Err(TestError::Fail(reason, _)) => panic!("{reason}"),
        Err(e) => panic!("{e}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
    // Both outcomes must be common for every seed (at least 1 in 50; loading is the rarer, from
    // about 4% for the ASCII PLYs to 13% for the binary ones), or the mutations are too weak or
    // too strong to mean much there.
    for (seed, &(loaded, rejected)) in seeds.iter().zip(&tally) {
        let n = loaded + rejected;
        assert!(
            loaded * 50 > n && rejected * 50 > n,
            "{}: {loaded} loaded, {rejected} rejected",
            seed.name
        );
    }
}
