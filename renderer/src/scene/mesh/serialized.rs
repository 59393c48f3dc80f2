//! Mitsuba's `.serialized` meshes (versions 3 and 4, the ones Mitsuba 0.6 and Mitsuba 3.9.1
//! write and read), learnt from the format description in Mitsuba 3.9.1's
//! `src/shapes/serialized.cpp`:
//!
//! * A file is a sequence of meshes. Each starts with the little-endian `u16` magic `0x041C`
//!   and a `u16` version (3 or 4), followed by one zlib stream holding: a `u32` flag word
//!   (`0x1` vertex normals, `0x2` texture coordinates, `0x8` vertex colours, `0x2000` double
//!   precision, else single); version 4 only: the mesh's name, NUL-terminated; `u64` vertex
//!   and triangle counts; the positions (3 values per vertex), then the normals, texture
//!   coordinates and colours that the flags announce (3, 2, 3 values per vertex); then the
//!   triangles as 3 `u32` indices each.
//! * The file ends with a table of where each mesh starts, `u64` byte offsets (version 3:
//!   `u32`), and a `u32` count of meshes. Mesh 0 is at offset 0; `shape_index` picks another.
//!
//! Texture coordinates are kept as stored (Mitsuba does not flip them), colours are skipped
//! (lumis has no vertex colours, and Mitsuba's loader skips them too).

use super::{MeshData, MeshError, check};
use glam::{Vec2, Vec3};
use std::io::Read;
use std::path::Path;

/// The magic number at the start of every mesh.
const MAGIC: u16 = 0x041C;
/// Flag: the mesh has vertex normals.
const HAS_NORMALS: u32 = 0x0001;
/// Flag: the mesh has texture coordinates.
const HAS_TEXCOORDS: u32 = 0x0002;
/// Flag: the mesh has vertex colours.
const HAS_COLORS: u32 = 0x0008;
/// Flag: values are `f64` rather than `f32`.
const DOUBLE_PRECISION: u32 = 0x2000;
/// DEFLATE expands at most about 1032 : 1, which bounds what a stream can honestly hold.
const MAX_INFLATE_RATIO: u64 = 1032;

/// Reads mesh `shape_index` of the `.serialized` file `path`.
pub fn load(path: &Path, shape_index: u32) -> Result<MeshData, MeshError> {
    let bytes = std::fs::read(path).map_err(|e| MeshError::at(path, "", e))?;
    load_bytes(path, &bytes, shape_index)
}

/// Reads mesh `shape_index` of the `.serialized` file content `bytes`; `path` names it in
/// errors.
pub fn load_bytes(path: &Path, bytes: &[u8], shape_index: u32) -> Result<MeshData, MeshError> {
    let at = |msg: String| MeshError::at(path, &format!("shape {shape_index}"), msg);
    let version = header(bytes).map_err(at)?;
    let start = if shape_index == 0 {
        0
    } else {
        offset(bytes, version, shape_index).map_err(at)?
    };
    let here = &bytes[start..];
    let v = header(here).map_err(|m| at(format!("at byte {start}: {m}")))?;
    if v != version {
        return Err(at(format!(
            "at byte {start}: version {v} differs from the file's version {version}"
        )));
    }
    let compressed = &here[4..];
    let mesh = decode(compressed, version).map_err(at)?;
    check(path, &mesh)?;
    Ok(mesh)
}

/// The version after the magic number at the start of `bytes`.
fn header(bytes: &[u8]) -> Result<u16, String> {
    if bytes.len() < 4 {
        return Err("the file is too short for a serialized mesh header".to_owned());
    }
    let magic = u16::from_le_bytes([bytes[0], bytes[1]]);
    if magic != MAGIC {
        return Err(format!(
            "not a Mitsuba serialized mesh (magic 0x{magic:04X}, expected 0x{MAGIC:04X})"
        ));
    }
    let version = u16::from_le_bytes([bytes[2], bytes[3]]);
    if !(3..=4).contains(&version) {
        return Err(format!(
            "serialized format version {version} is not supported (lumis reads 3 and 4)"
        ));
    }
    Ok(version)
}

/// Where mesh `index` starts, from the table at the end of the file.
fn offset(bytes: &[u8], version: u16, index: u32) -> Result<usize, String> {
    let n = bytes.len();
    let count = n
        .checked_sub(4)
        .map(|i| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap_or_default()))
        .ok_or("the file has no table of meshes at its end")?;
    if index >= count {
        return Err(format!(
            "shape_index {index} is out of range: the file holds {count} mesh{}",
            if count == 1 { "" } else { "es" }
        ));
    }
    let width = if version == 4 { 8 } else { 4 };
    let back = width as u64 * (count - index) as u64 + 4;
    let at = (n as u64)
        .checked_sub(back)
        .ok_or("the table of meshes at the end of the file is truncated")? as usize;
    let raw = &bytes[at..at + width];
    let off = if width == 8 {
        u64::from_le_bytes(raw.try_into().unwrap_or_default())
    } else {
        u32::from_le_bytes(raw.try_into().unwrap_or_default()) as u64
    };
    if off >= at as u64 {
        return Err(format!(
            "the table gives mesh {index} the offset {off}, beyond the meshes ({at} bytes)"
        ));
    }
    Ok(off as usize)
}

