//! The PLY format (Stanford polygon files): a reader for `ascii`, `binary_little_endian` and
//! `binary_big_endian` files, and a small writer (for generated test meshes, `make_mesh`).
//!
//! What is read:
//! - element `vertex`: properties `x`, `y`, `z` (required; any scalar type, usually `float` or
//!   `double`, in any order); `nx`, `ny`, `nz` as the normals when all three are there; texture
//!   coordinates from the first complete pair of `u`/`v`, `s`/`t`, `texture_u`/`texture_v`,
//!   `texture_s`/`texture_t`. Other properties are attributes (below) or skipped.
//! - element `face`: the list `vertex_indices` (or `vertex_index`), any integer types for the
//!   length and the entries; polygons are fanned from their first vertex. Other properties are
//!   attributes (below) or skipped.
//! - element `tristrips` (triangle strips, `ply_strips.rs`): the same index list, −1 separating
//!   strips; its other properties are skipped. A file may have it instead of `face` or beside
//!   it; the strips' triangles then follow the faces', and the face attributes, which have no
//!   values for them, are dropped.
//! - every other element (`edge`, `material`, …) is skipped; elements may come in any order.
//!
//! Named attributes ([`MeshAttribute`]) are read from the other scalar properties of `vertex`
//! and `face` exactly as Mitsuba 3.9.1's PLY loader reads them, because its `mesh_attribute`
//! texture looks them up by the names that loader gives: `r g b` (or `red green blue`, with
//! `a`/`alpha`) become `vertex_color`/`face_color`; a run of consecutive properties
//! `{prefix}_{c}` whose one-character postfixes follow `x y z w`, `r g b a`, `0 1 2 3` or
//! `1 2 3 4` becomes `vertex_{prefix}`/`face_{prefix}` (`…_color` for `r g b a`) when it has 1
//! or 3 components. Whatever Mitsuba ignores (with a warning) is skipped here silently: names
//! without `_`, longer postfixes, 2 or 4 components, broken sequences, a repeated prefix, with
//! the quirks of Mitsuba's loop (`ply_attributes.rs`). Integer properties but `uchar` are
//! normalized by their type's maximum and sRGB-decoded, as Mitsuba's converter does; a face's
//! value is repeated for each triangle of its fan. A non-finite value is an error.
//!
//! Errors name the file and the element (`mesh.ply element face 12: index 900 out of range
//! (512 vertices)`; ASCII files add the line), or the header line. Rejected: a missing `vertex`
//! element, neither `face` nor `tristrips`, no triangles, missing `x`/`y`/`z`, a non-finite
//! (or beyond-`f32`) position, normal, texture coordinate or attribute value, an index out of
//! range, a face with fewer than 3 vertices, a truncated file; never a panic.
//!
//! Why not ply-rs for this (it is kept as an independent check in the tests): its header
//! grammar panics on an element count beyond `u64` (`n.parse().unwrap()`), its ASCII grammar
//! rejects valid numbers (`.5`, `1E5`, `nan`), its errors carry no element index, and its
//! binary path builds a string-keyed map per element (several times slower; see the tests'
//! module doc). The format is small enough that a direct reader is the safer choice.

use super::{AttributeKind, MeshAttribute, MeshData, MeshError, check};
use glam::{Vec2, Vec3};
use std::fs::File;
use std::io::{self, BufRead, BufReader, BufWriter, Read, Write};
use std::path::Path;

#[path = "ply_attributes.rs"]
mod attributes;
use attributes::{Attributes, attribute_sources, attribute_vec};
#[path = "ply_strips.rs"]
mod strips;
use strips::{Strips, read_strips};

/// How a PLY file's payload (everything after `end_header`) is encoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Whitespace-separated numbers, one element per line.
    Ascii,
    /// Packed binary values, least significant byte first.
    BinaryLittleEndian,
    /// Packed binary values, most significant byte first.
    BinaryBigEndian,
}

/// A header line longer than this is not a PLY header (guards against reading a whole binary
/// file that merely lacks newlines).
const MAX_HEADER_LINE: u64 = 4096;

/// Names of texture-coordinate pairs, in the order they are looked for.
const UV_NAMES: [[&str; 2]; 4] = [
    ["u", "v"],
    ["s", "t"],
    ["texture_u", "texture_v"],
    ["texture_s", "texture_t"],
];

