//! Helpers shared by the integration tests: loading the copied scenes and references, rendering
//! with a given strategy, and the block z-test against a reference.

#![allow(dead_code)]

pub mod emitters;
pub mod ground;
pub mod hidden;
pub mod protocol;
pub mod surface_detail;
pub mod tier;

use glam::Vec3;
use lumis::engine::Progressive;
use lumis::image_io::Image;
use lumis::integrator::{Heuristic, Settings, Strategy};
use lumis::lights::LightSampling;
use lumis::metrics::{BlockTest, ImageWithVariance, block_z_test};
use lumis::scene::{Scene, parse_scene};
use std::path::PathBuf;
use std::sync::Arc;

/// The strategies every scene-level test runs: each single strategy, the original program's
/// 0.5/0.5 mixture, and MIS with both heuristics.
pub const STRATEGIES: [Strategy; 5] = [
    Strategy::Light,
    Strategy::Bsdf,
    Strategy::Mixture { light_weight: 0.5 },
    Strategy::Mis {
        heuristic: Heuristic::Power,
    },
    Strategy::Mis {
        heuristic: Heuristic::Balance,
    },
];

/// [`STRATEGIES`] and `mis-optimal` (optimal MIS weights, `integrator::optimal`), whose
/// per-pixel α the engine learns from each pixel's earlier samples: it differs from the balance
/// heuristic from sample 8 on, so renders of it need more than 8 spp to test it.
pub const STRATEGIES_AND_OPTIMAL: [Strategy; 6] = [
    STRATEGIES[0],
    STRATEGIES[1],
    STRATEGIES[2],
    STRATEGIES[3],
    STRATEGIES[4],
    Strategy::MisOptimal,
];

/// The strategies that can see a delta light (point, spot, directional, projector): every one
/// of [`STRATEGIES_AND_OPTIMAL`] but BSDF-only, which never finds one.
pub const DELTA_STRATEGIES: [Strategy; 5] = [
    STRATEGIES[0],
    STRATEGIES[2],
    STRATEGIES[3],
    STRATEGIES[4],
    Strategy::MisOptimal,
];

/// Both light-sampling methods.
pub const METHODS: [LightSampling; 2] = [LightSampling::Area, LightSampling::SolidAngle];

/// A JSON array for a vector.
pub fn json_vec(v: Vec3) -> String {
    format!("[{}, {}, {}]", v.x, v.y, v.z)
}

/// Parses and builds a scene from JSON text, panicking with the message and the text.
pub fn build(json: &str) -> Arc<Scene> {
    let desc = parse_scene(json).unwrap_or_else(|e| panic!("{e}\n{json}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}\n{json}")))
}

/// `tests/data` of the workspace.
pub fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/data")
}

/// Loads `tests/data/scenes/NAME.json`.
pub fn scene(name: &str) -> Arc<Scene> {
    let path = data_dir().join("scenes").join(format!("{name}.json"));
    Arc::new(Scene::load(&path).unwrap_or_else(|e| panic!("{e}")))
}

/// Reads `tests/data/refs/FILE`.
pub fn reference(file: &str) -> Image {
    Image::read(&data_dir().join("refs").join(file)).unwrap_or_else(|e| panic!("{e}"))
}

/// A variance image (a reference's `NAME.var.exr`) as the z-test's per-pixel f64 variances.
pub fn variance_image(img: &Image) -> Vec<[f64; 3]> {
    img.data
        .iter()
        .map(|c| [c.x as f64, c.y as f64, c.z as f64])
        .collect()
}

/// Renders `spp` samples per pixel.
pub fn render(scene: &Arc<Scene>, settings: Settings, spp: u32, seed: u32) -> Progressive {
    let mut r = Progressive::new(scene.clone(), settings, seed);
    // Several passes, like the progressive viewer; the result does not depend on the split.
    let pass = spp.div_ceil(4);
    while r.film().spp < spp {
        assert!(r.render_pass(pass.min(spp - r.film().spp)));
    }
    r
}

/// The block z-test of a render against a reference image with its variance image (or none, for
/// closed-form images): `block`×`block` pixels, family-wise α = 0.01 (Šidák over blocks and
/// channels).
pub fn test_against(
    render: &Progressive,
    reference: &Image,
    reference_var: Option<&Image>,
    block: u32,
) -> BlockTest {
    test_against_at(
        render,
        reference,
        reference_var,
        block,
        protocol::ALPHA_FIRST,
    )
}

/// [`test_against`] at family-wise `alpha` (the protocol's stages, [`protocol::decide`]).
pub fn test_against_at(
    render: &Progressive,
    reference: &Image,
    reference_var: Option<&Image>,
    block: u32,
    alpha: f64,
) -> BlockTest {
    let film = render.film();
    let mean = film.mean();
    let var = film.variance_of_mean();
    let ref_var: Vec<[f64; 3]> = match reference_var {
        Some(v) => variance_image(v),
        None => vec![[0.0; 3]; reference.data.len()],
    };
    assert_eq!(
        (film.width, film.height),
        (reference.width, reference.height)
    );
    block_z_test(
        film.width,
        film.height,
        &ImageWithVariance {
            mean: &mean,
            var: &var,
        },
        &ImageWithVariance {
            mean: &reference.data,
            var: &ref_var,
        },
        block,
        alpha,
    )
}

/// The block z-test (`block`×`block` pixels, family-wise `alpha`) of one render against
/// another, each with its own per-pixel variance of the mean.
pub fn renders_z_test(a: &Progressive, b: &Progressive, block: u32, alpha: f64) -> BlockTest {
    a.film().z_test(b.film(), block, alpha)
}

