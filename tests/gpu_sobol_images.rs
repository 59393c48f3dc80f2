//! The GPU's Sobol sampler (`sampler.wgsl`, issue 19) in whole renders: the same image as the
//! CPU's Sobol sampler with the same seed (so the GPU path tracer draws every number from the
//! dimension the CPU integrator uses), and unbiased against the stored independent reference and
//! a CPU Sobol render with other seeds by the block z-test.
//!
//! The z-test estimates each block's error from the per-pixel sample variance, which for
//! scrambled nets overestimates the error of the mean (`tests/sobol_sampler.rs` says why), so it
//! is conservative for noise but keeps its power against a bias. Runs on any wgpu adapter
//! (lavapipe where there is no GPU); `LUMIS_SKIP_GPU_TESTS=1` skips.

mod common;
mod gpu_common;

use common::{STRATEGIES, check_unbiased, data_dir, reference};
use gpu_common::images::{cpu_render, film_image_z_test, gpu_render};
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::sampler::SamplerKind;
use lumis::scene::Scene;
use std::sync::Arc;

fn scene(name: &str) -> Arc<Scene> {
    let path = data_dir().join("scenes").join(format!("{name}.json"));
    Arc::new(Scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

fn sobol(strategy: Strategy, light_sampling: LightSampling) -> Settings {
    Settings {
        strategy,
        light_sampling,
        sampler: SamplerKind::Sobol,
        ..Settings::default()
    }
}

/// Pixels of `g` that differ from `c` by more than 1e-3 (relative): diverged paths.
fn diverged(g: &[glam::Vec3], c: &[glam::Vec3]) -> usize {
    g.iter()
        .zip(c)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * (1.0 + b.max_element()))
        .count()
}

/// Same seed, same points: with the Sobol sampler the GPU draws each number from the CPU's
/// dimension, so a 2 spp render with seed 11 is the CPU's image up to floating-point differences
/// (a path diverges only where the two sides' roundings take different branches), as
/// `gpu_images::same_seed_gives_the_cpu_image` checks for the independent sampler, and with its
/// thresholds: at most 0.1% of pixels diverged and relMSE < 1e-5. Scenes: the seed Cornell box
/// (every material but glass), Veach's MIS scene, the glass room (dielectric lobes); every
/// strategy, both light-sampling methods. Catches a dimension drawn from the wrong place in
/// `path.wgsl`, which the sampler's own parity test (`gpu_parity_sampler.rs`) cannot see.
/// Deliberate bug tried: the light sample drawn with `sampler_bsdf_2d(bounce)` in `path.wgsl`:
/// failed on the 9 renders that sample lights (seed_cornell light-only: 51 289 of 65 536
/// pixels diverged, relMSE 0.21; the least, glass room light-only, 30 307 of 36 864, relMSE
/// 6e-3), the three BSDF-only renders unchanged; `gpu_parity_sampler` passed, as it should.
#[test]
fn sobol_same_seed_gives_the_cpu_image() {
    let strategies = [
        Strategy::Light,
        Strategy::Bsdf,
        Strategy::Mixture { light_weight: 0.5 },
        Strategy::Mis {
            heuristic: Heuristic::Power,
        },
    ];
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for name in ["seed_cornell", "veach_mis", "glass_room"] {
        let scene = scene(name);
        for (i, &strategy) in strategies.iter().enumerate() {
            let ls = [LightSampling::SolidAngle, LightSampling::Area][i % 2];
            let s = sobol(strategy, ls);
            let Some(gpu) = gpu_render(&scene, s, 2, 11) else {
                return;
            };
            assert_eq!(gpu.nonfinite, 0, "{name} {strategy:?}: non-finite samples");
            let cpu = cpu_render(&scene, s, 2, 11);
            let (g, c) = (gpu.mean(), cpu.mean());
            let e = lumis::metrics::relmse(&g, &c);
            let d = diverged(&g, &c);
            eprintln!(
                "{name} {strategy:?} {ls:?} sobol: relMSE {e:.2e}, {d} of {} pixels diverged",
                g.len()
            );
            worst = worst.max(e);
            if d * 1000 > g.len() {
                failures.push(format!(
                    "{name} {strategy:?}: {d} of {} pixels differ from the CPU's",
                    g.len()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert!(worst < 1e-5, "relMSE against the CPU up to {worst:e}");
}

/// `seed_cornell` on the GPU with the Sobol sampler, every strategy of `gpu_images.rs` (16 spp,
/// BSDF-only 32, as there), agrees with the stored independent reference (and its variance
/// image), and the light-only and MIS (power) renders with a CPU Sobol render of half the
/// samples: 32×32 blocks, Šidák-corrected family-wise α = 0.01 per comparison. Seeds: GPU
/// 4100 + i, CPU 4200 + i for strategy i of `STRATEGIES` (different seeds, so the two renders'
/// errors are independent).
///
/// Light-only is compared with the CPU only, not with the reference: at 16 spp that z-test is not
/// calibrated on this scene whatever the sampler (rare caustic paths through the mirror box and
/// the conductors: a render that misses them is low and its variance estimate too). Measured on
/// lavapipe, GPU seeds 4100–4107 against the reference: the independent sampler failed 2 of 8
/// (z −4.9 and −4.5), Sobol 1 of 8 (seed 4100, block (0, 192), z −5.05; that block's |z| < 2 at
/// the other seven seeds). The two renders compared with each other share the tails, and the
/// same-seed test above already pins the light-only estimator to the CPU's.
#[test]
fn gpu_sobol_seed_cornell_is_unbiased() {
    let scene = scene("seed_cornell");
    let reference_img = reference("seed_cornell.exr");
    let reference_var: Vec<[f64; 3]> = reference("seed_cornell.var.exr")
        .data
        .iter()
        .map(|c| [c.x as f64, c.y as f64, c.z as f64])
        .collect();
    let mut failures = Vec::new();
    for (i, &strategy) in STRATEGIES.iter().enumerate() {
        let s = sobol(strategy, LightSampling::SolidAngle);
        let n = if strategy == Strategy::Bsdf { 32 } else { 16 };
        let Some(film) = gpu_render(&scene, s, n, 4100 + i as u32) else {
            return;
        };
        let what = format!("gpu sobol seed_cornell {strategy:?} ({n} spp)");
        assert_eq!(film.nonfinite, 0, "{what}: non-finite samples");
        if strategy != Strategy::Light {
            let t = film_image_z_test(&film, &reference_img.data, &reference_var, 32);
            if let Err(msg) = check_unbiased(&format!("{what} vs reference"), &t) {
                failures.push(msg);
            }
        }
        if matches!(
            strategy,
            Strategy::Light
                | Strategy::Mis {
                    heuristic: Heuristic::Power
                }
        ) {
            let cpu = cpu_render(&scene, s, n / 2, 4200 + i as u32);
            let t = film_image_z_test(&film, &cpu.mean(), &cpu.variance_of_mean(), 32);
            if let Err(msg) = check_unbiased(&format!("{what} vs cpu sobol"), &t) {
                failures.push(msg);
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