/// A PLY scalar type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type of a header name (both the classic and the sized spellings).
    fn from_name(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    /// The classic header name.
    fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// Bytes in the binary encodings.
    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// The range of an integer type (`None` for the float types).
    fn int_range(self) -> Option<(i64, i64)> {
        match self {
            Scalar::I8 => Some((i8::MIN.into(), i8::MAX.into())),
            Scalar::U8 => Some((0, u8::MAX.into())),
            Scalar::I16 => Some((i16::MIN.into(), i16::MAX.into())),
            Scalar::U16 => Some((0, u16::MAX.into())),
            Scalar::I32 => Some((i32::MIN.into(), i32::MAX.into())),
            Scalar::U32 => Some((0, u32::MAX.into())),
            Scalar::F32 | Scalar::F64 => None,
        }
    }

    /// Decodes one value from exactly `self.size()` bytes. Every PLY type fits an `f64` exactly.
    fn decode(self, b: &[u8], big_endian: bool) -> f64 {
        macro_rules! num {
            ($t:ty, $n:literal) => {{
                let a: [u8; $n] = b[..$n].try_into().expect("slice of the type's size");
                if big_endian {
                    <$t>::from_be_bytes(a)
                } else {
                    <$t>::from_le_bytes(a)
                }
            }};
        }
        match self {
            Scalar::I8 => f64::from(b[0] as i8),
            Scalar::U8 => f64::from(b[0]),
            Scalar::I16 => f64::from(num!(i16, 2)),
            Scalar::U16 => f64::from(num!(u16, 2)),
            Scalar::I32 => f64::from(num!(i32, 4)),
            Scalar::U32 => f64::from(num!(u32, 4)),
            Scalar::F32 => f64::from(num!(f32, 4)),
            Scalar::F64 => num!(f64, 8),
        }
    }
}

/// A property's type: one scalar, or a list (its length's type, its entries' type).
#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List { len: Scalar, item: Scalar },
}

/// One `property` line.
#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
}

/// One `element` line with its properties.
#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    properties: Vec<Property>,
}

impl Element {
    /// The index of the scalar property `name`, if there is one.
    fn scalar(&self, name: &str) -> Option<usize> {
        self.properties
            .iter()
            .position(|p| p.name == name && matches!(p.kind, Kind::Scalar(_)))
    }

    /// The fewest bytes one element takes (binary: scalars and list lengths; ASCII: one
    /// character and a separator per property), to bound what a header's count may reserve.
    fn min_size(&self, encoding: Encoding) -> u64 {
        let bytes: usize = match encoding {
            Encoding::Ascii => 2 * self.properties.len(),
            _ => self
                .properties
                .iter()
                .map(|p| match p.kind {
                    Kind::Scalar(s) => s.size(),
                    Kind::List { len, .. } => len.size(),
                })
                .sum(),
        };
        bytes.max(1) as u64
    }
}

/// A parsed header.
struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Lines in the header (ASCII payload lines are numbered on from here).
    lines: usize,
    /// Bytes in the header.
    bytes: u64,
}

/// Reads `path` as a PLY file (see the module doc for what is read and rejected).
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let file =
        File::open(path).map_err(|e| MeshError::at(path, "", format!("cannot open: {e}")))?;
    let file_len = file.metadata().map(|m| m.len()).unwrap_or(u64::MAX);
    read(path, file, file_len)
}

/// Reads the PLY file `bytes` as [`load`] reads a file; `path` only names it in errors. The
/// entry point of the fuzz target `mesh_ply`.
pub fn load_bytes(path: &Path, bytes: &[u8]) -> Result<MeshData, MeshError> {
    read(path, bytes, bytes.len() as u64)
}

/// Reads a PLY file of `file_len` bytes from `source`; `path` names it in errors.
fn read(path: &Path, source: impl Read, file_len: u64) -> Result<MeshData, MeshError> {
    let mut reader = BufReader::with_capacity(1 << 16, source);
    let header = read_header(path, &mut reader)?;
    let left = file_len.saturating_sub(header.bytes);
    let mesh = match header.encoding {
        Encoding::Ascii => {
            let mut source = Ascii {
                reader,
                line: String::new(),
                number: header.lines,
                at: 0,
            };
            read_payload(path, &header, &mut source, left)?
        }
        Encoding::BinaryLittleEndian | Encoding::BinaryBigEndian => {
            let mut source = Binary {
                reader,
                big_endian: header.encoding == Encoding::BinaryBigEndian,
            };
            read_payload(path, &header, &mut source, left)?
        }
    };
    check(path, &mesh)?;
    Ok(mesh)
}

