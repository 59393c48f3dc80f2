//! Parsing and validating a scene file into a [`SceneDesc`]: the entry points, the root object
//! and the camera. Materials and shapes live in `parse_materials.rs` and `parse_shapes.rs`.
//!
//! The JSON is first read into a `serde_json::Value` and then walked by hand rather than derived
//! with serde, so that every error can name the JSON path of the problem.

use super::desc::{BackgroundDesc, CameraDesc, FilterDesc, ProjectionDesc, SceneDesc};
use super::error::SceneError;
use super::model::ModelOptions;
use super::parse_background::parse_background;
use super::parse_materials::parse_materials;
use super::parse_shapes::{parse_shapes, unit};
use super::parse_texture::{Preloaded, TextureLoader};
use super::walk::{Obj, array, check_components, integer, parse_json};
use glam::DVec3;
use serde_json::Value;
use std::path::Path;

/// Largest accepted image width or height: anything above is surely a typo, and would need
/// gigabytes of accumulation buffers.
pub const MAX_IMAGE_SIZE: u32 = 16384;

/// Largest accepted emitted or background radiance. A sample is the radiance times the
/// estimator's weights (BSDF over pdf, MIS), which reach 1e4 on the shipped scenes; this leaves
/// eight orders of magnitude of headroom below single precision's 3.4e38, where samples would
/// overflow to infinity and be discarded.
pub const MAX_RADIANCE: f64 = 1e30;

/// Parses and validates scene JSON text; files it names are relative to the current folder.
pub fn parse_scene(text: &str) -> Result<SceneDesc, SceneError> {
    parse_scene_in(text, Path::new(""))
}

/// Parses and validates scene JSON text whose file references are relative to `folder`.
pub fn parse_scene_in(text: &str, folder: &Path) -> Result<SceneDesc, SceneError> {
    parse_scene_value_in(&parse_json(text)?, folder)
}

/// Reads, parses and validates a scene file; errors name the file, and the files it refers to
/// are relative to its folder. A mesh file (`.obj`, `.ply`, `.gltf`, `.glb`) is opened as a
/// scene of its own ([`super::model::model_scene`]), a `.xml` file as a Mitsuba 3 scene
/// ([`super::mitsuba`]).
pub fn load_scene(path: &Path) -> Result<SceneDesc, SceneError> {
    load_scene_with(path, &[]).map(|s| s.desc)
}

/// A scene file as loaded: the description, and what a Mitsuba scene says about rendering it.
#[derive(Clone, Debug)]
pub struct LoadedScene {
    /// The scene.
    pub desc: SceneDesc,
    /// Default samples per pixel (a Mitsuba sensor's `sample_count`); `None` for JSON scenes.
    pub spp: Option<u32>,
    /// Russian roulette depth (a Mitsuba `path` integrator's `rr_depth`), if the file sets one.
    pub rr_depth: Option<u32>,
}

/// [`load_scene`] with the command line's `-D name=value` parameters, which only a Mitsuba
/// scene has (`$name` in its attributes); giving them for another file is an error.
pub fn load_scene_with(
    path: &Path,
    defines: &[(String, String)],
) -> Result<LoadedScene, SceneError> {
    let params = super::mitsuba::Params {
        defines: defines.to_vec(),
        spp: None,
    };
    load_scene_params(path, &params)
}

/// [`load_scene_with`] with all the command line's parameters for a Mitsuba scene (`-D` and
/// `--spp`, which gives `$spp`); only the `-D`s are an error for another file.
pub fn load_scene_params(
    path: &Path,
    params: &super::mitsuba::Params,
) -> Result<LoadedScene, SceneError> {
    load_scene_options(path, params, ModelOptions::default())
}

/// [`load_scene_params`] with the options of a model file opened on its own (`model`: the
/// studio or not; ignored for scene files).
pub fn load_scene_options(
    path: &Path,
    params: &super::mitsuba::Params,
    model: ModelOptions,
) -> Result<LoadedScene, SceneError> {
    let defines = &params.defines;
    if super::mitsuba::is_mitsuba_file(path) {
        let m = super::mitsuba::load_params(path, params)?;
        return Ok(LoadedScene {
            desc: m.desc,
            spp: Some(m.spp),
            rr_depth: m.rr_depth,
        });
    }
    if let Some((name, value)) = defines.first() {
        return Err(SceneError::new(
            "",
            format!("-D {name}={value}: parameters apply to Mitsuba XML scenes (.xml) only"),
        )
        .in_file(path));
    }
    let desc = if super::model::is_model_file(path) {
        super::model::model_scene_with(path, model)?
    } else {
        check_scene_extension(path)?;
        let folder = path.parent().unwrap_or(Path::new(""));
        parse_scene_in(&read_scene_file(path)?, folder).map_err(|e| e.in_file(path))?
    };
    Ok(LoadedScene {
        desc,
        spp: None,
        rr_depth: None,
    })
}

