//! Mitsuba 3 XML scenes (`lumis render scene.xml`): the document ([`xml`]) is translated into a
//! scene-format JSON value, which then goes through the JSON front end
//! ([`crate::scene::parse_scene_value_in`]), so an imported scene gets every check a JSON scene
//! gets. The supported subset, the mapping and the refusals are in `docs/mitsuba.md`.
//!
//! Every JSON path the translation writes is remembered with the XML element or attribute it
//! came from, so an error found by the JSON validation still names `file:line:col` and the
//! element path (`scene.xml:12:9: scene/shape[3]/bsdf/rgb@value: …`), as do errors found while
//! translating. Anything Mitsuba would render that lumis cannot render the same is refused with
//! one such error, never dropped.

mod bsdf;
mod cie;
mod delta_emitter;
mod emitter;
pub mod export;
mod export_bsdf;
mod export_shape;
mod integrator;
mod plugin;
mod presets;
pub mod scope;
mod sensor;
mod shape;
mod texture;
mod transform;
pub mod values;
pub mod xml;

#[cfg(test)]
mod tests;

use crate::scene::desc::SceneDesc;
use crate::scene::error::SceneError;
use crate::scene::parse::parse_scene_value_in;
use plugin::Plugin;
use serde_json::{Map, Value as Json, json};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use xml::{Element, Pos};

pub use presets::conductor_preset;
pub use transform::rotation;
pub use xml::Params;

/// A Mitsuba scene, imported: the description and what Mitsuba keeps outside it.
#[derive(Clone, Debug)]
pub struct Imported {
    /// The scene.
    pub desc: SceneDesc,
    /// The sensor's `sample_count` (Mitsuba's default 4 when the sensor has no sampler): the
    /// default samples per pixel.
    pub spp: u32,
    /// The `path` integrator's `rr_depth` (Russian roulette from this path length), if it has
    /// one; it changes the noise, not the image.
    pub rr_depth: Option<u32>,
    /// The translated scene in the JSON format, for `lumis` to save or show.
    pub json: Json,
}