/// A mean against a closed-form value: `z = (mean − expected) / sd` and whether it passes at
/// `critical`. A relative slack of 1e-5 of the expected value (plus 1e-7) absorbs f32 rounding; it
/// matters only where `sd` is 0, where z is then 0 within the slack and infinite beyond it.
pub fn closed_form_z(mean: f64, sd: f64, expected: f64, critical: f64) -> (f64, bool) {
    let diff = mean - expected;
    let slack = 1e-5 * expected.abs() + 1e-7;
    let ok = diff.abs() <= critical * sd + slack;
    let z = if sd > 0.0 {
        diff / sd
    } else if diff.abs() <= slack {
        0.0
    } else {
        f64::INFINITY
    };
    (z, ok)
}

/// Comparisons of means over pixels with closed-form values at one critical |z| (a file's
/// Šidák-corrected family): counts them, keeps the worst, and collects every failure so that a
/// failing run lists them all.
pub struct Tally {
    critical: f64,
    comparisons: usize,
    worst_z: f64,
    worst: String,
    failures: Vec<String>,
}

impl Tally {
    /// An empty tally whose comparisons pass within `critical` standard deviations.
    pub fn new(critical: f64) -> Tally {
        Tally {
            critical,
            comparisons: 0,
            worst_z: 0.0,
            worst: String::new(),
            failures: Vec::new(),
        }
    }

    /// The mean of `means` (pixel means, with `vars` their variances of the mean) against
    /// `expected`, by [`closed_form_z`].
    pub fn compare(&mut self, what: &str, means: &[f64], vars: &[f64], expected: f64) {
        assert!(!means.is_empty(), "{what}: no pixels");
        let n = means.len() as f64;
        let mean = means.iter().sum::<f64>() / n;
        let sd = (vars.iter().sum::<f64>() / (n * n)).sqrt();
        let (z, ok) = closed_form_z(mean, sd, expected, self.critical);
        self.comparisons += 1;
        let line = format!("{what}: mean {mean:.6} vs {expected:.6} (sd {sd:.2e}, z = {z:.2})");
        if z.abs() > self.worst_z || self.worst.is_empty() {
            self.worst_z = z.abs();
            self.worst = line.clone();
        }
        if !ok {
            self.failures.push(line);
        }
    }

    /// Prints the worst comparison and panics with every failure, or if the number of
    /// comparisons is not `expected_comparisons` (the size of the family the critical value was
    /// corrected for).
    pub fn finish(self, test: &str, expected_comparisons: usize) {
        eprintln!(
            "{test}: {} comparisons, critical |z| {:.2}, worst: {}",
            self.comparisons, self.critical, self.worst
        );
        assert!(
            self.failures.is_empty(),
            "{test}: {} of {} comparisons fail (|z| > {:.2}):\n{}",
            self.failures.len(),
            self.comparisons,
            self.critical,
            self.failures.join("\n")
        );
        assert_eq!(self.comparisons, expected_comparisons);
    }
}

/// One material per shared scene whose albedo × 1.03 the in-suite power checks
/// (`local_bias_is_detected`, CPU and GPU) inject: a wall, or the floor under the light.
pub const LOCAL_BIAS_MATERIALS: [(&str, &str); 4] = [
    ("analytic_polygon", "floor"),
    ("analytic_disk", "floor"),
    ("seed_cornell", "red"),
    ("veach_mis", "diffuse"),
];

/// `tests/data/scenes/NAME.json` with the albedo of `material` scaled by `factor`, through the
/// scene description as a real error would enter it.
pub fn scene_with_scaled_albedo(name: &str, material: &str, factor: f64) -> Arc<Scene> {
    let path = data_dir().join("scenes").join(format!("{name}.json"));
    let mut desc = lumis::scene::load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    lumis::mutants::scale_albedo(&mut desc, material, factor).unwrap_or_else(|e| panic!("{e}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}")))
}

/// `Err` with the worst blocks if the test found a bias; prints the worst block either way, and
/// one `z-test|WHAT|ok or BIASED|failed blocks|blocks|worst |z||critical` line that
/// `tools/power_table.py` reads (docs/testing.md).
pub fn check_unbiased(what: &str, test: &BlockTest) -> Result<(), String> {
    let failures = test.failures();
    let worst = test.worst().map_or(f64::NAN, |w| w.z.abs());
    eprintln!(
        "z-test|{what}|{}|{}|{}|{worst:.3}|{:.3}",
        if failures.is_empty() { "ok" } else { "BIASED" },
        failures.len(),
        test.blocks.len(),
        test.critical
    );
    if !failures.is_empty() {
        let mut msg = format!(
            "{what}: {} of {} blocks differ (|z| > {:.2}):\n",
            failures.len(),
            test.blocks.len(),
            test.critical
        );
        for b in failures.iter().take(8) {
            msg += &format!(
                "  block ({},{}) ch {}: mean {:.5} vs reference {:.5} (z = {:.2})\n",
                b.x, b.y, b.channel, b.mean, b.reference, b.z
            );
        }
        eprintln!("{msg}");
        return Err(msg);
    }
    let w = test.worst().expect("at least one block");
    eprintln!(
        "{what}: ok, {} blocks, worst |z| = {:.2} (critical {:.2})",
        test.blocks.len(),
        w.z.abs(),
        test.critical
    );
    Ok(())
}

/// Panics with the worst blocks if the test found a bias.
pub fn assert_unbiased(what: &str, test: &BlockTest) {
    if let Err(msg) = check_unbiased(what, test) {
        panic!("{msg}");
    }
}
