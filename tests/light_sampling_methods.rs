//! The light-sampling methods of issue 19 in whole renders: cosine-warped light sampling
//! (`LightSampling::SolidAngleCosine`, item 2: Hart et al. 2020's bilinear warp in front of the
//! spherical triangle and rectangle warps) and adaptive light sampling (`LightSampling::Adaptive`,
//! item 4: area or solid angle per light and shading point, a polygon's triangle picked by its
//! estimated solid angle). Each is unbiased for every strategy that samples lights, against the
//! stored references of the independent renderer, on the scenes whose lights it changes (polygons
//! in `seed_cornell` and `analytic_polygon`, a quad in `textured_mesh`). Their densities
//! themselves are checked by the χ² suite (`light/{triangle,hexagon,star,quad}/*/solidanglecosine`
//! and `…/adaptive` in `tests/chi2_samplers.rs`), which also compares every sample's reported pdf
//! with `Light::pdf` (the MIS side, through the inverse warps).
//!
//! **Test:** `common::test_against` per 32×32 block and channel, sd from the render's per-pixel
//! variance and the reference's variance image, Šidák-corrected family-wise α = 0.01 per render;
//! the spp of `reference_scenes.rs` for each scene; seeds [`SEED`] + the render's index.
//!
//! **Power, measured once** (the deliberate bug of forgetting the warp's density: samples warped
//! but the pdf left at `1/Ω`, on both the sampling and the MIS side): this file's
//! `seed_cornell` test fails for all four strategies (one block each, |z| 4.2 light, 4.2
//! mixture, 5.7 MIS power, 5.3 MIS balance, critical 4.05), and the χ² suite rejects 11 of its 16
//! cosine cases (all but the far ones, where the corners' cosines are nearly equal).

mod common;

use common::*;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;

/// Seed of the first render.
const SEED: u32 = 6100;

const COSINE: LightSampling = LightSampling::SolidAngleCosine;
const ADAPTIVE: LightSampling = LightSampling::Adaptive;

fn settings(strategy: Strategy, light_sampling: LightSampling) -> Settings {
    Settings {
        strategy,
        light_sampling,
        ..Settings::default()
    }
}

/// The strategies that sample lights (BSDF-only sampling never asks the light sampler).
const STRATEGIES_WITH_LIGHTS: [Strategy; 4] = [
    Strategy::Light,
    Strategy::Mixture { light_weight: 0.5 },
    Strategy::Mis {
        heuristic: Heuristic::Power,
    },
    Strategy::Mis {
        heuristic: Heuristic::Balance,
    },
];

/// Renders `name` with light-sampling `method` for each strategy and returns the failures.
fn check(
    name: &str,
    method: LightSampling,
    strategies: &[Strategy],
    spp: u32,
    seed: u32,
) -> Vec<String> {
    let scene = scene(name);
    let reference_img = reference(&format!("{name}.exr"));
    let reference_var = reference(&format!("{name}.var.exr"));
    let mut failures = Vec::new();
    for (i, &strategy) in strategies.iter().enumerate() {
        let r = render(&scene, settings(strategy, method), spp, seed + i as u32);
        assert_eq!(
            r.film().nonfinite,
            0,
            "{name} {strategy:?}: non-finite samples"
        );
        let t = test_against(&r, &reference_img, Some(&reference_var), 32);
        if let Err(msg) = check_unbiased(&format!("{name} {method:?} {strategy:?}"), &t) {
            failures.push(msg);
        }
    }
    failures
}

/// `seed_cornell` (a hexagon light, sampled by spherical triangles; two disks, unchanged by the
/// warp) agrees with its reference for every strategy that samples lights, at 128 spp.
#[test]
fn seed_cornell_matches_reference_with_cosine_warp() {
    let failures = check("seed_cornell", COSINE, &STRATEGIES_WITH_LIGHTS, 128, SEED);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `analytic_polygon` (one polygon light over a diffuse plane) agrees with its reference for
/// light-only and MIS sampling, at 32 spp.
#[test]
fn analytic_polygon_matches_reference_with_cosine_warp() {
    let strategies = [STRATEGIES_WITH_LIGHTS[0], STRATEGIES_WITH_LIGHTS[2]];
    let failures = check("analytic_polygon", COSINE, &strategies, 32, SEED + 10);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `textured_mesh` (a rectangular quad light, sampled by the spherical rectangle) agrees with
/// its Mitsuba reference for MIS, at 128 spp (light-only sampling is heavy-tailed on this scene:
/// `tests/mesh_reference.rs` says why).
#[test]
fn textured_mesh_matches_reference_with_cosine_warp() {
    let failures = check(
        "textured_mesh",
        COSINE,
        &[STRATEGIES_WITH_LIGHTS[2]],
        128,
        SEED + 20,
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `seed_cornell` with adaptive light sampling: the hexagon is sampled by area from most of the
/// room and by estimate-picked spherical triangles near it; light-only and MIS agree with the
/// reference at 128 spp (the mixture samples lights by the same code as light-only; the quad's
/// and the triangle's adaptive densities are in the χ² suites).
#[test]
fn seed_cornell_matches_reference_adaptive() {
    let strategies = [STRATEGIES_WITH_LIGHTS[0], STRATEGIES_WITH_LIGHTS[2]];
    let failures = check("seed_cornell", ADAPTIVE, &strategies, 128, SEED + 30);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `analytic_polygon` with adaptive light sampling, light-only and MIS, at 32 spp.
#[test]
fn analytic_polygon_matches_reference_adaptive() {
    let strategies = [STRATEGIES_WITH_LIGHTS[0], STRATEGIES_WITH_LIGHTS[2]];
    let failures = check("analytic_polygon", ADAPTIVE, &strategies, 32, SEED + 40);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The settings reach the engine: the images with the warp and with adaptive sampling differ
/// from the one with plain solid-angle sampling, at the same seed.
#[test]
fn the_methods_change_the_image() {
    let scene = scene("seed_cornell");
    let mis = STRATEGIES_WITH_LIGHTS[2];
    let a = render(&scene, settings(mis, LightSampling::SolidAngle), 2, 1);
    for method in [COSINE, ADAPTIVE] {
        let b = render(&scene, settings(mis, method), 2, 1);
        assert_ne!(a.film().mean(), b.film().mean(), "{method:?}");
    }
}
