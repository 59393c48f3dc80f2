//! The OBJ format (Wavefront): a reader through tobj, and a small writer (for generated test
//! meshes, `make_mesh`).
//!
//! What is read: `v` (a fourth number `w` divides x, y, z, as tobj does; three more numbers are a
//! colour, ignored), `vt` (u and v; a lone u gets v = 0), `vn`, and `f` with 1-based or
//! negative (relative) indices, forward references allowed. All objects and groups merge into
//! one mesh; polygons are fanned from their first vertex. A vertex is one distinct
//! `v/vt/vn` triple (tobj's `single_index`), so vertices are numbered in the order faces first
//! use them and unused `v` lines are dropped.
//!
//! Normals and texture coordinates are kept only when every face vertex has one; a file that
//! has them for some faces only reads as having none (`MeshData` has no room for a warning, and
//! Mitsuba 3 likewise needs them on every vertex), and is then shaded flat.
//!
//! Ignored: materials (`mtllib`, `usemtl`; no `.mtl` file is opened, so a missing one is no
//! error: a `mesh` shape has one material; `obj_materials.rs` reads them for an OBJ file opened
//! on its own), lines (`l`), points (`p`), smoothing groups, free-form geometry.
//!
//! Errors name the file and the line (`bunny.obj line 17: face index 4021 out of range (3000
//! vertices)`). tobj's own errors carry no line, so the text is checked first, here: numbers
//! that do not parse or are not finite, a face index of 0 or out of range (also for `vt` and
//! `vn`), a face with fewer than 3 vertices. A few constructs tobj mishandles are rewritten
//! before it sees them: `l` lines (tobj would turn a polyline into triangles), `usemtl` lines
//! (one without a name after a space is an error in tobj, and it reads another name where a
//! tab follows the keyword), vertex colours (tobj fails when only some vertices have one) and
//! one-number `vt` lines.

use super::{MeshData, MeshError, check};
use glam::{Vec2, Vec3};
use std::borrow::Cow;
use std::cell::Cell;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// Reads `path` as an OBJ file (see the module doc for what is read and rejected).
pub fn load(path: &Path) -> Result<MeshData, MeshError> {
    let bytes =
        std::fs::read(path).map_err(|e| MeshError::at(path, "", format!("cannot read: {e}")))?;
    load_bytes(path, &bytes)
}

/// Reads the OBJ text `bytes` as [`load`] reads a file; `path` only names it in errors (no file
/// is opened: materials are ignored). The entry point of the fuzz target `mesh_obj`.
pub fn load_bytes(path: &Path, bytes: &[u8]) -> Result<MeshData, MeshError> {
    let models = tobj_models(path, &text(bytes), &[])?;
    let mesh = merge(path, &models.iter().collect::<Vec<_>>())?;
    check(path, &mesh)?;
    Ok(mesh)
}

/// The text of an OBJ file (invalid UTF-8 can only matter in names and comments; tobj needs a
/// `str`).
pub(super) fn text(bytes: &[u8]) -> Cow<'_, str> {
    String::from_utf8_lossy(bytes)
}

/// The models tobj reads from the OBJ `text` (named `path` in errors), after this module's
/// checks and rewriting (the module doc): triangulated, one vertex per distinct `v/vt/vn`
/// triple, split where an `o` or `g` starts or the material changes. A `usemtl` resolves
/// against `materials`, the names of every material the file's `.mtl` files define, in order
/// (a name given twice: its last definition), wherever the `mtllib` lines are; a model's
/// `material_id` indexes `materials`. With no materials, every `material_id` is `None`.
pub(super) fn tobj_models(
    path: &Path,
    text: &str,
    materials: &[String],
) -> Result<Vec<tobj::Model>, MeshError> {
    let totals = count(text);
    let rewrite = scan(path, text, &totals)?;
    let mut text: Cow<str> = if rewrite {
        Cow::Owned(rewritten(text))
    } else {
        Cow::Borrowed(text)
    };
    if !materials.is_empty() {
        // tobj resolves a `usemtl` against the materials that `mtllib` lines before it have
        // loaded: one `mtllib` line in front, for which the loader returns them all, makes
        // every `usemtl` see every material (the file's own `mtllib` lines then load nothing).
        text = Cow::Owned(format!("mtllib\n{text}"));
    }
    let first = Cell::new(true);
    let loader = |_: &Path| -> tobj::MTLLoadResult {
        if materials.is_empty() || !first.replace(false) {
            return Err(tobj::LoadError::OpenFileFailed);
        }
        let names = materials
            .iter()
            .map(|name| tobj::Material {
                name: name.clone(),
                ..Default::default()
            })
            .collect();
        let index = materials
            .iter()
            .enumerate()
            .map(|(i, name)| (name.clone(), i))
            .collect();
        Ok((names, index))
    };
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &options, loader)
        .map_err(|e| MeshError::at(path, "", format!("tobj: {e}")))?;
    Ok(models)
}

/// The material a `usemtl` line names: everything after the keyword, trimmed (a name may hold
/// spaces); `None` if nothing.
pub(super) fn usemtl_name(line: &str) -> Option<&str> {
    let name = line.trim_start().strip_prefix("usemtl")?.trim();
    (!name.is_empty()).then_some(name)
}