/// Reads the header up to and including `end_header`.
fn read_header(path: &Path, reader: &mut impl BufRead) -> Result<Header, MeshError> {
    let mut raw = Vec::new();
    let (mut lines, mut bytes) = (0usize, 0u64);
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        lines += 1;
        let position = format!("header line {lines}");
        let fail = |message: String| MeshError::at(path, &position, message);
        raw.clear();
        let got = reader
            .by_ref()
            .take(MAX_HEADER_LINE)
            .read_until(b'\n', &mut raw)
            .map_err(|e| fail(format!("read error: {e}")))?;
        bytes += got as u64;
        if got == 0 {
            return Err(fail(if lines == 1 {
                "empty file".into()
            } else {
                "the file ends before end_header".into()
            }));
        }
        if raw.last() != Some(&b'\n') && got as u64 == MAX_HEADER_LINE {
            return Err(fail("line too long for a PLY header".into()));
        }
        let text = std::str::from_utf8(&raw).map_err(|_| {
            fail(if lines == 1 {
                "not a PLY file (it does not start with 'ply')".into()
            } else {
                "not text (a PLY header is ASCII)".into()
            })
        })?;
        let mut words = text.split_ascii_whitespace();
        let keyword = words.next();
        if lines == 1 {
            if keyword != Some("ply") || words.next().is_some() {
                return Err(fail("not a PLY file (it does not start with 'ply')".into()));
            }
            continue;
        }
        match keyword {
            None | Some("comment") | Some("obj_info") => {}
            Some("format") => {
                let e = match words.next() {
                    Some("ascii") => Encoding::Ascii,
                    Some("binary_little_endian") => Encoding::BinaryLittleEndian,
                    Some("binary_big_endian") => Encoding::BinaryBigEndian,
                    other => {
                        return Err(fail(format!(
                            "unknown format '{}' (ascii, binary_little_endian or binary_big_endian)",
                            other.unwrap_or("")
                        )));
                    }
                };
                if words.next().is_none() {
                    return Err(fail("format without a version".into()));
                }
                if encoding.replace(e).is_some() {
                    return Err(fail("a second format line".into()));
                }
            }
            Some("element") => {
                let (Some(name), Some(count), None) = (words.next(), words.next(), words.next())
                else {
                    return Err(fail("expected 'element NAME COUNT'".into()));
                };
                let count = count
                    .parse::<u64>()
                    .map_err(|_| fail(format!("element count '{count}' is not a whole number")))?;
                if elements.iter().any(|e| e.name == name) {
                    return Err(fail(format!("a second element '{name}'")));
                }
                elements.push(Element {
                    name: name.to_owned(),
                    count,
                    properties: Vec::new(),
                });
            }
            Some("property") => {
                let Some(element) = elements.last_mut() else {
                    return Err(fail("property before any element".into()));
                };
                let ty = |w: Option<&str>| {
                    let w = w.unwrap_or("");
                    Scalar::from_name(w).ok_or_else(|| fail(format!("unknown type '{w}'")))
                };
                let kind = match words.next() {
                    Some("list") => {
                        let len = ty(words.next())?;
                        let item = ty(words.next())?;
                        if len.int_range().is_none() {
                            return Err(fail("a list's length must have an integer type".into()));
                        }
                        Kind::List { len, item }
                    }
                    w => Kind::Scalar(ty(w)?),
                };
                let (Some(name), None) = (words.next(), words.next()) else {
                    return Err(fail("expected 'property TYPE NAME'".into()));
                };
                if element.properties.iter().any(|p| p.name == name) {
                    return Err(fail(format!(
                        "a second property '{name}' in element '{}'",
                        element.name
                    )));
                }
                element.properties.push(Property {
                    name: name.to_owned(),
                    kind,
                });
            }
            Some("end_header") => break,
            Some(other) => return Err(fail(format!("unknown header keyword '{other}'"))),
        }
    }
    let encoding = encoding.ok_or_else(|| MeshError::at(path, "header", "no format line"))?;
    Ok(Header {
        encoding,
        elements,
        lines,
        bytes,
    })
}

