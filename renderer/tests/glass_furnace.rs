//! Glass in a white furnace: smooth dielectrics neither create nor destroy energy, so in a uniform
//! environment of radiance `L` every pixel is exactly `L`, whatever the strategy.
//!
//! - **Exact, one path at a time.** A smooth glass sphere (ior 1.5, 2.4, and 0.75: an air bubble
//!   in water seen from the water) under a constant background, BSDF strategy, unlimited depth and
//!   no Russian roulette: every path is reflections (weight 1) and refractions whose weights
//!   1/η'² and η'² cancel once the path leaves the sphere, so every *sample* is `L` to f32
//!   rounding (checked per pixel to 1e-5 relative). This catches a missing or doubled η² factor,
//!   a Fresnel term that does not sum to one, and rays lost or trapped at the boundary (a sphere
//!   has no total internal reflection for light that entered it). Light sampling plays no part:
//!   a smooth dielectric is a delta BSDF.
//! - **Inside glass.** The camera inside a glass sphere sees η²·L exactly (every sample), which
//!   pins the exponent of the η'² rule (from outside, two refractions cancel any power of η).
//! - **Every strategy.** A smooth glass sphere, a smooth glass box (rotated: total internal
//!   reflection inside it) and a white diffuse sphere (albedo 1) in the same environment, every
//!   strategy × light-sampling method, unlimited depth with Russian roulette: every pixel is `L`.
//!   Light sampling at the diffuse sphere is blocked by the glass (shadow rays stop at dielectrics,
//!   as in Mitsuba's `path`); the BSDF-sampled path through the glass then carries that light with
//!   full weight, which this checks. Russian roulette must see the throughput without the
//!   η'² of radiance (pbrt-v4's `etaScale`) or it would end paths inside the glass with the wrong
//!   probability; that would still be unbiased, so this test cannot see it: `rr_keeps_paths_in_glass`
//!   does.
//!
//! **Test:** per render and channel, the mean of the image and of each 8×8 block is compared with
//! `L` by a two-sided z-test with sd from the film's per-pixel variance of the mean; family-wise
//! α = 0.01 over all [`N_COMPARISONS`] comparisons, Šidák-corrected. Seeds are fixed.

mod common;

use common::{METHODS, STRATEGIES, Tally, build, render};
use lumis::integrator::{Settings, Strategy};
use lumis::metrics::{normal_two_sided_critical, sidak};
use std::sync::Arc;

/// Image size (square) and block size.
const SIZE: u32 = 16;
const BLOCK: u32 = 8;
/// Environment radiance per channel (coloured, so a channel mix-up shows).
const L: [f64; 3] = [0.8, 1.0, 1.3];
/// Comparisons of one render: the image and its blocks, per channel.
const PER_RENDER: usize = 3 * (1 + (SIZE / BLOCK * SIZE / BLOCK) as usize);
/// Every comparison in this file.
const N_COMPARISONS: usize = STRATEGIES.len() * METHODS.len() * PER_RENDER;

fn critical() -> f64 {
    normal_two_sided_critical(sidak(0.01, N_COMPARISONS))
}

/// `shapes` (JSON) under the constant background `L`, seen from outside.
fn furnace_scene(materials: &str, shapes: &str) -> Arc<lumis::scene::Scene> {
    build(&format!(
        r#"{{
  "camera": {{"from": [0, 0.6, -4], "to": [0, 0, 0], "up": [0, 1, 0], "vfov_deg": 40, "width": {SIZE}, "height": {SIZE}}},
  "max_depth": -1,
  "background": [{}, {}, {}],
  "materials": {{{materials}}},
  "shapes": [{shapes}]
}}"#,
        L[0], L[1], L[2]
    ))
}

/// A sphere filling most of the view, of a smooth dielectric of `ior`.
fn glass_sphere(ior: f64) -> Arc<lumis::scene::Scene> {
    furnace_scene(
        &format!(r#""glass": {{"type": "dielectric", "ior": {ior}}}"#),
        r#"{"type": "sphere", "center": [0, 0, 0], "radius": 1.2, "material": "glass"}"#,
    )
}

/// Renders `scene` by BSDF sampling with unlimited depth and no Russian roulette, and asserts
/// that every pixel is `expected` with zero variance: every sample, not only their mean, is exact
/// (to the f32 rounding of a few dozen bounces, 1e-5 relative).
fn assert_every_sample_is(
    scene: &Arc<lumis::scene::Scene>,
    expected: [f64; 3],
    seed: u32,
    what: &str,
) {
    let settings = Settings {
        strategy: Strategy::Bsdf,
        rr_depth: u32::MAX,
        ..Settings::default()
    };
    let r = render(scene, settings, 64, seed);
    let film = r.film();
    assert_eq!(film.nonfinite, 0, "{what}");
    let var = film.variance_of_mean();
    for (p, (m, v)) in film.mean().iter().zip(&var).enumerate() {
        for c in 0..3 {
            let rel = (m[c] as f64 - expected[c]).abs() / expected[c];
            assert!(
                rel < 1e-5 && v[c] < 1e-10,
                "{what} pixel {p} ch {c}: {} vs {} (var {})",
                m[c],
                expected[c],
                v[c]
            );
        }
    }
}

#[test]
fn smooth_glass_sphere_returns_every_path_unchanged() {
    for (i, ior) in [1.5, 2.4, 0.75].into_iter().enumerate() {
        assert_every_sample_is(&glass_sphere(ior), L, 70 + i as u32, &format!("ior {ior}"));
    }
}

/// The camera inside glass of index η sees η²·L (radiance over η² is invariant along a ray):
/// every path leaves the sphere once, carrying η'² = η² from its one refraction outwards. The
/// camera sits at 0.35 radii from the centre, so rays meet the surface at up to asin(0.35) =
/// 20.5°, below every critical angle here (24.6° for η = 2.4): no path is trapped. Unlike the
/// view from outside, where the two refractions cancel whatever power of η they carry, this
/// fails for any exponent but 2.
#[test]
fn camera_inside_glass_sees_eta_squared() {
    for (i, ior) in [1.5f64, 2.4, 0.75].into_iter().enumerate() {
        let scene = build(&format!(
            r#"{{
  "camera": {{"from": [0.35, 0, 0], "to": [0.35, 0.3, 1], "up": [0, 1, 0], "vfov_deg": 90, "width": {SIZE}, "height": {SIZE}}},
  "max_depth": -1,
  "background": [{}, {}, {}],
  "materials": {{"glass": {{"type": "dielectric", "ior": {ior}}}}},
  "shapes": [{{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "glass"}}]
}}"#,
            L[0], L[1], L[2]
        ));
        let expected = L.map(|l| ior * ior * l);
        assert_every_sample_is(
            &scene,
            expected,
            80 + i as u32,
            &format!("inside ior {ior}"),
        );
    }
}

