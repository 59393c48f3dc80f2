//! The valid files the mutations start from (see `main.rs`).

use lumis::scene::mesh::gltf::bytes::{self, base64};
use lumis::scene::mesh::{MeshData, obj, ply};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};

/// A 3×3 grid of vertices (8 triangles) with normals and texture coordinates: small counts, so
/// that the small integers among the replacement numbers land on and around them.
pub(crate) fn grid() -> MeshData {
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
pub(crate) enum Kind {
    /// OBJ or ASCII PLY: text all through.
    Text,
    /// Binary PLY: a text header, then data in this byte order (`true`: big-endian).
    BinaryPly { big_endian: bool },
    /// An OBJ opened on its own with its `.mtl` ([`MTL_NAME`], beside it in a folder): the OBJ
    /// text is mutated at the text and byte levels, the `.mtl` text at the buffer and JSON
    /// levels (which have no buffer or JSON to mutate here).
    ObjMtl { mtl: Vec<u8> },
    /// glTF: the JSON and the buffer, packed into a `.gltf` (`glb` false) or a `.glb`.
    Gltf {
        json: Value,
        bin: Vec<u8>,
        glb: bool,
    },
}

/// A valid file to start from.
pub(crate) struct Seed {
    pub(crate) name: &'static str,
    pub(crate) ext: &'static str,
    pub(crate) kind: Kind,
    /// The file (for glTF: packed from `json` and `bin` unmutated).
    pub(crate) bytes: Vec<u8>,
}

/// A per-process folder for the files.
pub(crate) fn dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lumis-mesh-mutations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A PLY header and rows of typed values, encoded as the header's format says.
pub(crate) fn ply_by_hand(
    header: &str,
    rows: &[Vec<(char, f64)>],
    big_endian: Option<bool>,
) -> Vec<u8> {
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
pub(crate) fn rich_ply(big_endian: Option<bool>) -> Vec<u8> {
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
pub(crate) const RICH_OBJ: &str = "# by hand\nmtllib none.mtl\no grid\n\
v -1 -1 0\nv 0 -1 0\nv 1 -1 0\nv -1 0 0\nv 0 0 0.5 1\nv 1 0 0\nv -1 1 0\nv 0 1 0\nv 1 1 0\n\
vt 0 0\nvt 0.5 0\nvt 1 0\nvt 0 0.5\nvt 0.5 0.5\nvt 1 0.5\nvt 0 1\nvt 0.5 1\nvt 1 1\n\
vn 0 0 1\nvn 0 0.1 1\ng left\nusemtl red\ns 1\n\
f 1/1/1 2/2/1 5/5/2 4/4/2\nf 4/4/2 5/5/2 8/8/1 7/7/1\ng right\nusemtl blue\n\
f -8/-8/-2 -7/-7/-2 -4/-4/-1 -1/-1/-1 -5/-5/-1\nf 5/5/2 9/9/1 8/8/1\n";

/// Triangle strips over the 3×3 grid (the Igea head's layout: `list int int`, −1 between
/// strips), as two elements, the second joined to its first strip by degenerate triangles and
/// with a property to skip; the binary seed also has a `face` element (read before the strips)
/// and `uchar` list lengths.
pub(crate) fn strips_ply(big_endian: Option<bool>) -> Vec<u8> {
    let binary = big_endian.is_some();
    let len = if binary { ('b', "uchar") } else { ('i', "int") };
    let mut header = "comment triangle strips\nelement vertex 9\nproperty float x\n\
                      property float y\nproperty float z\n"
        .to_owned();
    if binary {
        header += "element face 1\nproperty list uchar int vertex_indices\n";
    }
    header += &format!(
        "element tristrips 2\nproperty list {} int vertex_indices\nproperty uchar flags\n",
        len.1
    );
    let mut rows: Vec<Vec<(char, f64)>> = grid()
        .positions
        .iter()
        .map(|p| vec![('f', p.x as f64), ('f', p.y as f64), ('f', p.z as f64)])
        .collect();
    if binary {
        rows.push(vec![('b', 3.0), ('i', 0.0), ('i', 1.0), ('i', 4.0)]);
    }
    let strips: [&[f64]; 2] = [
        &[0.0, 3.0, 1.0, 4.0, -1.0, 1.0, 4.0, 2.0, 5.0],
        &[3.0, 6.0, 4.0, 7.0, 7.0, 4.0, 4.0, 7.0, 5.0, 8.0],
    ];
    for strip in strips {
        let mut row = vec![(len.0, strip.len() as f64)];
        row.extend(strip.iter().map(|&i| ('i', i)));
        row.push(('b', 1.0));
        rows.push(row);
    }
    ply_by_hand(&header, &rows, big_endian)
}

/// Where the OBJ+MTL seed's `.mtl` is, relative to the OBJ's folder.
pub(crate) const MTL_NAME: &str = "mats/grid.mtl";

/// The OBJ+MTL seed's `.mtl`: a plastic with a texture and its options, a transparent diffuse,
/// an emitter, and statements lumis names but does not render.
pub(crate) const GRID_MTL: &str = "# by hand\nnewmtl red\nKa 0.1 0.1 0.1\nKd 0.8 0.1 0.1\n\
Ks 0.5 0.5 0.5\nNs 96\nNi 1.45\nillum 2\nmap_Kd -s 2 2 textures/red.png\nmap_Bump bump.png\n\
newmtl blue\nKd 0.1 0.1 0.8\nd 0.5\nTr 0.25\nillum 7\n\
newmtl lamp\nKe 4 4 3\nd 0.9\nillum 1\nKd 0.5\n";

/// The OBJ+MTL seed's OBJ: [`RICH_OBJ`] with the `.mtl`, an emitter and a name no `.mtl`
/// defines.
pub(crate) fn grid_mtl_obj() -> String {
    RICH_OBJ.replace("none.mtl", MTL_NAME) + "usemtl lamp\nf 1 2 5\nusemtl green\nf 2 3 6\n"
}

/// The glTF asset: JSON (buffer 0 without a `uri`) and its buffer.
pub(crate) fn gltf_asset() -> (Value, Vec<u8>) {
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
pub(crate) fn pack(json_text: &str, bin: &[u8], glb: bool) -> Vec<u8> {
    if glb {
        bytes::glb(json_text, Some(bin))
    } else {
        json_text.as_bytes().to_vec()
    }
}

/// Gives a `.gltf`'s buffer 0 its data URI (if the JSON still has a buffer 0 object).
pub(crate) fn embed(json: &mut Value, bin: &[u8]) {
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
pub(crate) fn seeds() -> Vec<Seed> {
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
    seeds.push(Seed {
        name: "strips_ascii.ply",
        ext: "ply",
        kind: Kind::Text,
        bytes: strips_ply(None),
    });
    seeds.push(Seed {
        name: "strips_le.ply",
        ext: "ply",
        kind: Kind::BinaryPly { big_endian: false },
        bytes: strips_ply(Some(false)),
    });
    seeds.push(Seed {
        name: "grid_mtl.obj",
        ext: "obj",
        kind: Kind::ObjMtl {
            mtl: GRID_MTL.as_bytes().to_vec(),
        },
        bytes: grid_mtl_obj().into_bytes(),
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
