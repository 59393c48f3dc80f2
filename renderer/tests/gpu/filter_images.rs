//! The GPU's gaussian, tent and signed (lanczos, mitchell, catmullrom) pixel filters in whole images (issue 18; `camera/filter.wgsl` function by function
//! in `renderer/tests/gpu/parity_filter.rs`): the imported `gaussian_edges.xml` (Mitsuba's default
//! gaussian, σ = 0.5 px, r = 2 px, sample_border false: sharp tilted edges, one leaving the film)
//! rendered on the GPU agrees with its Mitsuba 3.9.1 reference by the block z-test of the CPU's
//! `imported_gaussian_filter_renders_to_the_mitsuba_reference` (`renderer/tests/mitsuba_xml.rs`), and a
//! box filter fails it; and the GPU draws the CPU's film positions from the same random numbers.
//!
//! Runs on any wgpu adapter (lavapipe where there is no GPU); `LUMIS_SKIP_GPU_TESTS=1` skips.

use crate::common;
use crate::gpu_common;
use common::protocol::decide;
use common::{data_dir, reference, variance_image};
use gpu_common::images::{cpu_render, gpu_render};
use lumis::engine::Film;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::metrics::{BlockTest, ImageWithVariance, block_z_test};
use lumis::scene::{FilterDesc, Scene, SceneDesc, mitsuba};
use std::sync::Arc;

/// GPU samples per pixel of the reference test. Measured on lavapipe (2 shared cores): 7.2 s a
/// render, the file's two tests 11 s. The gaussian passed at worst |z| 2.98 and the box failed 17
/// of 36 blocks at worst |z| 8.55 (critical 3.63: a margin of 2.4×); at 256 spp the box failed
/// only 7 blocks at |z| 4.98, too close to the critical value to keep.
const SPP: u32 = 1024;

/// The imported `tests/data/mitsuba/NAME.xml` and the CPU test's settings (MIS with the power
/// heuristic, the file's Russian roulette depth), checking that it has `filter`.
fn imported_as(name: &str, filter: FilterDesc) -> (SceneDesc, Settings) {
    let m = mitsuba::load(&data_dir().join(format!("mitsuba/{name}.xml")), &[]).unwrap();
    assert_eq!(m.desc.camera.filter, filter);
    let settings = Settings {
        strategy: Strategy::Mis {
            heuristic: Heuristic::Power,
        },
        rr_depth: m.rr_depth.unwrap_or(5),
        ..Default::default()
    };
    (m.desc, settings)
}

/// `gaussian_edges.xml`: Mitsuba's default gaussian.
fn imported() -> (SceneDesc, Settings) {
    imported_as(
        "gaussian_edges",
        FilterDesc::Gaussian {
            stddev: 0.5,
            radius: 2.0,
        },
    )
}

fn build(desc: &SceneDesc) -> Arc<Scene> {
    Arc::new(Scene::from_desc(desc).unwrap_or_else(|e| panic!("{e}")))
}

/// The CPU test's z-test: 16×16 blocks × 3 channels, family-wise `alpha` (Šidák), the film's
/// per-pixel variance of the mean plus the reference's variance image.
fn against_reference(name: &str, film: &Film, alpha: f64) -> BlockTest {
    let img = reference(&format!("{name}.exr"));
    let var = variance_image(&reference(&format!("{name}.var.exr")));
    assert_eq!((film.width, film.height), (img.width, img.height));
    let (mean, film_var) = (film.mean(), film.variance_of_mean());
    block_z_test(
        film.width,
        film.height,
        &ImageWithVariance {
            mean: &mean,
            var: &film_var,
        },
        &ImageWithVariance {
            mean: &img.data,
            var: &var,
        },
        16,
        alpha,
    )
}

/// `gaussian_edges.xml` on the GPU against the Mitsuba reference (MIS, [`SPP`] spp, seed 1818,
/// the block z-test of [`against_reference`]: 12 blocks × 3 channels, critical |z| ≈ 3.2), and
/// the same scene with a box filter must fail it. Catches a filter that is not Mitsuba's on the
/// GPU (box, wrong σ or window, no truncation at the film border: the light's edge leaves the
/// film at the left). Deliberate bug tried: `filter_film_axis` sampling `[−r, r]` instead of the
/// film's interval (positions off the film at the edges): failed at 256 spp already (3 of 36
/// blocks, |z| 4.80).
#[test]
fn gpu_gaussian_filter_renders_to_the_mitsuba_reference() {
    if gpu_common::context().is_none() {
        return;
    }
    let (desc, settings) = imported();
    // One decision of the suite's protocol each (`common/protocol.rs`), the box filter's too.
    let decision = |what: &str, desc: &SceneDesc| {
        let scene = build(desc);
        decide(what, 1818, SPP, |seed, n, alpha| {
            let film = gpu_render(&scene, settings, n, seed).expect("a GPU");
            assert_eq!(film.nonfinite, 0, "{what}: non-finite samples");
            against_reference("gaussian_edges", &film, alpha)
        })
    };
    decision("gpu gaussian_edges.xml", &desc).unwrap_or_else(|msg| panic!("{msg}"));
    let mut boxed = desc.clone();
    boxed.camera.filter = FilterDesc::Box;
    assert!(
        decision("gpu box-filtered gaussian_edges", &boxed).is_err(),
        "a box filter must fail against the gaussian reference"
    );
}