/// Whether `path` names a Mitsuba XML scene (by its `.xml` extension).
pub fn is_mitsuba_file(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// Reads the Mitsuba scene `path` with the command line's `-D name=value` parameters.
pub fn load(path: &Path, defines: &[(String, String)]) -> Result<Imported, SceneError> {
    let params = Params {
        defines: defines.to_vec(),
        spp: None,
    };
    load_params(path, &params)
}

/// Reads the Mitsuba scene `path` with the command line's parameters (`-D`, `--spp`).
pub fn load_params(path: &Path, params: &Params) -> Result<Imported, SceneError> {
    let doc = xml::load(path, params)?;
    let ids = doc.ids()?;
    let folder = path.parent().unwrap_or(Path::new("")).to_owned();
    let mut ctx = Ctx {
        ids,
        folder: folder.clone(),
        search: doc.search.clone(),
        origins: Vec::new(),
        warnings: Vec::new(),
        materials: Map::new(),
        material_names: HashMap::new(),
        used_names: HashMap::new(),
        area_owners: HashMap::new(),
        max_depth: -1,
    };
    let scene = ctx.plugin(&doc.root)?;

    let (mapped, integrator_pos) = match scene.object("integrator")? {
        Some(p) => {
            let it = ctx.plugin(target(p))?;
            (
                integrator::integrator(&mut ctx, &it)?,
                Some(it.pos().clone()),
            )
        }
        // Mitsuba's default integrator is `path` with its defaults.
        None => (
            integrator::Mapped {
                max_depth: -1,
                rr_depth: None,
                hide_emitters: false,
                ptracer: false,
            },
            None,
        ),
    };
    ctx.max_depth = mapped.max_depth;
    let sensors = scene.objects("sensor");
    let Some(first) = sensors.first() else {
        return Err(doc.root.pos.error(
            "the scene has no <sensor>: lumis needs a camera (Mitsuba would place a default \
             one, which lumis does not)",
        ));
    };
    if let Some(second) = sensors.get(1) {
        ctx.warnings.push(format!(
            "{}: the scene has {} sensors; lumis renders the first, as `mitsuba` does by default",
            second.el.pos.describe(),
            sensors.len()
        ));
    }
    let sensor_plugin = ctx.plugin(target(first))?;
    let cam = sensor::sensor(&mut ctx, &sensor_plugin)?;

    let mut background = None;
    let mut lights = Vec::new();
    let mut declared_areas = Vec::new();
    for e in scene.objects("emitter") {
        let plugin = ctx.plugin(target(e))?;
        // A top-level area emitter is a declaration for a shape's <ref> (Mitsuba ignores one
        // that no shape takes).
        if plugin.ty == "area" {
            declared_areas.push(plugin.el);
            continue;
        }
        if delta_emitter::is_delta(plugin.ty) {
            let json_path = format!("lights[{}]", lights.len());
            lights.push(delta_emitter::light(&mut ctx, &plugin, &json_path)?);
            continue;
        }
        let this = emitter::background(&mut ctx, &plugin)?;
        if background.is_some() {
            return Err(plugin.error(
                "a second environment emitter: lumis has one background (constant or envmap)",
            ));
        }
        background = Some(this);
    }
    let mut shapes = Vec::new();
    let mut shape_pos = Vec::new();
    for s in scene.objects("shape") {
        let plugin = ctx.plugin(target(s))?;
        match plugin.ty {
            // Its shapes appear where instances place them (Mitsuba renders none of its own).
            "shapegroup" => {}
            "instance" => {
                for (obj, pos) in shape::instance(&mut ctx, &plugin, shapes.len())? {
                    shapes.push(obj);
                    shape_pos.push(pos);
                }
            }
            _ => {
                if let Some(obj) = shape::shape(&mut ctx, &plugin, shapes.len())? {
                    shapes.push(obj);
                    shape_pos.push(plugin.pos().clone());
                }
            }
        }
    }
    for el in declared_areas {
        if !ctx.area_owners.contains_key(&(el as *const Element)) {
            ctx.warnings.push(format!(
                "{}: an area emitter that no shape takes emits nothing (as in Mitsuba)",
                el.pos.describe()
            ));
        }
    }
    // Declarations for <ref>: translated where they are used (Mitsuba ignores the others).
    for tag in ["bsdf", "texture", "sampler", "film", "rfilter"] {
        scene.objects(tag);
    }
    // <medium>, <phase> and <volume> are out of scope, refused when the scene was read (`scope`).
    scene.finish(
        "integrator, sensor, shape, emitter; bsdf, texture, sampler, film and rfilter as \
         declarations for <ref>",
    )?;

    let mut json = json!({
        "comment": format!("imported from the Mitsuba scene {}", path.display()),
        "camera": cam.camera,
        "max_depth": mapped.max_depth,
        "hide_emitters": mapped.hide_emitters,
        "materials": Json::Object(ctx.materials.clone()),
        "shapes": shapes,
    });
    if !lights.is_empty() {
        json["lights"] = Json::Array(lights);
    }
    if let Some(bg) = background {
        json["background"] = bg;
    }
    let mut desc = parse_scene_value_in(&json, &folder).map_err(|e| ctx.locate(e, path))?;
    if mapped.ptracer
        && let (Err(why), Some(pos)) = (integrator::check_ptracer(&desc), &integrator_pos)
    {
        return Err(pos.error(why));
    }
    for (shape, pos) in desc.shapes.iter_mut().zip(&shape_pos) {
        shape.json_path = pos.describe();
    }
    desc.warnings.extend(ctx.warnings);
    Ok(Imported {
        desc,
        spp: cam.spp,
        rr_depth: mapped.rr_depth,
        json,
    })
}

/// The element a child property names (itself, or a `<ref>`'s target).
pub(crate) fn target<'a>(p: &plugin::Prop<'a>) -> &'a Element {
    p.object().unwrap_or(p.el)
}