/// How many `v`, `vt` and `vn` lines a file has.
#[derive(Default)]
struct Counts {
    v: usize,
    vt: usize,
    vn: usize,
}

/// Counts the vertex lines (for positive face indices, which may point forward).
fn count(text: &str) -> Counts {
    let mut c = Counts::default();
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => c.v += 1,
            Some("vt") => c.vt += 1,
            Some("vn") => c.vn += 1,
            _ => {}
        }
    }
    c
}

/// Checks every line tobj would read; returns whether the text must be rewritten for tobj.
fn scan(path: &Path, text: &str, totals: &Counts) -> Result<bool, MeshError> {
    let mut seen = Counts::default();
    let mut rewrite = false;
    for (i, line) in text.lines().enumerate() {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        let result = match keyword {
            Some("v") => {
                seen.v += 1;
                vertex(words, &mut rewrite)
            }
            Some("vt") => {
                seen.vt += 1;
                texcoord(words, &mut rewrite)
            }
            Some("vn") => {
                seen.vn += 1;
                numbers(words, &["x", "y", "z"], "vn").map(|_| ())
            }
            Some("f") => face(words, totals, &seen),
            Some("l") => {
                rewrite = true;
                Ok(())
            }
            Some("usemtl") => {
                // tobj takes the name after the first space: none (a bare `usemtl`, or a tab)
                // is an error there, and a space in front or a tab after the keyword gives
                // another name than `usemtl_name`'s.
                let tobj_name = line
                    .split_once(' ')
                    .map(|(_, name)| name.trim())
                    .filter(|name| !name.is_empty());
                rewrite |= tobj_name.is_none() || tobj_name != usemtl_name(line);
                Ok(())
            }
            _ => Ok(()),
        };
        result.map_err(|m| MeshError::at(path, &format!("line {}", i + 1), m))?;
    }
    Ok(rewrite)
}

/// Parses exactly `names.len()` finite numbers after `keyword`.
fn numbers<'a>(
    words: impl Iterator<Item = &'a str>,
    names: &[&str],
    keyword: &str,
) -> Result<Vec<f32>, String> {
    let values = words
        .zip(names.iter().chain(std::iter::repeat(&"")))
        .map(|(w, n)| number(w, n))
        .collect::<Result<Vec<_>, _>>()?;
    if values.len() != names.len() {
        return Err(format!(
            "'{keyword}' needs {} numbers, found {}",
            names.len(),
            values.len()
        ));
    }
    Ok(values)
}

/// One finite number, parsed as tobj does (`f32`), or why not (named `name`).
fn number(word: &str, name: &str) -> Result<f32, String> {
    let v: f32 = word
        .parse()
        .map_err(|_| format!("'{word}' is not a number"))?;
    let name = if name.is_empty() { "a value" } else { name };
    if v.is_finite() {
        Ok(v)
    } else if v.is_nan() {
        Err(format!("{name} is NaN"))
    } else if word.parse::<f64>().is_ok_and(f64::is_finite) {
        Err(format!("{name} = {word} is beyond single precision"))
    } else {
        Err(format!("{name} is infinite"))
    }
}

/// A `v` line: x y z, optionally w or an r g b colour.
fn vertex<'a>(words: impl Iterator<Item = &'a str>, rewrite: &mut bool) -> Result<(), String> {
    let words: Vec<&str> = words.collect();
    let names: &[&str] = match words.len() {
        3 => &["x", "y", "z"],
        4 => &["x", "y", "z", "w"],
        6 => &["x", "y", "z", "r", "g", "b"],
        n => {
            return Err(format!(
                "'v' needs 3 numbers (4 with w, 6 with a colour), found {n}"
            ));
        }
    };
    let v = numbers(words.into_iter(), names, "v")?;
    if v.len() == 4 {
        if v[3] == 0.0 {
            return Err("w is 0".into());
        }
        for (c, name) in v[..3].iter().zip(["x", "y", "z"]) {
            if !(c / v[3]).is_finite() {
                return Err(format!("{name} / w is beyond single precision"));
            }
        }
    }
    *rewrite |= v.len() == 6;
    Ok(())
}

/// A `vt` line: u, optionally v and w.
fn texcoord<'a>(words: impl Iterator<Item = &'a str>, rewrite: &mut bool) -> Result<(), String> {
    let words: Vec<&str> = words.collect();
    let names: &[&str] = match words.len() {
        1 => &["u"],
        2 => &["u", "v"],
        3 => &["u", "v", "w"],
        n => return Err(format!("'vt' needs 1 to 3 numbers, found {n}")),
    };
    numbers(words.into_iter(), names, "vt")?;
    *rewrite |= names.len() == 1;
    Ok(())
}

