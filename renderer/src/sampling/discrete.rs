//! Sampling an index in proportion to non-negative weights.

/// A discrete distribution: the CDF of non-negative weights, accumulated in f64 so that long
/// lists of lights with very different powers keep their small entries.
#[derive(Clone, Debug)]
pub struct DiscreteDistribution {
    /// `cdf[0] = 0`, `cdf[n] = 1`, non-decreasing; entry `i` owns `[cdf[i], cdf[i+1])`.
    cdf: Vec<f64>,
    /// Normalised weights.
    pmf: Vec<f32>,
}

impl DiscreteDistribution {
    /// Builds the distribution; `None` if any weight is negative or not finite, or they sum to 0.
    pub fn new(weights: &[f32]) -> Option<Self> {
        if weights.iter().any(|w| !(w.is_finite() && *w >= 0.0)) {
            return None;
        }
        let mut cdf = Vec::with_capacity(weights.len() + 1);
        let mut sum = 0.0f64;
        cdf.push(0.0);
        for &w in weights {
            sum += w as f64;
            cdf.push(sum);
        }
        if sum <= 0.0 {
            return None;
        }
        for c in &mut cdf {
            *c /= sum;
        }
        // sum/sum is exactly 1, so any u < 1 falls inside some entry.
        let pmf = weights.iter().map(|&w| (w as f64 / sum) as f32).collect();
        Some(DiscreteDistribution { cdf, pmf })
    }

    /// Number of entries (including zero-weight ones).
    pub fn len(&self) -> usize {
        self.pmf.len()
    }

    /// Whether there are no entries (never true for a successfully built distribution).
    pub fn is_empty(&self) -> bool {
        self.pmf.is_empty()
    }

    /// Probability of entry `i` (0 outside the range).
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }

    /// The CDF (`len() + 1` entries, the first 0, the last 1), for the GPU's f32 copy.
    pub(crate) fn cdf(&self) -> &[f64] {
        &self.cdf
    }

    /// Picks an entry for `u ∈ [0, 1)`: `(index, pmf, u remapped to [0, 1))`, the remapped value
    /// being uniform and independent of the choice, so it can drive a further sample.
    pub fn sample(&self, u: f32) -> (usize, f32, f32) {
        let u = (u as f64).clamp(0.0, 1.0 - f64::EPSILON);
        // Largest i with cdf[i] ≤ u. Since cdf[i] ≤ u < cdf[i+1], entry i has positive weight:
        // zero-weight entries own empty intervals and are never returned.
        let i = self.cdf[1..].partition_point(|&c| c <= u);
        let (lo, hi) = (self.cdf[i], self.cdf[i + 1]);
        let remapped = ((u - lo) / (hi - lo)) as f32;
        (i, self.pmf[i], remapped.min(super::ONE_MINUS_EPSILON))
    }

    /// Inverse of [`DiscreteDistribution::sample`]: the `u` that picks entry `i` with remapped
    /// value `remapped`.
    pub fn invert(&self, i: usize, remapped: f32) -> f32 {
        let (lo, hi) = (self.cdf[i], self.cdf[i + 1]);
        ((lo + remapped as f64 * (hi - lo)) as f32).min(super::ONE_MINUS_EPSILON)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    #[test]
    fn rejects_invalid_weights() {
        assert!(DiscreteDistribution::new(&[]).is_none());
        assert!(DiscreteDistribution::new(&[0.0, 0.0]).is_none());
        assert!(DiscreteDistribution::new(&[1.0, -0.5]).is_none());
        assert!(DiscreteDistribution::new(&[1.0, f32::NAN]).is_none());
        assert!(DiscreteDistribution::new(&[1.0, f32::INFINITY]).is_none());
    }

    #[test]
    fn pmf_sums_to_one_and_frequencies_match() {
        let w = [0.0, 3.0, 0.0, 1.0, 0.5, 0.0, 2.5, 0.0];
        let d = DiscreteDistribution::new(&w).unwrap();
        assert_eq!(d.len(), w.len());
        let total: f32 = (0..d.len()).map(|i| d.pmf(i)).sum();
        assert!((total - 1.0).abs() < 1e-6);
        let n = 200_000;
        let mut counts = [0u32; 8];
        let mut remapped_sum = 0.0f64;
        let mut rng = Rng::new(60, 0, 0);
        for _ in 0..n {
            let (i, pmf, ur) = d.sample(rng.next_f32());
            assert!(w[i] > 0.0, "zero-weight entry {i} chosen");
            assert_eq!(pmf, d.pmf(i));
            assert!((0.0..1.0).contains(&ur));
            remapped_sum += ur as f64;
            counts[i] += 1;
        }
        for i in 0..w.len() {
            let p = w[i] as f64 / 7.0;
            let sigma = (p * (1.0 - p) / n as f64).sqrt();
            // 5σ (binomial).
            assert!(
                (counts[i] as f64 / n as f64 - p).abs() <= 5.0 * sigma,
                "{counts:?}"
            );
        }
        // Remapped u is uniform: mean 1/2, std 1/√12 per sample; 5σ.
        assert!((remapped_sum / n as f64 - 0.5).abs() < 5.0 * 0.289 / (n as f64).sqrt());
    }

    #[test]
    fn zero_weights_never_chosen_at_the_boundaries() {
        let w = [0.0, 1.0, 0.0, 0.0, 1e-30, 0.0];
        let d = DiscreteDistribution::new(&w).unwrap();
        for u in [0.0, 1e-30, 0.5, 0.99999994, 1.0, -1.0, 2.0] {
            let (i, pmf, ur) = d.sample(u);
            assert!(w[i] > 0.0 && pmf > 0.0, "u = {u} chose {i}");
            assert!((0.0..1.0).contains(&ur));
        }
        // Exactly at an entry boundary the upper entry owns u.
        let d = DiscreteDistribution::new(&[1.0, 0.0, 1.0]).unwrap();
        assert_eq!(d.sample(0.5).0, 2);
        assert_eq!(d.sample(0.49999997).0, 0);
    }

    #[test]
    fn tiny_entries_survive_the_f64_cdf() {
        // In an f32 CDF, 1e-9 next to 1 would be lost.
        let d = DiscreteDistribution::new(&[1.0, 1e-9]).unwrap();
        assert!(d.pmf(1) > 0.0);
        assert_eq!(d.sample(0.99999994).0, 0);
    }
}
