//! Adapter: samples computed elsewhere — by the GPU backend's WGSL sampling functions — for
//! exactly the uniforms a χ² test will draw ([`drawn_uniforms`]), checked against the density of a
//! reference adapter (the Rust twin's pdf and histogram domain). The χ² test then judges the
//! distribution of the GPU's samples, not the CPU's.

use super::chi2::drawn_uniforms;
use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use glam::{Vec2, Vec3};

/// Samples looked up by their position in the test's draws, each stored with the uniforms it
/// was computed for, so that a lookup for other uniforms is caught; `pdf` and `domain` from
/// `density`. (They were looked up by their uniforms in a hash map before: hashing and probing
/// half a million keys per case was a fifth of the GPU χ² test's time, 2026-12-08.)
pub struct Precomputed<D> {
    samples: Vec<([u32; 3], Option<DirectionSample>)>,
    /// The density the samples are tested against.
    pub density: D,
}

/// The uniform pair's exact bits.
fn key(u1: f32, u2: Vec2) -> [u32; 3] {
    [u1.to_bits(), u2.x.to_bits(), u2.y.to_bits()]
}

impl<D: DirectionalSampler> Precomputed<D> {
    /// Computes the samples of a test with `seed` and `sample_count` samples with `compute`,
    /// which gets every uniform pair the test will draw, in order, and returns one result each
    /// (`None`: no sample).
    pub fn new(
        density: D,
        seed: u32,
        sample_count: usize,
        compute: impl FnOnce(&[(f32, Vec2)]) -> Vec<Option<DirectionSample>>,
    ) -> Precomputed<D> {
        let uniforms = drawn_uniforms(seed, sample_count);
        let results = compute(&uniforms);
        assert_eq!(results.len(), uniforms.len(), "one result per uniform pair");
        let samples = uniforms
            .iter()
            .zip(results)
            .map(|(&(u1, u2), s)| (key(u1, u2), s))
            .collect();
        Precomputed { samples, density }
    }
}

impl<D: DirectionalSampler> DirectionalSampler for Precomputed<D> {
    /// Only draws by position have samples here ([`Self::sample_at`]).
    fn sample(&self, _u1: f32, _u2: Vec2) -> Option<DirectionSample> {
        panic!("precomputed samples are drawn by position (sample_at)")
    }

    /// The precomputed sample; other uniforms at that position (a test with another seed or
    /// count) are a bug in the caller.
    fn sample_at(&self, index: usize, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        match self.samples.get(index) {
            Some((k, s)) if *k == key(u1, u2) => *s,
            _ => panic!("uniforms not precomputed: same seed and sample count as the test?"),
        }
    }

    fn pdf(&self, w: Vec3) -> f32 {
        self.density.pdf(w)
    }

    fn domain(&self) -> Domain {
        self.density.domain()
    }

    /// Only the precomputed uniforms have samples: no second stage.
    fn can_resample(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{ChiSquareTest, Warp};

    /// Precomputing the CPU's own samples reproduces the direct test exactly, and precomputed
    /// samples from another distribution are rejected: the adapter passes samples through
    /// unchanged and nothing else.
    #[test]
    fn precomputed_samples_are_what_the_test_sees() {
        let n = 200_000;
        let direct = ChiSquareTest::new(&Warp::CosineHemisphere)
            .samples(n)
            .seed(3)
            .run();
        let same = Precomputed::new(Warp::CosineHemisphere, 3, n, |us| {
            us.iter()
                .map(|&(u1, u2)| Warp::CosineHemisphere.sample(u1, u2))
                .collect()
        });
        let via = ChiSquareTest::new(&same).samples(n).seed(3).run();
        assert_eq!(direct.p_value, via.p_value);
        assert!(via.passed());
        let other = Precomputed::new(Warp::CosineHemisphere, 3, n, |us| {
            us.iter()
                .map(|&(u1, u2)| {
                    Warp::UniformSphere.sample(u1, u2).map(|mut s| {
                        s.w.z = s.w.z.abs();
                        s
                    })
                })
                .collect()
        });
        assert!(!ChiSquareTest::new(&other).samples(n).seed(3).run().passed());
    }
}