/// Where an element's values come from: packed bytes, or the tokens of one ASCII line.
trait Source {
    /// Starts the next element (ASCII: reads its line).
    fn begin(&mut self) -> Result<(), String>;
    /// The next value, of type `t`.
    fn value(&mut self, t: Scalar) -> Result<f64, String>;
    /// Ends the element (ASCII: nothing may be left on the line).
    fn end(&mut self) -> Result<(), String>;
    /// The position of element `index` of `element` for messages.
    fn position(&self, element: &str, index: u64) -> String;

    /// A list's length.
    fn list_len(&mut self, t: Scalar) -> Result<u64, String> {
        let n = self.value(t)?;
        if n < 0.0 {
            return Err(format!("negative list length {n}"));
        }
        Ok(n as u64)
    }
}

/// The binary encodings.
struct Binary<R> {
    reader: R,
    big_endian: bool,
}

impl<R: Read> Source for Binary<R> {
    fn begin(&mut self) -> Result<(), String> {
        Ok(())
    }

    fn value(&mut self, t: Scalar) -> Result<f64, String> {
        let mut b = [0u8; 8];
        let b = &mut b[..t.size()];
        self.reader.read_exact(b).map_err(|e| {
            if e.kind() == io::ErrorKind::UnexpectedEof {
                "truncated: the file ends before this element is complete".to_owned()
            } else {
                format!("read error: {e}")
            }
        })?;
        Ok(t.decode(b, self.big_endian))
    }

    fn end(&mut self) -> Result<(), String> {
        Ok(())
    }

    fn position(&self, element: &str, index: u64) -> String {
        format!("element {element} {index}")
    }
}

/// The ASCII encoding: one element per line (blank lines are skipped).
struct Ascii<R> {
    reader: R,
    line: String,
    /// The 1-based number of `line` in the file.
    number: usize,
    /// Byte offset of the next token in `line`.
    at: usize,
}

impl<R: BufRead> Source for Ascii<R> {
    fn begin(&mut self) -> Result<(), String> {
        loop {
            self.line.clear();
            self.number += 1;
            let got = self
                .reader
                .read_line(&mut self.line)
                .map_err(|e| format!("read error: {e}"))?;
            if got == 0 {
                return Err("truncated: the file ends before this element".into());
            }
            if !self.line.trim_ascii().is_empty() {
                self.at = 0;
                return Ok(());
            }
        }
    }

    fn value(&mut self, t: Scalar) -> Result<f64, String> {
        let rest = &self.line[self.at..];
        let start = rest.len() - rest.trim_ascii_start().len();
        let token_len = rest[start..]
            .find(|c: char| c.is_ascii_whitespace())
            .unwrap_or(rest.len() - start);
        if token_len == 0 {
            return Err("too few values on the line".into());
        }
        let token = &rest[start..start + token_len];
        self.at += start + token_len;
        let parsed = match t.int_range() {
            Some((lo, hi)) => token
                .parse::<i64>()
                .ok()
                .filter(|v| (lo..=hi).contains(v))
                .map(|v| v as f64),
            // f32 values are parsed as f32, so they come out exactly as a binary file holds them.
            None if t == Scalar::F32 => token.parse::<f32>().ok().map(f64::from),
            None => token.parse::<f64>().ok(),
        };
        parsed.ok_or_else(|| format!("'{token}' is not a value of type {}", t.name()))
    }

    fn end(&mut self) -> Result<(), String> {
        if self.line[self.at..].trim_ascii().is_empty() {
            Ok(())
        } else {
            Err("too many values on the line".into())
        }
    }

    fn position(&self, element: &str, index: u64) -> String {
        format!("element {element} {index} (line {})", self.number)
    }
}

/// Which vertex properties hold what.
struct VertexRoles {
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    uv: Option<[usize; 2]>,
}

