//! Optimal MIS weights (Kondapaneni et al. 2019, "Optimal Multiple Importance Sampling"):
//! the pieces of [`super::Strategy::MisOptimal`] that do not trace rays — the per-pixel moments,
//! the solve for α, the stage schedule and the control-variate terms. The path tracer
//! (`path.rs`) calls them at the camera ray's first vertex; the engine keeps one [`PixelState`]
//! per pixel.
//!
//! # The estimator
//!
//! With techniques `i` (here light sampling L and BSDF sampling B, one sample each, `n_i = 1`)
//! the optimal weights turn the MIS estimator into a control-variate form,
//!
//! ```text
//! F = α_L + α_B + Σ_{X ∈ {X_L, X_B}} (f(X) − α_L p_L(X) − α_B p_B(X)) / (p_L(X) + p_B(X)),
//! ```
//!
//! that is: the balance heuristic's estimate plus `CV = α_L + α_B − Σ_X α·r(X)` with
//! `r_k = p_k / (p_L + p_B)`, the balance weights. `E[CV] = 0` for **any** α that does not depend
//! on `X_L`, `X_B`, provided every `p_k` is the exact, normalised density of what technique `k`
//! produces, so F is unbiased whatever α is; α only decides the variance. The α minimising it
//! solves `M α = b` (per colour channel, `M` shared), with `M_ik = ∫ p_i p_k / D`,
//! `b_i = ∫ f p_i / D`, `D = p_L + p_B`, which the samples estimate without bias: each sample adds
//! `r_i r_k` to `M_ik` and `(f / D)·r_i` to `b_i`, and `f / D` is the sample's balance-heuristic
//! contribution.
//!
//! # Outcomes where the densities are not both known: "pure" samples
//!
//! The domain is what a sample ends at: a point `y` on an emitter seen from the vertex (or a
//! direction to an environment light), and, for each technique, what else it may produce. Two
//! techniques only agree on the first kind, and there both densities are evaluated (light:
//! selection pmf × the light's solid-angle pdf; BSDF: its non-delta pdf). Everywhere else a
//! sample is *pure*: the other technique cannot produce that outcome (or both treat it as pure,
//! by the same rule), and the sample adds `−α_own` instead of `−α·r`. Pure outcomes:
//!
//! - light sampling fails (no light selected, a light behind its one-sided emitter, a black
//!   texel, a pdf that overflows), its direction is below the horizon or on different sides of
//!   the geometric and shading normals (`docs/shading-normals.md`: the BSDF side ends such paths
//!   by the same rule), or the shadow ray is blocked (BSDF sampling reaches only visible points);
//!   light sampling picks a delta light (point, spot, directional, projector: no BSDF sample
//!   finds one; such a sample adds its contribution `h` to `b_L`, as a delta lobe's does to
//!   `b_B`);
//! - BSDF sampling fails (`None`, below the horizon: the failure mass is part of B's outcome
//!   space, so `∫ p_B` over valid directions plus it is exactly 1), returns a **delta** lobe
//!   (a smooth coat, mirror or glass: an atom light sampling never produces), its direction
//!   breaks the shading-normal rule, or its ray ends anywhere but on an emitter facing it with
//!   non-zero radiance and non-zero light pdf.
//!
//! The rule deciding "emitter facing the vertex with non-zero radiance" is evaluated by both
//! sides on the same point (light sampling returns `None` for back faces and black texels;
//! BSDF sampling looks at the radiance it found), so each outcome is classified alike whichever
//! technique produced it — what unbiasedness needs: `Σ_i p_i v_{i,k} = p_k` at every outcome,
//! with `v_{i,k}` the coefficient of `α_k` in technique `i`'s term. A pure sample of `k` in the
//! moments adds 1 to `M_kk` (and its own contribution `h` to `b_k`, for a delta sample's emission):
//! the variance-optimal α of this mixed estimator solves `(A + Π) α = b`, `Π` the pure masses.
//!
//! Russian roulette: the control variate of the BSDF sample is resolved when its ray is traced,
//! before roulette may end the path (the path tracer traces that ray even when roulette or a zero
//! throughput would end the path there), so it is never scaled by 1/q. Environment lights are
//! emitters like the others (their pdf is the map's). Glass, mirrors: no next-event estimation, no
//! control variate at that vertex.
//!
//! # Which vertices
//!
//! α is per pixel and applies at the camera ray's first vertex only: there all samples of the
//! pixel integrate nearly the same direct-light integral, so one α per pixel is a good control
//! variate (the paper's setting, per pixel for direct illumination). Deeper vertices are spread
//! over the scene; one α per pixel and depth would be a poor fit and cost 9 more sums per depth.
//! They use the power heuristic, like `mis`. α is optimal for the first vertex's direct light
//! alone: its covariance with the indirect light the BSDF sample also carries is not modelled.
//!
//! # Progressive estimation and determinism
//!
//! Sample `s` of a pixel uses α solved from the moments of that pixel's samples `0..t`, with `t`
//! the largest power of two `≤ s` ([`stage_start`]) — samples `s < FIRST_STAGE` use α = 0 (the
//! balance heuristic). The engine adds each pixel's samples in order on one thread, so the image
//! is a function of (seed, spp) only, not of threads or pass sizes. A `--sample-range` part
//! starting after sample 0 cannot know the moments of the samples before it and is refused.
//!
//! # The solve
//!
//! `M` is 2×2 and symmetric; [`Moments::solve`] adds a ridge of [`RIDGE`] × trace(M) to its
//! diagonal (so a pixel whose samples all have the same `r` still gets a finite α, shrunk towards
//! 0), and returns α = 0 (the balance heuristic) for an empty or non-finite system.
//!
//! WGSL twin: `integrator/optimal.wgsl` (the GPU keeps the moments in f32).

