//! An OBJ file opened on its own (`lumis render model.obj`): its faces grouped by the `.mtl`
//! material they use, each material mapped to a scene-format material by the rule in
//! docs/scene-format.md, "OBJ materials". A `mesh` shape of a JSON scene has one material, so
//! [`super::obj::load`] keeps merging everything into one mesh and reads no `.mtl`.
//!
//! The geometry is `obj.rs`'s, through the same checks, rewriting and tobj call
//! ([`super::obj::tobj_models`]), with the same conventions (`v` flipped to `1 − v`; normals and
//! texture coordinates kept per group, where every vertex of the group has them). tobj splits a
//! group into several models where an `o` or `g` starts; they are merged per material. Every
//! `mtllib` is read before the faces are grouped, so a `usemtl` sees the materials of every
//! `.mtl` the file names, wherever its `mtllib` line is (a name defined twice: the last
//! definition). An `mtllib` names one file, which may hold spaces; where no file has the whole
//! name and it has several words, each word is a file (the MTL spec's list).
//!
//! A missing or unreadable `.mtl`, and a `usemtl` that names no material, are warnings (those
//! faces get lumis' default material); so is, in one line, everything the used materials have
//! that lumis does not render. A `.mtl` value that does not parse, or is NaN or infinite, is an
//! error naming the `.mtl` file, its line and the material (`obj_mtl.rs`).

use super::obj::{merge, text, tobj_models, usemtl_name};
use super::{MeshData, MeshError, check, one_line};
use serde_json::{Value, json};
use std::collections::HashSet;
use std::path::{Path, PathBuf};

#[path = "obj_mtl.rs"]
mod mtl;
use mtl::MtlMaterial;

/// An OBJ file opened on its own: its faces grouped by the material they use.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjModel {
    /// One mesh per material used, in order of first use (faces in file order); `material`
    /// indexes `materials`, `None` = faces with no `usemtl`, or a `usemtl` name that no `.mtl`
    /// defines (lumis' default material).
    pub groups: Vec<ObjGroup>,
    /// The materials the groups use, mapped to scene-format JSON (docs/scene-format.md, "OBJ
    /// materials"), in the order of `groups`.
    pub materials: Vec<ObjMaterial>,
    /// Warnings for the user, each one line, without the OBJ's own path in front (the caller
    /// prints `warning: FILE: …`): a `.mtl` that is missing or unreadable, the `usemtl` names no
    /// material has, and one listing what the used materials have that lumis does not render.
    pub warnings: Vec<String>,
}

/// The faces of one material.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjGroup {
    /// The faces, with the vertices they use.
    pub mesh: MeshData,
    /// An index into [`ObjModel::materials`]; `None`: lumis' default material.
    pub material: Option<usize>,
}

/// One `.mtl` material as lumis renders it.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjMaterial {
    /// Its `newmtl` name.
    pub name: String,
    /// A scene-format material: a `diffuse` or a `plastic`, with an `opacity` where it has one;
    /// a texture's `file` is relative to the OBJ's folder.
    pub json: Value,
    /// `Ke` (emitted radiance, RGB), when a channel is positive: the shape's `emission`.
    pub emission: Option<[f64; 3]>,
}

/// The albedo of a material without `Kd` (lumis' default material for a model file).
const DEFAULT_ALBEDO: f64 = 0.8;

/// The `ior` of a plastic whose `Ni` is missing or out of (1, 10].
const DEFAULT_IOR: f64 = 1.5;

/// At most this many `usemtl` names, and materials with what lumis does not render, are named
/// in a warning.
const MAX_NAMES: usize = 10;

/// Reads `path` as an OBJ file with its `.mtl` files (see the module doc).
pub fn load_obj_model(path: &Path) -> Result<ObjModel, MeshError> {
    let bytes =
        std::fs::read(path).map_err(|e| MeshError::at(path, "", format!("cannot read: {e}")))?;
    load_obj_model_bytes(path, &bytes, &|mtl| std::fs::read(mtl).ok())
}

