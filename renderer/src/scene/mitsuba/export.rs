//! Export: a [`SceneDesc`] as a Mitsuba 3 XML scene (`lumis export scene.json -o scene.xml`),
//! the inverse of the importer in this module, so that importing the written file gives a scene
//! that renders like the original (`renderer/tests/mitsuba_export.rs`). Meshes Mitsuba cannot read from
//! the scene's own files (glTF, inline triangles, polygons) go into binary PLY files beside the
//! XML. Anything the exporter cannot express exactly (a `mix`, a bitmap's `scale`, a textured
//! sphere, …) is an error naming the JSON path, never a silently different scene.
//!
//! Numbers are written with Rust's shortest round-trip formatting (`{:?}`), so the importer
//! reads back the very `f64` (or `f32`) the description holds; where the importer computes a
//! value from a transform (a rectangle's corner), the transform is chosen so that it computes
//! exactly the original (see [`super::export_shape`]).

use super::export_bsdf::{Bsdfs, color_value, texture_xml};
use super::export_shape::shape;
use crate::integrator::Settings;
use crate::scene::desc::{
    BackgroundDesc, FilterDesc, LightDesc, LookAt, ProjectionDesc, SceneDesc,
};
use crate::scene::error::SceneError;
use crate::scene::mesh::MeshData;
use crate::scene::mesh::ply::{Encoding, write as write_ply};
use glam::DVec3;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// What the XML says beyond the scene description.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportOptions {
    /// The sampler's `sample_count`; `None` leaves Mitsuba's default (4).
    pub spp: Option<u32>,
    /// The `path` integrator's `rr_depth` (lumis' [`Settings::rr_depth`]: Russian roulette from
    /// this path length, which the importer maps back one to one).
    pub rr_depth: u32,
}

impl Default for ExportOptions {
    /// No sample count, lumis' default Russian roulette depth.
    fn default() -> ExportOptions {
        ExportOptions {
            spp: None,
            rr_depth: Settings::default().rr_depth,
        }
    }
}

/// An exported scene: the XML text and the mesh files it names.
#[derive(Clone, Debug)]
pub struct Exported {
    /// The Mitsuba 3 XML document.
    pub xml: String,
    /// PLY files to write beside the XML: the path (in the XML's folder) and the mesh.
    pub meshes: Vec<(PathBuf, MeshData)>,
}

/// `desc` as a Mitsuba scene to be written at `xml_path` (whose folder the file names written
/// are relative to, and where the PLY files go, named `STEM_shapes_N.ply` after their shape).
pub fn export_scene(
    desc: &SceneDesc,
    xml_path: &Path,
    options: &ExportOptions,
) -> Result<Exported, SceneError> {
    let folder = xml_path.parent().unwrap_or(Path::new("")).to_owned();
    let stem = xml_path
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let mut x = Xml::default();
    x.line("<?xml version=\"1.0\" encoding=\"utf-8\"?>");
    x.line(&format!(
        "<!-- exported by lumis {} (lumis export); docs/mitsuba.md, Export -->",
        env!("CARGO_PKG_VERSION")
    ));
    x.open("scene", &[("version", "3.0.0")]);
    integrator(&mut x, desc, options);
    sensor(&mut x, desc, options)?;
    background(&mut x, desc, &folder)?;
    lights(&mut x, desc, &folder)?;
    let mut ctx = ExportCtx {
        folder,
        stem,
        meshes: Vec::new(),
        bsdfs: Bsdfs::default(),
    };
    let mut shapes = Xml {
        depth: x.depth,
        ..Xml::default()
    };
    for s in &desc.shapes {
        shape(&mut ctx, &mut shapes, desc, s)?;
    }
    // BSDFs first (declared with ids, referenced by the shapes).
    x.out.push_str(
        &ctx.bsdfs
            .xml(&desc.materials, &ctx.folder, x.depth, desc.max_depth)?,
    );
    x.out.push_str(&shapes.out);
    x.close("scene");
    Ok(Exported {
        xml: x.out,
        meshes: ctx.meshes,
    })
}

