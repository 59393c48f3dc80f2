//! White-furnace tests: scenes whose every pixel has a closed-form value, rendered with every
//! strategy (light, BSDF, mixture w = 0.5, MIS power and balance, MIS with optimal weights) and
//! both light-sampling methods (area, solid angle), seeded.
//!
//! - **Closed emissive box.** The camera sits inside a cube of six inward-facing diffuse quads, each
//!   with albedo `a` and one-sided (inward) emission `L`. Every pixel sees `L·(1 + a + … + a^{k−1})`
//!   per channel at `max_depth` k (Mitsuba's convention) and `L/(1−a)` at `max_depth −1`
//!   (Russian roulette must stay unbiased). Cases: grey a = 0.5 and a = 0.8, a coloured albedo with a
//!   coloured emission, each at k = 1, 2, 3, −1; and a = 1 at k = 5 (`5L`; Russian roulette starts
//!   after the fifth segment, so it cannot play a part). With the light strategy, emission after the
//!   camera ray is only counted by light sampling, so this checks every strategy's bookkeeping.
//! - **Background furnace.** A 10⁴-wide diffuse quad (albedo `a`, normal up) under a constant
//!   background `L`, seen from above: pixels that see only the quad are `a·L` at `max_depth` 2 and −1
//!   (a plane cannot see itself) and 0 at `max_depth` 1; pixels that see only the sky are `L`.
//!   Pixels straddling the horizon are left out.
//!
//! **Light strategy with area sampling in the box** has infinite variance: a receiver at distance ε
//! from the edge shared with an emitting face gets per-sample variance ~1/ε², and camera or path
//! vertices come arbitrarily close to the cube's edges (the sample tail is P(X > t) ~ t^(−3/2)). Its
//! sample variance then understates the error and block z-scores drift negative (z ≈ −5 at 2048 spp
//! in 8×8 blocks). It stays unbiased; it is compared on the whole image per channel only. Every other
//! combination bounds the light-sample weight (solid angle: `f·L·cos·Ω`; MIS and the mixture divide
//! by at least a BSDF pdf), so its variance is finite.
//!
//! The a = 1 case uses 2048 spp: every path of the BSDF strategy is exactly `5L`, so any lost path
//! segment (a ray escaping the closed box) shows up as a deficit far beyond its tiny variance.
//!
//! **Test:** per render and channel, the image mean (box: also four 8×8 blocks; background: the
//! ground pixels and the sky pixels) is compared with the closed form by a two-sided z-test,
//! z = (mean − expected) / sd with sd from the film's per-pixel variance of the mean (pixels are
//! independent). Family-wise α = 0.01 over all [`N_COMPARISONS`] comparisons in this file,
//! Šidák-corrected (per comparison `1 − 0.99^(1/N)`). A relative slack of 1e-5 of the expected value
//! absorbs f32 rounding (it matters only where the variance is 0: `max_depth` 1, the sky). Every
//! render must also have no non-finite samples.

mod common;