/// An `f` line: at least 3 references `v`, `v/vt`, `v//vn` or `v/vt/vn`, all in range.
fn face<'a>(
    words: impl Iterator<Item = &'a str>,
    totals: &Counts,
    seen: &Counts,
) -> Result<(), String> {
    let mut n = 0;
    for word in words {
        n += 1;
        let parts: Vec<&str> = word.split('/').collect();
        if parts.len() > 3 || parts[0].is_empty() {
            return Err(format!("bad vertex reference '{word}'"));
        }
        let kinds = [
            ("face index", "vertices", totals.v, seen.v),
            (
                "face texture index",
                "texture coordinates",
                totals.vt,
                seen.vt,
            ),
            ("face normal index", "normals", totals.vn, seen.vn),
        ];
        for (part, (what, unit, total, so_far)) in parts.iter().zip(kinds) {
            if part.is_empty() {
                continue;
            }
            let i: isize = part
                .parse()
                .map_err(|_| format!("bad vertex reference '{word}'"))?;
            if i == 0 {
                return Err(format!("{what} 0 (OBJ indices start at 1)"));
            }
            if i > 0 && i.unsigned_abs() > total {
                return Err(format!("{what} {i} out of range ({total} {unit})"));
            }
            if i < 0 && i.unsigned_abs() > so_far {
                return Err(format!(
                    "{what} {i} out of range ({so_far} {unit} before this line)"
                ));
            }
        }
    }
    if n < 3 {
        return Err(format!("a face needs at least 3 vertices, found {n}"));
    }
    Ok(())
}

/// The text with the constructs tobj mishandles replaced (see the module doc); line numbers
/// stay the same.
fn rewritten(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            ["l", ..] => {}
            ["usemtl", ..] => {
                if let Some(name) = usemtl_name(line) {
                    out.push_str("usemtl ");
                    out.push_str(name);
                }
            }
            ["v", x, y, z, _, _, _] => out.push_str(&format!("v {x} {y} {z}")),
            ["vt", u] => out.push_str(&format!("vt {u} 0")),
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    out
}

/// tobj's `models` as one mesh (normals and texture coordinates only if all of them have them).
pub(super) fn merge(path: &Path, models: &[&tobj::Model]) -> Result<MeshData, MeshError> {
    let complete = |len: fn(&tobj::Mesh) -> usize| {
        models
            .iter()
            .all(|m| len(&m.mesh) == m.mesh.positions.len() / 3)
    };
    let has_normals = complete(|m| m.normals.len() / 3);
    let has_uvs = complete(|m| m.texcoords.len() / 2);
    let mut mesh = MeshData {
        normals: has_normals.then(Vec::new),
        uvs: has_uvs.then(Vec::new),
        ..Default::default()
    };
    for m in models.iter().map(|m| &m.mesh) {
        let base = u32::try_from(mesh.positions.len())
            .map_err(|_| MeshError::at(path, "", "more vertices than 32-bit indices reach"))?;
        mesh.positions
            .extend(m.positions.chunks_exact(3).map(Vec3::from_slice));
        mesh.indices.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [base + t[0], base + t[1], base + t[2]]),
        );
        if let Some(normals) = &mut mesh.normals {
            normals.extend(m.normals.chunks_exact(3).map(Vec3::from_slice));
        }
        if let Some(uvs) = &mut mesh.uvs {
            // OBJ's v runs up from the image's bottom; textures index rows from the top
            // (Mitsuba 3 flips OBJ texture coordinates the same way).
            uvs.extend(
                m.texcoords
                    .chunks_exact(2)
                    .map(|t| Vec2::new(t[0], 1.0 - t[1])),
            );
        }
    }
    if mesh.indices.is_empty() {
        return Err(MeshError::at(path, "", "no faces"));
    }
    Ok(mesh)
}

/// Writes `mesh` to `path` as OBJ (`v`, `vt`, `vn` one per vertex, `f` with shared indices).
/// Values use Rust's shortest round-trip formatting, so the file reads back exactly (with
/// vertices renumbered in the order the faces first use them, as the reader numbers them).
pub fn write(path: &Path, mesh: &MeshData) -> io::Result<()> {
    let mut w = BufWriter::with_capacity(1 << 20, File::create(path)?);
    writeln!(w, "# written by lumis")?;
    for p in &mesh.positions {
        writeln!(w, "v {} {} {}", p.x, p.y, p.z)?;
    }
    for t in mesh.uvs.iter().flatten() {
        // Back to OBJ's bottom-up v (the reader flips it).
        writeln!(w, "vt {} {}", t.x, 1.0 - t.y)?;
    }
    for n in mesh.normals.iter().flatten() {
        writeln!(w, "vn {} {} {}", n.x, n.y, n.z)?;
    }
    let (uv, normal) = (mesh.uvs.is_some(), mesh.normals.is_some());
    for t in &mesh.indices {
        w.write_all(b"f")?;
        for i in t.map(|i| i + 1) {
            match (uv, normal) {
                (false, false) => write!(w, " {i}")?,
                (true, false) => write!(w, " {i}/{i}")?,
                (false, true) => write!(w, " {i}//{i}")?,
                (true, true) => write!(w, " {i}/{i}/{i}")?,
            }
        }
        w.write_all(b"\n")?;
    }
    w.flush()
}

#[cfg(test)]
#[path = "obj_tests.rs"]
mod tests;