/// Every file type lumis opens, for messages.
const FILE_TYPES: &str = ".json (lumis' scene format), .xml (a Mitsuba 3 scene) and the model \
     files .obj, .ply, .gltf, .glb and .serialized";

/// Refuses a file that is neither a JSON scene nor anything else lumis reads, by its extension,
/// naming what lumis reads (and pbrt-v4's format by name), instead of a JSON syntax error about
/// a file that was never JSON. A file without an extension is read as JSON.
fn check_scene_extension(path: &Path) -> Result<(), SceneError> {
    let Some(ext) = path.extension().and_then(|e| e.to_str()) else {
        return Ok(());
    };
    let message = match ext.to_ascii_lowercase().as_str() {
        "json" => return Ok(()),
        "pbrt" => format!(
            "a pbrt-v4 scene: lumis does not read pbrt's format (yet); it opens {FILE_TYPES}"
        ),
        _ => format!("lumis does not open '.{ext}' files: it opens {FILE_TYPES}"),
    };
    Err(SceneError::new("", message).in_file(path))
}

/// The text of a scene file; the error (missing, a directory, not UTF-8, …) names the file.
pub(crate) fn read_scene_file(path: &Path) -> Result<String, SceneError> {
    std::fs::read_to_string(path)
        .map_err(|e| SceneError::new("", format!("cannot read the scene file: {e}")).in_file(path))
}

/// Validates an already parsed JSON value (e.g. one from [`SceneDesc::to_json`]); files it names
/// are relative to the current folder.
pub fn parse_scene_value(value: &Value) -> Result<SceneDesc, SceneError> {
    parse_scene_value_in(value, Path::new(""))
}

/// Validates an already parsed JSON value whose file references are relative to `folder`.
pub fn parse_scene_value_in(value: &Value, folder: &Path) -> Result<SceneDesc, SceneError> {
    parse_scene_value_preloaded(value, folder, Preloaded::default())
}

/// [`parse_scene_value_in`] with some of the files already in memory (`preloaded`, looked up
/// before the file system), for a front end that has read them itself.
pub(crate) fn parse_scene_value_preloaded(
    value: &Value,
    folder: &Path,
    preloaded: Preloaded,
) -> Result<SceneDesc, SceneError> {
    if !value.is_object() {
        // No JSON path to name, so say where in words.
        return Err(SceneError::new(
            "",
            "the root of a scene file must be a JSON object",
        ));
    }
    let root = Obj::new(value, "")?;
    root.only_keys(
        &[
            "camera",
            "max_depth",
            "hide_emitters",
            "background",
            "materials",
            "shapes",
            "lights",
        ],
        true,
    )?;
    let camera = parse_camera(&Obj::new(root.req("camera")?, "camera")?)?;

    let max_depth = match root.get("max_depth") {
        None => -1,
        Some(v) => integer(v, "max_depth", -1, i32::MAX as i64)? as i32,
    };
    if max_depth == 0 {
        return Err(SceneError::new(
            "max_depth",
            "0 is not allowed: use -1 (unlimited) or at least 1 (1 = emission seen directly)",
        ));
    }

    let hide_emitters = root.opt_bool("hide_emitters")?.unwrap_or(false);

    // One loader for the whole scene, so that a file named twice is read once.
    let mut textures = TextureLoader::new(folder).with_preloaded(preloaded);
    let background = match root.get("background") {
        None => BackgroundDesc::Constant(DVec3::ZERO),
        Some(v) => parse_background(v, folder, &textures)?,
    };
    let materials = match root.get("materials") {
        Some(v) => parse_materials(&Obj::new(v, "materials")?, &mut textures)?,
        None => Vec::new(),
    };
    let mut warnings = Vec::new();
    let mut materials = materials;
    let mut shapes = parse_shapes(
        array(root.req("shapes")?, "shapes")?,
        &materials,
        folder,
        &mut textures,
        &mut warnings,
    )?;
    let mesh_attributes =
        super::parse_mesh_attribute::bind_mesh_attributes(&mut materials, &mut shapes)?;
    let lights = match root.get("lights") {
        Some(v) => super::parse_lights::parse_lights(array(v, "lights")?, &mut textures)?,
        None => Vec::new(),
    };
    Ok(SceneDesc {
        camera,
        max_depth,
        hide_emitters,
        background,
        materials,
        shapes,
        lights,
        warnings,
        mesh_attributes,
    })
}

