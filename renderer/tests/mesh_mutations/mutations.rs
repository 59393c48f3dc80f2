//! The mutations: the values, keys and bytes they write, and how a case is built from a seed
//! file (see `main.rs`).

use crate::seeds::*;
use proptest::prelude::*;
use proptest::sample::Index;
use serde_json::{Value, json};

/// Numbers written over number tokens in text: non-finite, beyond `f32`, beyond the integer
/// types, negative, and small counts and indices around the seeds' own (9 vertices, 8
/// triangles, 24 indices, 6 strip indices), plus tokens that are not numbers at all.
pub(crate) const TEXT_NUMBERS: &[&str] = &[
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
pub(crate) fn json_values() -> Vec<Value> {
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
pub(crate) const JSON_KEYS: &[&str] = &[
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
pub(crate) const INSERTIONS: &[&str] = &[
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
pub(crate) const BINARY_VALUES: &[(u8, u64)] = &[
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
pub(crate) enum Level {
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
pub(crate) enum Mutation {
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
pub(crate) struct Case {
    pub(crate) seed: Index,
    pub(crate) mutations: Vec<(Level, Mutation)>,
}

pub(crate) fn mutation() -> impl Strategy<Value = Mutation> {
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

pub(crate) fn case() -> impl Strategy<Value = Case> {
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
pub(crate) fn number_tokens(data: &[u8]) -> Vec<(usize, usize)> {
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
pub(crate) fn mutate_bytes(data: &mut Vec<u8>, m: &Mutation, binary: Option<(usize, bool)>) {
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
pub(crate) fn json_paths(
    v: &Value,
    here: String,
    slots: &mut Vec<String>,
    objects: &mut Vec<String>,
) {
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
pub(crate) fn mutate_json(json: &mut Value, m: &Mutation, values: &[Value]) -> bool {
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
pub(crate) fn build(seed: &Seed, case: &Case, values: &[Value]) -> Vec<u8> {
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
    for (level, m) in mutations {
        if matches!(seed.kind, Kind::ObjMtl { .. }) && *level < Level::Text {
            // The `.mtl`'s (`build_mtl`).
            continue;
        }
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

/// The mutated `.mtl` of an OBJ+MTL seed (`None` for the other seeds): its buffer- and
/// JSON-level mutations, applied to the `.mtl` text.
pub(crate) fn build_mtl(seed: &Seed, case: &Case) -> Option<Vec<u8>> {
    let Kind::ObjMtl { mtl } = &seed.kind else {
        return None;
    };
    let mut mtl = mtl.clone();
    for (_, m) in case.mutations.iter().filter(|(l, _)| *l < Level::Text) {
        mutate_bytes(&mut mtl, m, None);
    }
    Some(mtl)
}