/// [`load_obj_model`] from the OBJ text `obj`, with the `.mtl` files supplied by `mtl` (given
/// the path the OBJ's `mtllib` names, joined to the folder of `path`; `None` if it is missing
/// or unreadable), for tests and the mutation harness. `path` names the OBJ in errors.
pub fn load_obj_model_bytes(
    path: &Path,
    obj: &[u8],
    mtl: &dyn Fn(&Path) -> Option<Vec<u8>>,
) -> Result<ObjModel, MeshError> {
    let text = text(obj);
    let folder = path.parent().unwrap_or(Path::new(""));
    let mut warnings = Vec::new();
    let library = read_libraries(folder, &text, mtl, &mut warnings)?;
    let names: Vec<String> = library.iter().map(|(_, m)| m.name.clone()).collect();
    let models = tobj_models(path, &text, &names)?;

    // The models of each material, in the order of first use.
    let mut keys: Vec<Option<usize>> = Vec::new();
    let mut members: Vec<Vec<&tobj::Model>> = Vec::new();
    for model in models.iter().filter(|m| !m.mesh.indices.is_empty()) {
        let key = model.mesh.material_id;
        match keys.iter().position(|&k| k == key) {
            Some(g) => members[g].push(model),
            None => {
                keys.push(key);
                members.push(vec![model]);
            }
        }
    }
    if keys.is_empty() {
        return Err(MeshError::at(path, "", "no faces"));
    }
    let mut groups = Vec::with_capacity(keys.len());
    let mut materials = Vec::new();
    let mut unrendered = Vec::new();
    for (key, models) in keys.iter().zip(&members) {
        let mesh = merge(path, models)?;
        check(path, &mesh)?;
        let material = key.map(|k| {
            let (dir, m) = &library[k];
            let (material, notes) = map_material(m, dir);
            if !notes.is_empty() {
                unrendered.push(format!("mtl '{}': {}", m.name, notes.join(", ")));
            }
            materials.push(material);
            materials.len() - 1
        });
        groups.push(ObjGroup { mesh, material });
    }
    warnings.extend(unknown_usemtl(&text, &names));
    if !unrendered.is_empty() {
        warnings.push(format!(
            "lumis does not render these .mtl statements: {}",
            listed(unrendered, "; ")
        ));
    }
    // They quote the files' own words, which may hold line breaks.
    let warnings = warnings.into_iter().map(one_line).collect();
    Ok(ObjModel {
        groups,
        materials,
        warnings,
    })
}

/// Every material of the `.mtl` files the OBJ `text` names, in order, each with the folder its
/// file is in relative to the OBJ's (where its textures are); each file is read once. The files
/// that cannot be read are one warning.
fn read_libraries(
    folder: &Path,
    text: &str,
    mtl: &dyn Fn(&Path) -> Option<Vec<u8>>,
    warnings: &mut Vec<String>,
) -> Result<Vec<(PathBuf, MtlMaterial)>, MeshError> {
    let mut library = Vec::new();
    let mut seen = HashSet::new();
    let mut missing = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.split_whitespace().next() != Some("mtllib") {
            continue;
        }
        // An `mtllib` without a name reads nothing; its `usemtl`s are warned about.
        let name = line.trim_start()["mtllib".len()..].trim();
        if name.is_empty() || !seen.insert(folder.join(name)) {
            continue;
        }
        let files = match mtl(&folder.join(name)) {
            Some(bytes) => vec![(name, Some(bytes))],
            None if name.contains(char::is_whitespace) => name
                .split_whitespace()
                .filter(|word| seen.insert(folder.join(word)))
                .map(|word| (word, mtl(&folder.join(word))))
                .collect(),
            None => vec![(name, None)],
        };
        for (name, bytes) in files {
            let file = folder.join(name);
            let Some(bytes) = bytes else {
                missing.push(format!("{} (line {})", file.display(), i + 1));
                continue;
            };
            let materials = mtl::parse(&file, &String::from_utf8_lossy(&bytes))?;
            let dir = Path::new(name).parent().unwrap_or(Path::new("")).to_owned();
            library.extend(materials.into_iter().map(|m| (dir.clone(), m)));
        }
    }
    if !missing.is_empty() {
        warnings.push(format!(
            "cannot read the material library {} (its materials get lumis' default material)",
            listed(missing, ", ")
        ));
    }
    Ok(library)
}

/// `items` joined by `separator`, at most [`MAX_NAMES`] of them.
fn listed(mut items: Vec<String>, separator: &str) -> String {
    if items.len() > MAX_NAMES {
        let more = items.len() - MAX_NAMES;
        items.truncate(MAX_NAMES);
        items.push(format!("and {more} more"));
    }
    items.join(separator)
}

