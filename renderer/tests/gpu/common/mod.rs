//! Helpers shared by the GPU tests: one device per test binary, scene building, and a tolerant
//! comparison that reports the worst mismatches.

#![allow(dead_code)]

pub mod images;
pub mod parity;

use glam::Vec3;
use lumis::gpu::{GpuContext, GpuError};
use lumis::scene::{Scene, parse_scene};
use std::sync::{Arc, OnceLock};

/// The shared device, or `None` (the test then passes vacuously) when `LUMIS_SKIP_GPU_TESTS` is
/// set. Without an adapter and without that variable the tests fail: CI must exercise the GPU
/// path (on lavapipe where there is no GPU).
pub fn context() -> Option<Arc<GpuContext>> {
    if std::env::var_os("LUMIS_SKIP_GPU_TESTS").is_some() {
        eprintln!("LUMIS_SKIP_GPU_TESTS is set: skipping a GPU test");
        return None;
    }
    static CTX: OnceLock<Result<Arc<GpuContext>, String>> = OnceLock::new();
    match CTX.get_or_init(|| GpuContext::new().map_err(|e: GpuError| e.to_string())) {
        Ok(c) => Some(c.clone()),
        Err(e) => panic!("{e} (set LUMIS_SKIP_GPU_TESTS=1 to skip the GPU tests)"),
    }
}

/// Parses and builds a scene from JSON text.
pub fn build(json: &str) -> Arc<Scene> {
    let desc = parse_scene(json).unwrap_or_else(|e| panic!("{e}\n{json}"));
    Arc::new(Scene::from_desc(&desc).unwrap_or_else(|e| panic!("{e}\n{json}")))
}

/// Counts values outside `|got − want| ≤ atol + rtol·max(|got|, |want|)` and remembers the worst.
///
/// Where a test allows a few values out of that tolerance ([`Compare::finish`]'s `allowed`), it
/// also sets a looser cap those outliers must still meet ([`Compare::outliers_within`]), so that an
/// allowance for rounding cannot hide a rare branch that is simply wrong.
pub struct Compare {
    name: String,
    rtol: f32,
    atol: f32,
    /// (rtol, atol) that every value out of tolerance must still meet.
    cap: Option<(f32, f32)>,
    /// Values compared.
    pub n: usize,
    /// Values out of tolerance.
    pub bad: usize,
    /// Values out of tolerance and beyond the cap.
    pub beyond_cap: usize,
    examples: Vec<String>,
    cap_examples: Vec<String>,
    /// The outliers' largest |got − want| and |got − want| / max(|got|, |want|), as they read.
    worst_abs: Option<(f32, String)>,
    worst_rel: Option<(f32, String)>,
}

impl Compare {
    /// A comparison named `name` with relative and absolute tolerances.
    pub fn new(name: &str, rtol: f32, atol: f32) -> Compare {
        Compare {
            name: name.into(),
            rtol,
            atol,
            cap: None,
            n: 0,
            bad: 0,
            beyond_cap: 0,
            examples: Vec::new(),
            cap_examples: Vec::new(),
            worst_abs: None,
            worst_rel: None,
        }
    }

    /// Values out of tolerance (at most `allowed` of them, see [`Compare::finish`]) must still be
    /// within `atol + rtol·max(|got|, |want|)` (plus any conditioning term of the comparison);
    /// one beyond it fails the test however few there are.
    pub fn outliers_within(mut self, rtol: f32, atol: f32) -> Compare {
        self.cap = Some((rtol, atol));
        self
    }

