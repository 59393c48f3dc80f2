//! Helpers shared by the GPU tests: one device per test binary, scene building, and a tolerant
//! comparison that reports the worst mismatches.

#![allow(dead_code)]

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
pub struct Compare {
    name: String,
    rtol: f32,
    atol: f32,
    /// Values compared.
    pub n: usize,
    /// Values out of tolerance.
    pub bad: usize,
    examples: Vec<String>,
}

impl Compare {
    /// A comparison named `name` with relative and absolute tolerances.
    pub fn new(name: &str, rtol: f32, atol: f32) -> Compare {
        Compare {
            name: name.into(),
            rtol,
            atol,
            n: 0,
            bad: 0,
            examples: Vec::new(),
        }
    }

    fn record(&mut self, ok: bool, what: &str, got: f32, want: f32) {
        self.n += 1;
        if !ok {
            self.bad += 1;
            if self.examples.len() < 8 {
                self.examples.push(format!(
                    "{what}: gpu {got:e} cpu {want:e} (diff {:e})",
                    got - want
                ));
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
        let same =
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()) || got == want;
        let ok = same || (got - want).abs() <= self.atol + self.rtol * scale;
        self.record(ok, what, got, want);
    }

    /// Compares one value with `extra` added to the tolerance: the part of the difference that
    /// the inputs' conditioning explains (rounding amplified by the geometry), stated per test.
    pub fn scalar_conditioned(&mut self, got: f32, want: f32, extra: f32, what: &str) {
        let scale = got.abs().max(want.abs());
        let same =
            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()) || got == want;
        let ok = same || (got - want).abs() <= self.atol + self.rtol * scale + extra;
        self.record(ok, what, got, want);
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

    /// Panics if more than `allowed` values were out of tolerance; prints the tally either way.
    pub fn finish(self, allowed: usize) {
        eprintln!(
            "{}: {} of {} values out of tolerance (rtol {:e}, atol {:e})",
            self.name, self.bad, self.n, self.rtol, self.atol
        );
        assert!(
            self.bad <= allowed,
            "{}: {} of {} values out of tolerance:\n  {}",
            self.name,
            self.bad,
            self.n,
            self.examples.join("\n  ")
        );
    }
}