/// Reads all elements after the header into a mesh.
fn read_payload<S: Source>(
    path: &Path,
    header: &Header,
    source: &mut S,
    bytes_left: u64,
) -> Result<MeshData, MeshError> {
    let find = |name: &str| header.elements.iter().find(|e| e.name == name);
    let vertex = find("vertex").ok_or_else(|| MeshError::at(path, "", "no vertex element"))?;
    let face = find("face");
    let tristrips = find("tristrips");
    if face.is_none() && tristrips.is_none() {
        return Err(MeshError::at(
            path,
            "",
            "no face or tristrips element (a point cloud has no surface to render)",
        ));
    }
    let roles = vertex_roles(path, vertex)?;
    let face_list = face.map(|f| index_list(path, f)).transpose()?;
    let strips = tristrips
        .map(|t| {
            Ok::<_, MeshError>(Strips {
                index_list: index_list(path, t)?,
                vertices: vertex.count,
            })
        })
        .transpose()?;
    if let Some(face) = face
        && face.count == 0
        && tristrips.is_none()
    {
        return Err(MeshError::at(path, "element face", "no faces"));
    }
    if vertex.count > u64::from(u32::MAX) {
        return Err(MeshError::at(
            path,
            "element vertex",
            "more vertices than 32-bit indices reach",
        ));
    }
    // A header's count reserves no more than the rest of the file could hold.
    let reserve = |e: &Element| e.count.min(bytes_left / e.min_size(header.encoding)) as usize;
    let mut mesh = MeshData {
        positions: Vec::with_capacity(reserve(vertex)),
        indices: Vec::with_capacity(face.map_or(0, reserve)),
        normals: roles.normal.map(|_| Vec::with_capacity(reserve(vertex))),
        uvs: roles.uv.map(|_| Vec::with_capacity(reserve(vertex))),
        attributes: Vec::new(),
    };
    let is = |element: &Element, other: Option<&Element>| {
        other.is_some_and(|o| std::ptr::eq(element, o))
    };
    // The attributes of both elements, in the order the elements come in the file.
    let mut vertex_attributes = None;
    let mut face_attributes = None;
    for element in &header.elements {
        let (kind, slot) = if std::ptr::eq(element, vertex) {
            (AttributeKind::Vertex, &mut vertex_attributes)
        } else if is(element, face) {
            (AttributeKind::Face, &mut face_attributes)
        } else {
            continue;
        };
        let sources = attribute_sources(element, kind);
        let first = mesh.attributes.len();
        mesh.attributes
            .extend(sources.iter().map(|source| MeshAttribute {
                name: source.name.clone(),
                dim: source.properties.len() as u8,
                values: Vec::with_capacity(reserve(element)),
            }));
        *slot = Some(Attributes { sources, first });
    }
    let vertex_attributes = vertex_attributes.expect("the vertex element is in the header");
    let mut values = vec![0.0f64; vertex.properties.len()];
    let mut face_values = vec![0.0f64; face.map_or(0, |f| f.properties.len())];
    let mut polygon = Vec::new();
    // The strips' triangles, kept apart so that they follow the faces' (whose attributes,
    // one value per triangle, come first), whichever element comes first in the file.
    let mut strip_triangles = Vec::new();
    for element in &header.elements {
        // An element without properties takes no bytes: nothing to read, however many.
        if element.properties.is_empty() {
            continue;
        }
        for i in 0..element.count {
            let done = if std::ptr::eq(element, vertex) {
                read_vertex(
                    source,
                    element,
                    &roles,
                    &vertex_attributes,
                    &mut values,
                    &mut mesh,
                )
            } else if let (true, Some(index_list), Some(attributes)) =
                (is(element, face), face_list, &face_attributes)
            {
                let face = Face {
                    index_list,
                    vertices: vertex.count,
                    attributes,
                };
                read_face(
                    source,
                    element,
                    &face,
                    &mut face_values,
                    &mut polygon,
                    &mut mesh,
                )
            } else if let (true, Some(strips)) = (is(element, tristrips), &strips) {
                read_strips(source, element, strips, &mut polygon, &mut strip_triangles)
            } else {
                skip(source, element)
            };
            done.map_err(|m| MeshError::at(path, &source.position(&element.name, i), m))?;
        }
    }
    if !strip_triangles.is_empty() {
        // Face attributes have no values for the strips' triangles: dropped (see the module
        // doc), rather than refusing a file that has a surface to show.
        mesh.attributes
            .retain(|a| a.kind() == AttributeKind::Vertex);
        mesh.indices.append(&mut strip_triangles);
    }
    if mesh.indices.is_empty() {
        return Err(MeshError::at(
            path,
            "element tristrips",
            "no triangles (every strip has fewer than 3 vertices or only degenerate triangles)",
        ));
    }
    Ok(mesh)
}