/// Reads little-endian values from the inflated stream.
struct Stream<R: Read> {
    r: R,
}

impl<R: Read> Stream<R> {
    fn bytes(&mut self, n: usize, what: &str) -> Result<Vec<u8>, String> {
        let mut v = Vec::new();
        let got = (&mut self.r)
            .take(n as u64)
            .read_to_end(&mut v)
            .map_err(|e| format!("cannot inflate the mesh data ({what}): {e}"))?;
        if got != n {
            return Err(format!(
                "the mesh data ends early: {what} needs {n} bytes, {got} remain"
            ));
        }
        Ok(v)
    }
    fn u32(&mut self, what: &str) -> Result<u32, String> {
        Ok(u32::from_le_bytes(
            self.bytes(4, what)?.try_into().unwrap_or_default(),
        ))
    }
    fn u64(&mut self, what: &str) -> Result<u64, String> {
        Ok(u64::from_le_bytes(
            self.bytes(8, what)?.try_into().unwrap_or_default(),
        ))
    }
    /// `n` values as f32, stored as f64 when `double`.
    fn floats(&mut self, n: usize, double: bool, what: &str) -> Result<Vec<f32>, String> {
        let size = if double { 8 } else { 4 };
        let raw = self.bytes(n * size, what)?;
        Ok(if double {
            raw.chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap_or_default()) as f32)
                .collect()
        } else {
            raw.chunks_exact(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap_or_default()))
                .collect()
        })
    }
}

