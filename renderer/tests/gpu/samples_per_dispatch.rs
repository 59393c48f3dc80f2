//! Dispatches of several samples per pixel (`GpuProgressive::set_samples_per_dispatch`, what small
//! images get on a real GPU) give the same film, bit for bit, as one sample per dispatch: each
//! layer's radiance waits in a scratch plane and `fold` adds the layers in sample order with the
//! same updates. Passes of 5 and 6 samples exercise a last dispatch of fewer layers. On lavapipe
//! (a CPU adapter, where the default is one sample per dispatch) this is the only coverage of the
//! multi-sample path. Both samplers; and the split into passes does not matter either. With
//! `mis-optimal` the layers' moments wait in scratch planes too, and dispatches are split where
//! a stage starts: the same film for every layering and pass split.

use crate::gpu_common;
use gpu_common::*;
use lumis::engine::Film;
use lumis::gpu::GpuProgressive;
use lumis::integrator::{Settings, Strategy};
use lumis::sampler::SamplerKind;
use lumis::scene::Scene;
use std::sync::Arc;

/// The seed Cornell box at 40×30 (a Cornell box with a hexagonal light, all material kinds).
fn small_cornell() -> Arc<Scene> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/seed_cornell.json");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
    json["camera"]["width"] = 40.into();
    json["camera"]["height"] = 30.into();
    build(&json.to_string())
}

/// A 40×30 `seed_cornell` render with `sampler`, seed 7, `samples_per_dispatch` samples per
/// dispatch, in passes of `passes` samples.
fn render(
    scene: &Arc<Scene>,
    sampler: SamplerKind,
    samples_per_dispatch: u32,
    passes: &[u32],
) -> Option<Film> {
    let settings = Settings {
        sampler,
        ..Settings::default()
    };
    render_with(scene, settings, samples_per_dispatch, passes)
}

/// [`render`] with any settings.
fn render_with(
    scene: &Arc<Scene>,
    settings: Settings,
    samples_per_dispatch: u32,
    passes: &[u32],
) -> Option<Film> {
    let ctx = context()?;
    let mut r = GpuProgressive::with_context(ctx, scene.clone(), settings, 7)
        .unwrap_or_else(|e| panic!("{e}"));
    r.set_samples_per_dispatch(samples_per_dispatch);
    assert_eq!(r.samples_per_dispatch(), samples_per_dispatch);
    for &n in passes {
        r.render_pass(n);
    }
    Some(r.film().unwrap_or_else(|e| panic!("{e}")))
}

/// The film's sums as bits.
fn bits(f: &Film) -> Vec<[[u64; 3]; 3]> {
    f.pixels
        .iter()
        .map(|p| [p.sum, p.sum_sq, p.sum_even].map(|v| v.map(f64::to_bits)))
        .collect()
}

/// With either sampler, 11 spp rendered 1, 2, 4 or 8 samples per dispatch in passes of 5 and 6,
/// in one pass of 11 (8 + 3 per dispatch) or in 11 passes of one are the same film bit for bit:
/// the image is a function of the seed and the spp only, however the progressive renderer splits
/// the samples (the Sobol sampler's sample `s` of a pixel is the same point in every split).
#[test]
fn films_do_not_depend_on_samples_per_dispatch() {
    let scene = small_cornell();
    for sampler in [SamplerKind::Independent, SamplerKind::Sobol] {
        let Some(one) = render(&scene, sampler, 1, &[5, 6]) else {
            return;
        };
        assert!(one.pixels.iter().any(|p| p.sum[0] > 0.0), "a black image");
        for (k, passes) in [
            (2, &[5, 6][..]),
            (4, &[5, 6]),
            (8, &[5, 6]),
            (8, &[11]),
            (1, &[1; 11]),
        ] {
            let other = render(&scene, sampler, k, passes).unwrap();
            assert_eq!(other.spp, one.spp);
            assert_eq!(other.nonfinite, one.nonfinite);
            for (i, (a, b)) in bits(&one).iter().zip(&bits(&other)).enumerate() {
                assert_eq!(
                    a, b,
                    "{sampler:?}, {k} samples per dispatch, passes {passes:?}, pixel {i}"
                );
            }
        }
    }
}

/// mis-optimal: 20 spp (α solved at samples 8 and 16) rendered 1, 2, 4 or 8 samples per dispatch
/// in passes of 5, 6 and 9, in one pass (dispatches split at 8 and 16), or 20 passes of one, are
/// the same film bit for bit: the moments are added in sample order by `fold` or by the sample
/// itself, and α is solved once per stage from the samples before it.
#[test]
fn mis_optimal_films_do_not_depend_on_samples_per_dispatch() {
    let scene = small_cornell();
    let settings = Settings {
        strategy: Strategy::MisOptimal,
        ..Settings::default()
    };
    let Some(one) = render_with(&scene, settings, 1, &[5, 6, 9]) else {
        return;
    };
    assert!(one.pixels.iter().any(|p| p.sum[0] > 0.0), "a black image");
    for (k, passes) in [
        (2, &[5, 6, 9][..]),
        (4, &[5, 6, 9]),
        (8, &[5, 6, 9]),
        (8, &[20]),
        (1, &[1; 20]),
    ] {
        let other = render_with(&scene, settings, k, passes).unwrap();
        assert_eq!(other.spp, one.spp);
        assert_eq!(other.nonfinite, one.nonfinite);
        for (i, (a, b)) in bits(&one).iter().zip(&bits(&other)).enumerate() {
            assert_eq!(
                a, b,
                "{k} samples per dispatch, passes {passes:?}, pixel {i}"
            );
        }
    }
}
