//! Error metrics and the statistical image test used against reference renders.

use glam::Vec3;

/// Mean over pixels and channels of `(a − b)² / (b² + 0.01)`.
pub fn relmse(img: &[Vec3], reference: &[Vec3]) -> f64 {
    assert_eq!(img.len(), reference.len());
    let mut s = 0.0f64;
    for (a, b) in img.iter().zip(reference) {
        for c in 0..3 {
            let (a, b) = (a[c] as f64, b[c] as f64);
            s += (a - b) * (a - b) / (b * b + 0.01);
        }
    }
    s / (3 * img.len()) as f64
}

/// Root of the mean over pixels and channels of `(a − b)²`.
pub fn rmse(img: &[Vec3], reference: &[Vec3]) -> f64 {
    assert_eq!(img.len(), reference.len());
    let s: f64 = img
        .iter()
        .zip(reference)
        .map(|(a, b)| (0..3).map(|c| ((a[c] - b[c]) as f64).powi(2)).sum::<f64>())
        .sum();
    (s / (3 * img.len()) as f64).sqrt()
}

/// Standard normal upper tail `P(Z > z)`.
pub fn normal_sf(z: f64) -> f64 {
    0.5 * libm::erfc(z / std::f64::consts::SQRT_2)
}

/// The `z` with `P(|Z| > z) = alpha` (two-sided), by bisection on [`normal_sf`].
pub fn normal_two_sided_critical(alpha: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 40.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if 2.0 * normal_sf(mid) > alpha {
            lo = mid
        } else {
            hi = mid
        }
    }
    0.5 * (lo + hi)
}

/// Per-test significance for `m` tests so that the family-wise rate is `alpha` (Šidák).
pub fn sidak(alpha: f64, m: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / m as f64)
}

/// One block of the block test.
#[derive(Clone, Copy, Debug)]
pub struct BlockResult {
    /// Top-left pixel.
    pub x: u32,
    /// Top-left pixel.
    pub y: u32,
    /// Channel.
    pub channel: usize,
    /// Block mean of the image under test.
    pub mean: f64,
    /// Block mean of the reference.
    pub reference: f64,
    /// `(mean − reference) / sqrt(var + var_ref)`.
    pub z: f64,
}

/// Outcome of [`block_z_test`].
#[derive(Clone, Debug)]
pub struct BlockTest {
    /// Every block and channel.
    pub blocks: Vec<BlockResult>,
    /// `|z|` above which a block fails (Šidák-corrected).
    pub critical: f64,
}

impl BlockTest {
    /// Blocks whose `|z|` exceeds the critical value.
    pub fn failures(&self) -> Vec<BlockResult> {
        self.blocks
            .iter()
            .copied()
            .filter(|b| b.z.abs() > self.critical)
            .collect()
    }

    /// The block with the largest `|z|`.
    pub fn worst(&self) -> Option<BlockResult> {
        self.blocks
            .iter()
            .copied()
            .max_by(|a, b| a.z.abs().total_cmp(&b.z.abs()))
    }
}

/// Inputs of the block test: an image with the variance of each pixel's mean.
pub struct ImageWithVariance<'a> {
    /// Pixel means.
    pub mean: &'a [Vec3],
    /// Variance of each pixel mean, per channel.
    pub var: &'a [[f64; 3]],
}

/// Compares two independent unbiased estimates of the same image, block by block and channel by
/// channel: the block means' difference divided by its standard deviation (the sum of both images'
/// per-pixel variances over the block, divided by the pixel count²) is a z-score. Blocks are
/// `block`×`block` pixels (partial blocks at the right and bottom edges are kept); the family-wise
/// significance `alpha` is Šidák-corrected over all blocks and channels. Blocks where both variances
/// are 0 (e.g. black in both) compare exactly.
pub fn block_z_test(
    width: u32,
    height: u32,
    a: &ImageWithVariance,
    b: &ImageWithVariance,
    block: u32,
    alpha: f64,
) -> BlockTest {
    let mut blocks = Vec::new();
    for by in (0..height).step_by(block as usize) {
        for bx in (0..width).step_by(block as usize) {
            for c in 0..3 {
                let (mut sa, mut sb, mut va, mut vb, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0f64);
                for y in by..by.saturating_add(block).min(height) {
                    for x in bx..bx.saturating_add(block).min(width) {
                        let i = (y * width + x) as usize;
                        sa += a.mean[i][c] as f64;
                        sb += b.mean[i][c] as f64;
                        va += a.var[i][c];
                        vb += b.var[i][c];
                        n += 1.0;
                    }
                }
                let (ma, mb) = (sa / n, sb / n);
                let sd = ((va + vb) / (n * n)).sqrt();
                let z = if sd > 0.0 {
                    (ma - mb) / sd
                } else if (ma - mb).abs() <= 1e-6 * ma.abs().max(mb.abs()) {
                    0.0
                } else {
                    f64::INFINITY
                };
                blocks.push(BlockResult {
                    x: bx,
                    y: by,
                    channel: c,
                    mean: ma,
                    reference: mb,
                    z,
                });
            }
        }
    }
    let critical = normal_two_sided_critical(sidak(alpha, blocks.len()));
    BlockTest { blocks, critical }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn critical_values() {
        assert!((normal_two_sided_critical(0.05) - 1.959964).abs() < 1e-5);
        assert!((normal_two_sided_critical(0.01) - 2.575829).abs() < 1e-5);
        assert!((sidak(0.01, 1) - 0.01).abs() < 1e-15);
    }

    #[test]
    fn metrics_basics() {
        let a = vec![Vec3::new(1.0, 2.0, 3.0); 4];
        let b = vec![Vec3::new(1.0, 2.0, 2.0); 4];
        assert_eq!(relmse(&a, &a), 0.0);
        assert!((relmse(&a, &b) - (1.0 / 4.01) / 3.0).abs() < 1e-9);
        assert!((rmse(&a, &b) - (1.0f64 / 3.0).sqrt()).abs() < 1e-7);
    }

    /// Same-mean noise passes; a 2% bias with the same noise fails.
    #[test]
    fn block_test_detects_bias_and_accepts_noise() {
        let (w, h) = (64u32, 64u32);
        let sigma = 0.05f32; // per-pixel std of the mean
        let mut rng = Rng::new(5, 0, 0);
        let mut noisy = |bias: f32| -> Vec<Vec3> {
            (0..w * h)
                .map(|_| {
                    // sum of 12 uniforms − 6 ≈ N(0, 1)
                    let mut g = || (0..12).map(|_| rng.next_f32()).sum::<f32>() - 6.0;
                    Vec3::new(
                        1.0 + bias + sigma * g(),
                        1.0 + bias + sigma * g(),
                        1.0 + bias + sigma * g(),
                    )
                })
                .collect()
        };
        let var = vec![[(sigma * sigma) as f64; 3]; (w * h) as usize];
        let reference = noisy(0.0);
        let same = noisy(0.0);
        let biased = noisy(0.02);
        let r = ImageWithVariance {
            mean: &reference,
            var: &var,
        };
        let ok = block_z_test(
            w,
            h,
            &ImageWithVariance {
                mean: &same,
                var: &var,
            },
            &r,
            32,
            0.01,
        );
        assert!(ok.failures().is_empty(), "{:?}", ok.worst());
        let bad = block_z_test(
            w,
            h,
            &ImageWithVariance {
                mean: &biased,
                var: &var,
            },
            &r,
            32,
            0.01,
        );
        assert_eq!(bad.failures().len(), bad.blocks.len());
    }
}
