//! The ZSobol sampler (`lumis::sampler`, `Settings::sampler = Sobol`) in whole renders: unbiased
//! for every strategy against the independent reference renderer's image, and as deterministic
//! as the independent sampler (any thread count, any split into sample ranges).
//!
//! The block z-test (`common::test_against`: 32×32 blocks, Šidák-corrected family-wise α = 0.01
//! per render) estimates each block's error from the per-pixel sample variance. For scrambled
//! nets that variance overestimates the error of the mean (the samples of a pixel are negatively
//! correlated, and so are neighbouring pixels of one Morton tile), so the test is conservative
//! for noise: |z| comes out smaller than for independent samples. A bias still shows in full:
//! the mean moves while the estimated sd does not shrink.
//!
//! Power: the same scene-level bias as `reference_scenes::local_bias_is_detected` (the red
//! wall's albedo × 1.03) fails the MIS render here too (`sobol_local_bias_is_detected`); sampler
//! bugs that break independence between dimensions are `renderer/src/mutants.rs`'
//! `sampler:shared_bounces` and `sampler:light_camera` (run with `--features mutants` and
//! `LUMIS_MUTANT`; not yet run, see `docs/testing.md`, "Sobol sampler").

mod common;

use common::protocol::decide_against;
use common::*;
use lumis::engine::Progressive;
use lumis::integrator::{Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::sampler::SamplerKind;

/// Seed of the first strategy's render (see `seed_cornell_matches_reference_with_sobol`): the
/// first seeds this test ran with, restored under the suite's protocol (issue 36).
const SEED: u32 = 3000;

fn sobol(strategy: Strategy) -> Settings {
    Settings {
        strategy,
        light_sampling: LightSampling::SolidAngle,
        sampler: SamplerKind::Sobol,
        ..Settings::default()
    }
}

/// Every strategy of `reference_scenes.rs` (the mixture at 0.25, 0.5 and 0.75).
fn strategies() -> impl Iterator<Item = Strategy> {
    STRATEGIES.into_iter().chain([
        Strategy::Mixture { light_weight: 0.25 },
        Strategy::Mixture { light_weight: 0.75 },
    ])
}

/// `reference_scenes.rs`' sample counts on `seed_cornell` (powers of two, so whole nets in
/// 1-D and, at 256, in 2-D).
fn spp(strategy: Strategy) -> u32 {
    match strategy {
        Strategy::Bsdf => 256,
        _ => 128,
    }
}

/// `seed_cornell` rendered with the Sobol sampler agrees with the stored reference
/// (`tests/data/refs/seed_cornell.exr` and its variance image) for every strategy, seeds
/// 3000–3006, 32×32 blocks, each render one decision of the suite's two-stage protocol
/// (`common/protocol.rs`). History: at these seeds MIS (power) at 3003 failed one block of 192
/// comparisons at α = 0.01 (block (224, 128), green: 1.2% low, z −4.17, critical 4.04) and the
/// seeds were moved to 4000–4006; that was a seed chosen after a failure, which the protocol
/// forbids, so the first seeds are back and a failure goes to the protocol's second stage (a
/// seed derived from the decision's name, 2× the samples). Today's renderer passes all seven in
/// stage 1 (MIS at 3003: worst |z| 2.74 of critical 4.05, 2026-12-05; the draws have changed
/// since that failure). Its power against a scene-level bias
/// is `sobol_local_bias_is_detected`; no deliberate sampler bug has been run through it yet (the
/// mutants `sampler:light_camera` and `sampler:shared_bounces` are there for that).
#[test]
fn seed_cornell_matches_reference_with_sobol() {
    let scene = scene("seed_cornell");
    let reference_img = reference("seed_cornell.exr");
    let reference_var = reference("seed_cornell.var.exr");
    let mut failures = Vec::new();
    // The CI tier renders MIS (power) alone, which draws every dimension a light sample and a
    // BSDF sample use (`common/tier.rs`).
    for (i, strategy) in strategies().enumerate().filter(|(_, s)| tier::runs(*s)) {
        let what = format!("seed_cornell sobol {strategy:?}");
        let var = Some(&reference_var);
        let (seed, n) = (SEED + i as u32, spp(strategy));
        let decision = decide_against(&what, seed, n, &reference_img, var, 32, |seed, n| {
            render(&scene, sobol(strategy), n, seed)
        });
        if let Err(msg) = decision {
            failures.push(msg);
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The z-test keeps its power with the Sobol sampler although the variance estimate is
/// conservative: the red wall's albedo × 1.03 fails the MIS decision (both stages) at the spp
/// and seed of the loop above.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn sobol_local_bias_is_detected() {
    let biased = scene_with_scaled_albedo("seed_cornell", "red", 1.03);
    let mis = STRATEGIES[3];
    let (reference_img, reference_var) = (
        reference("seed_cornell.exr"),
        reference("seed_cornell.var.exr"),
    );
    let what = "seed_cornell sobol MIS, red albedo x 1.03";
    let var = Some(&reference_var);
    let decision = decide_against(
        what,
        SEED + 3,
        spp(mis),
        &reference_img,
        var,
        32,
        |seed, n| render(&biased, sobol(mis), n, seed),
    );
    assert!(
        decision.is_err(),
        "the red wall's albedo x 1.03 went undetected with the Sobol sampler"
    );
}

/// Same seed and sample count give the same image, bit for bit, on 1 and on 3 threads.
#[test]
fn sobol_image_is_independent_of_thread_count() {
    let scene = scene("seed_cornell");
    let s = sobol(STRATEGIES[3]);
    let on = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| render(&scene, s, 3, 9))
    };
    let (one, three) = (on(1), on(3));
    assert_eq!(one.film().mean(), three.film().mean());
    assert!(one.film().mean().iter().any(|c| c.x > 0.0));
}

/// Sample ranges are exact slices with the Sobol sampler too: samples 0..3 and 3..8 (the second
/// in passes of 2 and 3) add up to one render of 0..8 within f64 rounding (the bound of
/// `engine::tests::sample_offset_slices_add_up_to_the_whole_render`), and a render of 0..8 in
/// passes of 3 and 5 is bit for bit the render in one pass. A sampler that depended on the
/// pass (or on the first sample of a range) would fail both (not tried).
#[test]
fn sobol_sample_ranges_add_up_to_the_whole_render() {
    let scene = scene("seed_cornell");
    let s = sobol(STRATEGIES[3]);
    let mut whole = Progressive::new(scene.clone(), s, 4);
    assert!(whole.render_pass(8));
    let mut passes = Progressive::new(scene.clone(), s, 4);
    assert!(passes.render_pass(3) && passes.render_pass(5));
    assert_eq!(whole.film().mean(), passes.film().mean());
    let mut head = Progressive::with_first_sample(scene.clone(), s, 4, 0);
    assert!(head.render_pass(3));
    let mut tail = Progressive::with_first_sample(scene, s, 4, 3);
    assert!(tail.render_pass(2) && tail.render_pass(3));
    let (w, h, t) = (whole.film(), head.film(), tail.film());
    for ((w, h), t) in w.pixels.iter().zip(&h.pixels).zip(&t.pixels) {
        for c in 0..3 {
            for (whole, parts) in [
                (w.sum[c], h.sum[c] + t.sum[c]),
                (w.sum_sq[c], h.sum_sq[c] + t.sum_sq[c]),
                (w.sum_even[c], h.sum_even[c] + t.sum_even[c]),
            ] {
                assert!(
                    (whole - parts).abs() <= 8.0 * f64::EPSILON * whole,
                    "{whole} vs {parts}"
                );
            }
        }
    }
    assert!(w.pixels.iter().any(|p| p.sum[0] > 0.0));
}

/// The Sobol image differs from the independent one (the setting reaches the engine) while the
/// independent sampler's image is unchanged by the sampler's existence (`Settings::default()`
/// draws the same numbers as before; `sampler::zsobol_tests` checks the stream itself).
#[test]
fn sampler_setting_reaches_the_engine() {
    let scene = scene("seed_cornell");
    let a = render(&scene, Settings::default(), 2, 1);
    let b = render(
        &scene,
        Settings {
            sampler: SamplerKind::Sobol,
            ..Settings::default()
        },
        2,
        1,
    );
    assert_ne!(a.film().mean(), b.film().mean());
}

/// The GPU backend accepts the Sobol sampler (it refused it with `GpuError::Sampler` before
/// `sampler/mod.wgsl`): a render is created wherever there is an adapter, and without one the only
/// error is the missing adapter. Its images are `renderer/tests/gpu/sobol_images.rs`.
#[test]
fn gpu_backend_accepts_sobol() {
    use lumis::engine::{AnyProgressive, Backend};
    if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
        return;
    }
    match AnyProgressive::new(Backend::Gpu, scene("seed_cornell"), sobol(STRATEGIES[3]), 1) {
        Ok(r) => assert_eq!(r.spp(), 0),
        Err(e) => panic!("the GPU backend refused the Sobol sampler: {e}"),
    }
}
