//! Alpha masks on the CPU (issue 40 item 2; `materials/mask.rs`, `scene/trace.rs`), beside the
//! agreement with Mitsuba (`renderer/tests/mitsuba_xml_refs.rs`, `xml_mask`; the gallery's
//! `bsdf_mask_after` in `renderer/tests/gallery.rs`) and the GPU's with the CPU
//! (`renderer/tests/gpu/mask.rs`):
//!
//! - opacity 1 on every material leaves every image bit for bit as it was, in every strategy,
//!   though every ray then takes the masked traversals (closest and any hit, through the BVH, on
//!   meshes and quads); opacity ½ changes it (the test's power);
//! - a closed form: a floor (albedo ρ) under a black sheet of opacity α, both 10⁴ wide, under a
//!   constant sky L, seen from above through the sheet, is (1 − α)²·ρ·L in every pixel: the
//!   camera's ray passes the sheet with probability 1 − α and so does the light the floor
//!   receives, by next-event estimation and by BSDF sampling alike;
//! - bad input is one error naming the key: an opacity outside [0, 1] (a number or a texture's
//!   texel), on a mix's material, on an emitter's material.

mod common;

use common::surface_detail::{assert_same_bits, with_opacity};
use common::{STRATEGIES_AND_OPTIMAL, Tally, build, render};
use lumis::integrator::Settings;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::scene::{Scene, parse_scene};
use std::sync::Arc;

#[test]
fn opacity_one_changes_no_bit() {
    let name = "textured_mesh";
    let plain = with_opacity(name, None);
    let opaque = with_opacity(name, Some(1.0));
    let half = with_opacity(name, Some(0.5));
    assert!(plain.opacity.is_empty() && !opaque.opacity.is_empty());
    assert!(
        plain.accel.cwbvh().is_some(),
        "the BVH's traversals are tested"
    );
    assert_same_bits(&plain, &opaque, &half, 2710, ["opacity 1", "opacity ½"]);
}

/// The closed-form scene: a floor (albedo `rho`) at y = 0 under a black sheet of opacity `alpha`
/// at y = 0.5, both 10⁴ wide (the sky beyond their edges is 10⁻⁸ of a floor point's
/// cosine-weighted hemisphere), a sky of radiance 1, seen straight down from y = 1 (16², 60°).
fn sheet_scene(alpha: f64, rho: f64) -> Arc<Scene> {
    let h = 5000.0;
    build(&format!(
        r#"{{
  "camera": {{"from": [0, 1, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 60,
             "width": 16, "height": 16}},
  "background": [1, 1, 1],
  "materials": {{
    "floor": {{"type": "diffuse", "albedo": [{rho}, {rho}, {rho}]}},
    "sheet": {{"type": "diffuse", "albedo": [0, 0, 0], "opacity": {alpha}}}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-{h}, 0, -{h}], "edge_u": [0, 0, {w}], "edge_v": [{w}, 0, 0],
      "material": "floor"}},
    {{"type": "quad", "corner": [-{h}, 0.5, -{h}], "edge_u": [0, 0, {w}], "edge_v": [{w}, 0, 0],
      "material": "sheet"}}
  ]
}}"#,
        w = 2.0 * h
    ))
}