use super::Heuristic;
use glam::Vec3;

/// The first sample index that uses a solved α; samples before it use α = 0 (the balance
/// heuristic), since a handful of samples gives a noisy α.
pub const FIRST_STAGE: u32 = 8;

/// Relative ridge added to the diagonal of `M` before solving.
pub const RIDGE: f64 = 1e-3;

/// The first sample of the stage holding sample `s`: the largest power of two `≤ s` from
/// [`FIRST_STAGE`] on, 0 before. α for sample `s` comes from samples `0..stage_start(s)`.
#[inline]
pub fn stage_start(s: u32) -> u32 {
    if s < FIRST_STAGE {
        0
    } else {
        1 << (31 - s.leading_zeros())
    }
}

/// Whether α is re-solved before sample `s` (a stage starts there).
#[inline]
pub fn is_stage_start(s: u32) -> bool {
    s >= FIRST_STAGE && s.is_power_of_two()
}

/// The per-channel α of the two techniques.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Alpha {
    /// α of light sampling (next-event estimation).
    pub light: Vec3,
    /// α of BSDF sampling.
    pub bsdf: Vec3,
}

/// The balance weights `(r_L, r_B)` of an outcome both techniques can produce, with light pdf
/// `p_light` (selection included) and BSDF pdf `p_bsdf`, or `None` where they are unusable (both
/// zero, or not finite): then the outcome is pure.
#[inline]
pub fn balance_ratios(p_light: f32, p_bsdf: f32) -> Option<(f32, f32)> {
    let ok = |p: f32| p.is_finite() && p >= 0.0;
    if !ok(p_light) || !ok(p_bsdf) || p_light + p_bsdf <= 0.0 {
        return None;
    }
    Some((
        Heuristic::Balance.weight(p_light, p_bsdf),
        Heuristic::Balance.weight(p_bsdf, p_light),
    ))
}

/// Sums of one pixel's moments: `M` (symmetric: LL, LB, BB) and `b` per channel and technique.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Moments {
    /// `M_LL, M_LB, M_BB`.
    pub m: [f64; 3],
    /// `b_L` per channel.
    pub b_light: [f64; 3],
    /// `b_B` per channel.
    pub b_bsdf: [f64; 3],
}

impl Moments {
    /// A sample (of either technique) at an outcome both can produce: `contribution` is its
    /// balance-heuristic contribution `f / D`, `(rl, rb)` its [`balance_ratios`].
    #[inline]
    pub fn add_combined(&mut self, contribution: Vec3, rl: f32, rb: f32) {
        let (rl, rb) = (rl as f64, rb as f64);
        self.m[0] += rl * rl;
        self.m[1] += rl * rb;
        self.m[2] += rb * rb;
        for c in 0..3 {
            let x = contribution[c] as f64;
            self.b_light[c] += x * rl;
            self.b_bsdf[c] += x * rb;
        }
    }

    /// A pure light sample of contribution zero (a failure, a blocked or rejected direction).
    #[inline]
    pub fn add_pure_light(&mut self) {
        self.m[0] += 1.0;
    }

    /// A pure light sample with contribution `h`: a delta light's.
    #[inline]
    pub fn add_delta_light(&mut self, h: Vec3) {
        self.m[0] += 1.0;
        for c in 0..3 {
            self.b_light[c] += h[c] as f64;
        }
    }

    /// A pure BSDF sample with contribution `h` (a delta lobe's emission; zero otherwise).
    #[inline]
    pub fn add_pure_bsdf(&mut self, h: Vec3) {
        self.m[2] += 1.0;
        for c in 0..3 {
            self.b_bsdf[c] += h[c] as f64;
        }
    }

