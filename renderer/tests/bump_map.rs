//! Bump maps on the CPU (issue 40 item 1; `materials/bump_map.rs`), beside the gallery's
//! agreement with Mitsuba (`renderer/tests/gallery.rs`, `bsdf_bumpmap_with`) and the GPU's with
//! the CPU (`renderer/tests/gpu/normal_map.rs`):
//!
//! - a flat height field (every texel equal: gradient 0) leaves every image bit for bit as it
//!   was, in every strategy, on a scene of meshes and quads with UVs, textures and vertex
//!   normals; a ramp of heights changes it (the test's power);
//! - strong random bumps let no light through a one-sided plane lit from below it, and at
//!   grazing views stay finite;
//! - the back of a two-sided bump-mapped material is Mitsuba's `twosided` around a `bumpmap`:
//!   `tests/data/mitsuba/bumpmap_back.xml` (linear heights, so one bumped normal and one exact
//!   value, Mitsuba 3.9.1's 0.14164494) to 1e-5 with light sampling, MIS and mis-optimal; this
//!   also checks the gradient through `to_uv` and the rectangle's partials;
//! - bad input is one error naming the key: a checkerboard or constant for heights, a normal
//!   map beside a bump map, a bump map on a sphere, a non-finite height.

mod common;

use common::surface_detail::*;
use common::*;
use glam::Vec3;
use lumis::image_io::Image;
use lumis::integrator::Settings;
use lumis::rng::Rng;
use lumis::scene::desc::NormalMapDesc;
use lumis::scene::{Scene, TextureDesc, load_scene, parse_scene_in};
use lumis::textures::{BitmapOptions, BitmapTexture, Texture};
use std::path::PathBuf;
use std::sync::Arc;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lumis-bump-map-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `tests/data/scenes/NAME.json` with a bump map of the 2 × 2 `heights` (scale 0.05) on every
/// material but mixes.
fn with_heights(name: &str, heights: Option<[f32; 4]>) -> Arc<Scene> {
    let mut desc = load_scene(&data_dir().join("scenes").join(format!("{name}.json")))
        .unwrap_or_else(|e| panic!("{e}"));
    for m in desc.materials.iter_mut().filter(|m| m.mix.is_none()) {
        m.normal_map = heights.map(|h| {
            let image = Image {
                width: 2,
                height: 2,
                data: h.iter().map(|&x| Vec3::splat(x)).collect(),
            };
            NormalMapDesc {
                texture: TextureDesc {
                    texture: Texture::Bitmap(BitmapTexture::new(
                        Arc::new(image),
                        BitmapOptions::default(),
                    )),
                },
                flip_invalid_normals: true,
                shadowing: true,
                height_scale: Some(0.05),
            }
        });
    }
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

#[test]
fn a_flat_height_field_changes_no_bit() {
    let name = "textured_mesh";
    let plain = with_heights(name, None);
    let flat = with_heights(name, Some([0.4; 4]));
    let ramp = with_heights(name, Some([0.0, 1.0, 0.0, 1.0]));
    assert!(!flat.normal_maps.is_empty());
    let what = ["a flat height field", "a ramp"];
    assert_same_bits(&plain, &flat, &ramp, 2560, what);
}

/// A `size`² EXR of random heights in [0, 1].
fn rough_heights(dir: &std::path::Path, size: u32) -> PathBuf {
    let mut r = Rng::new(2570, 0, 0);
    let data = (0..size * size)
        .map(|_| Vec3::splat(r.next_f32()))
        .collect();
    let path = dir.join("heights.exr");
    Image {
        width: size,
        height: size,
        data,
    }
    .write(&path, 0.0)
    .unwrap();
    path
}

/// A one-sided plane under strong random bumps (slopes up to ~10: heights in [0, 1] over 16
/// texels, three times repeated, scale 0.2), seen from `from` with vertical field of view
/// `vfov`, lit by a sphere light at `light`.
fn plane_scene(dir: &std::path::Path, from: [f32; 3], vfov: f32, light: [f32; 3]) -> Arc<Scene> {
    let file = rough_heights(dir, 16);
    let map = format!(
        r#""bump_map": {{"texture": {{"type": "bitmap", "file": "{}", "uv_scale": [3, 3]}}, "scale": 0.2}}"#,
        file.file_name().unwrap().to_string_lossy()
    );
    plane_under_map(dir, &map, from, vfov, light)
}

#[test]
fn strong_bumps_let_no_light_through_the_surface() {
    let dir = scratch("leak");
    // 30°: the camera sees only the plane, never the light.
    let below = plane_scene(&dir, [0.0, 3.0, 0.5], 30.0, [1.6, -0.3, 0.0]);
    let above = plane_scene(&dir, [0.0, 3.0, 0.5], 30.0, [1.6, 0.3, 0.0]);
    assert_no_light_through(&below, &above, 2580, 2590);
}

#[test]
fn grazing_views_of_strong_bumps_stay_finite() {
    let dir = scratch("grazing");
    assert_finite_at_grazing_views(|from| plane_scene(&dir, from, 50.0, [0.3, 1.5, 0.2]), 2600);
}

#[test]
fn the_back_of_a_two_sided_bump_map_is_mitsubas() {
    let scene = mitsuba_scene("bumpmap_back");
    assert!(
        scene.two_sided[0]
            && scene.normal_maps[0]
                .as_ref()
                .is_some_and(|n| n.height_scale == Some(1.0))
    );
    // Not the one-sample mixture, whose samples are 0 or twice the value.
    let exact = DELTA_STRATEGIES
        .into_iter()
        .filter(|s| !matches!(s, lumis::integrator::Strategy::Mixture { .. }));
    for (i, strategy) in exact.enumerate() {
        let s = Settings {
            strategy,
            ..Settings::default()
        };
        let got = render(&scene, s, 4, 2640 + i as u32).film().mean();
        assert_pixels_match(&got, "bumpmap_back.exr", 1e-5, &format!("{strategy:?}"));
    }
}

/// The error of parsing `materials` with `shape` (using material `m`) in `dir`; it must name
/// `path` and contain each of `fragments`.
fn refused(dir: &std::path::Path, materials: &str, shape: &str, path: &str, fragments: &[&str]) {
    let json = format!(
        r#"{{"camera": {{"from": [0, 0, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                        "width": 8, "height": 8}},
            "materials": {{{materials}}},
            "shapes": [{shape}]}}"#
    );
    let e = parse_scene_in(&json, dir)
        .err()
        .unwrap_or_else(|| panic!("accepted: {materials}"))
        .to_string();
    assert!(e.contains(path), "expected {path} in: {e}");
    for f in fragments {
        assert!(e.contains(f), "expected `{f}` in: {e}");
    }
    assert!(!e.contains('\n'), "one line: {e}");
}

