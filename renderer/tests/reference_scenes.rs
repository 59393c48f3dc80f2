//! Every shared scene, and lumis' own glass and environment-map scenes, rendered with every strategy, agrees with the
//! independent reference renderer's converged image (and the analytic scenes with their
//! closed-form images).
//!
//! Test: per 32×32 block and channel, z = (our block mean − reference block mean) / sd, where sd
//! combines our per-pixel sample variances and the reference's variance image; Šidák-corrected
//! family-wise α per render, each render one decision of the suite's two-stage protocol
//! (`common/protocol.rs`: α = 0.01, and a failure is re-rendered at a derived seed with 2× the
//! samples at α = 0.005). Seeds are fixed, so results are deterministic. The sample
//! counts are chosen so that a 3% local bias is detected; `docs/testing.md` has the measured table
//! (which bias each scene × strategy catches) and `local_bias_is_detected` checks one per scene.

mod common;

use common::protocol::decide_against;
use common::*;

use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;

fn settings(strategy: Strategy, light_sampling: LightSampling) -> Settings {
    Settings {
        strategy,
        light_sampling,
        ..Settings::default()
    }
}

/// Every strategy; the mixture at two more weights besides the original program's 0.5; MIS with
/// optimal weights last (its seed 1007 leaves the others' seeds as they were).
fn strategies() -> impl Iterator<Item = Strategy> {
    STRATEGIES.into_iter().chain([
        Strategy::Mixture { light_weight: 0.25 },
        Strategy::Mixture { light_weight: 0.75 },
        Strategy::MisOptimal,
    ])
}

/// Samples per pixel per scene and strategy: enough for a block standard error well under 0.5%.
/// MIS with optimal weights at 64 spp on the full scenes (half of MIS's, to keep the suite's time;
/// its α is learnt from sample 8 on, so 8..64 use it) and 32 on the analytic ones.
fn spp(scene: &str, strategy: Strategy) -> u32 {
    match (scene, strategy) {
        ("analytic_polygon" | "analytic_disk", Strategy::MisOptimal) => 32,
        (_, Strategy::MisOptimal) => 64,
        ("analytic_polygon" | "analytic_disk", Strategy::Bsdf) => 256,
        ("analytic_polygon" | "analytic_disk", _) => 32,
        ("seed_cornell", Strategy::Bsdf) => 256,
        ("seed_cornell", _) => 128,
        ("veach_mis", Strategy::Bsdf | Strategy::Light) => 128,
        ("veach_mis", _) => 128,
        ("glass_room", _) => 128,
        ("envmap_objects", _) => 128,
        _ => 64,
    }
}

/// Block size of the z-test. On `veach_mis`, light-only and BSDF-only sampling are heavy-tailed by
/// design (BSDF sampling of the r = 1/30 light; light sampling of caustics through the sharp
/// plates): a single 512-spp render has a ~20% standard deviation in some 32×32 blocks, made of a
/// few huge samples that most renders miss, so a block's sample variance is no guide to its
/// error. No renderer can test those blocks to 2% at CI cost. These two are compared on the whole
/// image per channel, where such events are numerous; every other combination uses 32×32 blocks.
/// Their power is low, measured (`docs/testing.md`, `python3 tools/power_table.py --sweep`):
/// every emission × 1.1 fails both (|z| 4.3 light, 7.0 BSDF; critical 2.9), × 1.05 passes both
/// (1.8, 2.7), and no local 3% bias of the power table is caught except a conductor pdf error in
/// BSDF-only (3.8). MIS and the mixtures on this scene catch them.
///
/// On `glass_room` every strategy finds the light focused by the glass onto the walls only by
/// BSDF sampling from the diffuse walls (shadow rays stop at glass), a rare event of large weight.
/// A single render's sample variance then understates its error in 32×32 blocks: MIS (balance)
/// at seed 1004 failed one back-wall block at 128 and at 256 spp (z −3.97, −4.29: a 1% deficit
/// of the missed rare paths), while 16 independent 128-spp renders (seeds 2001–2016) with the
/// spread *between* them as sd agree with the reference in every 32×32 block (z sd 0.98, max
/// |z| 3.16 over 108 for their mean; 3.08 for any one of them; critical 3.91). 64×64 blocks hold
/// four times as many of those events, which makes a render's own variance a fair estimate.
///
/// On `envmap_objects`, light-only sampling with the map sampled uniformly (area) finds the sun
/// (5° radius, 10³ × the sky) from the rough gold sphere rarely and with large weight (f·L/pdf
/// grows towards the sphere's silhouette): heavy-tailed by design, like `veach_mis` above. Seed
/// 1007 at 128 spp fails one 32×32 block (z −4.9; a 3% deficit), and in eight more renders
/// (seeds 5000–5007) one fails a 64×64 block, while an 8192-spp render agrees with the reference
/// within 0.9% in every 32×32 block (its own noise). It is compared on the whole image per
/// channel; the same strategy with importance sampling, and every other one, in 32×32 blocks.
fn block_size(scene: &str, strategy: Strategy, light_sampling: LightSampling) -> u32 {
    match (scene, strategy, light_sampling) {
        ("veach_mis", Strategy::Light | Strategy::Bsdf, _) => u32::MAX,
        ("envmap_objects", Strategy::Light, LightSampling::Area) => u32::MAX,
        ("glass_room", _, _) => 64,
        _ => 32,
    }
}

