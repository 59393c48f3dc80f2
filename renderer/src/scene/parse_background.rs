//! The `background`: a constant radiance `[r, g, b]` or an environment map
//! `{"envmap": FILE, "scale": s, "rotate_y_deg": a, "rotation": R}` (scene format Version 2;
//! `rotation` and HDR files Version 3). The map and the rotation are read and checked here, once,
//! so that every front end gets the same errors: the file, the pixel of a bad texel, a rotation
//! that is not one.

use super::desc::{BackgroundDesc, EnvmapDesc};
use super::error::SceneError;
use super::parse::{MAX_RADIANCE, check_radiance};
use super::parse_texture::TextureLoader;
use super::walk::{Obj, array, number, vec3};
use crate::image_io::Image;
use glam::{DMat3, DVec3};
use serde_json::Value;
use std::path::Path;
use std::sync::Arc;

/// Largest accepted map, in texels (a 16k × 8k map); its sampling tables take 12 bytes a texel.
pub const MAX_ENVMAP_TEXELS: u64 = 1 << 27;

/// Parses `background`; an envmap's `file` is relative to `folder`.
/// A map the front end holds in memory (`textures`' preloaded images, such as a model's studio,
/// `scene/model_studio.rs`) is taken from there and checked as a file's would be.
pub(crate) fn parse_background(
    v: &Value,
    folder: &Path,
    textures: &TextureLoader,
) -> Result<BackgroundDesc, SceneError> {
    let path = "background";
    if !v.is_object() {
        let le = vec3(v, path)?;
        check_radiance(le, path)?;
        return Ok(BackgroundDesc::Constant(le));
    }
    let obj = Obj::new(v, path)?;
    obj.only_keys(&["envmap", "scale", "rotate_y_deg", "rotation"], false)?;
    let scale = obj.opt_number("scale")?.unwrap_or(1.0);
    if !(0.0..=MAX_RADIANCE).contains(&scale) {
        return Err(SceneError::new(
            obj.at("scale"),
            format!("{scale} is out of range: the scale must be in [0, 1e30]"),
        ));
    }
    let rotate_y_deg = obj.opt_number("rotate_y_deg")?.unwrap_or(0.0);
    let rotation = match obj.get("rotation") {
        None => None,
        Some(r) => Some(parse_rotation(r, &obj.at("rotation"))?),
    };
    let file_path = obj.at("envmap");
    let name = obj.string("envmap")?;
    if name.is_empty() {
        return Err(SceneError::new(file_path, "the file name is empty"));
    }
    let file = folder.join(name);
    let image = match textures.preloaded_image(&file) {
        Some(image) => Image::clone(&image),
        None => {
            Image::read_rgb_map(&file).map_err(|e| SceneError::new(&file_path, e.to_string()))?
        }
    };
    let texels = image.width as u64 * image.height as u64;
    if texels == 0 || texels > MAX_ENVMAP_TEXELS {
        return Err(SceneError::new(
            &file_path,
            format!(
                "{}: {}×{} texels; an environment map needs 1 to {MAX_ENVMAP_TEXELS}",
                file.display(),
                image.width,
                image.height
            ),
        ));
    }
    check_texels(&image, scale, &file, &file_path)?;
    Ok(BackgroundDesc::Envmap(EnvmapDesc {
        file,
        image: Arc::new(image),
        scale,
        rotate_y_deg,
        rotation,
    }))
}

/// How far from orthonormal a given rotation may be (the largest entry of `RᵀR − I`): loose
/// enough for matrices written with six digits, as Mitsuba's exporters write them, and far
/// tighter than any scale or shear a scene would mean.
pub const ROTATION_TOLERANCE: f64 = 1e-4;

/// `r` as `parse_rotation` reads it back: three rows.
pub(crate) fn rotation_json(r: DMat3) -> Value {
    let t = r.transpose();
    let row = |v: DVec3| serde_json::json!([v.x, v.y, v.z]);
    serde_json::json!([row(t.x_axis), row(t.y_axis), row(t.z_axis)])
}

