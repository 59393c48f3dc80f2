//! Distribution tests of the ZSobol sampler through the [`Sampler`] interface, with the
//! dimensions the integrator uses.

use super::*;
use crate::stats::gamma::{chi2_sf, sidak};

/// The 2-D samples the integrator draws at bounces 0 and 3, and the camera's.
fn two_d_dims() -> [u32; 5] {
    [
        dim::CAMERA,
        dim::at(0, dim::LIGHT),
        dim::at(0, dim::BSDF),
        dim::at(3, dim::LIGHT),
        dim::at(3, dim::BSDF),
    ]
}

/// The 1-D samples the integrator draws at bounces 0 and 2.
fn one_d_dims() -> Vec<u32> {
    [0, 2]
        .into_iter()
        .flat_map(|b| {
            [dim::MIXTURE, dim::LIGHT_SELECT, dim::BSDF_LOBE, dim::RR].map(|o| dim::at(b, o))
        })
        .collect()
}

/// Pixels spread over tiles and positions within them.
const PIXELS: [(u32, u32); 4] = [(0, 0), (5, 3), (63, 64), (1000, 777)];

fn sobol(seed: u32, (x, y): (u32, u32), s: u32) -> Sampler {
    Sampler::new(SamplerKind::Sobol, seed, x, y, 2048, s)
}

