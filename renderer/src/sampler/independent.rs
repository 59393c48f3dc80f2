//! The independent sampler: today's counter-based PCG stream ([`crate::rng::Rng`]) per (seed,
//! pixel, sample), drawn in call order. It ignores the dimension numbers, so the renderer with it
//! consumes exactly the numbers it consumed before samplers existed, bit for bit.

use crate::rng::Rng;
use glam::Vec2;

/// Independent uniforms from one [`Rng`] stream.
#[derive(Clone, Debug)]
pub struct IndependentSampler {
    rng: Rng,
}

impl IndependentSampler {
    /// The stream of sample `sample` of the pixel with row-major index `pixel`.
    pub fn new(seed: u32, pixel: u32, sample: u32) -> IndependentSampler {
        IndependentSampler {
            rng: Rng::new(seed, pixel, sample),
        }
    }

    /// Wraps an existing stream.
    pub fn from_rng(rng: Rng) -> IndependentSampler {
        IndependentSampler { rng }
    }

    /// The next uniform (the dimension is not used).
    #[inline]
    pub fn get_1d(&mut self) -> f32 {
        self.rng.next_f32()
    }

    /// The next two uniforms (the dimension is not used).
    #[inline]
    pub fn get_2d(&mut self) -> Vec2 {
        self.rng.next_2d()
    }
}