/// Finds `x`, `y`, `z` (required), the normals and the texture coordinates.
fn vertex_roles(path: &Path, vertex: &Element) -> Result<VertexRoles, MeshError> {
    let mut position = [0; 3];
    for (slot, name) in position.iter_mut().zip(["x", "y", "z"]) {
        *slot = vertex.scalar(name).ok_or_else(|| {
            MeshError::at(
                path,
                "element vertex",
                format!("no scalar property '{name}'"),
            )
        })?;
    }
    let all = |names: &[&str]| {
        names
            .iter()
            .map(|n| vertex.scalar(n))
            .collect::<Option<Vec<_>>>()
    };
    Ok(VertexRoles {
        position,
        normal: all(&["nx", "ny", "nz"]).map(|v| [v[0], v[1], v[2]]),
        uv: UV_NAMES
            .iter()
            .find_map(|pair| all(pair))
            .map(|v| [v[0], v[1]]),
    })
}

/// The index of the index list (`vertex_indices` or `vertex_index`) of a `face` or
/// `tristrips` element.
fn index_list(path: &Path, element: &Element) -> Result<usize, MeshError> {
    let at = |m: &str| MeshError::at(path, &format!("element {}", element.name), m);
    let i = element
        .properties
        .iter()
        .position(|p| p.name == "vertex_indices" || p.name == "vertex_index")
        .ok_or_else(|| at("no property 'vertex_indices' (or 'vertex_index')"))?;
    match element.properties[i].kind {
        Kind::List { item, .. } if item.int_range().is_some() => Ok(i),
        Kind::List { .. } => Err(at("the vertex index list must have an integer type")),
        Kind::Scalar(_) => Err(at("the vertex indices must be a list")),
    }
}

/// Reads one vertex into `mesh`; `values` is scratch space, one slot per property.
fn read_vertex(
    source: &mut impl Source,
    element: &Element,
    roles: &VertexRoles,
    attributes: &Attributes,
    values: &mut [f64],
    mesh: &mut MeshData,
) -> Result<(), String> {
    source.begin()?;
    for (slot, p) in values.iter_mut().zip(&element.properties) {
        match p.kind {
            Kind::Scalar(t) => *slot = source.value(t)?,
            Kind::List { len, item } => skip_list(source, len, item)?,
        }
    }
    source.end()?;
    let get = |i: usize| finite(&element.properties[i].name, values[i]);
    let [x, y, z] = roles.position;
    mesh.positions.push(Vec3::new(get(x)?, get(y)?, get(z)?));
    if let (Some([x, y, z]), Some(normals)) = (roles.normal, mesh.normals.as_mut()) {
        normals.push(Vec3::new(get(x)?, get(y)?, get(z)?));
    }
    if let (Some([u, v]), Some(uvs)) = (roles.uv, mesh.uvs.as_mut()) {
        uvs.push(Vec2::new(get(u)?, get(v)?));
    }
    for (j, a) in attributes.sources.iter().enumerate() {
        let value = attribute_vec(element, a, values)?;
        mesh.attributes[attributes.first + j].values.push(value);
    }
    Ok(())
}

/// `value` as a finite `f32`, or why not (named by the property).
fn finite(name: &str, value: f64) -> Result<f32, String> {
    let f = value as f32;
    if f.is_finite() {
        Ok(f)
    } else if value.is_nan() {
        Err(format!("{name} is NaN"))
    } else if value.is_infinite() {
        Err(format!("{name} is infinite"))
    } else {
        Err(format!("{name} = {value:e} is beyond single precision"))
    }
}

/// What [`read_face`] needs besides the element: the index of its index list, the number of
/// vertices, its attributes.
struct Face<'a> {
    index_list: usize,
    vertices: u64,
    attributes: &'a Attributes,
}

