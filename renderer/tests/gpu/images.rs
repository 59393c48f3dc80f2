//! The GPU renders the same images as the CPU, in two ways:
//!
//! - **Same seed, same samples** (`same_seed_gives_the_cpu_image`): the GPU draws the CPU's
//!   random streams and runs the same estimator, so a 2 spp render with the same seed is the
//!   CPU's image up to floating-point differences. Every shared scene, every strategy, every
//!   light-sampling method and both light selections. This pins every GPU estimator to its CPU
//!   twin far more tightly than a z-test at lavapipe's sample counts could (a GPU-only pdf × 1.03
//!   changes every pixel it touches by ~3%, thirty times the divergence threshold), and the
//!   CPU's own tests (`reference_scenes.rs`, `light_sampling_methods.rs`, `light_bvh_images.rs`)
//!   show that every CPU estimator converges to the reference.
//! - **Against the reference** (`gpu_*_matches_reference`): the MIS (power) render of every
//!   shared scene and of the glass room (issue 15), at sample indices the same-seed test does not
//!   reach, by the CPU tests' block z-test (32×32 blocks unless `block_size` says otherwise,
//!   Šidák-corrected family-wise α = 0.01, per-pixel sample variances plus the reference's
//!   variance image). The `*_is_detected` tests show, at the same spp and seed, which local
//!   biases these renders catch.
//!
//! Sample counts are smaller than the CPU tests' where lavapipe (Mesa's software Vulkan, the
//! device CI has) would make them slow; the z-test accounts for the larger variance, so the
//! thresholds are the same, only the power is lower: `docs/testing.md` has the measured table.
//! Until 2026-12-03 every strategy was also z-tested here on the GPU (and light-only and MIS
//! against a CPU render); the same-seed table replaced those renders, which took 270 of this
//! file's 370 s on 2 cores and caught nothing the CPU tests and the same-seed test do not.

use crate::common;
use crate::gpu_common;
use common::protocol::decide;
use common::{
    LOCAL_BIAS_MATERIALS, STRATEGIES, data_dir, reference, scene_with_scaled_albedo, variance_image,
};
use gpu_common::images::{
    SAME_SEED_MAX_RELMSE, film_image_z_test_at, gpu_render, same_seed_check, same_seed_check_spp,
};
use lumis::integrator::{Settings, Strategy};
use lumis::lights::{LightSampling, LightSelection};
use lumis::scene::Scene;
use std::sync::Arc;