/// One mesh's zlib stream.
fn decode(compressed: &[u8], version: u16) -> Result<MeshData, String> {
    let mut s = Stream {
        r: flate2::read::ZlibDecoder::new(compressed),
    };
    let flags = s.u32("flags")?;
    if version == 4 {
        // The mesh's name, NUL-terminated; lumis does not keep it.
        let mut len = 0usize;
        while s.bytes(1, "the mesh name")?[0] != 0 {
            len += 1;
            if len > 1 << 16 {
                return Err("the mesh name is not terminated".to_owned());
            }
        }
    }
    let vertices = s.u64("the vertex count")?;
    let triangles = s.u64("the triangle count")?;
    let double = flags & DOUBLE_PRECISION != 0;
    let size = if double { 8 } else { 4 };
    let per_vertex = 3
        + 3 * (flags & HAS_NORMALS != 0) as u64
        + 2 * (flags & HAS_TEXCOORDS != 0) as u64
        + 3 * (flags & HAS_COLORS != 0) as u64;
    let needed = vertices
        .checked_mul(per_vertex * size)
        .and_then(|b| b.checked_add(triangles.checked_mul(12)?));
    let bound = MAX_INFLATE_RATIO * compressed.len() as u64 + 64;
    if needed.is_none_or(|b| b > bound) || vertices > u32::MAX as u64 {
        return Err(format!(
            "{vertices} vertices and {triangles} triangles cannot fit in {} compressed bytes",
            compressed.len()
        ));
    }
    let (nv, nt) = (vertices as usize, triangles as usize);
    let to_vec3 = |v: Vec<f32>| -> Vec<Vec3> {
        v.chunks_exact(3)
            .map(|c| Vec3::new(c[0], c[1], c[2]))
            .collect()
    };
    let positions = to_vec3(s.floats(3 * nv, double, "the positions")?);
    let normals = match flags & HAS_NORMALS {
        0 => None,
        _ => Some(to_vec3(s.floats(3 * nv, double, "the normals")?)),
    };
    let uvs = match flags & HAS_TEXCOORDS {
        0 => None,
        _ => Some(
            s.floats(2 * nv, double, "the texture coordinates")?
                .chunks_exact(2)
                .map(|c| Vec2::new(c[0], c[1]))
                .collect(),
        ),
    };
    if flags & HAS_COLORS != 0 {
        s.floats(3 * nv, double, "the vertex colours")?;
    }
    let raw = s.bytes(12 * nt, "the triangles")?;
    let indices = raw
        .chunks_exact(12)
        .map(|c| {
            let i =
                |k: usize| u32::from_le_bytes(c[4 * k..4 * k + 4].try_into().unwrap_or_default());
            [i(0), i(1), i(2)]
        })
        .collect();
    Ok(MeshData {
        positions,
        indices,
        normals,
        uvs,
        attributes: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    /// One mesh record of `version` (3 or 4) with `flags`, holding `v` vertices of `values`
    /// (already laid out as the flags say) and `tris`.
    fn record(version: u16, flags: u32, v: u64, values: &[u8], tris: &[[u32; 3]]) -> Vec<u8> {
        let mut raw = flags.to_le_bytes().to_vec();
        if version == 4 {
            raw.extend(b"name\0");
        }
        raw.extend(v.to_le_bytes());
        raw.extend((tris.len() as u64).to_le_bytes());
        raw.extend(values);
        tris.iter()
            .flatten()
            .for_each(|i| raw.extend(i.to_le_bytes()));
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
        z.write_all(&raw).unwrap();
        let mut out = MAGIC.to_le_bytes().to_vec();
        out.extend(version.to_le_bytes());
        out.extend(z.finish().unwrap());
        out
    }

    /// A file of `records` with the end table of `version`.
    fn file(version: u16, records: &[Vec<u8>]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut offsets = Vec::new();
        for r in records {
            offsets.push(out.len() as u64);
            out.extend(r);
        }
        for o in offsets {
            if version == 4 {
                out.extend(o.to_le_bytes());
            } else {
                out.extend((o as u32).to_le_bytes());
            }
        }
        out.extend((records.len() as u32).to_le_bytes());
        out
    }

    fn f32s(v: &[f32]) -> Vec<u8> {
        v.iter().flat_map(|x| x.to_le_bytes()).collect()
    }

    const TRI: [f32; 9] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];

    /// Both versions, every attribute, double precision, and shape_index through the table.
    #[test]
    fn reads_versions_attributes_and_indices() {
        let path = Path::new("m.serialized");
        for version in [3u16, 4] {
            let plain = record(version, 0x1000, 3, &f32s(&TRI), &[[0, 1, 2]]);
            let mut all = f32s(&TRI);
            all.extend(f32s(&[0.0, 0.0, 1.0].repeat(3)));
            all.extend(f32s(&[0.0, 0.0, 1.0, 0.0, 0.0, 1.0]));
            all.extend(f32s(&[1.0; 9])); // colours, skipped
            let full = record(version, 0x1000 | 0xB, 3, &all, &[[2, 1, 0]]);
            let doubles: Vec<u8> = TRI
                .iter()
                .flat_map(|&x| (x as f64 * 2.0).to_le_bytes())
                .collect();
            let double = record(version, 0x2000, 3, &doubles, &[[0, 1, 2]]);
            let bytes = file(version, &[plain, full, double]);
            let m0 = load_bytes(path, &bytes, 0).unwrap();
            assert_eq!(
                (m0.positions.len(), m0.indices, m0.normals, m0.uvs),
                (3, vec![[0, 1, 2]], None, None)
            );
            let m1 = load_bytes(path, &bytes, 1).unwrap();
            assert_eq!(m1.indices, vec![[2, 1, 0]]);
            assert_eq!(m1.normals.as_ref().unwrap()[2], Vec3::Z);
            assert_eq!(m1.uvs.as_ref().unwrap()[2], Vec2::new(0.0, 1.0));
            let m2 = load_bytes(path, &bytes, 2).unwrap();
            assert_eq!(m2.positions[1], Vec3::new(2.0, 0.0, 0.0));
            let e = load_bytes(path, &bytes, 3).unwrap_err().to_string();
            assert!(
                e.contains("shape 3") && e.contains("the file holds 3 meshes"),
                "{e}"
            );
        }
    }

    /// Each malformed input is one error naming the file and the mesh.
    #[test]
    fn malformed_files_are_named_errors() {
        let path = Path::new("bad.serialized");
        let good = file(4, &[record(4, 0x1000, 3, &f32s(&TRI), &[[0, 1, 2]])]);
        let cases: Vec<(Vec<u8>, u32, &str)> = vec![
            (vec![1, 2], 0, "too short"),
            ([&[0u8, 0], &good[2..]].concat(), 0, "magic 0x0000"),
            (
                [&good[..2], &[5u8, 0], &good[4..]].concat(),
                0,
                "version 5 is not supported",
            ),
            (good[..good.len() - 30].to_vec(), 0, "mesh data"),
            (
                file(4, &[record(4, 0x1000, 3, &f32s(&TRI[..6]), &[])]),
                0,
                "ends early",
            ),
            (
                file(4, &[record(4, 0x1000, 3, &f32s(&TRI), &[[0, 1, 7]])]),
                0,
                "out of range",
            ),
            (
                file(4, &[record(4, 0x1000, 1 << 40, &f32s(&TRI), &[])]),
                0,
                "cannot fit",
            ),
            (good.clone(), 1, "shape_index 1 is out of range"),
        ];
        for (bytes, index, fragment) in cases {
            let e = load_bytes(path, &bytes, index).unwrap_err().to_string();
            assert!(
                e.starts_with("bad.serialized") && e.contains(fragment),
                "{fragment}: {e}"
            );
        }
    }
}