use common::ground::{background_scene, classify_pixels};
use common::{METHODS, STRATEGIES_AND_OPTIMAL as STRATEGIES, Tally, build, json_vec, render};
use glam::Vec3;
use lumis::integrator::{Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::metrics::{normal_two_sided_critical, sidak};
use lumis::scene::Scene;
use std::sync::Arc;

const SETTINGS_PER_SCENE: usize = STRATEGIES.len() * METHODS.len();

/// Image size (square).
const SIZE: u32 = 16;
/// Block size of the box test.
const BLOCK: u32 = 8;
/// Samples per pixel.
const SPP: u32 = 256;

/// Box scenes: three albedo/emission pairs × four depths, plus a = 1 at depth 5.
const BOX_SCENES: usize = 3 * 4 + 1;
/// Comparisons per box render: the image mean and every block, per channel.
const BOX_COMPARISONS: usize = 3 * (1 + (SIZE / BLOCK * SIZE / BLOCK) as usize);
/// Light strategy with area sampling: the image mean only (see the file comment).
const BOX_COMPARISONS_LIGHT_AREA: usize = 3;
/// Comparisons of one box scene over all settings.
const BOX_COMPARISONS_PER_SCENE: usize =
    (SETTINGS_PER_SCENE - 1) * BOX_COMPARISONS + BOX_COMPARISONS_LIGHT_AREA;
/// Background scenes: two albedo/emission pairs × three depths.
const BACKGROUND_SCENES: usize = 2 * 3;
/// Comparisons per background render: ground and sky, per channel.
const BACKGROUND_COMPARISONS: usize = 3 * 2;
/// Every comparison in this file.
const N_COMPARISONS: usize = BOX_SCENES * BOX_COMPARISONS_PER_SCENE
    + BACKGROUND_SCENES * SETTINGS_PER_SCENE * BACKGROUND_COMPARISONS;

/// Critical |z| of one comparison.
fn critical() -> f64 {
    normal_two_sided_critical(sidak(0.01, N_COMPARISONS))
}

fn settings(strategy: Strategy, light_sampling: LightSampling, max_depth: i32) -> Settings {
    Settings {
        strategy,
        light_sampling,
        max_depth: Some(max_depth),
        ..Settings::default()
    }
}

/// The cube [−1, 1]³ made of six quads whose normals `cross(edge_u, edge_v)` point inwards, all
/// diffuse with `albedo` and emitting `le`; the camera inside looks towards a corner so that every
/// face and several edges are in view.
fn closed_box(albedo: Vec3, le: Vec3) -> Arc<Scene> {
    let (x, y, z) = ([2, 0, 0], [0, 2, 0], [0, 0, 2]);
    // (corner, edge_u, edge_v): normal = edge_u × edge_v, pointing into the cube.
    let faces = [
        ([-1, -1, -1], y, z), // x = −1, normal +x
        ([1, -1, -1], z, y),  // x = +1, normal −x
        ([-1, -1, -1], z, x), // y = −1, normal +y
        ([-1, 1, -1], x, z),  // y = +1, normal −y
        ([-1, -1, -1], x, y), // z = −1, normal +z
        ([-1, -1, 1], y, x),  // z = +1, normal −z
    ];
    let shapes: Vec<String> = faces
        .iter()
        .map(|(c, u, v)| {
            format!(
                r#"{{"type": "quad", "corner": {c:?}, "edge_u": {u:?}, "edge_v": {v:?}, "material": "wall", "emission": {}}}"#,
                json_vec(le)
            )
        })
        .collect();
    let json = format!(
        r#"{{
  "camera": {{"from": [0.1, 0.05, -0.2], "to": [1, 0.8, 0.9], "up": [0, 1, 0], "vfov_deg": 100, "width": {SIZE}, "height": {SIZE}}},
  "materials": {{"wall": {{"type": "diffuse", "albedo": {}}}}},
  "shapes": [{}]
}}"#,
        json_vec(albedo),
        shapes.join(",\n    ")
    );
    let scene = build(&json);
    assert_eq!(scene.lights.len(), 6);
    scene
}

/// `L·(1 + a + … + a^{k−1})`, or `L/(1−a)` for `k = −1`.
fn box_radiance(albedo: Vec3, le: Vec3, max_depth: i32) -> Vec3 {
    if max_depth < 0 {
        return le / (Vec3::ONE - albedo);
    }
    let mut sum = Vec3::ZERO;
    let mut term = le;
    for _ in 0..max_depth {
        sum += term;
        term *= albedo;
    }
    sum
}

