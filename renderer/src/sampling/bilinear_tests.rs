//! Tests of the linear and bilinear warps: densities integrate to 1, each sample inverts to its
//! `u`, and a χ² test of the samples against the density, whose power is shown on a wrong
//! sampler.

use super::*;
use crate::rng::Rng;
use crate::stats::gamma::{chi2_sf, sidak};

/// Corner weights of the χ² and round-trip tests: uniform, strongly skewed, one corner zero,
/// two corners (one edge) zero, a single nonzero corner, and |cos θ|-like weights.
const WEIGHTS: [[f32; 4]; 7] = [
    [1.0, 1.0, 1.0, 1.0],
    [0.05, 1.0, 0.3, 2.0],
    [0.0, 1.0, 1.0, 1.0],
    [0.0, 0.0, 1.0, 0.5],
    [0.0, 0.0, 0.0, 1.0],
    [0.9, 0.2, 0.7, 0.01],
    [0.0; 4],
];

#[test]
fn linear_density_integrates_to_one_and_inverts() {
    let mut rng = Rng::new(21, 0, 0);
    for (a, b) in [(1.0, 1.0), (0.0, 1.0), (1.0, 0.0), (0.01, 3.0), (0.0, 0.0)] {
        // Midpoint rule: exact for a linear density.
        let n = 1000;
        let total: f32 = (0..n)
            .map(|i| linear_pdf((i as f32 + 0.5) / n as f32, a, b) / n as f32)
            .sum();
        assert!((total - 1.0).abs() < 1e-4, "({a}, {b}): {total}");
        for i in 0..10_000 {
            let u = if i == 0 { 0.0 } else { rng.next_f32() };
            let x = sample_linear(u, a, b);
            assert!((0.0..1.0).contains(&x), "({a}, {b}) u {u} -> {x}");
            let back = invert_linear_sample(x, a, b);
            assert!((back - u).abs() < 2e-6, "({a}, {b}) u {u} -> {x} -> {back}");
        }
        // Monotone: a larger u never gives a smaller x.
        assert!(sample_linear(0.3, a, b) <= sample_linear(0.7, a, b));
    }
}

#[test]
fn bilinear_density_integrates_to_one() {
    for w in WEIGHTS {
        // The cell-centre rule is exact for a bilinear function.
        let n = 64;
        let mut total = 0.0f64;
        for j in 0..n {
            for i in 0..n {
                let p = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                total += bilinear_pdf(p, w) as f64 / (n * n) as f64;
            }
        }
        assert!((total - 1.0).abs() < 1e-5, "{w:?}: {total}");
        assert_eq!(bilinear_pdf(Vec2::new(1.1, 0.5), w), 0.0);
    }
}

#[test]
fn bilinear_samples_invert_to_their_u() {
    let mut rng = Rng::new(22, 0, 0);
    for w in WEIGHTS {
        for _ in 0..20_000 {
            let u = rng.next_2d();
            let p = sample_bilinear(u, w);
            assert!(
                p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0,
                "{w:?} {u} -> {p}"
            );
            let back = invert_bilinear_sample(p, w);
            // Where the density is tiny the inverse is steep: compare in u within a few ulp
            // of the CDF's arithmetic.
            assert!(
                (back - u).abs().max_element() < 1e-5,
                "{w:?} {u} -> {p} -> {back}"
            );
        }
    }
}

/// Pearson's χ² of `n` samples of `sample` in a `g`×`g` grid against [`bilinear_pdf`] for `w`:
/// a cell's probability is its area times the density at its centre, exact for a bilinear
/// density (independent of the sampler's inverse). Returns the p-value.
fn chi2_p_value(w: [f32; 4], sample: impl Fn(Vec2) -> Vec2, n: u32, seed: u32) -> f64 {
    let g = 16;
    let mut counts = vec![0u32; g * g];
    let mut rng = Rng::new(seed, 0, 0);
    for _ in 0..n {
        let p = sample(rng.next_2d());
        let (i, j) = (
            ((p.x * g as f32) as usize).min(g - 1),
            ((p.y * g as f32) as usize).min(g - 1),
        );
        counts[j * g + i] += 1;
    }
    let (mut chi2, mut cells) = (0.0f64, 0);
    for j in 0..g {
        for i in 0..g {
            let centre = Vec2::new((i as f32 + 0.5) / g as f32, (j as f32 + 0.5) / g as f32);
            let expected = bilinear_pdf(centre, w) as f64 / (g * g) as f64 * n as f64;
            let observed = counts[j * g + i] as f64;
            if expected < 5.0 {
                // Too few for Pearson's approximation; a sample there at all is a bug only if
                // the density is 0, which a zero-weight corner cell never is at its centre.
                continue;
            }
            chi2 += (observed - expected).powi(2) / expected;
            cells += 1;
        }
    }
    chi2_sf(chi2, (cells - 1) as f64)
}

/// χ² of `sample_bilinear` for every weight set: 10⁶ samples each in a 16×16 grid, seeds 100 +
/// set, family-wise α = 0.01 (Šidák over the 7 sets). Power: the same test rejects a sampler
/// that swaps the two middle corners (the density transposed) on the asymmetric sets, and one
/// that draws `x` with the bottom edge's weights at every `y` (the conditional ignored).
#[test]
fn bilinear_samples_follow_the_density() {
    let alpha = sidak(0.01, WEIGHTS.len());
    const N: u32 = 1_000_000;
    for (k, w) in WEIGHTS.iter().enumerate() {
        let p = chi2_p_value(*w, |u| sample_bilinear(u, *w), N, 100 + k as u32);
        assert!(p > alpha, "{w:?}: p = {p:e} (α {alpha:e})");
    }
    // The test's power, on two wrong samplers.
    let w = WEIGHTS[1];
    let transposed = [w[0], w[2], w[1], w[3]];
    let p = chi2_p_value(w, |u| sample_bilinear(u, transposed), N, 200);
    assert!(p < alpha, "transposed weights not detected: p = {p:e}");
    let no_conditional = |u: Vec2| {
        let y = sample_linear(u.y, w[0] + w[1], w[2] + w[3]);
        Vec2::new(sample_linear(u.x, w[0], w[1]), y)
    };
    let p = chi2_p_value(w, no_conditional, N, 201);
    assert!(p < alpha, "ignored conditional not detected: p = {p:e}");
}