    /// Records one comparison: `scale` is what the relative tolerances apply to, `extra` the
    /// comparison's conditioning term added to the tolerance, `cap_extra` the one added to the cap.
    fn record(&mut self, got: f32, want: f32, scale: f32, extra: f32, cap_extra: f32, what: &str) {
        self.n += 1;
        let same =
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()) || got == want;
        let diff = (got - want).abs();
        if same || diff <= self.atol + self.rtol * scale + extra {
            return;
        }
        self.bad += 1;
        let text = format!("{what}: gpu {got:e} cpu {want:e} (diff {:e})", got - want);
        if self.examples.len() < 8 {
            self.examples.push(text.clone());
        }
        // NaN differences count as the worst.
        let rel = diff / scale;
        let worse =
            |w: &Option<(f32, String)>, v: f32| w.as_ref().is_none_or(|w| v.is_nan() || v > w.0);
        if worse(&self.worst_abs, diff) {
            self.worst_abs = Some((diff, text.clone()));
        }
        if worse(&self.worst_rel, rel) {
            self.worst_rel = Some((rel, text.clone()));
        }
        if let Some((rtol, atol)) = self.cap
            && (diff.is_nan() || diff > atol + rtol * scale + cap_extra)
        {
            self.beyond_cap += 1;
            if self.cap_examples.len() < 8 {
                self.cap_examples.push(text);
            }
        }
    }

    /// Compares one value.
    pub fn scalar(&mut self, got: f32, want: f32, what: &str) {
        let scale = got.abs().max(want.abs());
        self.scalar_scaled(got, want, scale, what);
    }

    /// Compares one value, the relative tolerance applying to `scale`.
    pub fn scalar_scaled(&mut self, got: f32, want: f32, scale: f32, what: &str) {
        self.record(got, want, scale, 0.0, 0.0, what);
    }

    /// Compares one value with `extra` added to the tolerance: the part of the difference that
    /// the inputs' conditioning explains (rounding amplified by the geometry), stated per test.
    pub fn scalar_conditioned(&mut self, got: f32, want: f32, extra: f32, what: &str) {
        let scale = got.abs().max(want.abs());
        self.record(got, want, scale, extra, extra, what);
    }

    /// [`Compare::scalar_conditioned`] with a larger conditioning term for the outlier cap: where
    /// the inputs' error has a bound for most values and a wider one for rare ill-conditioned
    /// ones (stated per test), each carried through the same conditioning.
    pub fn scalar_conditioned_capped(
        &mut self,
        got: f32,
        want: f32,
        extra: f32,
        cap_extra: f32,
        what: &str,
    ) {
        let scale = got.abs().max(want.abs());
        self.record(got, want, scale, extra, cap_extra, what);
    }

    /// Compares the xyz of a GPU vec4 with a `Vec3`, each with `extra` added to the tolerance.
    pub fn v3_conditioned(&mut self, got: [f32; 4], want: Vec3, extra: f32, what: &str) {
        for (g, w) in got[..3].iter().zip(want.to_array()) {
            self.scalar_conditioned(*g, w, extra, what);
        }
    }

    /// Compares slices element by element.
    pub fn vec(&mut self, got: &[f32], want: &[f32], what: &str) {
        for (g, w) in got.iter().zip(want) {
            self.scalar(*g, *w, what);
        }
    }

    /// Compares the xyz of a GPU vec4 with a `Vec3`.
    pub fn v3(&mut self, got: [f32; 4], want: Vec3, what: &str) {
        self.vec(&got[..3], &want.to_array(), what);
    }

    /// Panics if more than `allowed` values were out of tolerance, or any beyond the outlier cap;
    /// prints the tally and the worst outliers either way (what the caps are chosen from).
    pub fn finish(self, allowed: usize) {
        eprintln!(
            "{}: {} of {} values out of tolerance (rtol {:e}, atol {:e}), {} allowed",
            self.name, self.bad, self.n, self.rtol, self.atol, allowed
        );
        for (kind, w) in [("absolute", &self.worst_abs), ("relative", &self.worst_rel)] {
            if let Some((v, text)) = w {
                eprintln!("  {}: largest {kind} difference {v:e}: {text}", self.name);
            }
        }
        assert!(
            allowed == 0 || self.cap.is_some(),
            "{}: an allowance needs an outlier cap (outliers_within)",
            self.name
        );
        assert!(
            self.bad <= allowed,
            "{}: {} of {} values out of tolerance:\n  {}",
            self.name,
            self.bad,
            self.n,
            self.examples.join("\n  ")
        );
        if let Some((rtol, atol)) = self.cap {
            assert!(
                self.beyond_cap == 0,
                "{}: {} values beyond the outlier cap (rtol {rtol:e}, atol {atol:e}):\n  {}",
                self.name,
                self.beyond_cap,
                self.cap_examples.join("\n  ")
            );
        }
    }
}