#[test]
fn bad_bump_maps_are_one_error_naming_the_key() {
    let dir = scratch("bad");
    rough_heights(&dir, 4);
    let mut wild = Image {
        width: 2,
        height: 2,
        data: vec![Vec3::ONE; 4],
    };
    wild.data[2] = Vec3::new(0.5, f32::INFINITY, 0.5);
    wild.write(&dir.join("wild.exr"), 0.0).unwrap();
    let quad = r#"{"type": "quad", "corner": [0, 0, 0], "edge_u": [1, 0, 0], "edge_v": [0, 1, 0], "material": "m"}"#;
    let diffuse = r#""type": "diffuse", "albedo": [0.5, 0.5, 0.5]"#;
    let bitmap = r#"{"type": "bitmap", "file": "heights.exr"}"#;
    let checker = r#"{"type": "checkerboard", "color0": [0, 0, 0], "color1": [1, 1, 1]}"#;
    for texture in [checker, "[0.5, 0.5, 0.5]"] {
        refused(
            &dir,
            &format!(r#""m": {{{diffuse}, "bump_map": {{"texture": {texture}}}}}"#),
            quad,
            "materials.m.bump_map.texture",
            &["must be a bitmap", "no gradient"],
        );
    }
    refused(
        &dir,
        &format!(
            r#""m": {{{diffuse}, "bump_map": {{"texture": {{"type": "bitmap", "file": "wild.exr"}}}}}}"#
        ),
        quad,
        "materials.m.bump_map.texture.file",
        &["wild.exr", "not finite"],
    );
    refused(
        &dir,
        &format!(
            r#""m": {{{diffuse}, "normal_map": {{"texture": [0.5, 0.5, 1]}},
                      "bump_map": {{"texture": {bitmap}}}}}"#
        ),
        quad,
        "materials.m.bump_map",
        &["not both"],
    );
    refused(
        &dir,
        &format!(r#""m": {{{diffuse}, "bump_map": {{"texture": {bitmap}, "scale": "big"}}}}"#),
        quad,
        "materials.m.bump_map.scale",
        &["number"],
    );
    refused(
        &dir,
        &format!(r#""m": {{{diffuse}, "bump_map": {{"texture": {bitmap}}}}}"#),
        r#"{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}"#,
        "shapes[0].material",
        &["bump map on a sphere", "∂p/∂v"],
    );
}
