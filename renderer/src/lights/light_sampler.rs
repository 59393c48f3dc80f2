//! Chooses a light in proportion to its emitted power.
//! WGSL twin: `light_sampler.wgsl` and `light.wgsl`.

use super::Light;
use crate::sampling::DiscreteDistribution;

/// Power-proportional light selection.
#[derive(Clone, Debug)]
pub struct LightSampler {
    dist: DiscreteDistribution,
}

impl LightSampler {
    /// `None` if no light has power.
    pub fn new(lights: &[Light]) -> Option<LightSampler> {
        let powers: Vec<f32> = lights.iter().map(|l| l.power().max(0.0)).collect();
        DiscreteDistribution::new(&powers).map(|dist| LightSampler { dist })
    }

    /// Picks a light: `(index, probability)`.
    #[inline]
    pub fn sample(&self, u: f32) -> (usize, f32) {
        let (i, pmf, _) = self.dist.sample(u);
        (i, pmf)
    }

    /// Probability of picking light `i`.
    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.dist.pmf(i)
    }
}