/// A rotation: a 3×3 matrix as three rows, or `{"axis": [x, y, z], "angle_deg": a}` (right-handed
/// about the axis, as Mitsuba's `rotate`).
fn parse_rotation(v: &Value, path: &str) -> Result<DMat3, SceneError> {
    if v.is_object() {
        let obj = Obj::new(v, path)?;
        obj.only_keys(&["axis", "angle_deg"], false)?;
        // Zero if the axis is zero or too long to normalise.
        let axis = obj.vec3("axis")?.normalize_or_zero();
        if axis == DVec3::ZERO {
            return Err(SceneError::new(obj.at("axis"), "the axis must not be zero"));
        }
        let angle = obj.number("angle_deg")?;
        return Ok(DMat3::from_axis_angle(axis, angle.to_radians()));
    }
    let rows = array(v, path)?;
    if rows.len() != 3 {
        return Err(SceneError::new(
            path,
            "expected a rotation: three rows of three numbers, or {\"axis\", \"angle_deg\"}",
        ));
    }
    let mut r = [DVec3::ZERO; 3];
    for (i, row) in rows.iter().enumerate() {
        let p = format!("{path}[{i}]");
        let items = array(row, &p)?;
        if items.len() != 3 {
            return Err(SceneError::new(&p, "expected a row of three numbers"));
        }
        for (j, x) in items.iter().enumerate() {
            r[i][j] = number(x, &format!("{p}[{j}]"))?;
        }
    }
    let m = DMat3::from_cols(r[0], r[1], r[2]).transpose();
    proper_rotation(m).map_err(|e| SceneError::new(path, e))
}

/// `m` orthonormalised if it is a proper rotation to [`ROTATION_TOLERANCE`]; otherwise why it is
/// not (singular, a mirror, or a scale or shear). The environment is looked up through the inverse
/// of its rotation, so anything else would distort the map or turn it inside out.
pub fn proper_rotation(m: DMat3) -> Result<DMat3, String> {
    let det = m.determinant();
    if !det.is_finite() || !m.to_cols_array().iter().all(|x| x.is_finite()) {
        return Err("the rotation must be finite".into());
    }
    if det.abs() < 1e-6 {
        return Err(format!("the rotation is singular (determinant {det:e})"));
    }
    if det < 0.0 {
        return Err(format!(
            "the rotation mirrors (determinant {det}): an environment map takes a proper \
             rotation only"
        ));
    }
    let off = (m.transpose() * m - DMat3::IDENTITY)
        .to_cols_array()
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()));
    if off > ROTATION_TOLERANCE {
        return Err(format!(
            "the matrix is not a rotation (RᵀR differs from the identity by {off:.1e}; a scale \
             or shear would distort the map)"
        ));
    }
    // Gram–Schmidt, so that sampling (R) and lookup (Rᵀ) are exact inverses.
    let x = m.x_axis.normalize();
    let y = (m.y_axis - x * x.dot(m.y_axis)).normalize();
    Ok(DMat3::from_cols(x, y, x.cross(y)))
}

