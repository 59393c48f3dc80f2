//! Pearson's χ² goodness-of-fit test of a direction sampler against its own pdf, after
//! Mitsuba 3's `ChiSquareTest`: histogram the samples over the cells of a [`Domain`], integrate
//! the pdf over the same cells for the expected counts, pool the cells expected to hold fewer than
//! five samples, and reject when the statistic's p-value falls below the Šidák-corrected level.
//!
//! Beyond the statistic, a run also fails when a sample is malformed (not finite, not unit, a
//! reported pdf ≤ 0), when the pdf is 0 at a sampled direction and within 1e-5 rad of it (or too
//! many samples lie at the support's edge, or in cells of zero expected count: the sampler
//! reaches where its pdf says it cannot), when the reported pdf
//! disagrees with `pdf(w)`, or when `∫pdf` differs from the fraction of non-delta samples
//! (binomial 5σ plus the quadrature's 1e-3).

use super::domain::Domain;
use super::gamma::{chi2_sf, sidak};
use super::quadrature::{Rect, adaptive, midpoint};
use super::sampler::DirectionalSampler;
use crate::math::Frame;
use crate::rng::Rng;
use glam::{Vec2, Vec3};
use rayon::prelude::*;
use std::f64::consts::TAU;
use std::fmt;

/// Samples per work item: the histogram does not depend on the thread count.
const CHUNK: usize = 1 << 16;

/// The uniforms `(u1, u2)` chunk `c` of a test with `seed` feeds its sampler, `n` of them.
fn chunk_uniforms(seed: u32, c: usize, n: usize) -> impl Iterator<Item = (f32, Vec2)> {
    let mut rng = Rng::new(seed, c as u32, 0x5eed);
    (0..n).map(move |_| {
        let u1 = rng.next_f32();
        (u1, rng.next_2d())
    })
}

/// Every uniform pair a test with `seed` and `sample_count` samples feeds its sampler, in the
/// order it draws them: a sampler that runs elsewhere (the GPU backend's WGSL) computes its
/// samples for exactly these, ahead of the test (see [`super::precomputed`]).
pub fn drawn_uniforms(seed: u32, sample_count: usize) -> Vec<(f32, Vec2)> {
    (0..sample_count.div_ceil(CHUNK))
        .flat_map(|c| chunk_uniforms(seed, c, CHUNK.min(sample_count - c * CHUNK)))
        .collect()
}
/// Relative difference beyond which a sample's reported pdf and `pdf(w)` disagree.
const PDF_REL_TOL: f32 = 1e-2;
/// Largest fraction of samples allowed to disagree that way: an area pdf recomputed from a
/// traced ray differs from the sampled point's near silhouettes, where `1/cos` is steep.
const PDF_MISMATCH_FRACTION: f64 = 1e-3;
/// Largest fraction of samples allowed in cells of expected count 0: a sample at the support's
/// edge (see [`EDGE_ANGLE`]) can round into a neighbouring cell that the support does not reach.
const EMPTY_CELL_FRACTION: f64 = 3e-5;
/// A sample where `pdf(w)` is 0 but positive within this angle (radians) is rounding at the
/// support's edge, not a sample outside it (any sample farther out fails the test): an f32 ray cast towards a point sampled on a light's
/// very edge can miss it, by ~1e-7 rad on the CPU and up to ~1.5e-6 rad on a GPU whose sin/cos
/// are approximate (measured on an H100, a star light seen 5° above its plane). 100 times
/// smaller than any histogram cell.
const EDGE_ANGLE: f32 = 1e-5;
/// Largest fraction of samples allowed at the support's edge (as for pdf mismatches: a sampler
/// that overshoots its support puts far more samples there).
const EDGE_FRACTION: f64 = 1e-3;

