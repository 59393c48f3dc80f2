//! The `background`: a constant radiance `[r, g, b]` or an environment map
//! `{"envmap": FILE, "scale": s, "rotate_y_deg": a}` (scene format Version 2). The map is read and
//! checked here, once, so that every front end gets the same errors: the file, and the pixel of
//! a bad texel.

use super::desc::{BackgroundDesc, EnvmapDesc};
use super::error::SceneError;
use super::parse::{MAX_RADIANCE, check_radiance};
use super::walk::{Obj, vec3};
use crate::image_io::Image;
use serde_json::Value;
use std::path::Path;
use std::sync::Arc;

/// Largest accepted map, in texels (a 16k × 8k map); its sampling tables take 12 bytes a texel.
pub const MAX_ENVMAP_TEXELS: u64 = 1 << 27;

/// Parses `background`; an envmap's `file` is relative to `folder`.
pub(crate) fn parse_background(v: &Value, folder: &Path) -> Result<BackgroundDesc, SceneError> {
    let path = "background";
    if !v.is_object() {
        let le = vec3(v, path)?;
        check_radiance(le, path)?;
        return Ok(BackgroundDesc::Constant(le));
    }
    let obj = Obj::new(v, path)?;
    obj.only_keys(&["envmap", "scale", "rotate_y_deg"], false)?;
    let scale = obj.opt_number("scale")?.unwrap_or(1.0);
    if !(0.0..=MAX_RADIANCE).contains(&scale) {
        return Err(SceneError::new(
            obj.at("scale"),
            format!("{scale} is out of range: the scale must be in [0, 1e30]"),
        ));
    }
    let rotate_y_deg = obj.opt_number("rotate_y_deg")?.unwrap_or(0.0);
    let file_path = obj.at("envmap");
    let name = obj.string("envmap")?;
    if name.is_empty() {
        return Err(SceneError::new(file_path, "the file name is empty"));
    }
    let file = folder.join(name);
    let image =
        Image::read_rgb_exr(&file).map_err(|e| SceneError::new(&file_path, e.to_string()))?;
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
    }))
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
            "must be an RGB EXR",
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