/// Reads one face, fanned into triangles in `mesh`, its attributes repeated for each; `values`
/// (one slot per property) and `polygon` are scratch space.
fn read_face(
    source: &mut impl Source,
    element: &Element,
    face: &Face,
    values: &mut [f64],
    polygon: &mut Vec<u32>,
    mesh: &mut MeshData,
) -> Result<(), String> {
    let vertices = face.vertices;
    source.begin()?;
    for (k, p) in element.properties.iter().enumerate() {
        match p.kind {
            Kind::List { len, item } if k == face.index_list => {
                let n = source.list_len(len)?;
                polygon.clear();
                for _ in 0..n {
                    let i = source.value(item)?;
                    if i < 0.0 || i >= vertices as f64 {
                        return Err(format!("index {i} out of range ({vertices} vertices)"));
                    }
                    polygon.push(i as u32);
                }
                if n < 3 {
                    return Err(format!("{n} vertices (a face needs at least 3)"));
                }
            }
            Kind::List { len, item } => skip_list(source, len, item)?,
            Kind::Scalar(t) => values[k] = source.value(t)?,
        }
    }
    source.end()?;
    let triangles = polygon.len() - 2;
    for (j, a) in face.attributes.sources.iter().enumerate() {
        let value = attribute_vec(element, a, values)?;
        mesh.attributes[face.attributes.first + j]
            .values
            .extend(std::iter::repeat_n(value, triangles));
    }
    let first = polygon[0];
    mesh.indices
        .extend(polygon[1..].windows(2).map(|w| [first, w[0], w[1]]));
    Ok(())
}

/// Reads and drops one list.
fn skip_list(source: &mut impl Source, len: Scalar, item: Scalar) -> Result<(), String> {
    for _ in 0..source.list_len(len)? {
        source.value(item)?;
    }
    Ok(())
}

/// Reads and drops one element of a kind the mesh does not use.
fn skip(source: &mut impl Source, element: &Element) -> Result<(), String> {
    source.begin()?;
    for p in &element.properties {
        match p.kind {
            Kind::Scalar(t) => {
                source.value(t)?;
            }
            Kind::List { len, item } => skip_list(source, len, item)?,
        }
    }
    source.end()
}

/// Writes `mesh` to `path` as PLY: `float` positions (and normals `nx ny nz`, texture
/// coordinates `u v` where the mesh has them), faces as `list uchar uint vertex_indices`, and
/// each attribute as `float` properties `{prefix}_0 {prefix}_1 {prefix}_2` (`{prefix}_0` for one
/// component; `prefix` is the name after `vertex_`/`face_`), vertex ones after the vertex
/// properties, face ones after the index list, which the reader takes back as the same name.
/// ASCII values use Rust's shortest round-trip formatting, so every encoding reads back to the
/// same `MeshData`. An attribute that cannot round-trip is refused (`InvalidInput`): 4
/// components (`r g b a`: the alpha is not kept), a name that does not start with `vertex_` or
/// `face_` or holds whitespace, a name given twice, a value count that does not match.
pub fn write(path: &Path, mesh: &MeshData, encoding: Encoding) -> io::Result<()> {
    let prefixes = attribute_prefixes(mesh)?;
    let mut w = BufWriter::with_capacity(1 << 20, File::create(path)?);
    let format = match encoding {
        Encoding::Ascii => "ascii",
        Encoding::BinaryLittleEndian => "binary_little_endian",
        Encoding::BinaryBigEndian => "binary_big_endian",
    };
    let of_kind = |kind: AttributeKind| {
        mesh.attributes
            .iter()
            .zip(&prefixes)
            .filter(move |(a, _)| a.kind() == kind)
    };
    let properties = |w: &mut BufWriter<File>, kind: AttributeKind| -> io::Result<()> {
        for (a, prefix) in of_kind(kind) {
            for c in 0..a.dim {
                writeln!(w, "property float {prefix}_{c}")?;
            }
        }
        Ok(())
    };
    writeln!(w, "ply\nformat {format} 1.0\ncomment written by lumis")?;
    writeln!(w, "element vertex {}", mesh.positions.len())?;
    let mut names = vec!["x", "y", "z"];
    if mesh.normals.is_some() {
        names.extend(["nx", "ny", "nz"]);
    }
    if mesh.uvs.is_some() {
        names.extend(["u", "v"]);
    }
    for n in &names {
        writeln!(w, "property float {n}")?;
    }
    properties(&mut w, AttributeKind::Vertex)?;
    writeln!(w, "element face {}", mesh.indices.len())?;
    writeln!(w, "property list uchar uint vertex_indices")?;
    properties(&mut w, AttributeKind::Face)?;
    writeln!(w, "end_header")?;
    // The values of element `i`'s attributes of `kind`, appended to `row`.
    let attribute_values = |row: &mut Vec<f32>, kind: AttributeKind, i: usize| {
        for (a, _) in of_kind(kind) {
            row.extend(&a.values[i].to_array()[..usize::from(a.dim)]);
        }
    };
    let mut row = Vec::with_capacity(8);
    for (i, p) in mesh.positions.iter().enumerate() {
        row.clear();
        row.extend(p.to_array());
        if let Some(n) = &mesh.normals {
            row.extend(n[i].to_array());
        }
        if let Some(uv) = &mesh.uvs {
            row.extend(uv[i].to_array());
        }
        attribute_values(&mut row, AttributeKind::Vertex, i);
        write_floats(&mut w, encoding, "", &row)?;
    }
    for (i, t) in mesh.indices.iter().enumerate() {
        row.clear();
        attribute_values(&mut row, AttributeKind::Face, i);
        match encoding {
            Encoding::Ascii => write!(w, "3 {} {} {}", t[0], t[1], t[2])?,
            Encoding::BinaryLittleEndian => {
                w.write_all(&[3])?;
                t.iter().try_for_each(|i| w.write_all(&i.to_le_bytes()))?;
            }
            Encoding::BinaryBigEndian => {
                w.write_all(&[3])?;
                t.iter().try_for_each(|i| w.write_all(&i.to_be_bytes()))?;
            }
        }
        write_floats(&mut w, encoding, " ", &row)?;
    }
    w.flush()
}