/// True if `pdf` is positive at some direction within [`EDGE_ANGLE`] of `w` (probed on three
/// rings of eight directions, so that a support thinner than the angle is not stepped over).
fn near_support(sampler: &dyn DirectionalSampler, w: Vec3) -> bool {
    let f = Frame::from_normal(w);
    [EDGE_ANGLE / 100.0, EDGE_ANGLE / 10.0, EDGE_ANGLE]
        .iter()
        .any(|&r| {
            (0..8).any(|k| {
                let a = k as f32 * std::f32::consts::TAU / 8.0;
                let probe = (w + r * (f.s * a.cos() + f.t * a.sin())).normalize();
                sampler.pdf(probe) > 0.0
            })
        })
}

/// Settings and results of one χ² test of a [`DirectionalSampler`].
pub struct ChiSquareTest<'a> {
    sampler: &'a dyn DirectionalSampler,
    domain: Domain,
    /// Rows (polar direction); the cells are `res_theta × res_phi`.
    pub res_theta: usize,
    /// Columns (azimuth).
    pub res_phi: usize,
    /// Number of samples drawn.
    pub sample_count: usize,
    /// Seed of the sample streams.
    pub seed: u32,
    /// Family-wise significance level.
    pub alpha: f64,
    /// Number of tests in the family, for the Šidák correction.
    pub test_count: usize,
    /// Cells expected to hold fewer samples are pooled.
    pub min_expected: f64,
    observed: Vec<f64>,
    expected: Vec<f64>,
}

/// The outcome of [`ChiSquareTest::run`].
#[derive(Clone, Debug, Default)]
pub struct Chi2Result {
    /// Pearson's statistic over the (pooled) cells.
    pub statistic: f64,
    /// Degrees of freedom: cells used minus one.
    pub dof: usize,
    /// `P(χ²_dof ≥ statistic)`.
    pub p_value: f64,
    /// The per-test (Šidák-corrected) significance level.
    pub alpha: f64,
    /// Cells merged into the pooled cell.
    pub pooled_cells: usize,
    /// `∫pdf` over the domain, by quadrature.
    pub integral: f64,
    /// Fraction of the samples that were non-delta directions.
    pub sampled_fraction: f64,
    /// Samples malformed (non-finite, not unit, reported pdf ≤ 0 or non-finite).
    pub bad_samples: usize,
    /// Samples where `pdf(w)` is 0, also within [`EDGE_ANGLE`] of `w`.
    pub zero_pdf_samples: usize,
    /// Samples where `pdf(w)` is 0 but positive within [`EDGE_ANGLE`]: rounding at the edge.
    pub edge_samples: usize,
    /// Samples in cells whose expected count is 0 even on a 128 × 128 grid.
    pub samples_in_empty_cells: usize,
    /// Samples whose reported pdf differs from `pdf(w)` by more than 1%.
    pub pdf_mismatches: usize,
    /// Why the test failed, or `None`.
    pub failure: Option<String>,
}

impl Chi2Result {
    /// True if no check failed.
    pub fn passed(&self) -> bool {
        self.failure.is_none()
    }

    /// True if the χ² statistic alone rejects the sampler.
    pub fn chi2_rejects(&self) -> bool {
        self.p_value < self.alpha
    }
}

impl fmt::Display for Chi2Result {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "χ²={:.1} dof={} p={:.3e} (α={:.2e}) pooled={} ∫pdf={:.5} sampled={:.5} \
             bad={} pdf0={} edge={} empty={} mismatch={}",
            self.statistic,
            self.dof,
            self.p_value,
            self.alpha,
            self.pooled_cells,
            self.integral,
            self.sampled_fraction,
            self.bad_samples,
            self.zero_pdf_samples,
            self.edge_samples,
            self.samples_in_empty_cells,
            self.pdf_mismatches
        )?;
        match &self.failure {
            Some(why) => write!(f, " FAILED: {why}"),
            None => write!(f, " ok"),
        }
    }
}

/// Per-chunk sampling tallies.
#[derive(Default)]
struct Tally {
    hist: Vec<u32>,
    delta_or_none: usize,
    bad: usize,
    zero_pdf: usize,
    edge: usize,
    empty: usize,
    mismatch: usize,
}