/// The translation's state.
pub(crate) struct Ctx<'a> {
    /// Elements by `id`.
    ids: HashMap<&'a str, &'a Element>,
    /// The main file's folder: the JSON's file names are relative to it.
    folder: PathBuf,
    /// The main file's search list, through which objects' file names resolve (`xml`).
    search: Vec<PathBuf>,
    /// JSON paths written, with where they came from.
    origins: Vec<(String, Pos)>,
    /// Things accepted that do not match Mitsuba exactly.
    warnings: Vec<String>,
    /// The `materials` object being built.
    materials: Map<String, Json>,
    /// Material names by BSDF element (`None`: a null BSDF).
    material_names: HashMap<*const Element, Option<String>>,
    /// How often each base name was used, to keep generated names unique.
    used_names: HashMap<String, usize>,
    /// Each area emitter element with the shape it is attached to.
    area_owners: HashMap<*const Element, Pos>,
    /// The integrator's `max_depth` (−1 unlimited), known before any BSDF is read.
    max_depth: i64,
}

impl<'a> Ctx<'a> {
    /// The object `el` with its properties.
    fn plugin(&self, el: &'a Element) -> Result<Plugin<'a>, SceneError> {
        Plugin::new(el, &self.ids)
    }

    /// Records that JSON path `path` came from `pos`.
    fn origin(&mut self, path: &str, pos: &Pos) {
        match self.origins.iter_mut().find(|(p, _)| p == path) {
            Some(entry) => entry.1 = pos.clone(),
            None => self.origins.push((path.to_owned(), pos.clone())),
        }
    }

    /// A fresh material name for BSDF `el`, whose BSDF proper is `inner` (a wrapper's nested
    /// one, else `el`): its id, `WRAPPER(ID)` for an anonymous wrapper of `inner` with an id,
    /// or `TYPE@LINE:COL`.
    fn material_name(&mut self, el: &Element, inner: &Element) -> String {
        let at = |e: &Element| {
            format!(
                "{}@{}:{}",
                e.value("type").unwrap_or("bsdf"),
                e.pos.line,
                e.pos.col
            )
        };
        let base = match (el.value("id"), inner.value("id")) {
            (Some(id), _) => id.to_owned(),
            (None, Some(id)) if !std::ptr::eq(el, inner) => {
                format!("{}({id})", el.value("type").unwrap_or("bsdf"))
            }
            _ => at(el),
        };
        let n = self.used_names.entry(base.clone()).or_insert(0);
        *n += 1;
        let name = if *n == 1 { base } else { format!("{base}#{n}") };
        if self.materials.contains_key(&name) {
            return self.material_name(el, inner);
        }
        name
    }

    /// A file an object names, resolved as Mitsuba resolves it (the main file's `<path>`s,
    /// then its folder, then the working directory: `xml`), written as the JSON should say it:
    /// relative to the main file's folder where it can be, else absolute. A file found nowhere
    /// keeps its name, and reading the scene then fails naming it.
    fn resolve_file(&self, name: &str) -> String {
        let found = xml::resolve(Path::new(name), &self.search);
        if !found.exists() {
            return name.to_owned();
        }
        if let Ok(rel) = found.strip_prefix(&self.folder) {
            return rel.to_string_lossy().into_owned();
        }
        // Outside the main folder (an absolute <path>, or the working directory).
        std::path::absolute(&found)
            .unwrap_or(found)
            .to_string_lossy()
            .into_owned()
    }

    /// A JSON validation error, placed at the XML it came from (the longest recorded prefix of
    /// its path), or at the file when nothing matches.
    fn locate(&self, e: SceneError, file: &Path) -> SceneError {
        let matches = |p: &str| {
            e.path == p
                || (e.path.starts_with(p)
                    && matches!(e.path.as_bytes().get(p.len()), Some(b'.') | Some(b'[')))
        };
        let best = self
            .origins
            .iter()
            .filter(|(p, _)| matches(p))
            .max_by_key(|(p, _)| p.len());
        match best {
            Some((_, pos)) => pos.error(format!("{} (lumis scene key {})", e.message, e.path)),
            None => e.in_file(file),
        }
    }
}
