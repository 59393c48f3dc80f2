//! Light selection by the light BVH (`LightSelection::Bvh`, issue 19 item 3) in whole renders:
//! unbiased against the stored references of the independent renderer on the scenes with
//! several lights (`veach_mis`: four spheres of equal power and radii 0.033 to 0.9 in a row;
//! `seed_cornell`: a hexagon and two disks), for light-only sampling (the selection pmf
//! divides every sample) and MIS (whose weights need the BSDF-sampled hits' pmf at the previous
//! vertex to be the one the light sample used). The selection's own distribution is checked by
//! the unit tests of `lights::light_bvh` and, composed with light sampling, by
//! `chi2_light_selection` in `renderer/tests/chi2_samplers.rs`.
//!
//! **Test:** `common::test_against` per block (whole image per channel for light-only sampling
//! on `veach_mis`, heavy-tailed there as `reference_scenes.rs` explains; 32×32 otherwise) and
//! channel, sd from the render's per-pixel variance and the reference's variance image,
//! Šidák-corrected family-wise α = 0.01 per render; 32 spp (MIS) and 64 spp (light only);
//! seeds [`SEED`] + the render's index.
//!
//! **Power, measured once** (the deliberate bug of a `LightBvh::pmf` that ignores the receiver
//! normal while `sample` uses it, CPU only): this file's renders still pass (the MIS weights of
//! BSDF-sampled hits shift little on these scenes); it is caught by the unit tests
//! `sample_pmf_is_pmf_bitwise`, `pmf_is_the_trees_distribution` and `choices_follow_the_pmf`,
//! by `chi2_light_selection` (3 of its 4 BVH cases, the no-normal one passes as it must) and by
//! `gpu_parity`'s `light_bvh_selection_matches` (10,066 of 24,350 pmfs differ).

mod common;

use common::protocol::decide_against;
use common::*;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSelection;

/// Seed of the first render.
const SEED: u32 = 6300;

fn settings(strategy: Strategy) -> Settings {
    Settings {
        strategy,
        light_selection: LightSelection::Bvh,
        ..Settings::default()
    }
}

const MIS: Strategy = Strategy::Mis {
    heuristic: Heuristic::Power,
};

/// Renders `name` with BVH selection for each `(strategy, spp, block)` and returns the failures.
fn check(name: &str, runs: &[(Strategy, u32, u32)], seed: u32) -> Vec<String> {
    let scene = scene(name);
    let reference_img = reference(&format!("{name}.exr"));
    let reference_var = reference(&format!("{name}.var.exr"));
    let mut failures = Vec::new();
    for (i, &(strategy, spp, block)) in runs.iter().enumerate() {
        let what = format!("{name} light BVH {strategy:?}");
        let var = Some(&reference_var);
        let decision = decide_against(
            &what,
            seed + i as u32,
            spp,
            &reference_img,
            var,
            block,
            |seed, n| render(&scene, settings(strategy), n, seed),
        );
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    failures
}

/// `veach_mis` with BVH selection agrees with its reference for MIS and light-only sampling.
#[test]
fn veach_mis_matches_reference_with_light_bvh() {
    let runs = [(MIS, 32, 32), (Strategy::Light, 64, u32::MAX)];
    let failures = check("veach_mis", &runs, SEED);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `seed_cornell` with BVH selection agrees with its reference for MIS and light-only sampling.
#[test]
fn seed_cornell_matches_reference_with_light_bvh() {
    let runs = [(MIS, 32, 32), (Strategy::Light, 64, 32)];
    let failures = check("seed_cornell", &runs, SEED + 10);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The setting reaches the engine: the image with the BVH differs from power selection's at the
/// same seed.
#[test]
fn the_light_bvh_changes_the_image() {
    let scene = scene("veach_mis");
    let power = Settings {
        light_selection: LightSelection::Power,
        ..settings(MIS)
    };
    let a = render(&scene, power, 2, 1);
    let b = render(&scene, settings(MIS), 2, 1);
    assert_ne!(a.film().mean(), b.film().mean());
}
