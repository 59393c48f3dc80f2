//! Rendering helpers of the GPU image tests: a GPU render in passes, the CPU render of the same
//! settings, and the block z-test of one film against another image with its variance (the
//! comparison of `renderer/tests/gpu/images.rs`).

use super::context;
use lumis::engine::{Film, Progressive};
use lumis::gpu::GpuProgressive;
use lumis::integrator::Settings;
use lumis::metrics::{BlockTest, ImageWithVariance, block_z_test};
use lumis::scene::Scene;
use std::sync::Arc;

/// A GPU render of `spp` samples in four passes (like the viewer would), as a film; `None` when
/// GPU tests are skipped.
pub fn gpu_render(scene: &Arc<Scene>, settings: Settings, spp: u32, seed: u32) -> Option<Film> {
    let ctx = context()?;
    let mut r = GpuProgressive::with_context(ctx, scene.clone(), settings, seed)
        .unwrap_or_else(|e| panic!("{e}"));
    let pass = spp.div_ceil(4);
    while r.spp() < spp {
        r.render_pass(pass.min(spp - r.spp()));
    }
    Some(r.film().unwrap_or_else(|e| panic!("{e}")))
}

/// A CPU render of `spp` samples in one pass.
pub fn cpu_render(scene: &Arc<Scene>, settings: Settings, spp: u32, seed: u32) -> Film {
    let mut r = Progressive::new(scene.clone(), settings, seed);
    assert!(r.render_pass(spp));
    r.film().clone()
}

/// The CPU render's seed for a GPU render at `seed` in a GPU-against-CPU test (the tests' old
/// pairs 4000/5000, 4100/5100, … keep their seeds).
pub const CPU_SEED_OFFSET: u32 = 1000;

/// The strategies a GPU-against-CPU z-test renders, as indices into
/// [`crate::common::STRATEGIES_AND_OPTIMAL`]: light sampling, BSDF sampling and MIS with the
/// power heuristic, the three estimators a material or light feeds. The mixture, the balance
/// heuristic and mis-optimal only weight those same samples differently; their GPU weights are
/// pinned to the CPU's by the same-seed renders of `gpu/images.rs` (every strategy on the shared
/// scenes). All six were z-tested here until 2026-12-07, when the suite's time (CI 80 minutes
/// of a 90-minute limit) made the other three the cheapest to drop: about 270 s of the GPU
/// binary's test time on lavapipe.
pub const GPU_VS_CPU_STRATEGIES: [usize; 3] = [0, 1, 3];

/// [`decide_gpu_vs_cpu`] for each strategy `i` of [`GPU_VS_CPU_STRATEGIES`] at GPU seed
/// `seed + i` (default settings otherwise), named `{label} {strategy:?} vs cpu`: the failures,
/// or `None` when GPU tests are skipped.
pub fn gpu_vs_cpu_estimators(
    label: &str,
    scene: &Arc<Scene>,
    spp: u32,
    seed: u32,
    block: u32,
) -> Option<Vec<String>> {
    let mut failures = Vec::new();
    for i in GPU_VS_CPU_STRATEGIES {
        let strategy = crate::common::STRATEGIES_AND_OPTIMAL[i];
        // The CI tier renders MIS (power) alone (`common/tier.rs`).
        if !crate::common::tier::runs(strategy) {
            continue;
        }
        let settings = Settings {
            strategy,
            ..Settings::default()
        };
        let what = format!("{label} {strategy:?} vs cpu");
        if let Err(e) = decide_gpu_vs_cpu(&what, scene, settings, spp, seed + i as u32, block)? {
            failures.push(e);
        }
    }
    Some(failures)
}