/// Every strategy on `name`; the failures (all of them: one report shows every strategy, and a
/// measured bias in `docs/testing.md` reaches every row).
fn check_scene(name: &str, light_sampling: LightSampling) -> Vec<String> {
    let scene = scene(name);
    let reference = reference(&format!("{name}.exr"));
    let reference_var = reference_var_image(name);
    let mut failures = Vec::new();
    for (i, strategy) in strategies().enumerate() {
        // The CI tier: every estimator on seed_cornell, MIS (power) elsewhere (`common/tier.rs`).
        let in_tier = if name == "seed_cornell" {
            tier::runs_estimator(strategy)
        } else {
            tier::runs(strategy)
        };
        if !in_tier {
            continue;
        }
        let what = format!("{name} {strategy:?} {light_sampling:?}");
        let block = block_size(name, strategy, light_sampling);
        let s = settings(strategy, light_sampling);
        let decision = decide_against(
            &what,
            1000 + i as u32,
            spp(name, strategy),
            &reference,
            Some(&reference_var),
            block,
            |seed, n| render(&scene, s, n, seed),
        );
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    failures
}

/// Panics with every failure of `failures`, if any.
fn assert_none(failures: Vec<String>) {
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn reference_var_image(name: &str) -> lumis::image_io::Image {
    reference(&format!("{name}.var.exr"))
}

#[test]
fn analytic_polygon_matches_reference() {
    let mut failures = check_scene("analytic_polygon", LightSampling::SolidAngle);
    failures.extend(check_scene("analytic_polygon", LightSampling::Area));
    assert_none(failures);
}

#[test]
fn analytic_disk_matches_reference() {
    assert_none(check_scene("analytic_disk", LightSampling::SolidAngle));
}

#[test]
fn seed_cornell_matches_reference() {
    assert_none(check_scene("seed_cornell", LightSampling::SolidAngle));
}

#[test]
fn veach_mis_matches_reference() {
    assert_none(check_scene("veach_mis", LightSampling::SolidAngle));
}

/// lumis' own glass scene (a smooth glass sphere and a rough glass slab in a closed room, caustics
/// on the floor) against Mitsuba 3's `dielectric`/`roughdielectric` (`tests/data/refs/README.md`).
/// Power, measured once for MIS (power heuristic) at 128 spp: the white walls' albedo × 1.03 fails
/// all 27 blocks (|z| up to 19.9), and the sphere's and slab's ior 1.45 instead of 1.5 fails 3
/// (|z| 3.78; critical 3.56).
#[test]
fn glass_room_matches_reference() {
    assert_none(check_scene("glass_room", LightSampling::SolidAngle));
}

/// lumis' own environment-map scene (diffuse, rough gold and a box on a ground, lit only by a
/// rotated, scaled sky map with a soft sun) against Mitsuba 3's `envmap`
/// (`tests/data/refs/README.md`), with the map importance-sampled (solid angle) and sampled
/// uniformly (area), every strategy.
#[test]
fn envmap_objects_matches_reference() {
    let mut failures = check_scene("envmap_objects", LightSampling::SolidAngle);
    failures.extend(check_scene("envmap_objects", LightSampling::Area));
    assert_none(failures);
}

/// MIS with area sampling on a full scene (the strategy loop above uses solid angle there).
fn check_mis_with_area_sampling(name: &str, seed: u32) {
    let s = settings(
        Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        LightSampling::Area,
    );
    let (scene, reference) = (scene(name), reference(&format!("{name}.exr")));
    let reference_var = reference_var_image(name);
    let what = format!("{name} mis area");
    let var = Some(&reference_var);
    let decision = decide_against(&what, seed, 128, &reference, var, 32, |seed, n| {
        render(&scene, s, n, seed)
    });
    decision.unwrap_or_else(|msg| panic!("{msg}"));
}

#[test]
fn seed_cornell_with_area_sampling_matches_reference() {
    check_mis_with_area_sampling("seed_cornell", 77);
}

#[test]
#[cfg_attr(
    not(feature = "full-suite"),
    ignore = "full tier: area sampling is z-tested on seed_cornell"
)]
fn veach_mis_with_area_sampling_matches_reference() {
    check_mis_with_area_sampling("veach_mis", 78);
}