/// The first `4^k` samples (k = 1…4) of a pixel put exactly one point in each elementary
/// interval of area `4^-k` (every shape `2^-a × 2^-(2k−a)`, the squares included) in every 2-D
/// dimension the integrator uses, for several pixels, seeds and for a later epoch's first
/// samples. Deterministic: no α. Catches an index permutation that is not nested, a scramble that is not
/// nested, or wrong Sobol direction numbers (tried once with all three at the same time:
/// digits permuted by the *low* digits, `x ^ (x >> 2)` columns, a lossy scramble: fails at
/// k = 1).
#[test]
fn first_4k_samples_stratify_every_2d_dimension() {
    for seed in [0u32, 9] {
        for px in PIXELS {
            for d in two_d_dims() {
                for first in [0u32, 1 << zsobol::EPOCH_LOG2] {
                    for k in 1..=4u32 {
                        let m = 2 * k;
                        let pts: Vec<Vec2> = (first..first + (1 << m))
                            .map(|s| sobol(seed, px, s).get_2d(d))
                            .collect();
                        for a in 0..=m {
                            let mut seen = vec![false; 1 << m];
                            for p in &pts {
                                let cx = (p.x * (1u32 << a) as f32) as u32;
                                let cy = (p.y * (1u32 << (m - a)) as f32) as u32;
                                let cell = ((cx << (m - a)) | cy) as usize;
                                assert!(
                                    !seen[cell],
                                    "seed {seed} pixel {px:?} dim {d} k {k} shape {a}: two points"
                                );
                                seen[cell] = true;
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The first `4^k` samples (k = 1…4) of a pixel put exactly one point in each interval
/// `[i/4^k, (i+1)/4^k)` in every 1-D dimension the integrator uses, also in a later epoch.
/// Deterministic. (Prefixes of `2^(2k+1)` samples are not stratified in 1-D: the index
/// permutation is base 4, as pbrt-v4's.) Catches the same bugs as the 2-D test (tried with the same
/// three at once: fails at k = 1).
#[test]
fn first_4k_samples_stratify_every_1d_dimension() {
    for seed in [0u32, 9] {
        for px in PIXELS {
            for d in one_d_dims() {
                for (first, m) in [0u32, 3 << zsobol::EPOCH_LOG2]
                    .into_iter()
                    .flat_map(|f| [2u32, 4, 6, 8].map(|m| (f, m)))
                {
                    let mut seen = vec![false; 1 << m];
                    for s in first..first + (1u32 << m) {
                        let v = sobol(seed, px, s).get_1d(d);
                        let cell = (v * (1u32 << m) as f32) as usize;
                        assert!(!seen[cell], "seed {seed} pixel {px:?} dim {d} m {m}");
                        seen[cell] = true;
                    }
                }
            }
        }
    }
}

/// Different dimensions are independent: for every pair (a, b), a ≠ b, of the 18 coordinates the
/// integrator draws at bounces 0 and 1 (each 1-D sample, each component of each 2-D sample), the
/// 4096 samples of one pixel binned on an 8×8 grid of (coordinate a, coordinate b) pass Pearson's
/// χ² against uniform (63 degrees of freedom), at family-wise α = 0.01 (Šidák over 153 pairs × 2
/// pixels × 2 seeds), seeds 3 and 4. Stratified margins make χ² smaller than for random points,
/// so the test is conservative; what it rejects is dependence: the critical value ≈ 121 (the
/// largest χ² measured is 110) is exceeded when every cell count is off by about ±11 of its 64
/// (χ² ≈ d² then). Catches dimensions that share an index permutation (tried: `index_for`
/// ignoring `dim`, so that dimensions differ only by their scrambles: χ² 28672, while both
/// stratification tests still pass).
#[test]
fn dimensions_are_pairwise_independent() {
    let coords = |s: &mut Sampler| -> Vec<f32> {
        let mut c = s.camera_2d().to_array().to_vec();
        for b in 0..2 {
            c.push(s.mixture_1d(b));
            c.push(s.light_select_1d(b));
            c.extend(s.light_2d(b).to_array());
            c.push(s.bsdf_lobe_1d(b));
            c.extend(s.bsdf_2d(b).to_array());
            c.push(s.rr_1d(b));
        }
        c
    };
    let (n, grid) = (4096u32, 8usize);
    let pairs = 18 * 17 / 2;
    let tests = pairs * 2 * 2;
    let alpha = sidak(0.01, tests);
    let mut worst = (0.0f64, String::new());
    for seed in [3u32, 4] {
        for px in [(2u32, 7u32), (300, 41)] {
            let samples: Vec<Vec<f32>> = (0..n).map(|s| coords(&mut sobol(seed, px, s))).collect();
            for a in 0..18 {
                for b in a + 1..18 {
                    let mut counts = vec![0u32; grid * grid];
                    for c in &samples {
                        let i = (c[a] * grid as f32) as usize;
                        let j = (c[b] * grid as f32) as usize;
                        counts[i * grid + j] += 1;
                    }
                    let expected = n as f64 / (grid * grid) as f64;
                    let chi2: f64 = counts
                        .iter()
                        .map(|&k| (k as f64 - expected).powi(2) / expected)
                        .sum();
                    let p = chi2_sf(chi2, (grid * grid - 1) as f64);
                    if chi2 > worst.0 {
                        worst = (chi2, format!("seed {seed} pixel {px:?} coords {a},{b}"));
                    }
                    assert!(
                        p > alpha,
                        "seed {seed} pixel {px:?}: coordinates {a} and {b} dependent: \
                         χ² {chi2:.1}, p {p:.2e} < {alpha:.2e}"
                    );
                }
            }
        }
    }
    eprintln!(
        "largest χ² {:.1} ({}), α per test {alpha:.2e}",
        worst.0, worst.1
    );
}

/// The same (seed, pixel, sample, dimension) always gives the same value, whatever else was
/// drawn before (the named dimensions are fixed, not a running counter), and different pixels,
/// samples and seeds differ.
#[test]
fn samples_are_a_function_of_seed_pixel_sample_and_dimension() {
    let mut a = sobol(1, (4, 4), 17);
    let mut b = sobol(1, (4, 4), 17);
    let _ = b.light_2d(0);
    let _ = b.rr_1d(5);
    assert_eq!(a.bsdf_2d(1), b.bsdf_2d(1));
    let v = sobol(1, (4, 4), 17).get_2d(dim::CAMERA);
    assert_ne!(v, sobol(1, (5, 4), 17).get_2d(dim::CAMERA));
    assert_ne!(v, sobol(1, (4, 4), 18).get_2d(dim::CAMERA));
    assert_ne!(v, sobol(2, (4, 4), 17).get_2d(dim::CAMERA));
    // The same position in another tile and another epoch are fresh randomisations.
    assert_ne!(v, sobol(1, (4 + 64, 4), 17).get_2d(dim::CAMERA));
    assert_ne!(v, sobol(1, (4, 4), 17 + 4096).get_2d(dim::CAMERA));
}

/// The independent sampler draws exactly the stream of [`Rng`], in call order, whatever the
/// dimension numbers: the renderer with it is bit for bit the renderer before samplers.
#[test]
fn independent_sampler_is_the_rng_stream() {
    let mut s = Sampler::new(SamplerKind::Independent, 5, 3, 2, 10, 7);
    let mut r = Rng::new(5, 23, 7);
    assert_eq!(s.camera_2d(), r.next_2d());
    assert_eq!(s.light_select_1d(4).to_bits(), r.next_f32().to_bits());
    assert_eq!(s.bsdf_2d(0), r.next_2d());
    assert_eq!(s.rr_1d(9).to_bits(), r.next_f32().to_bits());
}