/// The warning about `usemtl` names that no material has, if any: each name once, with the line
/// of its first use.
fn unknown_usemtl(text: &str, names: &[String]) -> Option<String> {
    let defined: HashSet<&str> = names.iter().map(String::as_str).collect();
    let mut seen = HashSet::new();
    let mut unknown: Vec<(&str, usize)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.split_whitespace().next() != Some("usemtl") {
            continue;
        }
        if let Some(name) = usemtl_name(line)
            && !defined.contains(name)
            && seen.insert(name)
        {
            unknown.push((name, i + 1));
        }
    }
    if unknown.is_empty() {
        return None;
    }
    let quoted = unknown
        .iter()
        .map(|(name, line)| format!("'{name}' (line {line})"))
        .collect();
    Some(format!(
        "usemtl names a material no .mtl file defines: {} (its faces get lumis' default material)",
        listed(quoted, ", ")
    ))
}

/// `m` as a scene-format material, with what it has that lumis does not render (or renders
/// changed: clamped values) for the warning. `dir`: the folder of its `.mtl` file relative to
/// the OBJ's.
fn map_material(m: &MtlMaterial, dir: &Path) -> (ObjMaterial, Vec<String>) {
    let mut notes = m.unrendered.clone();
    let mut clamped = |what: &str, changed: bool| {
        if changed {
            notes.push(format!("{what} (clamped)"));
        }
    };
    let kd = m.kd.map(|kd| {
        let c = kd.map(|v| v.clamp(0.0, 1.0));
        clamped("Kd", c != kd);
        c
    });
    let albedo = match &m.map_kd {
        Some(file) => {
            // The MTL spec and three.js multiply the texture by Kd.
            let mut texture = json!({"type": "bitmap", "file": texture_path(dir, file)});
            if let Some(kd) = kd {
                texture["scale"] = json!(kd);
            }
            texture
        }
        None => json!(kd.unwrap_or([DEFAULT_ALBEDO; 3])),
    };
    // illum 0 and 1 mean no highlight, whatever Ks says.
    let specular =
        m.ks.is_some_and(|ks| ks.iter().any(|&c| c > 0.0)) && !matches!(m.illum, Some(0 | 1));
    let mut json = if specular {
        let ns = m.ns.unwrap_or(0.0);
        clamped("Ns", ns < 0.0);
        // Walter et al. 2007's match of a Phong exponent to a GGX roughness.
        let alpha = (2.0 / (ns.max(0.0) + 2.0)).sqrt().clamp(0.001, 1.0);
        let ior =
            m.ni.filter(|&n| n > 1.0 && n <= 10.0)
                .unwrap_or(DEFAULT_IOR);
        json!({"type": "plastic", "albedo": albedo, "alpha": alpha, "ior": ior})
    } else {
        json!({"type": "diffuse", "albedo": albedo})
    };
    let emission = m.ke.filter(|ke| ke.iter().any(|&c| c > 0.0)).map(|ke| {
        let c = ke.map(|v| v.max(0.0));
        clamped("Ke", c != ke);
        c
    });
    let opacity = match (m.d, m.tr) {
        (Some(d), _) => Some(("d", d)),
        (None, Some(tr)) => Some(("Tr", 1.0 - tr)),
        (None, None) => None,
    };
    if let Some((keyword, opacity)) = opacity {
        let a = opacity.clamp(0.0, 1.0);
        clamped(keyword, a != opacity);
        if a < 1.0 {
            if emission.is_some() {
                notes.push(format!("{keyword} (an emitting material cannot be masked)"));
            } else {
                json["opacity"] = json!(a);
            }
        }
    }
    let material = ObjMaterial {
        name: m.name.clone(),
        json,
        emission,
    };
    (material, notes)
}

/// A texture file named in a `.mtl` in folder `dir` (relative to the OBJ's), relative to the
/// OBJ's folder; `\` separators (Windows exporters) become `/`.
fn texture_path(dir: &Path, file: &str) -> String {
    let file = file.replace('\\', "/");
    dir.join(file).to_string_lossy().into_owned()
}

#[cfg(test)]
#[path = "obj_materials_tests.rs"]
mod tests;