/// [`export_scene`], then writes the XML to `xml_path` and the PLY files beside it; returns
/// every file written, the XML first.
pub fn write_export(
    desc: &SceneDesc,
    xml_path: &Path,
    options: &ExportOptions,
) -> Result<Vec<PathBuf>, SceneError> {
    let e = export_scene(desc, xml_path, options)?;
    let io = |p: &Path, err: std::io::Error| {
        SceneError::new("", format!("cannot write {}: {err}", p.display()))
    };
    std::fs::write(xml_path, &e.xml).map_err(|err| io(xml_path, err))?;
    let mut written = vec![xml_path.to_owned()];
    for (path, mesh) in &e.meshes {
        write_ply(path, mesh, Encoding::BinaryLittleEndian).map_err(|err| io(path, err))?;
        written.push(path.clone());
    }
    Ok(written)
}

/// The state of one export.
pub(crate) struct ExportCtx {
    /// The XML's folder.
    pub folder: PathBuf,
    /// The XML's file stem, for the PLY names.
    pub stem: String,
    /// PLY files to write.
    pub meshes: Vec<(PathBuf, MeshData)>,
    /// The materials used, declared once each.
    pub bsdfs: Bsdfs,
}

/// `<integrator type="path">`: the importer reads `max_depth` and `rr_depth` one to one.
fn integrator(x: &mut Xml, desc: &SceneDesc, options: &ExportOptions) {
    x.open("integrator", &[("type", "path")]);
    x.leaf(
        "integer",
        &[
            ("name", "max_depth"),
            ("value", &desc.max_depth.to_string()),
        ],
    );
    x.leaf(
        "integer",
        &[
            ("name", "rr_depth"),
            ("value", &options.rr_depth.to_string()),
        ],
    );
    if desc.hide_emitters {
        x.leaf("boolean", &[("name", "hide_emitters"), ("value", "true")]);
    }
    x.close("integrator");
}

/// Where the exported orthographic camera's rays start, ahead of its lookat origin (Mitsuba's
/// default; any positive value would do).
const ORTHOGRAPHIC_NEAR_CLIP: f64 = 1e-2;