#[test]
fn glass_and_white_diffuse_furnace_every_strategy() {
    let scene = furnace_scene(
        r#""glass": {"type": "dielectric", "ior": 1.5}, "white": {"type": "diffuse", "albedo": [1, 1, 1]}"#,
        r#"{"type": "sphere", "center": [-0.55, 0, 0], "radius": 0.5, "material": "glass"},
    {"type": "box", "min": [-0.3, -0.3, -0.3], "max": [0.3, 0.3, 0.3], "rotate_y_deg": 30, "translate": [0.6, 0.35, -0.2], "material": "glass"},
    {"type": "sphere", "center": [0.45, -0.45, 0.3], "radius": 0.35, "material": "white"}"#,
    );
    let mut tally = Tally::new(critical());
    for (s, strategy) in STRATEGIES.into_iter().enumerate() {
        for (m, method) in METHODS.into_iter().enumerate() {
            let settings = Settings {
                strategy,
                light_sampling: method,
                ..Settings::default()
            };
            let r = render(&scene, settings, 4096, 500 + (10 * s + m) as u32);
            let film = r.film();
            let what = format!("{strategy:?} {method:?}");
            assert_eq!(film.nonfinite, 0, "{what}");
            let (mean, var) = (film.mean(), film.variance_of_mean());
            for c in 0..3 {
                let regions = std::iter::once((0, 0, SIZE)).chain(
                    (0..SIZE).step_by(BLOCK as usize).flat_map(|y| {
                        (0..SIZE)
                            .step_by(BLOCK as usize)
                            .map(move |x| (x, y, BLOCK))
                    }),
                );
                for (x0, y0, size) in regions {
                    let idx: Vec<usize> = (y0..y0 + size)
                        .flat_map(|y| (x0..x0 + size).map(move |x| (y * SIZE + x) as usize))
                        .collect();
                    let means: Vec<f64> = idx.iter().map(|&i| mean[i][c] as f64).collect();
                    let vars: Vec<f64> = idx.iter().map(|&i| var[i][c]).collect();
                    let region = format!("{what} ch {c} ({x0},{y0})×{size}");
                    tally.compare(&region, &means, &vars, L[c]);
                }
            }
        }
    }
    tally.finish("glass furnace", N_COMPARISONS);
}

/// Russian roulette sees beta·η'² (pbrt-v4's etaScale): inside glass of ior 2.4 a path's weight
/// is 1/2.4² ≈ 0.17, and a roulette on that alone would end ~83% of the paths at each bounce
/// from `rr_depth` on. With the η'² taken out the throughput seen is 1 (capped at 0.95), so the
/// variance of a glass sphere's image stays that of the 0.95 roulette: this test bounds the
/// per-sample variance by what the correct roulette gives. Measured: 0.09 with `etaScale`, 3.4
/// with a roulette on beta alone (the bound is 1).
#[test]
fn rr_keeps_paths_in_glass() {
    let scene = glass_sphere(2.4);
    let settings = Settings {
        strategy: Strategy::Bsdf,
        rr_depth: 1,
        ..Settings::default()
    };
    let spp = 256;
    let r = render(&scene, settings, spp, 91);
    let film = r.film();
    let var = film.variance_of_mean();
    // Per-sample variance relative to L², averaged over the pixels that see the sphere (variance
    // > 0). A path that survives k roulettes of q = 0.95 carries L/0.95^k; through glass k is the
    // number of bounces, a handful, so the relative variance is ~(1/0.95)^k − 1 ≲ 0.5. A roulette
    // on beta alone (q ≈ 0.17 inside) gives (1/0.17) − 1 ≈ 5 per bounce inside.
    let rel: Vec<f64> = var
        .iter()
        .filter(|v| v[1] > 0.0)
        .map(|v| v[1] * spp as f64 / (L[1] * L[1]))
        .collect();
    assert!(rel.len() > 50, "the sphere fills the view");
    let mean_rel = rel.iter().sum::<f64>() / rel.len() as f64;
    eprintln!("relative per-sample variance inside the sphere: {mean_rel:.3}");
    assert!(mean_rel < 1.0, "{mean_rel}");
}