fn scene(name: &str) -> Arc<Scene> {
    let path = data_dir().join("scenes").join(format!("{name}.json"));
    Arc::new(Scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

fn settings(strategy: Strategy, light_sampling: LightSampling) -> Settings {
    Settings {
        strategy,
        light_sampling,
        ..Settings::default()
    }
}

/// GPU samples per pixel of the MIS renders, per scene.
fn spp(scene: &str) -> u32 {
    match scene {
        "analytic_polygon" | "analytic_disk" | "glass_room" => 32,
        _ => 16,
    }
}

/// The MIS (power) strategy.
const MIS: Strategy = STRATEGIES[3];
/// The seed of every MIS render here (the power tests reuse it, so they measure the power of
/// the renders `check_mis` tests).
const MIS_SEED: u32 = 2003;

/// Block size of the z-test per scene. See `gpu_glass_room_matches_reference`.
fn block_size(scene: &str) -> u32 {
    match scene {
        "glass_room" => 64,
        _ => 32,
    }
}

/// The GPU's render of `scene` with `s` against the reference of the shared scene `name`, one
/// decision of the suite's two-stage protocol (`common/protocol.rs`) at [`MIS_SEED`] and this
/// file's spp; `None` when GPU tests are skipped.
fn decide_against_reference(
    what: &str,
    scene: &Arc<Scene>,
    s: Settings,
    name: &str,
) -> Option<Result<(), String>> {
    gpu_common::context()?;
    let reference_img = reference(&format!("{name}.exr"));
    let reference_var = variance_image(&reference(&format!("{name}.var.exr")));
    Some(decide(what, MIS_SEED, spp(name), |seed, n, alpha| {
        let film = gpu_render(scene, s, n, seed).expect("a GPU");
        assert_eq!(film.nonfinite, 0, "{what}: non-finite samples");
        let block = block_size(name);
        film_image_z_test_at(&film, &reference_img.data, &reference_var, block, alpha)
    }))
}

/// The GPU's MIS (power) render of `name` with `light_sampling` and `selection` against the
/// reference; the failure, if any.
fn check_mis(name: &str, light_sampling: LightSampling, selection: LightSelection) -> Vec<String> {
    let s = Settings {
        light_selection: selection,
        ..settings(MIS, light_sampling)
    };
    let what = format!("gpu {name} {MIS:?} {light_sampling:?} {selection:?} vs reference");
    decide_against_reference(&what, &scene(name), s, name)
        .and_then(Result::err)
        .into_iter()
        .collect()
}

/// Panics with every failure, if any (all sub-tests run first, so one report shows them all and
/// a bias measured by `tools/power_table.py` reaches every row).
fn assert_none(failures: Vec<String>) {
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// MIS with the polygon lights sampled by solid angle and by area.
#[test]
fn gpu_analytic_polygon_matches_reference() {
    let polygon = |ls| check_mis("analytic_polygon", ls, LightSelection::Power);
    let mut failures = polygon(LightSampling::SolidAngle);
    failures.extend(polygon(LightSampling::Area));
    assert_none(failures);
}

#[test]
fn gpu_analytic_disk_matches_reference() {
    assert_none(check_mis(
        "analytic_disk",
        LightSampling::SolidAngle,
        LightSelection::Power,
    ));
}

#[test]
fn gpu_seed_cornell_matches_reference() {
    assert_none(check_mis(
        "seed_cornell",
        LightSampling::SolidAngle,
        LightSelection::Power,
    ));
}

/// MIS with light selection by power and by the light BVH (issue 19 item 3).
#[test]
fn gpu_veach_mis_matches_reference() {
    let veach = |selection| check_mis("veach_mis", LightSampling::SolidAngle, selection);
    let mut failures = veach(LightSelection::Power);
    failures.extend(veach(LightSelection::Bvh));
    assert_none(failures);
}

/// Glass (issue 15) against Mitsuba 3's `dielectric` and `roughdielectric`: a smooth sphere and
/// a rough slab in a room. 64×64 blocks: the caustic paths through the smooth sphere are sampled
/// by the BSDF alone in every strategy (shadow rays are blocked by glass), rare and bright, and at
/// 32 spp a 32×32 block holds too few of them for the normal approximation. Measured on lavapipe,
/// 6 to 8 seeds per strategy: 32×32 blocks reached |z| 6.1, always negative (the mean and the
/// variance estimate missing the same rare samples; 128 spp passed), 64×64 blocks at most 3.0
/// (critical 3.56). What this still detects: `glass_error_is_detected`.
#[test]
fn gpu_glass_room_matches_reference() {
    assert_none(check_mis(
        "glass_room",
        LightSampling::SolidAngle,
        LightSelection::Power,
    ));
}

/// The glass room test sees an error in the glass: the rough slab at α 0.25 instead of 0.2 fails
/// the GPU's MIS render at that test's spp and seed (measured: 3 of 27 blocks, |z| 5.4; light
/// sampling alone also catches it, BSDF sampling at 32 spp does not). Measured power otherwise:
/// the floor, ceiling and back wall's albedo × 1.03 fail light and MIS (|z| 10), the red wall's
/// (|z| 5.9) too; the sphere's IOR 1.45 instead of 1.5 and the slab's 1.4 pass every strategy.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn glass_error_is_detected() {
    let text = std::fs::read_to_string(data_dir().join("scenes/glass_room.json")).unwrap();
    let mut desc: serde_json::Value = serde_json::from_str(&text).unwrap();
    desc["materials"]["rough_glass"]["alpha"] = serde_json::json!(0.25);
    let biased = common::build(&desc.to_string());
    // Same seed as `check_mis`'s render.
    let s = settings(MIS, LightSampling::SolidAngle);
    let what = "gpu glass_room MIS, rough glass alpha 0.25";
    let Some(decision) = decide_against_reference(what, &biased, s, "glass_room") else {
        return;
    };
    assert!(
        decision.is_err(),
        "the rough glass at alpha 0.25 instead of 0.2 went undetected on the GPU"
    );
}

/// The environment map (issue 16) against Mitsuba 3's `envmap`: `envmap_objects` (a diffuse and a
/// rough gold sphere and a box on a ground, lit only by a rotated, scaled sky map with a soft sun)
/// with MIS, the map importance-sampled and sampled uniformly (area). History: the uniform case
/// was dropped from this test after it failed at seed 2003 (block (0, 64) 12% low, z
/// −4.0/−4.3/−6.9 over the channels; seed 2001 had passed), a test weakened after a failure; it
/// is back under the suite's protocol (issue 36), where that failure goes to stage 2.
#[test]
fn gpu_envmap_objects_matches_reference() {
    let mut failures = check_mis(
        "envmap_objects",
        LightSampling::SolidAngle,
        LightSelection::Power,
    );
    failures.extend(check_mis(
        "envmap_objects",
        LightSampling::Area,
        LightSelection::Power,
    ));
    assert_none(failures);
}

/// The environment-map test sees an error in the map or in the light it casts: `envmap_objects`
/// with the sky turned by 1° more, scaled by 1.01, or the white sphere's albedo × 1.03, fails the
/// GPU's MIS render at that test's spp and seed (measured on lavapipe: 32, 38 and 6 of 108
/// blocks, worst |z| 99, 3160 and 6.5; critical 3.91; the sky seen directly is nearly noise-free,
/// hence the first two).
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn envmap_error_is_detected() {
    let text = std::fs::read_to_string(data_dir().join("scenes/envmap_objects.json")).unwrap();
    let folder = data_dir().join("scenes");
    let s = settings(MIS, LightSampling::SolidAngle);
    for (path, value) in [
        (["background", "rotate_y_deg"], 31.0),
        (["background", "scale"], 0.75 * 1.01),
        (["materials", "white"], 0.75 * 1.03),
    ] {
        let (key, value) = (path.join("."), value);
        let mut desc: serde_json::Value = serde_json::from_str(&text).unwrap();
        match path {
            ["materials", m] => {
                desc["materials"][m]["albedo"] = serde_json::json!([value, value, value])
            }
            [a, b] => desc[a][b] = serde_json::json!(value),
        }
        let parsed = lumis::scene::parse_scene_in(&desc.to_string(), &folder).unwrap();
        let biased = Arc::new(Scene::from_desc(&parsed).unwrap());
        // Same seed as `check_mis`'s render.
        let what = format!("gpu envmap_objects MIS, {key} {value}");
        let Some(decision) = decide_against_reference(&what, &biased, s, "envmap_objects") else {
            return;
        };
        assert!(
            decision.is_err(),
            "the envmap's {key} at {value} went undetected on the GPU"
        );
    }
}

/// The test has power against a local bias, inside the normal suite: one material's albedo × 1.03
/// (the same as `reference_scenes::local_bias_is_detected`) fails the GPU's MIS render of every
/// scene at this file's spp and seed. The full table is in `docs/testing.md`.
#[test]
#[cfg_attr(not(feature = "full-suite"), ignore = "full tier: a power check")]
fn local_bias_is_detected() {
    for (name, material) in LOCAL_BIAS_MATERIALS {
        let biased = scene_with_scaled_albedo(name, material, 1.03);
        // Same seed as `check_mis`'s render.
        let s = settings(MIS, LightSampling::SolidAngle);
        let what = format!("gpu {name} MIS, {material} albedo x 1.03");
        let Some(decision) = decide_against_reference(&what, &biased, s, name) else {
            return;
        };
        assert!(
            decision.is_err(),
            "{name}: the albedo of {material} x 1.03 went undetected on the GPU"
        );
    }
}

/// The shared scenes the same-seed tests render.
const SAME_SEED_SCENES: [&str; 6] = [
    "analytic_polygon",
    "analytic_disk",
    "seed_cornell",
    "veach_mis",
    "glass_room",
    "envmap_objects",
];

/// Same seed, same samples, on every shared scene with every strategy and light-sampling method
/// and both light selections (`same_seed_check`: at most 0.1% of the pixels diverged, relMSE
/// below [`SAME_SEED_MAX_RELMSE`]). The cases:
/// - every strategy of `STRATEGIES` with solid-angle and area sampling (BSDF-only once: it
///   samples no light) on every shared scene: polygons, disks, the seed Cornell box, Veach's
///   spheres, glass (transmission, both-sided next-event estimation, the η² in Russian
///   roulette) and the environment map (lookup, importance and uniform sampling, the MIS weights
///   of rays that miss);
/// - the cosine warp and adaptive sampling (issue 19 items 2 and 4), and projected-solid-angle
///   sampling (issue 20 item 2), with light-only, the 0.5 mixture and MIS on the scenes whose
///   planar lights they change (adaptive also on `analytic_disk`: disks by their spherical
///   ellipse or by area, issue 20), and projected solid angle with light-only and MIS in the
///   glass room (transmitting receivers fall back to solid angle);
/// - light selection by the light BVH (issue 19 item 3) with light-only, the mixture and MIS on
///   the scenes with more than one light.
#[test]
fn same_seed_gives_the_cpu_image() {
    let light_strategies = [STRATEGIES[0], STRATEGIES[2], MIS];
    let mut cases = Vec::new();
    for name in SAME_SEED_SCENES {
        for strategy in STRATEGIES {
            for ls in [LightSampling::SolidAngle, LightSampling::Area] {
                if !(strategy == Strategy::Bsdf && ls == LightSampling::Area) {
                    cases.push((name, strategy, ls, LightSelection::Power));
                }
            }
        }
    }
    for name in ["analytic_polygon", "seed_cornell"] {
        for ls in [
            LightSampling::SolidAngleCosine,
            LightSampling::Adaptive,
            LightSampling::ProjectedSolidAngle,
        ] {
            for strategy in light_strategies {
                cases.push((name, strategy, ls, LightSelection::Power));
            }
        }
    }
    // Adaptive sampling of disks (issue 20; the cosine warp leaves disks alone).
    for strategy in light_strategies {
        cases.push((
            "analytic_disk",
            strategy,
            LightSampling::Adaptive,
            LightSelection::Power,
        ));
    }
    // Projected solid angle through glass: transmitting receivers give the light sampler no
    // normal (`LightSampling::receiver_normal`), on both sides.
    for strategy in [STRATEGIES[0], MIS] {
        cases.push((
            "glass_room",
            strategy,
            LightSampling::ProjectedSolidAngle,
            LightSelection::Power,
        ));
    }
    for name in ["veach_mis", "seed_cornell"] {
        for strategy in light_strategies {
            cases.push((
                name,
                strategy,
                LightSampling::SolidAngle,
                LightSelection::Bvh,
            ));
        }
    }
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for (name, strategy, ls, selection) in cases {
        let s = Settings {
            light_selection: selection,
            ..settings(strategy, ls)
        };
        let what = format!("{name} {strategy:?} {ls:?} {selection:?}");
        match same_seed_check(&what, &scene(name), s) {
            None => return,
            Some(Ok(e)) => worst = worst.max(e),
            Some(Err(msg)) => failures.push(msg),
        }
    }
    eprintln!("worst relMSE against the CPU: {worst:.2e} (limit {SAME_SEED_MAX_RELMSE:e})");
    assert_none(failures);
}

/// mis-optimal, same seed at 12 spp: its α is solved from samples 0..8 (f32 sums on the GPU, f64
/// on the CPU) and used for 8..12, so this pins the whole control variate (the first vertex's
/// light and BSDF outcomes, their moments, the solve, the stage) to the CPU, on every shared scene
/// with solid-angle sampling and on the polygon and the environment map with area sampling too
/// (same limits as `same_seed_gives_the_cpu_image`; the α's rounding differences are far below
/// them).
#[test]
fn mis_optimal_same_seed_gives_the_cpu_image() {
    let mut cases = Vec::new();
    for name in SAME_SEED_SCENES {
        cases.push((name, LightSampling::SolidAngle));
    }
    cases.push(("analytic_polygon", LightSampling::Area));
    cases.push(("envmap_objects", LightSampling::Area));
    let mut worst = 0.0f64;
    let mut failures = Vec::new();
    for (name, ls) in cases {
        let s = settings(Strategy::MisOptimal, ls);
        let what = format!("{name} MisOptimal {ls:?} 12 spp");
        match same_seed_check_spp(&what, &scene(name), s, 12) {
            None => return,
            Some(Ok(e)) => worst = worst.max(e),
            Some(Err(msg)) => failures.push(msg),
        }
    }
    eprintln!("mis-optimal: worst relMSE against the CPU: {worst:.2e}");
    assert_none(failures);
}