    /// Adds another pixel's (or sample's) sums.
    #[inline]
    pub fn add(&mut self, o: &Moments) {
        for i in 0..3 {
            self.m[i] += o.m[i];
            self.b_light[i] += o.b_light[i];
            self.b_bsdf[i] += o.b_bsdf[i];
        }
    }

    /// Whether every sum is finite (a sample whose moments are not is dropped, like its value).
    pub fn is_finite(&self) -> bool {
        self.m
            .iter()
            .chain(&self.b_light)
            .chain(&self.b_bsdf)
            .all(|v| v.is_finite())
    }

    /// α from `(M + λI) α = b` per channel, `λ` = [`RIDGE`] × trace(M); α = 0 where `M` is
    /// empty or anything is not finite.
    pub fn solve(&self) -> Alpha {
        let [a, c, d] = self.m;
        let trace = a + d;
        if !(trace > 0.0 && trace.is_finite()) {
            return Alpha::default();
        }
        let lambda = RIDGE * trace;
        let (a, d) = (a + lambda, d + lambda);
        let det = a * d - c * c;
        if !(det > 0.0 && det.is_finite()) {
            return Alpha::default();
        }
        let mut light = Vec3::ZERO;
        let mut bsdf = Vec3::ZERO;
        for ch in 0..3 {
            let (bl, bb) = (self.b_light[ch], self.b_bsdf[ch]);
            let al = (d * bl - c * bb) / det;
            let ab = (a * bb - c * bl) / det;
            if !(al.is_finite() && ab.is_finite()) {
                return Alpha::default();
            }
            light[ch] = al as f32;
            bsdf[ch] = ab as f32;
        }
        if !(light.is_finite() && bsdf.is_finite()) {
            return Alpha::default();
        }
        Alpha { light, bsdf }
    }
}

/// What one camera sample of [`super::Strategy::MisOptimal`] reads (α of its pixel and stage)
/// and writes (its moments) at its first vertex.
#[derive(Clone, Copy, Debug, Default)]
pub struct OptimalSample {
    /// α for this sample (from earlier samples only).
    pub alpha: Alpha,
    /// This sample's moments (zero if the first vertex had no next-event estimation).
    pub moments: Moments,
}

impl OptimalSample {
    /// The constant term `α_L + α_B` of a vertex with both techniques.
    #[inline]
    pub fn constant(&self) -> Vec3 {
        self.alpha.light + self.alpha.bsdf
    }

    /// A sample at an outcome both techniques can produce: records it and returns its control
    /// variate term `−α·r`.
    #[inline]
    pub fn combined(&mut self, contribution: Vec3, rl: f32, rb: f32) -> Vec3 {
        self.moments.add_combined(contribution, rl, rb);
        -(self.alpha.light * rl + self.alpha.bsdf * rb)
    }

    /// A pure light sample: records it and returns `−α_L`.
    #[inline]
    pub fn pure_light(&mut self) -> Vec3 {
        self.moments.add_pure_light();
        if crate::mutants::optimal_pure_zero() {
            return Vec3::ZERO;
        }
        -self.alpha.light
    }

    /// A delta light's sample of contribution `h`: pure (no BSDF sample finds a delta light),
    /// recorded as such with its contribution (as a delta lobe's in [`Self::pure_bsdf`]);
    /// returns `−α_L`.
    #[inline]
    pub fn delta_light(&mut self, h: Vec3) -> Vec3 {
        self.moments.add_delta_light(h);
        if crate::mutants::optimal_pure_zero() {
            return Vec3::ZERO;
        }
        -self.alpha.light
    }

    /// A pure BSDF sample of contribution `h`: records it and returns `−α_B`.
    #[inline]
    pub fn pure_bsdf(&mut self, h: Vec3) -> Vec3 {
        self.moments.add_pure_bsdf(h);
        if crate::mutants::optimal_pure_zero() {
            return Vec3::ZERO;
        }
        -self.alpha.bsdf
    }
}

/// One pixel's state in the engine: its moments so far and the α of its current stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelState {
    /// Moments of every sample rendered so far.
    pub moments: Moments,
    /// α for the samples of the current stage.
    pub alpha: Alpha,
}

impl PixelState {
    /// The α for sample `s`, re-solved first when a stage starts at `s` (the moments then hold
    /// exactly the samples `0..s`, since the engine adds them in order).
    #[inline]
    pub fn alpha_for(&mut self, s: u32) -> Alpha {
        if is_stage_start(s) {
            self.alpha = self.moments.solve();
        }
        self.alpha
    }
}

#[cfg(test)]
#[path = "optimal_tests.rs"]
mod tests;