/// Every channel of every texel finite, ≥ 0, and at most [`MAX_RADIANCE`] once scaled; the error
/// names the first bad texel by column and row.
fn check_texels(image: &Image, scale: f64, file: &Path, json_path: &str) -> Result<(), SceneError> {
    for (k, t) in image.data.iter().enumerate() {
        for (c, x) in t.to_array().into_iter().enumerate() {
            let problem = if x.is_nan() {
                "is NaN"
            } else if x < 0.0 {
                "is negative"
            } else if x.is_infinite() || x as f64 * scale > MAX_RADIANCE {
                "is too large (scaled radiance must be at most 1e30)"
            } else {
                continue;
            };
            let (col, row) = (k as u32 % image.width, k as u32 / image.width);
            return Err(SceneError::new(
                json_path,
                format!(
                    "{}: pixel (column {col}, row {row}) channel {c} = {x} {problem}",
                    file.display()
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::desc::BackgroundDesc;
    use super::super::parse::{load_scene, parse_scene, parse_scene_value_in};
    use super::super::tests::{base, expect_err};
    use crate::image_io::Image;
    use glam::Vec3;
    use serde_json::json;
    use std::path::{Path, PathBuf};

    fn scenes_dir() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/scenes")
    }

    /// A map written to this test's own scratch folder.
    fn write_map(name: &str, data: Vec<Vec3>, w: u32) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("lumis-parse-envmap-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        let height = data.len() as u32 / w;
        Image {
            width: w,
            height,
            data,
        }
        .write(&path, 0.0)
        .unwrap();
        path
    }

    fn with_background(background: serde_json::Value) -> serde_json::Value {
        let mut s = base();
        s["background"] = background;
        s
    }

    /// `envmap` is relative to the scene file's folder, not to the current one.
    #[test]
    fn map_is_found_next_to_the_scene_file() {
        let path = scenes_dir().join("envmap_objects.json");
        let desc = load_scene(&path).unwrap();
        let BackgroundDesc::Envmap(e) = &desc.background else {
            panic!("not an envmap: {:?}", desc.background);
        };
        assert_eq!((e.image.width, e.image.height), (128, 64));
        assert_eq!((e.scale, e.rotate_y_deg), (0.75, 30.0));
        assert_eq!(e.file, scenes_dir().join("envmap_test_sky.exr"));
        // The same text read from elsewhere does not find it, and says which file it looked for.
        let text = std::fs::read_to_string(&path).unwrap();
        let err = parse_scene(&text).unwrap_err();
        assert_eq!(err.path, "background.envmap");
        assert!(err.message.contains("envmap_test_sky.exr"), "{err}");
        // Written back, the description reads the same map again from anywhere.
        let again = parse_scene(&desc.to_json().to_string()).unwrap();
        assert_eq!(again.background, desc.background);
    }

    #[test]
    fn bad_envmaps_name_the_key_and_the_file() {
        let bg = |v| with_background(v);
        expect_err(
            &bg(json!({"envmap": "no_such_map.exr"})),
            "background.envmap",
            "no_such_map.exr",
        );
        expect_err(
            &bg(json!({"envmap": "sky.png"})),
            "background.envmap",
            "must be an RGB EXR or Radiance HDR",
        );
        expect_err(&bg(json!({"envmap": ""})), "background.envmap", "empty");
        expect_err(&bg(json!({"envmap": 3})), "background.envmap", "a string");
        expect_err(
            &bg(json!({"scale": 2})),
            "background.envmap",
            "missing required key",
        );
        expect_err(
            &bg(json!({"envmap": "a.exr", "sky": 1})),
            "background.sky",
            "unknown key",
        );
        expect_err(
            &bg(json!({"envmap": "a.exr", "scale": -1})),
            "background.scale",
            "out of range",
        );
        expect_err(
            &bg(json!({"envmap": "a.exr", "rotate_y_deg": "x"})),
            "background.rotate_y_deg",
            "",
        );
    }

    /// `rotation` as rows or axis–angle, written back and read again the same; a matrix close to a
    /// rotation is orthonormalised; anything but a proper rotation is refused at
    /// `background.rotation` with what is wrong (issue 38, item 1).
    #[test]
    fn rotations_are_read_checked_and_written_back() {
        use glam::{DMat3, DVec3};
        let path = scenes_dir().join("envmap_objects.json");
        let mut v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let folder = path.parent().unwrap();
        let read = |v: &serde_json::Value| {
            let d = parse_scene_value_in(v, folder).unwrap_or_else(|e| panic!("{e}"));
            let BackgroundDesc::Envmap(e) = &d.background else {
                panic!("not an envmap")
            };
            (e.rotation, d.to_json())
        };
        let want = DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let close = |a: DMat3, b: DMat3| (a - b).to_cols_array().iter().all(|x| x.abs() < 1e-12);
        v["background"]["rotation"] = json!({"axis": [1, 2, 3], "angle_deg": 0.7f64.to_degrees()});
        let (r, written) = read(&v);
        assert!(close(r.unwrap(), want), "{r:?}");
        // Written as rows; read again from them.
        let rows = written["background"]["rotation"].clone();
        assert!(rows.is_array(), "{written}");
        v["background"]["rotation"] = rows;
        let (again, _) = read(&v);
        assert!(close(again.unwrap(), want));
        // Six digits, as exporters write them: accepted, then exactly orthonormal.
        let t = want.transpose();
        let six = |x: DVec3| [x.x, x.y, x.z].map(|c| (c * 1e6).round() / 1e6);
        v["background"]["rotation"] = json!([six(t.x_axis), six(t.y_axis), six(t.z_axis)]);
        let r = read(&v).0.unwrap();
        let off = (r.transpose() * r - DMat3::IDENTITY).to_cols_array();
        assert!(off.iter().all(|x| x.abs() < 1e-15), "{off:?}");
        assert!((r.determinant() - 1.0).abs() < 1e-15);
        for (rotation, what) in [
            (json!([[1, 0, 0], [0, 1, 0], [0, 0, -1]]), "mirrors"),
            (json!([[2, 0, 0], [0, 2, 0], [0, 0, 2]]), "not a rotation"),
            (json!([[1, 0.1, 0], [0, 1, 0], [0, 0, 1]]), "not a rotation"),
            (json!([[1, 0, 0], [0, 0, 0], [0, 0, 1]]), "singular"),
            (json!([[1, 0, 0], [0, 1, 0]]), "three rows"),
            (
                json!({"axis": [0, 0, 0], "angle_deg": 3}),
                "must not be zero",
            ),
        ] {
            v["background"]["rotation"] = rotation;
            let e = parse_scene_value_in(&v, folder).unwrap_err();
            assert!(e.path.starts_with("background.rotation"), "{e}");
            assert!(e.message.contains(what), "{what}: {e}");
        }
        v["background"]["rotation"] = json!([[1, 0, 0], [0, 1, "x"], [0, 0, 1]]);
        let e = parse_scene_value_in(&v, folder).unwrap_err();
        assert_eq!(e.path, "background.rotation[1][2]", "{e}");
    }

    /// A Radiance HDR file is an environment map like an EXR with the same texels: the same
    /// description's image, bit for bit (the texels are powers of two, exact in RGBE).
    #[test]
    fn hdr_maps_read_like_exr() {
        let data: Vec<Vec3> = (0..12)
            .map(|i| Vec3::new(1.0, 0.5, 0.25) * (1 << (i % 5)) as f32)
            .collect();
        let exr = write_map("same.exr", data.clone(), 4);
        let hdr = exr.with_extension("hdr");
        {
            let file = std::fs::File::create(&hdr).unwrap();
            let rgb: Vec<image::Rgb<f32>> = data.iter().map(|v| image::Rgb(v.to_array())).collect();
            image::codecs::hdr::HdrEncoder::new(std::io::BufWriter::new(file))
                .encode(&rgb, 4, 3)
                .unwrap();
        }
        let rgbe = exr.with_extension("rgbe");
        std::fs::copy(&hdr, &rgbe).unwrap();
        let read = |name: &str| {
            let s = with_background(json!({"envmap": name}));
            let d =
                parse_scene_value_in(&s, exr.parent().unwrap()).unwrap_or_else(|e| panic!("{e}"));
            let BackgroundDesc::Envmap(e) = d.background else {
                panic!("not an envmap")
            };
            e.image
        };
        let want = read("same.exr");
        assert_eq!(want.data, data);
        assert_eq!(read("same.hdr"), want);
        assert_eq!(read("same.rgbe"), want);
        // A texture reads it as linear floats too.
        let t = crate::textures::load::load_texture_image(&hdr, false).unwrap();
        assert_eq!(t.data, data);
    }

    /// NaN, negative and overflowing texels are rejected with their pixel, whatever the folder.
    #[test]
    fn bad_texels_are_named_by_pixel() {
        for (name, bad, what) in [
            ("nan.exr", f32::NAN, "is NaN"),
            ("negative.exr", -1.0, "is negative"),
            ("inf.exr", f32::INFINITY, "too large"),
        ] {
            let mut data = vec![Vec3::ONE; 12];
            data[4 + 2] = Vec3::new(1.0, bad, 1.0);
            let path = write_map(name, data, 4);
            let s = with_background(json!({"envmap": name}));
            let e = parse_scene_value_in(&s, path.parent().unwrap()).unwrap_err();
            assert_eq!(e.path, "background.envmap", "{e}");
            assert!(e.message.contains(name), "{e}");
            assert!(
                e.message.contains("pixel (column 2, row 1) channel 1"),
                "{e}"
            );
            assert!(e.message.contains(what), "{e}");
        }
        // A scale that pushes a fine texel past the limit.
        let path = write_map("bright.exr", vec![Vec3::splat(1e20); 2], 2);
        let s = with_background(json!({"envmap": "bright.exr", "scale": 1e11}));
        let e = parse_scene_value_in(&s, path.parent().unwrap()).unwrap_err();
        assert!(e.message.contains("too large"), "{e}");
    }
}