/// Checks emitted or background radiance: every channel in `[0, MAX_RADIANCE]`.
pub(crate) fn check_radiance(le: DVec3, path: &str) -> Result<DVec3, SceneError> {
    check_components(le, path, |x| x >= 0.0, "is negative: radiance must be ≥ 0")?;
    check_components(
        le,
        path,
        |x| x <= MAX_RADIANCE,
        "is too large: radiance must be at most 1e30 (single precision would overflow)",
    )
}

fn parse_camera(obj: &Obj) -> Result<CameraDesc, SceneError> {
    const FRAME: [&str; 7] = [
        "type",
        "from",
        "to",
        "up",
        "width",
        "height",
        "principal_point_offset",
    ];
    let own: &[&str] = match camera_type(obj)? {
        "perspective" => &["vfov_deg"],
        "thinlens" => &["vfov_deg", "aperture_radius", "focus_distance"],
        "orthographic" => &["view_size"],
        other => {
            let hint = match other {
                "pinhole" => " (a pinhole is `perspective`)",
                "spherical" | "fisheye" | "radiancemeter" | "irradiancemeter" | "batch" => {
                    " (lumis renders an image through a lens or a pinhole only)"
                }
                _ => "",
            };
            return Err(SceneError::new(
                obj.at("type"),
                format!(
                    "unknown camera type `{other}`{hint}: expected perspective, thinlens or \
                     orthographic"
                ),
            ));
        }
    };
    let keys: Vec<&str> = FRAME
        .iter()
        .chain(own)
        .chain(&["filter"])
        .copied()
        .collect();
    obj.only_keys(&keys, false)?;
    let (from, to, up) = (obj.vec3("from")?, obj.vec3("to")?, obj.vec3("up")?);

    // The camera's position bounds every ray origin: beyond the supported scene size, f32 ray
    // arithmetic has no digits left for the scene (and traversal would see infinities).
    let limit = crate::scene::build::MAX_SCENE_SIZE as f64;
    for (key, p) in [("from", from), ("to", to)] {
        if p.abs().max_element() > limit {
            let msg = format!(
                "coordinate {:e} is beyond the supported scene size {:e} (single precision)",
                p.abs().max_element(),
                crate::scene::build::MAX_SCENE_SIZE
            );
            return Err(SceneError::new(obj.at(key), msg));
        }
    }

    // Relative to the coordinates' magnitude, so a camera 1e5 units out still works.
    let view = to - from;
    let scale = from.abs().max(to.abs()).max_element();
    if view.length() <= 1e-12 * scale || view == DVec3::ZERO {
        return Err(SceneError::new(
            obj.at("to"),
            "`to` equals `from`, so the view direction is undefined",
        ));
    }
    if up == DVec3::ZERO {
        return Err(SceneError::new(obj.at("up"), "`up` has zero length"));
    }
    // sin(angle) below 1e-6: the image's horizontal axis `cross(forward, up)` would be noise.
    if unit(view).cross(unit(up)).length() < 1e-6 {
        return Err(SceneError::new(
            obj.at("up"),
            "`up` is parallel to the view direction `to - from`",
        ));
    }

    let projection = parse_projection(obj)?;
    let mut principal_point_offset = [0.0; 2];
    if let Some(v) = obj.get("principal_point_offset") {
        let at = obj.at("principal_point_offset");
        let o = array(v, &at)?;
        if o.len() != 2 {
            return Err(SceneError::new(
                at,
                "expected [x, y] (fractions of the film)",
            ));
        }
        for (i, v) in o.iter().enumerate() {
            // Beyond ten films away the view has left the film entirely many times over.
            principal_point_offset[i] =
                v.as_f64().filter(|x| x.abs() <= 10.0).ok_or_else(|| {
                    SceneError::new(
                        format!("{at}[{i}]"),
                        format!("{v} must be a number in [-10, 10]"),
                    )
                })?;
        }
    }
    let size = |key: &str| -> Result<u32, SceneError> {
        Ok(integer(obj.req(key)?, &obj.at(key), 1, MAX_IMAGE_SIZE as i64)? as u32)
    };
    let (width, height) = (size("width")?, size("height")?);
    let filter = match obj.get("filter") {
        Some(v) => {
            let f = Obj::new(v, obj.at("filter"))?;
            let filter = parse_filter(&f)?;
            // A signed filter's weights divide by its integral over each pixel's part of the film.
            if let Err(why) = filter.filter().check_film(width, height) {
                return Err(SceneError::new(f.at("type"), why));
            }
            filter
        }
        None => FilterDesc::Box,
    };
    Ok(CameraDesc {
        from,
        to,
        up,
        projection,
        principal_point_offset,
        width,
        height,
        filter,
    })
}