/// Same seed, same samples: the render kernel takes the film position from the stream's first
/// two numbers through `film_position`, as the CPU's engine does, so a 2-spp GPU render of the
/// gaussian scene is the CPU's image up to rounding (positions agree within
/// `gpu/parity_filter.rs`'s tolerance; a path diverges only where that sends a ray across an
/// edge). The bound is `gpu/images.rs`'s: at most 1 pixel in 1000 diverged, relMSE < 1e-5.
/// Catches the kernel drawing the position from other numbers or passing other pixel or film
/// coordinates. Deliberate bugs tried: `film_position(…, gid.y, gid.x, …)` (axes swapped): 1664
/// of 3072 pixels diverged; `filter_film_axis` sampling `[−r, r]`: relMSE 4.8e-4 (2 pixels).
#[test]
fn gaussian_same_seed_gives_the_cpu_image() {
    let (desc, settings) = imported();
    let scene = build(&desc);
    let Some(gpu) = gpu_render(&scene, settings, 2, 11) else {
        return;
    };
    let cpu = cpu_render(&scene, settings, 2, 11);
    let (g, c) = (gpu.mean(), cpu.mean());
    let e = lumis::metrics::relmse(&g, &c);
    let diverged = g
        .iter()
        .zip(&c)
        .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-3 * (1.0 + b.max_element()))
        .count();
    eprintln!(
        "gaussian_edges: relMSE {e:.2e}, {diverged} of {} pixels diverged",
        g.len()
    );
    assert!(
        diverged * 1000 <= g.len(),
        "{diverged} of {} pixels differ from the CPU's",
        g.len()
    );
    assert!(e < 1e-5, "relMSE against the CPU {e:e}");
}

/// `tent_edges.xml` (gaussian_edges.xml's scene under Mitsuba's `tent`, radius 1.5 px) on the
/// GPU against its Mitsuba 3.9.1 reference, as [`gpu_gaussian_filter_renders_to_the_mitsuba_reference`]
/// (MIS, [`SPP`] spp, seed 2151), and the box filter must fail it.
#[test]
fn gpu_tent_filter_renders_to_the_mitsuba_reference() {
    if gpu_common::context().is_none() {
        return;
    }
    let (desc, settings) = imported_as("tent_edges", FilterDesc::Tent { radius: 1.5 });
    let decision = |what: &str, desc: &SceneDesc| {
        let scene = build(desc);
        decide(what, 2151, SPP, |seed, n, alpha| {
            let film = gpu_render(&scene, settings, n, seed).expect("a GPU");
            assert_eq!(film.nonfinite, 0, "{what}: non-finite samples");
            against_reference("tent_edges", &film, alpha)
        })
    };
    decision("gpu tent_edges.xml", &desc).unwrap_or_else(|msg| panic!("{msg}"));
    let mut boxed = desc.clone();
    boxed.camera.filter = FilterDesc::Box;
    assert!(
        decision("gpu box-filtered tent_edges", &boxed).is_err(),
        "a box filter must fail against the tent reference"
    );
}

/// `NAME_edges.xml` under a filter with negative lobes on the GPU against its Mitsuba 3.9.1
/// reference with `strategy` ([`SPP`] spp, `seed`, the z-test of [`against_reference`]), and, if
/// `control`, the box filter must fail it (the lanczos test's control stands for the three: the
/// same edges, the same z-test).
fn signed_filter_matches(
    name: &str,
    filter: FilterDesc,
    strategy: Strategy,
    seed: u32,
    control: bool,
) {
    if gpu_common::context().is_none() {
        return;
    }
    let (desc, mut settings) = imported_as(&format!("{name}_edges"), filter);
    settings.strategy = strategy;
    let decision = |what: &str, desc: &SceneDesc| {
        let scene = build(desc);
        decide(what, seed, SPP, |seed, n, alpha| {
            let film = gpu_render(&scene, settings, n, seed).expect("a GPU");
            assert_eq!(film.nonfinite, 0, "{what}: non-finite samples");
            against_reference(&format!("{name}_edges"), &film, alpha)
        })
    };
    decision(&format!("gpu {name}_edges.xml"), &desc).unwrap_or_else(|msg| panic!("{msg}"));
    if !control {
        return;
    }
    let mut boxed = desc.clone();
    boxed.camera.filter = FilterDesc::Box;
    assert!(
        decision(&format!("gpu box-filtered {name}_edges"), &boxed).is_err(),
        "a box filter must fail against the {name} reference"
    );
}

/// `lanczos_edges.xml` (2 lobes) on the GPU, MIS, seed 2440.
#[test]
fn gpu_lanczos_filter_renders_to_the_mitsuba_reference() {
    let mis = Strategy::Mis {
        heuristic: Heuristic::Power,
    };
    signed_filter_matches("lanczos", FilterDesc::Lanczos { lobes: 2 }, mis, 2440, true);
}

/// `mitchell_edges.xml` (B 0.4, C 0.3) on the GPU under optimal MIS, seed 2441.
#[test]
fn gpu_mitchell_filter_renders_to_the_mitsuba_reference() {
    let mitchell = FilterDesc::Mitchell { b: 0.4, c: 0.3 };
    signed_filter_matches("mitchell", mitchell, Strategy::MisOptimal, 2441, false);
}

/// `catmullrom_edges.xml` on the GPU under the one-sample mixture of light and BSDF sampling,
/// seed 2442.
#[test]
fn gpu_catmullrom_filter_renders_to_the_mitsuba_reference() {
    let mixture = Strategy::Mixture { light_weight: 0.5 };
    signed_filter_matches("catmullrom", FilterDesc::CatmullRom, mixture, 2442, false);
}