/// The sensor: lumis' camera is Mitsuba's `lookat` frame; a perspective or thin-lens camera
/// with the vertical field of view (`fov_axis` y), an orthographic one with the film's size as
/// a `scale` before the `lookat` and its near plane at Mitsuba's default `near_clip` behind
/// `from`; an `hdrfilm` of the image size with the camera's pixel filter, and an independent
/// sampler. Mitsuba's gaussian has radius 4σ, so another radius is refused.
fn sensor(x: &mut Xml, desc: &SceneDesc, options: &ExportOptions) -> Result<(), SceneError> {
    let c = &desc.camera;
    let (mut from, mut to) = (c.from, c.to);
    if c.principal_point_offset != [0.0; 2]
        && !matches!(c.projection, ProjectionDesc::Perspective { .. })
    {
        return Err(SceneError::new(
            "camera.principal_point_offset",
            "Mitsuba's thinlens and orthographic sensors have no principal point offset",
        ));
    }
    match c.projection {
        ProjectionDesc::Perspective { vfov_deg } => {
            x.open("sensor", &[("type", "perspective")]);
            x.leaf("float", &[("name", "fov"), ("value", &num(vfov_deg))]);
            x.leaf("string", &[("name", "fov_axis"), ("value", "y")]);
            let [ox, oy] = c.principal_point_offset;
            if [ox, oy] != [0.0; 2] {
                x.leaf(
                    "float",
                    &[("name", "principal_point_offset_x"), ("value", &num(ox))],
                );
                x.leaf(
                    "float",
                    &[("name", "principal_point_offset_y"), ("value", &num(oy))],
                );
            }
        }
        ProjectionDesc::ThinLens {
            vfov_deg,
            aperture_radius,
            focus_distance,
        } => {
            x.open("sensor", &[("type", "thinlens")]);
            x.leaf("float", &[("name", "fov"), ("value", &num(vfov_deg))]);
            x.leaf("string", &[("name", "fov_axis"), ("value", "y")]);
            let leaf =
                |x: &mut Xml, name, v| x.leaf("float", &[("name", name), ("value", &num(v))]);
            leaf(x, "aperture_radius", aperture_radius);
            leaf(x, "focus_distance", focus_distance);
        }
        ProjectionDesc::Orthographic { .. } => {
            x.open("sensor", &[("type", "orthographic")]);
            let back = (c.to - c.from).normalize() * ORTHOGRAPHIC_NEAR_CLIP;
            (from, to) = (c.from - back, c.to - back);
            x.leaf(
                "float",
                &[
                    ("name", "near_clip"),
                    ("value", &num(ORTHOGRAPHIC_NEAR_CLIP)),
                ],
            );
        }
    }
    x.open("transform", &[("name", "to_world")]);
    if let ProjectionDesc::Orthographic { view_size: [w, h] } = c.projection {
        // Mitsuba's film spans [−1, 1] × [−1/aspect, 1/aspect] before `to_world`.
        let aspect = c.width as f64 / c.height as f64;
        x.leaf(
            "scale",
            &[("x", &num(0.5 * w)), ("y", &num(0.5 * h * aspect))],
        );
    }
    x.leaf(
        "lookat",
        &[
            ("origin", &vec3(from)),
            ("target", &vec3(to)),
            ("up", &vec3(c.up)),
        ],
    );
    x.close("transform");
    x.open("sampler", &[("type", "independent")]);
    if let Some(spp) = options.spp {
        x.leaf(
            "integer",
            &[("name", "sample_count"), ("value", &spp.to_string())],
        );
    }
    x.close("sampler");
    x.open("film", &[("type", "hdrfilm")]);
    x.leaf(
        "integer",
        &[("name", "width"), ("value", &c.width.to_string())],
    );
    x.leaf(
        "integer",
        &[("name", "height"), ("value", &c.height.to_string())],
    );
    x.leaf("string", &[("name", "pixel_format"), ("value", "rgb")]);
    match c.filter {
        FilterDesc::Box => x.leaf("rfilter", &[("type", "box")]),
        FilterDesc::Gaussian { stddev, radius } => {
            if radius != 4.0 * stddev {
                return Err(SceneError::new(
                    "camera.filter.radius",
                    format!(
                        "Mitsuba's gaussian filter has radius 4 × stddev ({}), not {radius}",
                        4.0 * stddev
                    ),
                ));
            }
            x.open("rfilter", &[("type", "gaussian")]);
            x.leaf("float", &[("name", "stddev"), ("value", &num(stddev))]);
            x.close("rfilter");
        }
        FilterDesc::Tent { radius } => {
            x.open("rfilter", &[("type", "tent")]);
            x.leaf("float", &[("name", "radius"), ("value", &num(radius))]);
            x.close("rfilter");
        }
        FilterDesc::Lanczos { lobes } => {
            x.open("rfilter", &[("type", "lanczos")]);
            x.leaf(
                "integer",
                &[("name", "lobes"), ("value", &lobes.to_string())],
            );
            x.close("rfilter");
        }
        FilterDesc::Mitchell { b, c } => {
            x.open("rfilter", &[("type", "mitchell")]);
            x.leaf("float", &[("name", "B"), ("value", &num(b))]);
            x.leaf("float", &[("name", "C"), ("value", &num(c))]);
            x.close("rfilter");
        }
        FilterDesc::CatmullRom => x.leaf("rfilter", &[("type", "catmullrom")]),
    }
    x.close("film");
    x.close("sensor");
    Ok(())
}