/// `camera.type`, default `perspective`.
fn camera_type<'a>(obj: &Obj<'a>) -> Result<&'a str, SceneError> {
    match obj.get("type") {
        None => Ok("perspective"),
        Some(_) => obj.string("type"),
    }
}

/// The projection of `camera` (its `type` already known to be one of the three) with its keys.
fn parse_projection(obj: &Obj) -> Result<ProjectionDesc, SceneError> {
    let vfov = || -> Result<f64, SceneError> {
        let vfov_deg = obj.number("vfov_deg")?;
        if !(vfov_deg > 0.0 && vfov_deg < 180.0) {
            return Err(SceneError::new(
                obj.at("vfov_deg"),
                format!("field of view {vfov_deg}° is outside (0, 180)"),
            ));
        }
        Ok(vfov_deg)
    };
    // Beyond the supported scene size a lens or a film is not meaningful in f32 either.
    let limit = crate::scene::build::MAX_SCENE_SIZE as f64;
    let length = |key: &str, min_excl: Option<f64>| -> Result<f64, SceneError> {
        let x = obj.number(key)?;
        let ok = match min_excl {
            Some(m) => x > m,
            None => x >= 0.0,
        } && x <= limit;
        if !ok {
            let range = if min_excl.is_some() { "(0" } else { "[0" };
            return Err(SceneError::new(
                obj.at(key),
                format!("{key} {x} is outside {range}, {limit:e}]"),
            ));
        }
        Ok(x)
    };
    Ok(match camera_type(obj)? {
        "thinlens" => ProjectionDesc::ThinLens {
            vfov_deg: vfov()?,
            aperture_radius: length("aperture_radius", None)?,
            focus_distance: length("focus_distance", Some(0.0))?,
        },
        "orthographic" => {
            let size = array(obj.req("view_size")?, &obj.at("view_size"))?;
            if size.len() != 2 {
                return Err(SceneError::new(
                    obj.at("view_size"),
                    format!("expected [width, height], got {} numbers", size.len()),
                ));
            }
            let mut view_size = [0.0; 2];
            for (i, v) in size.iter().enumerate() {
                let at = format!("{}[{i}]", obj.at("view_size"));
                let x = v
                    .as_f64()
                    .filter(|x| *x > 0.0 && *x <= limit)
                    .ok_or_else(|| {
                        SceneError::new(
                            &at,
                            format!("the film's size {v} must be a number in (0, {limit:e}]"),
                        )
                    })?;
                view_size[i] = x;
            }
            ProjectionDesc::Orthographic { view_size }
        }
        _ => ProjectionDesc::Perspective { vfov_deg: vfov()? },
    })
}

