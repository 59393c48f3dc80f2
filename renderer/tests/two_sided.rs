//! Two-sided pairs on the CPU (issue 40 item 3; `materials/two_sided.rs`, `Scene::resolve`),
//! beside the agreement with Mitsuba (`renderer/tests/mitsuba_xml_refs.rs`, `xml_two_sided`) and
//! the GPU's with the CPU (`renderer/tests/gpu/two_sided.rs`):
//!
//! - a pair of a material with itself renders the material with `"two_sided": true` bit for bit,
//!   in every strategy (the pair's resolution, side test and flipped frame are the flag's); the
//!   real pair (a different back) changes the image (the test's power);
//! - a closed form: a sheet 10⁴ wide under a constant sky, its front a diffuse ρ_f and its back a
//!   diffuse ρ_b, is ρ_f in every pixel seen from above and ρ_b seen from below;
//! - bad input is one error naming the key (`scene/parse_composite_tests.rs` has the parser's
//!   rules; here, the whole chain from text to a built scene).

mod common;

use common::surface_detail::{assert_same_bits, two_sided_variants};
use common::{STRATEGIES_AND_OPTIMAL, Tally, build, render};
use lumis::integrator::Settings;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::scene::{Scene, SceneDesc, parse_scene};
use std::sync::Arc;

/// `xml_two_sided.xml`'s cylinder (orange outside, gold inside) as the pair of orange with
/// itself, as a two-sided orange, and as imported: bit for bit the same image for the first two
/// in every strategy (4 spp, seeds 2790–2795), another for the third.
#[test]
fn a_pair_of_a_material_with_itself_is_the_two_sided_material() {
    let build = |d: &SceneDesc| Arc::new(Scene::from_desc(d).unwrap_or_else(|e| panic!("{e}")));
    let [flag, same, pair] = two_sided_variants();
    assert_same_bits(
        &build(&flag),
        &build(&same),
        &build(&pair),
        2790,
        ["the pair (orange, orange)", "the pair (orange, gold)"],
    );
}

/// A sheet at y = 0, 10⁴ wide, its front (+y) a diffuse `front` and its back a diffuse `back`,
/// under a sky of radiance 1, seen straight at from `y` = ±1 (16², 60°).
fn sheet_scene(front: f64, back: f64, y: f64) -> Arc<Scene> {
    let h = 5000.0;
    build(&format!(
        r#"{{
  "camera": {{"from": [0, {y}, 0], "to": [0, 0, 0], "up": [0, 0, 1], "vfov_deg": 60,
             "width": 16, "height": 16}},
  "background": [1, 1, 1],
  "materials": {{
    "front": {{"type": "diffuse", "albedo": [{front}, {front}, {front}], "two_sided": false}},
    "back": {{"type": "diffuse", "albedo": [{back}, {back}, {back}], "two_sided": false}},
    "sheet": {{"type": "two_sided", "front": "front", "back": "back"}}
  }},
  "shapes": [
    {{"type": "quad", "corner": [-{h}, 0, -{h}], "edge_u": [0, 0, {w}], "edge_v": [{w}, 0, 0],
      "material": "sheet"}}
  ]
}}"#,
        w = 2.0 * h
    ))
}

/// Every pixel of [`sheet_scene`] (ρ_f = 0.2, ρ_b = 0.7) against ρ_f from above and ρ_b from
/// below, per strategy (six, mis-optimal among them; 64 spp, seeds 2800 + 10·side + strategy,
/// fixed before the first run): the image mean of channel 0 (the scene is grey) by a z-test
/// from the film's per-pixel variances, family-wise α = 0.01 over the 12 comparisons,
/// Šidák-corrected (critical |z| 3.34). The sd of a mean is under 1% of the value, so a bias of
/// 4% is caught: the sides swapped (0.7 for 0.2), the back black as a one-sided material's
/// (0), or the back's frame not flipped (its light sampled below the surface: 0).
#[test]
fn a_sheet_with_two_sides_matches_the_closed_form() {
    let comparisons = 12;
    let mut tally = Tally::new(normal_two_sided_critical(sidak(0.01, comparisons)));
    let (front, back) = (0.2, 0.7);
    for (side, (y, expected)) in [(1.0, front), (-1.0, back)].into_iter().enumerate() {
        let scene = sheet_scene(front, back, y);
        for (i, strategy) in STRATEGIES_AND_OPTIMAL.into_iter().enumerate() {
            let s = Settings {
                strategy,
                ..Settings::default()
            };
            let r = render(&scene, s, 64, 2800 + 10 * side as u32 + i as u32);
            let film = r.film();
            assert_eq!(film.nonfinite, 0);
            let means: Vec<f64> = film.mean().iter().map(|p| p.x as f64).collect();
            let vars: Vec<f64> = film.variance_of_mean().iter().map(|p| p[0]).collect();
            let from = if y > 0.0 { "above" } else { "below" };
            tally.compare(&format!("{from} {strategy:?}"), &means, &vars, expected);
        }
    }
    tally.finish("two-sided sheet", comparisons);
}

/// From text to a built scene, a bad pair is one error naming its key.
#[test]
fn bad_pairs_are_located_errors() {
    let scene = |pair: &str| {
        format!(
            r#"{{"camera": {{"from": [0, 1, -3], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40,
                "width": 8, "height": 8}},
  "materials": {{
    "a": {{"type": "diffuse", "albedo": [0.5, 0.5, 0.5]}},
    "glass": {{"type": "dielectric", "ior": 1.5}},
    "pair": {pair}
  }},
  "shapes": [{{"type": "quad", "corner": [-1, 0, -1], "edge_u": [0, 0, 2], "edge_v": [2, 0, 0],
               "material": "pair"}}]
}}"#
        )
    };
    for (pair, path, fragment) in [
        (
            r#"{"type": "two_sided", "front": "a", "back": "glass"}"#,
            "materials.pair.back",
            "material `glass` transmits light",
        ),
        (
            r#"{"type": "two_sided", "front": "b", "back": "a"}"#,
            "materials.pair.front",
            "unknown material `b`",
        ),
        (
            r#"{"type": "two_sided", "front": "a", "back": "a", "opacity": 2}"#,
            "materials.pair.opacity",
            "outside [0, 1]",
        ),
    ] {
        let text = scene(pair);
        let err = match parse_scene(&text).and_then(|d| Scene::from_desc(&d)) {
            Ok(_) => panic!("accepted:\n{text}"),
            Err(e) => e.to_string(),
        };
        assert!(
            err.contains(path) && err.contains(fragment),
            "{pair}: {err}"
        );
    }
}