/// The background as a `constant` or `envmap` emitter (none for black, Mitsuba's default).
fn background(x: &mut Xml, desc: &SceneDesc, folder: &Path) -> Result<(), SceneError> {
    match &desc.background {
        BackgroundDesc::Constant(c) if *c == DVec3::ZERO => {}
        BackgroundDesc::Constant(c) => {
            x.open("emitter", &[("type", "constant")]);
            color_value(x, "radiance", *c);
            x.close("emitter");
        }
        BackgroundDesc::Envmap(e) => {
            let name = envmap_file(e, folder)?;
            x.open("emitter", &[("type", "envmap")]);
            x.leaf("string", &[("name", "filename"), ("value", &name)]);
            x.leaf("float", &[("name", "scale"), ("value", &num(e.scale))]);
            if e.rotate_y_deg != 0.0 || e.rotation.is_some() {
                // Mitsuba applies a transform's elements in order: the rotation, then the turn
                // about +y, as lumis does. Its rotate about +y is lumis' rotate_y_deg.
                x.open("transform", &[("name", "to_world")]);
                if let Some(r) = e.rotation {
                    x.leaf(
                        "matrix",
                        &[("value", &matrix_value(&glam::DMat4::from_mat3(r)))],
                    );
                }
                if e.rotate_y_deg != 0.0 {
                    x.leaf("rotate", &[("y", "1"), ("angle", &num(e.rotate_y_deg))]);
                }
                x.close("transform");
            }
            x.close("emitter");
        }
    }
    Ok(())
}

/// The envmap's file name for the exported scene: its own file, or, for a map that exists only
/// in memory (a model's studio, `scene/model_studio.rs`, named `model.obj#studio.exr`), the map
/// written as an EXR beside the scene (`#` becomes `_`).
fn envmap_file(e: &crate::scene::EnvmapDesc, folder: &Path) -> Result<String, SceneError> {
    if e.file.exists() {
        return Ok(file_name(&e.file, folder));
    }
    let name = e
        .file
        .file_name()
        .map(|n| n.to_string_lossy().replace('#', "_"))
        .unwrap_or_else(|| "environment.exr".into());
    e.image
        .write(&folder.join(&name), 0.0)
        .map_err(|err| SceneError::new("background", err.to_string()))?;
    Ok(name)
}

/// Each light as the Mitsuba delta emitter the importer maps back to it (`delta_emitter`): a
/// `point` at its `position`, a `directional` along its `direction`, a `spot` and a
/// `projector` in a `to_world` `lookat` of their frame (the importer takes its origin, axis and
/// orthonormalised up back); the projector's field of view is the horizontal one
/// (`fov_axis` x), which lumis stores.
fn lights(x: &mut Xml, desc: &SceneDesc, folder: &Path) -> Result<(), SceneError> {
    for (i, light) in desc.lights.iter().enumerate() {
        let path = format!("lights[{i}]");
        match light {
            LightDesc::Point {
                position,
                intensity,
            } => {
                x.open("emitter", &[("type", "point")]);
                x.leaf(
                    "point",
                    &[("name", "position"), ("value", &vec3(*position))],
                );
                color_value(x, "intensity", *intensity);
            }
            LightDesc::Spot {
                frame,
                intensity,
                cutoff_angle_deg,
                beam_width_deg,
                texture,
            } => {
                x.open("emitter", &[("type", "spot")]);
                color_value(x, "intensity", *intensity);
                x.leaf(
                    "float",
                    &[("name", "cutoff_angle"), ("value", &num(*cutoff_angle_deg))],
                );
                x.leaf(
                    "float",
                    &[("name", "beam_width"), ("value", &num(*beam_width_deg))],
                );
                if let Some(t) = texture {
                    texture_xml(x, "texture", t, false, folder, &format!("{path}.texture"))?;
                }
                look_at(x, frame);
            }
            LightDesc::Directional {
                direction,
                irradiance,
            } => {
                x.open("emitter", &[("type", "directional")]);
                x.leaf(
                    "vector",
                    &[("name", "direction"), ("value", &vec3(*direction))],
                );
                color_value(x, "irradiance", *irradiance);
            }
            LightDesc::Projector {
                frame,
                fov_x_deg,
                irradiance,
                texture,
                scale,
            } => {
                x.open("emitter", &[("type", "projector")]);
                match texture {
                    Some(t) => texture_xml(
                        x,
                        "irradiance",
                        t,
                        false,
                        folder,
                        &format!("{path}.irradiance"),
                    )?,
                    None => color_value(x, "irradiance", *irradiance),
                }
                x.leaf("float", &[("name", "scale"), ("value", &num(*scale))]);
                x.leaf("float", &[("name", "fov"), ("value", &num(*fov_x_deg))]);
                x.leaf("string", &[("name", "fov_axis"), ("value", "x")]);
                look_at(x, frame);
            }
        }
        x.close("emitter");
    }
    Ok(())
}