fn check_box(test: &str, albedo: Vec3, le: Vec3, depths: &[i32], spp: u32, seed: u32) {
    let scene = closed_box(albedo, le);
    let mut tally = Tally::new(critical());
    let mut nonfinite = Vec::new();
    for (d, &max_depth) in depths.iter().enumerate() {
        let expected = box_radiance(albedo, le, max_depth);
        for (s, strategy) in STRATEGIES.into_iter().enumerate() {
            for (m, method) in METHODS.into_iter().enumerate() {
                let r = render(
                    &scene,
                    settings(strategy, method, max_depth),
                    spp,
                    seed + (100 * d + 10 * s + m) as u32,
                );
                let film = r.film();
                let what = format!("{test} depth {max_depth} {strategy:?} {method:?}");
                if film.nonfinite != 0 {
                    nonfinite.push(format!("{what}: {} non-finite samples", film.nonfinite));
                }
                let mean = film.mean();
                let var = film.variance_of_mean();
                for c in 0..3 {
                    let means: Vec<f64> = mean.iter().map(|p| p[c] as f64).collect();
                    let vars: Vec<f64> = var.iter().map(|p| p[c]).collect();
                    tally.compare(
                        &format!("{what} ch {c} image"),
                        &means,
                        &vars,
                        expected[c] as f64,
                    );
                    let light_area = strategy == Strategy::Light && method == LightSampling::Area;
                    if light_area {
                        continue;
                    }
                    for by in (0..SIZE).step_by(BLOCK as usize) {
                        for bx in (0..SIZE).step_by(BLOCK as usize) {
                            let idx: Vec<usize> = (by..by + BLOCK)
                                .flat_map(|y| {
                                    (bx..bx + BLOCK).map(move |x| (y * SIZE + x) as usize)
                                })
                                .collect();
                            let bm: Vec<f64> = idx.iter().map(|&i| means[i]).collect();
                            let bv: Vec<f64> = idx.iter().map(|&i| vars[i]).collect();
                            tally.compare(
                                &format!("{what} ch {c} block ({bx},{by})"),
                                &bm,
                                &bv,
                                expected[c] as f64,
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(nonfinite.is_empty(), "{}", nonfinite.join("\n"));
    tally.finish(test, depths.len() * BOX_COMPARISONS_PER_SCENE);
}

const DEPTHS: [i32; 4] = [1, 2, 3, -1];

#[test]
fn closed_box_grey_half() {
    check_box(
        "box a=0.5",
        Vec3::splat(0.5),
        Vec3::ONE,
        &DEPTHS,
        SPP,
        10_000,
    );
}

#[test]
fn closed_box_grey_080() {
    check_box(
        "box a=0.8",
        Vec3::splat(0.8),
        Vec3::splat(0.7),
        &DEPTHS,
        SPP,
        20_000,
    );
}

#[test]
fn closed_box_coloured() {
    check_box(
        "box coloured",
        Vec3::new(0.8, 0.5, 0.2),
        Vec3::new(1.0, 0.5, 2.0),
        &DEPTHS,
        SPP,
        30_000,
    );
}

/// a = 1: the series does not converge, but `max_depth` 5 is the finite sum `5L`, reached before
/// Russian roulette may start (`rr_depth` 5), so no strategy can hide a bias behind it. This test
/// found the energy leak at inside edges (4.999771 instead of 5, z ≈ −6.6): obvhs's fixed node
/// epsilon and the triangle test's error bound lost walls right next to a path's origin.
#[test]
fn closed_box_white_depth_5() {
    check_box(
        "box a=1",
        Vec3::ONE,
        Vec3::new(0.3, 0.6, 1.0),
        &[5],
        2048,
        40_000,
    );
}

#[test]
fn background_furnace() {
    let cases = [
        (Vec3::splat(0.5), Vec3::ONE),
        (Vec3::new(0.8, 0.5, 0.2), Vec3::new(1.0, 0.5, 2.0)),
    ];
    let depths = [1, 2, -1];
    let mut tally = Tally::new(critical());
    let mut nonfinite = Vec::new();
    for (k, (albedo, le)) in cases.into_iter().enumerate() {
        let scene = background_scene(albedo, &json_vec(le), SIZE);
        let (ground, sky) = classify_pixels(&scene, SIZE);
        assert!(ground.len() >= 100 && sky.len() >= 16, "{ground:?} {sky:?}");
        for (d, &max_depth) in depths.iter().enumerate() {
            let ground_value = if max_depth == 1 {
                Vec3::ZERO
            } else {
                albedo * le
            };
            for (s, strategy) in STRATEGIES.into_iter().enumerate() {
                for (m, method) in METHODS.into_iter().enumerate() {
                    let seed = 50_000 + (1000 * k + 100 * d + 10 * s + m) as u32;
                    let r = render(&scene, settings(strategy, method, max_depth), SPP, seed);
                    let film = r.film();
                    let what = format!("background {k} depth {max_depth} {strategy:?} {method:?}");
                    if film.nonfinite != 0 {
                        nonfinite.push(format!("{what}: {} non-finite samples", film.nonfinite));
                    }
                    let mean = film.mean();
                    let var = film.variance_of_mean();
                    for c in 0..3 {
                        for (region, pixels, value) in
                            [("ground", &ground, ground_value), ("sky", &sky, le)]
                        {
                            let means: Vec<f64> =
                                pixels.iter().map(|&i| mean[i][c] as f64).collect();
                            let vars: Vec<f64> = pixels.iter().map(|&i| var[i][c]).collect();
                            tally.compare(
                                &format!("{what} ch {c} {region}"),
                                &means,
                                &vars,
                                value[c] as f64,
                            );
                        }
                    }
                }
            }
        }
    }
    assert!(nonfinite.is_empty(), "{}", nonfinite.join("\n"));
    tally.finish(
        "background furnace",
        BACKGROUND_SCENES * SETTINGS_PER_SCENE * BACKGROUND_COMPARISONS,
    );
}