/// The GPU's render of `scene` with `s` against the CPU's, one decision of the suite's protocol
/// (`common/protocol.rs`): the GPU at `seed`, the CPU at `seed + CPU_SEED_OFFSET`, `spp` each,
/// `block`×`block` blocks; `None` when GPU tests are skipped.
pub fn decide_gpu_vs_cpu(
    what: &str,
    scene: &Arc<Scene>,
    s: Settings,
    spp: u32,
    seed: u32,
    block: u32,
) -> Option<Result<(), String>> {
    context()?;
    Some(crate::common::protocol::decide(
        what,
        seed,
        spp,
        |seed, n, alpha| {
            let gpu = gpu_render(scene, s, n, seed).expect("a GPU");
            assert_eq!(gpu.nonfinite, 0, "{what}: non-finite samples");
            let cpu = cpu_render(scene, s, n, seed.wrapping_add(CPU_SEED_OFFSET));
            gpu.z_test(&cpu, block, alpha)
        },
    ))
}

/// The block z-test (`block`×`block` pixels, family-wise `alpha`: the protocol's stages,
/// `common::protocol::decide`) of `film` against an image `other` with the per-pixel variance of
/// its mean `other_var` (a reference and its variance image, or a CPU film's mean and variance).
pub fn film_image_z_test_at(
    film: &Film,
    other: &[glam::Vec3],
    other_var: &[[f64; 3]],
    block: u32,
    alpha: f64,
) -> BlockTest {
    let mean = film.mean();
    let var = film.variance_of_mean();
    block_z_test(
        film.width,
        film.height,
        &ImageWithVariance {
            mean: &mean,
            var: &var,
        },
        &ImageWithVariance {
            mean: other,
            var: other_var,
        },
        block,
        alpha,
    )
}

/// Pixels of `g` that differ from `c` by more than 1e-3 (relative): paths that the two sides'
/// roundings sent down different branches.
pub fn diverged_pixels(g: &[glam::Vec3], c: &[glam::Vec3]) -> usize {
    g.iter()
        .zip(c)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * (1.0 + b.max_element()))
        .count()
}

/// Worst relMSE a same-seed GPU render may have against the CPU's (measured on lavapipe: at
/// most 3.3e-7, Veach's scene with MIS, 14 diverged pixels; else below 2e-11).
pub const SAME_SEED_MAX_RELMSE: f64 = 1e-5;

/// Same seed, same samples: renders `settings` at 2 spp with seed 11 on the GPU and the CPU
/// and compares them. `None` when GPU tests are skipped; else `Err` when the GPU has non-finite
/// samples, more than 0.1% of the pixels diverged ([`diverged_pixels`]) or the relMSE exceeds
/// [`SAME_SEED_MAX_RELMSE`], and `Ok(relMSE)` otherwise. `what` names the case in the messages.
pub fn same_seed_check(
    what: &str,
    scene: &Arc<Scene>,
    settings: Settings,
) -> Option<Result<f64, String>> {
    same_seed_check_spp(what, scene, settings, 2)
}

/// [`same_seed_check`] at `spp` samples per pixel (mis-optimal needs more than 8 for its α to
/// play a part).
pub fn same_seed_check_spp(
    what: &str,
    scene: &Arc<Scene>,
    settings: Settings,
    spp: u32,
) -> Option<Result<f64, String>> {
    let gpu = gpu_render(scene, settings, spp, 11)?;
    let cpu = cpu_render(scene, settings, spp, 11);
    let (g, c) = (gpu.mean(), cpu.mean());
    let e = lumis::metrics::relmse(&g, &c);
    let d = diverged_pixels(&g, &c);
    eprintln!("{what}: relMSE {e:.2e}, {d} of {} pixels diverged", g.len());
    Some(if gpu.nonfinite != 0 {
        Err(format!("{what}: {} non-finite samples", gpu.nonfinite))
    } else if d * 1000 > g.len() {
        Err(format!(
            "{what}: {d} of {} pixels differ from the CPU's",
            g.len()
        ))
    } else if e >= SAME_SEED_MAX_RELMSE {
        Err(format!("{what}: relMSE against the CPU {e:e}"))
    } else {
        Ok(e)
    })
}