/// `<transform name="to_world"><lookat …/></transform>` of a light's frame.
fn look_at(x: &mut Xml, f: &LookAt) {
    x.open("transform", &[("name", "to_world")]);
    x.leaf(
        "lookat",
        &[
            ("origin", &vec3(f.from)),
            ("target", &vec3(f.to)),
            ("up", &vec3(f.up)),
        ],
    );
    x.close("transform");
}

/// A file as the XML names it: relative to the XML's folder when it lies inside it (both
/// made absolute first), else absolute.
pub(crate) fn file_name(file: &Path, folder: &Path) -> String {
    let abs = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_owned());
    let (file, folder) = (abs(file), abs(folder));
    match file.strip_prefix(&folder) {
        Ok(rel) => rel.to_string_lossy().into_owned(),
        Err(_) => file.to_string_lossy().into_owned(),
    }
}

/// A `<matrix value>`: the 16 entries row by row.
pub(crate) fn matrix_value(m: &glam::DMat4) -> String {
    let rows = m.transpose().to_cols_array();
    rows.iter().map(|&v| num(v)).collect::<Vec<_>>().join(" ")
}

/// `x` in shortest round-trip form (`0.1`, `1e-7`): the importer parses back this very `f64`.
pub(crate) fn num(x: f64) -> String {
    format!("{x:?}")
}

/// An `f32` in the shortest form that parses (as `f64`, then rounded to `f32`, as the importer
/// and the JSON front end read it) back to `x`.
pub(crate) fn num32(x: f32) -> String {
    let s = format!("{x:?}");
    if s.parse::<f64>().map(|d| d as f32) == Ok(x) {
        s
    } else {
        num(x as f64)
    }
}

/// Three numbers, space-separated.
pub(crate) fn vec3(v: DVec3) -> String {
    format!("{} {} {}", num(v.x), num(v.y), num(v.z))
}

/// A minimal XML writer: indented elements with escaped attribute values.
#[derive(Default)]
pub(crate) struct Xml {
    /// The text so far.
    pub out: String,
    /// The current nesting depth.
    pub depth: usize,
}

impl Xml {
    /// One raw line at the current depth.
    pub fn line(&mut self, text: &str) {
        let _ = writeln!(self.out, "{}{text}", "    ".repeat(self.depth));
    }

    fn tag(tag: &str, attrs: &[(&str, &str)]) -> String {
        let mut s = format!("<{tag}");
        for (k, v) in attrs {
            let _ = write!(s, " {k}=\"{}\"", escape(v));
        }
        s
    }

    /// `<tag attrs>`, then deeper.
    pub fn open(&mut self, tag: &str, attrs: &[(&str, &str)]) {
        self.line(&format!("{}>", Self::tag(tag, attrs)));
        self.depth += 1;
    }

    /// `</tag>`, one level up.
    pub fn close(&mut self, tag: &str) {
        self.depth -= 1;
        self.line(&format!("</{tag}>"));
    }

    /// `<tag attrs/>`.
    pub fn leaf(&mut self, tag: &str, attrs: &[(&str, &str)]) {
        self.line(&format!("{}/>", Self::tag(tag, attrs)));
    }
}

/// `s` as an attribute value between double quotes.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // The importer (like Mitsuba) substitutes `$name` parameters; `\$` is a dollar.
            '$' => out.push_str("\\$"),
            c => out.push(c),
        }
    }
    out
}