/// `camera.filter` (a lumis addition): `{"type": "box"}`,
/// `{"type": "gaussian", "stddev": σ, "radius": r}` (defaults 0.5 and 4σ, Mitsuba's) or
/// `{"type": "tent", "radius": r}` (default 1, Mitsuba's), `{"type": "lanczos", "lobes": n}`
/// (default 3), `{"type": "mitchell", "b": B, "c": C}` (defaults ⅓, ⅓) or `{"type": "catmullrom"}`.
fn parse_filter(obj: &Obj) -> Result<FilterDesc, SceneError> {
    match obj.string("type")? {
        "box" => {
            obj.only_keys(&["type"], false)?;
            Ok(FilterDesc::Box)
        }
        "gaussian" => {
            obj.only_keys(&["type", "stddev", "radius"], false)?;
            let max = crate::camera::filter::MAX_FILTER_RADIUS as f64;
            let stddev = obj.opt_number("stddev")?.unwrap_or(0.5);
            if !(stddev > 0.0 && stddev <= max) {
                return Err(SceneError::new(
                    obj.at("stddev"),
                    format!("stddev {stddev} must be in (0, {max}] pixels"),
                ));
            }
            let radius = obj.opt_number("radius")?.unwrap_or(4.0 * stddev);
            // Below σ the window's weight exp(−x²/2σ²) − exp(−r²/2σ²) loses its digits in f32.
            if !(radius >= stddev && radius <= max) {
                return Err(SceneError::new(
                    obj.at("radius"),
                    format!(
                        "radius {radius} must be in [stddev, {max}] pixels = [{stddev}, {max}]"
                    ),
                ));
            }
            Ok(FilterDesc::Gaussian { stddev, radius })
        }
        "tent" => {
            obj.only_keys(&["type", "radius"], false)?;
            let max = crate::camera::filter::MAX_FILTER_RADIUS as f64;
            let radius = obj.opt_number("radius")?.unwrap_or(1.0);
            if !(radius > 0.0 && radius <= max) {
                return Err(SceneError::new(
                    obj.at("radius"),
                    format!("radius {radius} must be in (0, {max}] pixels"),
                ));
            }
            Ok(FilterDesc::Tent { radius })
        }
        "lanczos" => {
            obj.only_keys(&["type", "lobes"], false)?;
            let max = crate::camera::filter::MAX_FILTER_RADIUS as i64;
            let lobes = match obj.get("lobes") {
                Some(v) => integer(v, &obj.at("lobes"), 1, max)? as u32,
                None => 3,
            };
            Ok(FilterDesc::Lanczos { lobes })
        }
        "mitchell" => {
            obj.only_keys(&["type", "b", "c"], false)?;
            let param = |key: &str| -> Result<f64, SceneError> {
                let v = obj.opt_number(key)?.unwrap_or(1.0 / 3.0);
                if !v.is_finite() {
                    return Err(SceneError::new(
                        obj.at(key),
                        format!("{key} {v} must be finite"),
                    ));
                }
                Ok(v)
            };
            Ok(FilterDesc::Mitchell {
                b: param("b")?,
                c: param("c")?,
            })
        }
        "catmullrom" => {
            obj.only_keys(&["type"], false)?;
            Ok(FilterDesc::CatmullRom)
        }
        other => Err(SceneError::new(
            obj.at("type"),
            format!(
                "unknown filter type `{other}` (expected `box`, `gaussian`, `tent`, `lanczos`, \
                 `mitchell` or `catmullrom`)"
            ),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::tests::{base, expect_err};
    use serde_json::json;

    #[test]
    fn root_rules() {
        expect_err(&json!([1, 2]), "", "must be a JSON object");
        let mut s = base();
        s["emitters"] = json!([]);
        expect_err(&s, "emitters", "unknown key `emitters`");
        let mut s = base();
        s["comment"] = json!("fine");
        s["name"] = json!("fine too");
        assert!(parse_scene_value(&s).is_ok());
        s["name"] = json!(3);
        expect_err(&s, "name", "expected a string");
        let mut s = base();
        s.as_object_mut().unwrap().remove("camera");
        expect_err(&s, "camera", "missing required key");
        let mut s = base();
        s.as_object_mut().unwrap().remove("shapes");
        expect_err(&s, "shapes", "missing required key");
        let mut s = base();
        s["shapes"] = json!({});
        expect_err(&s, "shapes", "expected an array, found an object");
    }

    #[test]
    fn defaults() {
        let mut s = base();
        for key in ["max_depth", "background", "materials"] {
            s.as_object_mut().unwrap().remove(key);
        }
        s["shapes"] = json!([{"type": "sphere", "center": [0, 0, 0], "radius": 1}]);
        let d = parse_scene_value(&s).unwrap();
        assert_eq!(
            (d.max_depth, d.background),
            (-1, BackgroundDesc::Constant(DVec3::ZERO))
        );
        assert!(d.materials.is_empty() && d.warnings.is_empty());
        assert_eq!(
            (d.shapes[0].material, d.shapes[0].emission),
            (None, DVec3::ZERO)
        );
    }

    #[test]
    fn max_depth_rules() {
        for (bad, fragment) in [(json!(0), "0 is not allowed"), (json!(-2), "out of range")] {
            let mut s = base();
            s["max_depth"] = bad;
            expect_err(&s, "max_depth", fragment);
        }
        let mut s = base();
        s["max_depth"] = json!(2.5);
        expect_err(&s, "max_depth", "expected an integer");
        s["max_depth"] = json!(1);
        assert_eq!(parse_scene_value(&s).unwrap().max_depth, 1);
    }

    #[test]
    fn negative_background() {
        let mut s = base();
        s["background"] = json!([0.1, -0.5, 0]);
        expect_err(&s, "background[1]", "negative");
    }

    /// Scene format Version 3's camera types: each parses to its projection with its own keys
    /// and writes back to the same description; a key of another type, a negative aperture, a
    /// zero focus distance, a film size of the wrong length or not positive, and an unknown
    /// type are each one error at their JSON path.
    #[test]
    fn camera_types_parse_round_trip_and_name_errors() {
        let with = |extra: serde_json::Value, drop_fov: bool| {
            let mut s = base();
            let cam = s["camera"].as_object_mut().unwrap();
            if drop_fov {
                cam.remove("vfov_deg");
            }
            for (k, v) in extra.as_object().unwrap() {
                cam.insert(k.clone(), v.clone());
            }
            s
        };
        let lens = with(
            json!({"type": "thinlens", "aperture_radius": 0.2, "focus_distance": 3.5}),
            false,
        );
        let ortho = with(json!({"type": "orthographic", "view_size": [4, 3]}), true);
        let d = parse_scene_value(&lens).unwrap();
        assert!(matches!(
            d.camera.projection,
            ProjectionDesc::ThinLens {
                aperture_radius: 0.2,
                focus_distance: 3.5,
                ..
            }
        ));
        let o = parse_scene_value(&ortho).unwrap();
        assert_eq!(
            o.camera.projection,
            ProjectionDesc::Orthographic {
                view_size: [4.0, 3.0]
            }
        );
        assert_eq!(o.camera.vfov_deg(), None);
        for desc in [&d, &o] {
            let back = parse_scene_value(&desc.to_json()).unwrap();
            assert_eq!(back.camera, desc.camera);
        }
        // The principal point offset, for any type.
        let shifted = with(json!({"principal_point_offset": [0.25, -0.5]}), false);
        let p = parse_scene_value(&shifted).unwrap();
        assert_eq!(p.camera.principal_point_offset, [0.25, -0.5]);
        assert_eq!(parse_scene_value(&p.to_json()).unwrap().camera, p.camera);
        let plain = parse_scene_value(&with(json!({"type": "perspective"}), false)).unwrap();
        assert_eq!(plain.camera, parse_scene_value(&base()).unwrap().camera);

        for (extra, drop_fov, at, fragment) in [
            (
                json!({"type": "fisheye"}),
                false,
                "camera.type",
                "unknown camera type `fisheye`",
            ),
            (
                json!({"aperture_radius": 0.1}),
                false,
                "camera.aperture_radius",
                "unknown key `aperture_radius`",
            ),
            (
                json!({"type": "thinlens", "aperture_radius": -0.1, "focus_distance": 1}),
                false,
                "camera.aperture_radius",
                "outside [0",
            ),
            (
                json!({"type": "thinlens", "aperture_radius": 0.1, "focus_distance": 0}),
                false,
                "camera.focus_distance",
                "outside (0",
            ),
            (
                json!({"type": "thinlens", "aperture_radius": 0.1}),
                false,
                "camera.focus_distance",
                "missing required key",
            ),
            (
                json!({"type": "orthographic", "view_size": [1, 2]}),
                false,
                "camera.vfov_deg",
                "unknown key `vfov_deg`",
            ),
            (
                json!({"type": "orthographic", "view_size": [1]}),
                true,
                "camera.view_size",
                "expected [width, height]",
            ),
            (
                json!({"type": "orthographic", "view_size": [1, 0]}),
                true,
                "camera.view_size[1]",
                "(0, ",
            ),
            (
                json!({"type": "orthographic", "view_size": [1, "a"]}),
                true,
                "camera.view_size[1]",
                "must be a number",
            ),
            (
                json!({"type": "orthographic"}),
                true,
                "camera.view_size",
                "missing required key",
            ),
            (
                json!({"principal_point_offset": [0.1]}),
                false,
                "camera.principal_point_offset",
                "expected [x, y]",
            ),
            (
                json!({"principal_point_offset": [0.1, 11]}),
                false,
                "camera.principal_point_offset[1]",
                "[-10, 10]",
            ),
        ] {
            expect_err(&with(extra, drop_fov), at, fragment);
        }
    }

    #[test]
    fn camera_rules() {
        let cases = [
            ("from", json!([0, 1, 0]), "camera.to", "`to` equals `from`"),
            (
                "from",
                json!([1.8446744073709552e19, 1, 0]),
                "camera.from",
                "beyond the supported scene size",
            ),
            (
                "to",
                json!([0, -2e15, 0]),
                "camera.to",
                "beyond the supported scene size",
            ),
            (
                "up",
                json!([0, 0, 2]),
                "camera.up",
                "parallel to the view direction",
            ),
            ("up", json!([0, 0, 0]), "camera.up", "zero length"),
            (
                "vfov_deg",
                json!(180),
                "camera.vfov_deg",
                "outside (0, 180)",
            ),
            ("vfov_deg", json!(0), "camera.vfov_deg", "outside (0, 180)"),
            ("width", json!(0), "camera.width", "out of range [1, 16384]"),
            (
                "height",
                json!(16385),
                "camera.height",
                "out of range [1, 16384]",
            ),
            ("width", json!(64.5), "camera.width", "expected an integer"),
            ("fov", json!(40), "camera.fov", "unknown key `fov`"),
            ("comment", json!("x"), "camera.comment", "unknown key"),
            (
                "from",
                json!([0, 1]),
                "camera.from",
                "expected 3 numbers, found 2",
            ),
            (
                "from",
                json!("origin"),
                "camera.from",
                "expected an array of 3 numbers",
            ),
            (
                "up",
                json!([0, "1", 0]),
                "camera.up[1]",
                "expected a number, found a string",
            ),
        ];
        for (key, value, path, fragment) in cases {
            let mut s = base();
            s["camera"][key] = value;
            expect_err(&s, path, fragment);
        }
        let mut s = base();
        s["camera"].as_object_mut().unwrap().remove("vfov_deg");
        expect_err(&s, "camera.vfov_deg", "missing required key `vfov_deg`");
        // Integral floats are integers; huge but distinct positions are fine.
        let mut s = base();
        s["camera"]["width"] = json!(64.0);
        s["camera"]["from"] = json!([1e5, 1e5, 1e5]);
        s["camera"]["to"] = json!([1e5, 1e5, 100000.01]);
        assert!(parse_scene_value(&s).is_ok());
    }

    #[test]
    fn json_syntax_errors_have_line_and_column() {
        let e = parse_scene("{\n  \"camera\": {,\n}").unwrap_err();
        assert_eq!(e.path, "camera");
        assert!(e.message.contains("line 2 column 14"), "{e}");
        let e = parse_scene("{\"max_depth\": 1e999}").unwrap_err();
        assert!(e.message.contains("number out of range at line 1"), "{e}");
        let e = parse_scene("{\"max_depth\": 1, \"max_depth\": 2}").unwrap_err();
        assert!(
            e.message.contains("duplicate key `max_depth` at line 1"),
            "{e}"
        );
        let e = parse_scene("{} trailing").unwrap_err();
        assert!(e.message.contains("trailing characters"), "{e}");
    }

    #[test]
    fn load_scene_names_the_file() {
        let missing = Path::new("/nonexistent/scene.json");
        let e = load_scene(missing).unwrap_err();
        assert_eq!(e.file.as_deref(), Some(missing));
        assert!(
            e.to_string()
                .starts_with("/nonexistent/scene.json: cannot read"),
            "{e}"
        );
        let dir = std::env::temp_dir().join(format!("lumis-scene-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("bad.json");
        std::fs::write(&file, r#"{"camera": 1, "shapes": []}"#).unwrap();
        let e = load_scene(&file).unwrap_err();
        std::fs::remove_dir_all(&dir).unwrap();
        let expected = format!(
            "{}: camera: expected an object, found a number",
            file.display()
        );
        assert_eq!(e.to_string(), expected);
    }
}