impl Tally {
    fn merge(mut self, o: Tally) -> Tally {
        if self.hist.is_empty() {
            self.hist = o.hist;
        } else {
            self.hist.iter_mut().zip(&o.hist).for_each(|(a, b)| *a += b);
        }
        self.delta_or_none += o.delta_or_none;
        self.bad += o.bad;
        self.zero_pdf += o.zero_pdf;
        self.edge += o.edge;
        self.empty += o.empty;
        self.mismatch += o.mismatch;
        self
    }
}

/// How a failure of the statistic alone begins (the only failure a second stage re-runs).
const CHI2_REJECTS: &str = "χ² rejects";

/// The protocol's second stage draws this many times the first stage's samples.
pub const SECOND_STAGE_SAMPLES: usize = 4;

/// The second stage's seed for a test at `seed`: a fixed mix (splitmix32's finaliser) into
/// [2³⁰, 2³¹), a range the suite's first-stage seeds do not use.
pub fn second_stage_seed(seed: u32) -> u32 {
    let mut h = seed ^ 0x9e37_79b9;
    h = (h ^ (h >> 16)).wrapping_mul(0x21f0_aaad);
    h = (h ^ (h >> 15)).wrapping_mul(0x735a_2d97);
    (1 << 30) | ((h ^ (h >> 15)) >> 2)
}