/// Light sampling of `name` by both methods against its closed-form image (Lambert's formula for
/// the polygon, the contour integral for the disk, computed by `../shared/tools/analytic_exact.py`).
fn check_closed_form(name: &str) {
    let scene = scene(name);
    let exact = reference(&format!("{name}.exact.exr"));
    let mut failures = Vec::new();
    for ls in [LightSampling::SolidAngle, LightSampling::Area] {
        let what = format!("{name} light {ls:?} vs closed form");
        let decision = decide_against(&what, 5, 64, &exact, None, 32, |seed, n| {
            render(&scene, settings(Strategy::Light, ls), n, seed)
        });
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    assert_none(failures);
}

#[test]
fn analytic_polygon_matches_closed_form() {
    check_closed_form("analytic_polygon");
}

#[test]
fn analytic_disk_matches_closed_form() {
    check_closed_form("analytic_disk");
}

/// The test has power against a local bias (a full-tier check, docs/testing.md "Tiers"): one material's albedo
/// × 1.03 (a wall, or the floor under the light), made through the scene itself so that it reaches
/// the estimator as a real error would, fails the MIS decision of every scene (both stages of the
/// protocol) at the spp and seed of the strategy loop above. The full table (every scene × strategy × backend × kind of bias) is in
/// `docs/testing.md` (`tools/power_table.py`).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn local_bias_is_detected() {
    for (name, material) in LOCAL_BIAS_MATERIALS {
        let biased = scene_with_scaled_albedo(name, material, 1.03);
        let mis = STRATEGIES[3];
        let (reference, reference_var) =
            (reference(&format!("{name}.exr")), reference_var_image(name));
        let what = format!("{name} MIS, {material} albedo x 1.03");
        // Same seed as the strategy loop's MIS render (index 3).
        let s = settings(mis, LightSampling::SolidAngle);
        let block = block_size(name, mis, LightSampling::SolidAngle);
        let var = Some(&reference_var);
        let decision = decide_against(
            &what,
            1003,
            spp(name, mis),
            &reference,
            var,
            block,
            |seed, n| render(&biased, s, n, seed),
        );
        assert!(
            decision.is_err(),
            "{name}: the albedo of {material} x 1.03 went undetected"
        );
    }
}

/// Same seed and sample count give the same image for any number of threads.
#[test]
fn image_is_independent_of_thread_count() {
    let scene = scene("seed_cornell");
    let s = Settings::default();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| render(&scene, s, 2, 9));
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap()
        .install(|| render(&scene, s, 2, 9));
    assert_eq!(one.film().mean(), two.film().mean());
}