/// Every pixel of [`sheet_scene`] against (1 − α)²·ρ, per strategy (six, mis-optimal among
/// them) and α ∈ {0.3, 0.75} (ρ = 0.5, 64 spp, seeds 2720 + 10·case + strategy, fixed before
/// the first run): the image mean of channel 0 (the scene is grey) by a z-test from the film's
/// per-pixel variances, family-wise α = 0.01 over the 12 comparisons, Šidák-corrected
/// (critical |z| 3.34). The sd of a mean is about 1% of the value, so a bias of 4% is caught:
/// masks that stopped shadow rays (light-only: 0; MIS: about half the light), the comparison
/// the wrong way round (α ↔ 1 − α: 0.09 for 0.245 at α = 0.3) or a camera ray that ignored the
/// mask ((1 − α)·ρ).
#[test]
fn a_floor_under_a_masked_sheet_matches_the_closed_form() {
    let comparisons = 12;
    let mut tally = Tally::new(normal_two_sided_critical(sidak(0.01, comparisons)));
    let rho = 0.5;
    for (case, alpha) in [0.3, 0.75].into_iter().enumerate() {
        let scene = sheet_scene(alpha, rho);
        let expected = (1.0 - alpha) * (1.0 - alpha) * rho;
        for (i, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
            let s = Settings {
                strategy,
                ..Settings::default()
            };
            let r = render(&scene, s, 64, 2720 + 10 * case as u32 + i as u32);
            let film = r.film();
            assert_eq!(film.nonfinite, 0);
            let means: Vec<f64> = film.mean().iter().map(|p| p.x as f64).collect();
            let vars: Vec<f64> = film.variance_of_mean().iter().map(|p| p[0]).collect();
            tally.compare(&format!("α {alpha} {strategy:?}"), &means, &vars, expected);
        }
    }
    tally.finish("masked sheet", comparisons);
}

/// `text` parsed and built: the error's message.
fn error_of(text: &str) -> String {
    match parse_scene(text).and_then(|d| Scene::from_desc(&d)) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// A scene with material `m` (JSON) on a quad and a quad light whose material is `light`.
fn with_material(m: &str, light: &str) -> String {
    format!(
        r#"{{
  "camera": {{"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
             "width": 8, "height": 8}},
  "materials": {{
    "m": {m},
    "a": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
    "b": {{"type": "diffuse", "albedo": [0.2, 0.2, 0.2]}},
    "glow": {light}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0],
      "material": "m"}},
    {{"type": "quad", "corner": [-0.5, 2, -0.5], "edge_u": [1, 0, 0], "edge_v": [0, 0, 1],
      "emission": [5, 5, 5], "material": "glow"}}
  ]
}}"#
    )
}

#[test]
fn bad_opacities_are_located_errors() {
    let plain = r#"{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}"#;
    let cases = [
        (
            r#"{"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "opacity": 1.5}"#,
            plain,
            "materials.m.opacity",
            "outside [0, 1]",
        ),
        (
            r#"{"type": "diffuse", "albedo": [0.5, 0.5, 0.5],
                "opacity": {"type": "checkerboard", "color0": 0.5, "color1": 1.2}}"#,
            plain,
            "materials.m.opacity",
            "an opacity must lie in [0, 1]",
        ),
        (
            r#"{"type": "conductor", "alpha": 0.1, "reflectance": [1, 1, 1], "opacity": "half"}"#,
            plain,
            "materials.m.opacity",
            "",
        ),
        (
            r#"{"type": "mix", "materials": ["a", "glow"], "weight": 0.5}"#,
            r#"{"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "opacity": 0.5}"#,
            "materials.m.materials[1]",
            "a mix's materials cannot",
        ),
        (
            plain,
            r#"{"type": "diffuse", "albedo": [0.5, 0.5, 0.5], "opacity": 0.5}"#,
            "shapes[1]",
            "an emitter's material cannot have an opacity",
        ),
    ];
    for (m, light, path, words) in cases {
        let e = error_of(&with_material(m, light));
        assert!(e.contains(path) && e.contains(words), "{m} / {light}: {e}");
    }
    // On a mix itself, and on every material type, an opacity is accepted.
    for m in [
        r#"{"type": "mix", "materials": ["a", "b"], "weight": 0.5, "opacity": 0.4}"#,
        r#"{"type": "conductor", "alpha": 0.1, "reflectance": [1, 1, 1], "opacity": 0.4}"#,
        r#"{"type": "plastic", "albedo": [0.5, 0.5, 0.5], "alpha": 0.1, "opacity": 0.4}"#,
        r#"{"type": "dielectric", "ior": 1.5, "opacity": 0.4}"#,
        r#"{"type": "thin_dielectric", "ior": 1.5, "opacity": 0.4}"#,
    ] {
        let text = with_material(m, plain);
        let scene = parse_scene(&text)
            .and_then(|d| Scene::from_desc(&d))
            .unwrap_or_else(|e| panic!("{m}: {e}"));
        assert!(!scene.opacity.is_empty(), "{m}");
    }
}