impl<'a> ChiSquareTest<'a> {
    /// A test with Mitsuba's defaults: 1M samples, 64 × 128 cells over the sampler's own
    /// [`DirectionalSampler::domain`], α = 0.01 for a single test.
    pub fn new(sampler: &'a dyn DirectionalSampler) -> ChiSquareTest<'a> {
        ChiSquareTest {
            sampler,
            domain: sampler.domain(),
            res_theta: 64,
            res_phi: 128,
            sample_count: 1_000_000,
            seed: 0,
            alpha: 0.01,
            test_count: 1,
            min_expected: 5.0,
            observed: Vec::new(),
            expected: Vec::new(),
        }
    }

    /// Sets the number of samples.
    pub fn samples(mut self, n: usize) -> Self {
        self.sample_count = n;
        self
    }

    /// Sets the grid to `n` rows (rounded up to even) by `2n` columns.
    pub fn resolution(mut self, n: usize) -> Self {
        self.res_theta = n.max(2).next_multiple_of(2);
        self.res_phi = 2 * self.res_theta;
        self
    }

    /// Sets the seed.
    pub fn seed(mut self, seed: u32) -> Self {
        self.seed = seed;
        self
    }

    /// Sets the family-wise level `alpha` over `test_count` tests.
    pub fn significance(mut self, alpha: f64, test_count: usize) -> Self {
        self.alpha = alpha;
        self.test_count = test_count;
        self
    }

    /// Replaces the sampler's domain.
    pub fn domain(mut self, domain: Domain) -> Self {
        self.domain = domain;
        self
    }

    /// The domain histogrammed.
    pub fn current_domain(&self) -> &Domain {
        &self.domain
    }

    /// Integrates the pdf over every cell: the expected *probabilities*, row-major.
    ///
    /// Adaptive Gauss–Legendre is accurate on smooth densities but can be fooled by a sliver (the
    /// thin tip of a light's silhouette) that sits on the nodes of one level and between those of
    /// the next. So every cell is also integrated by an 8×8 midpoint rule; where the two differ by
    /// more than a twentieth of the cell's Poisson noise, that cell and its neighbours (a sliver
    /// runs on into them) are integrated again by 64×64 and 128×128 midpoint rules; the finer one
    /// replaces the adaptive value when the two have converged (half a count's noise apart).
    fn integrate(&self) -> Vec<f64> {
        let edges = self.domain.row_edges(self.res_theta);
        let (sampler, domain) = (self.sampler, &self.domain);
        let pdf = |w: glam::Vec3| sampler.pdf(w);
        let f = |phi: f64, v: f64| domain.density(&pdf, phi, v);
        let dphi = TAU / self.res_phi as f64;
        let n = self.sample_count as f64;
        // A tenth of a count per cell, so quadrature error stays far below √E.
        let tol = 0.1 / n;
        let rect = |i: usize, j: usize| Rect {
            x0: j as f64 * dphi,
            x1: (j + 1) as f64 * dphi,
            y0: edges[i],
            y1: edges[i + 1],
        };
        // Counts closer than this are the same for the test.
        let close = |a: f64, b: f64| (a - b).abs() * n <= 0.05 * (a.max(b) * n).max(1.0).sqrt();
        let (res_theta, res_phi) = (self.res_theta, self.res_phi);
        let first: Vec<(f64, bool)> = (0..res_theta * res_phi)
            .into_par_iter()
            .map(|k| {
                let r = rect(k / res_phi, k % res_phi);
                let a = adaptive(&f, r, tol);
                (a, !close(a, midpoint(&f, r, 8)))
            })
            .collect();
        let suspect = |i: usize, j: usize| {
            (-1..=1).any(|di: isize| {
                (-1..=1).any(|dj: isize| {
                    let ii = i as isize + di;
                    // φ wraps around; rows do not.
                    let jj = (j as isize + dj).rem_euclid(res_phi as isize) as usize;
                    (0..res_theta as isize).contains(&ii) && first[ii as usize * res_phi + jj].1
                })
            })
        };
        (0..res_theta * res_phi)
            .into_par_iter()
            .map(|k| {
                let (i, j) = (k / res_phi, k % res_phi);
                let a = first[k].0;
                if !suspect(i, j) {
                    return a;
                }
                let m = midpoint(&f, rect(i, j), 64);
                if close(a, m) {
                    return a;
                }
                // A sliver is resolved once the midpoint rule has converged; an integrable
                // singularity (the 1/cos of area sampling at a sphere's silhouette) is not, and
                // there the adaptive rule, which refines towards it, is the better one.
                let fine = midpoint(&f, rect(i, j), 128);
                let converged = (fine - m).abs() * n <= 0.5 * (fine * n).max(1.0).sqrt();
                if converged { fine } else { a }
            })
            .collect()
    }

    /// Draws the samples and histograms them, checking each one against `expected`.
    fn histogram(&self, expected: &[f64]) -> Tally {
        let edges = self.domain.row_edges(self.res_theta);
        let n_chunks = self.sample_count.div_ceil(CHUNK);
        let cells = self.res_theta * self.res_phi;
        (0..n_chunks)
            .into_par_iter()
            .map(|c| {
                let mut t = Tally {
                    hist: vec![0; cells],
                    ..Tally::default()
                };
                let n = CHUNK.min(self.sample_count - c * CHUNK);
                for (k, (u1, u2)) in chunk_uniforms(self.seed, c, n).enumerate() {
                    let Some(s) = self.sampler.sample_at(c * CHUNK + k, u1, u2) else {
                        t.delta_or_none += 1;
                        continue;
                    };
                    if s.delta {
                        t.delta_or_none += 1;
                        continue;
                    }
                    let unit = (s.w.length() - 1.0).abs() < 1e-3;
                    if !(s.w.is_finite() && unit && s.pdf > 0.0 && s.pdf.is_finite()) {
                        t.bad += 1;
                        continue;
                    }
                    let Some((phi, v)) = self.domain.coords(s.w) else {
                        t.bad += 1;
                        continue;
                    };
                    let p = self.sampler.pdf(s.w);
                    if p <= 0.0 || !p.is_finite() {
                        if near_support(self.sampler, s.w) {
                            t.edge += 1;
                        } else {
                            t.zero_pdf += 1;
                        }
                    } else if (p - s.pdf).abs() > PDF_REL_TOL * p.max(s.pdf) {
                        t.mismatch += 1;
                    }
                    let row =
                        (edges.partition_point(|&e| e <= v).max(1) - 1).min(self.res_theta - 1);
                    let col = ((phi / TAU * self.res_phi as f64) as usize).min(self.res_phi - 1);
                    let cell = row * self.res_phi + col;
                    if expected[cell] <= 0.0 {
                        t.empty += 1;
                    }
                    t.hist[cell] += 1;
                }
                t
            })
            .reduce(Tally::default, Tally::merge)
    }

    /// Runs the test under the suite's two-stage protocol (docs/testing.md, "The protocol"):
    /// where the χ² statistic alone rejects (malformed samples, zero pdfs, a pdf mismatch or a
    /// wrong ∫pdf are deterministic failures, never re-run), the test runs again at a seed
    /// derived from this one ([`second_stage_seed`]: known before any run, chosen by no one) with
    /// [`SECOND_STAGE_SAMPLES`]× the samples at half the significance, and fails only if that
    /// rejects too (`failure` then names both). A sampler that cannot draw again
    /// ([`DirectionalSampler::can_resample`]) has one stage.
    pub fn run(&mut self) -> Chi2Result {
        let first = self.run_once();
        let chi2_only = first
            .failure
            .as_deref()
            .is_some_and(|f| f.starts_with(CHI2_REJECTS));
        if !(chi2_only && self.sampler.can_resample()) {
            return first;
        }
        let (seed, count, alpha) = (self.seed, self.sample_count, self.alpha);
        self.seed = second_stage_seed(seed);
        self.sample_count = SECOND_STAGE_SAMPLES * count;
        self.alpha = alpha / 2.0;
        let mut second = self.run_once();
        if let Some(f) = &mut second.failure {
            *f = format!(
                "{f} at stage 2 (seed {}, {} samples), after stage 1: {}",
                self.seed,
                self.sample_count,
                first.failure.as_deref().unwrap_or("")
            );
        }
        (self.seed, self.sample_count, self.alpha) = (seed, count, alpha);
        second
    }

    /// One stage: quadrature, sampling, pooling and the verdict.
    fn run_once(&mut self) -> Chi2Result {
        let mut probs = self.integrate();
        let mut tally = self.histogram(&probs);
        self.recheck_empty_cells(&mut probs, &mut tally);
        let n = self.sample_count as f64;
        self.expected = probs.iter().map(|p| p * n).collect();
        self.observed = tally.hist.iter().map(|&c| c as f64).collect();

        let mut r = Chi2Result {
            alpha: sidak(self.alpha, self.test_count),
            integral: probs.iter().sum(),
            sampled_fraction: tally.hist.iter().map(|&c| c as f64).sum::<f64>() / n,
            bad_samples: tally.bad,
            zero_pdf_samples: tally.zero_pdf,
            edge_samples: tally.edge,
            samples_in_empty_cells: tally.empty,
            pdf_mismatches: tally.mismatch,
            ..Chi2Result::default()
        };
        self.statistic(&mut r);

        let f = r.sampled_fraction;
        let mass_tol = 5.0 * (f * (1.0 - f) / n).sqrt() + 1e-3;
        r.failure = if r.bad_samples > 0 {
            Some(format!("{} malformed samples", r.bad_samples))
        } else if r.zero_pdf_samples > 0 {
            Some(format!("{} samples where pdf = 0", r.zero_pdf_samples))
        } else if r.edge_samples as f64 > EDGE_FRACTION * n {
            Some(format!(
                "{} samples where pdf = 0 within {EDGE_ANGLE:e} rad of its support",
                r.edge_samples
            ))
        } else if r.samples_in_empty_cells as f64 > EMPTY_CELL_FRACTION * n {
            Some(format!(
                "{} samples in cells of expected count 0",
                r.samples_in_empty_cells
            ))
        } else if r.pdf_mismatches as f64 > PDF_MISMATCH_FRACTION * n {
            Some(format!(
                "{} samples whose pdf differs from pdf(w)",
                r.pdf_mismatches
            ))
        } else if (r.integral - f).abs() > mass_tol || r.integral > 1.0 + 1e-3 {
            Some(format!(
                "∫pdf = {:.5} but {:.5} of the samples are non-delta",
                r.integral, f
            ))
        } else if r.dof == 0 {
            Some("no degrees of freedom".into())
        } else if r.p_value < r.alpha {
            Some(format!(
                "{CHI2_REJECTS}: p = {:.3e} < {:.3e}",
                r.p_value, r.alpha
            ))
        } else {
            None
        };
        r
    }

    /// Cells that received samples although quadrature found no mass: a sliver of support (the
    /// horizon seen in half-vector space, a silhouette) can slip between all the Gauss nodes.
    /// Such cells are integrated again on a 128 × 128 midpoint grid; samples in cells that still
    /// come out empty count as [`Chi2Result::samples_in_empty_cells`], which fails the test
    /// beyond the same small fraction as zero-pdf samples (a sample there with pdf 0 is
    /// counted as such anyway).
    fn recheck_empty_cells(&self, probs: &mut [f64], tally: &mut Tally) {
        let edges = self.domain.row_edges(self.res_theta);
        let pdf = |w: glam::Vec3| self.sampler.pdf(w);
        let dphi = TAU / self.res_phi as f64;
        const K: usize = 128;
        tally.empty = 0;
        for (i, p) in probs.iter_mut().enumerate() {
            if *p > 0.0 || tally.hist[i] == 0 {
                continue;
            }
            let (row, col) = (i / self.res_phi, i % self.res_phi);
            let (v0, v1) = (edges[row], edges[row + 1]);
            let mut sum = 0.0;
            for a in 0..K {
                let v = v0 + (v1 - v0) * (a as f64 + 0.5) / K as f64;
                for b in 0..K {
                    let phi = dphi * (col as f64 + (b as f64 + 0.5) / K as f64);
                    sum += self.domain.density(&pdf, phi, v);
                }
            }
            *p = sum * dphi * (v1 - v0) / (K * K) as f64;
            if *p <= 0.0 {
                tally.empty += tally.hist[i] as usize;
            }
        }
    }

    /// Pearson's statistic with Mitsuba's pooling: cells in increasing order of expected count;
    /// those below `min_expected` go into one pool, which also absorbs the next cells until it
    /// reaches `min_expected` itself.
    fn statistic(&self, r: &mut Chi2Result) {
        let mut order: Vec<usize> = (0..self.expected.len()).collect();
        order.sort_by(|&a, &b| self.expected[a].total_cmp(&self.expected[b]));
        let (mut pool_e, mut pool_o) = (0.0, 0.0);
        let (mut chi2, mut cells) = (0.0, 0usize);
        for i in order {
            let (e, o) = (self.expected[i], self.observed[i]);
            if e <= 0.0 && o == 0.0 {
                continue;
            }
            // Cells still empty after the recheck hold slivers of support: pooled with the rest.
            if e < self.min_expected || (pool_e > 0.0 && pool_e < self.min_expected) {
                pool_e += e;
                pool_o += o;
                r.pooled_cells += 1;
            } else {
                chi2 += (o - e) * (o - e) / e;
                cells += 1;
            }
        }
        if pool_e > 0.0 {
            chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
            cells += 1;
        }
        r.statistic = chi2;
        r.dof = cells.saturating_sub(1);
        r.p_value = if r.dof > 0 {
            chi2_sf(chi2, r.dof as f64)
        } else {
            1.0
        };
    }

    /// The observed and expected counts of the last run, row-major (`res_theta` rows of
    /// `res_phi` cells).
    pub fn render_histograms(&self) -> (Vec<f64>, Vec<f64>) {
        (self.observed.clone(), self.expected.clone())
    }

    /// The `k` cells that contribute most to the statistic: `(row, col, observed, expected)`.
    pub fn worst_cells(&self, k: usize) -> Vec<(usize, usize, f64, f64)> {
        let mut cells: Vec<(usize, usize, f64, f64)> = (0..self.expected.len())
            .map(|i| {
                let (row, col) = (i / self.res_phi, i % self.res_phi);
                (row, col, self.observed[i], self.expected[i])
            })
            .filter(|c| c.3 >= self.min_expected)
            .collect();
        let score = |c: &(usize, usize, f64, f64)| (c.2 - c.3).powi(2) / c.3;
        cells.sort_by(|a, b| score(b).total_cmp(&score(a)));
        cells.truncate(k);
        cells
    }
}