/// Writes `row` in `encoding`; ASCII: after `separator` if not empty, and ends the line.
fn write_floats(
    w: &mut impl Write,
    encoding: Encoding,
    separator: &str,
    row: &[f32],
) -> io::Result<()> {
    match encoding {
        Encoding::Ascii => {
            let text: Vec<String> = row.iter().map(f32::to_string).collect();
            let separator = if row.is_empty() { "" } else { separator };
            writeln!(w, "{separator}{}", text.join(" "))
        }
        Encoding::BinaryLittleEndian => row.iter().try_for_each(|v| w.write_all(&v.to_le_bytes())),
        Encoding::BinaryBigEndian => row.iter().try_for_each(|v| w.write_all(&v.to_be_bytes())),
    }
}

/// The property prefix of each of `mesh`'s attributes for [`write`] (its name after `vertex_`
/// or `face_`), or why it cannot be written so that it reads back the same.
fn attribute_prefixes(mesh: &MeshData) -> io::Result<Vec<&str>> {
    let refuse = |name: &str, why: String| {
        Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("PLY attribute '{name}': {why}"),
        ))
    };
    let mut prefixes = Vec::with_capacity(mesh.attributes.len());
    for (k, a) in mesh.attributes.iter().enumerate() {
        let (prefix, count) = match a.kind() {
            AttributeKind::Vertex => (a.name.strip_prefix("vertex_"), mesh.positions.len()),
            AttributeKind::Face => (a.name.strip_prefix("face_"), mesh.indices.len()),
        };
        let Some(prefix) = prefix else {
            return refuse(
                &a.name,
                "the name must start with 'vertex_' or 'face_'".into(),
            );
        };
        if a.dim == 4 {
            return refuse(
                &a.name,
                "4 components (r g b a) cannot be written: the values hold only 3".into(),
            );
        }
        if a.dim != 1 && a.dim != 3 {
            return refuse(
                &a.name,
                format!("{} components (1 or 3 can be written)", a.dim),
            );
        }
        if prefix.chars().any(|c| c.is_whitespace() || c.is_control()) {
            return refuse(&a.name, "a PLY property name cannot hold whitespace".into());
        }
        if mesh.attributes[..k].iter().any(|b| b.name == a.name) {
            return refuse(&a.name, "a second attribute of that name".into());
        }
        if a.values.len() != count {
            return refuse(&a.name, format!("{} values for {count}", a.values.len()));
        }
        prefixes.push(prefix);
    }
    Ok(prefixes)
}

#[cfg(test)]
#[path = "ply_attributes_tests.rs"]
mod attributes_tests;
#[cfg(test)]
#[path = "ply_tests.rs"]
pub(super) mod tests;
