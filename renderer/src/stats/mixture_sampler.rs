//! Adapter: the integrator's one-sample strategy mixture, `w·p_light + (1 − w)·p_bsdf`.

use super::domain::Domain;
use super::sampler::{DirectionSample, DirectionalSampler};
use glam::{Vec2, Vec3};

/// Samples `light` with probability `weight`, otherwise `bsdf`; the density is the mixture. Both
/// samplers must work in the same frame (put the receiver's shading frame on the world axes).
#[derive(Clone)]
pub struct Mixture<L, B> {
    /// The light-sampling strategy.
    pub light: L,
    /// The BSDF-sampling strategy.
    pub bsdf: B,
    /// Probability of sampling the light.
    pub weight: f32,
}

impl<L: DirectionalSampler, B: DirectionalSampler> DirectionalSampler for Mixture<L, B> {
    fn sample(&self, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        let w = self.weight;
        // Reuse u1 for the strategy's own choice after the mixture's, rescaled to [0, 1).
        let s = if u1 < w {
            self.light.sample(u1 / w, u2)?
        } else {
            let u = ((u1 - w) / (1.0 - w)).min(crate::sampling::ONE_MINUS_EPSILON);
            self.bsdf.sample(u, u2)?
        };
        if s.delta {
            return Some(s);
        }
        // The chosen strategy's own reported pdf, the other's evaluated: what the integrator
        // divides by.
        let pdf = if u1 < w {
            w * s.pdf + (1.0 - w) * self.bsdf.pdf(s.w)
        } else {
            (1.0 - w) * s.pdf + w * self.light.pdf(s.w)
        };
        Some(DirectionSample { pdf, ..s })
    }

    fn pdf(&self, w: Vec3) -> f32 {
        let (pl, pb) = if self.weight > 0.0 && self.weight < 1.0 {
            (self.light.pdf(w), self.bsdf.pdf(w))
        } else if self.weight >= 1.0 {
            (self.light.pdf(w), 0.0)
        } else {
            (0.0, self.bsdf.pdf(w))
        };
        self.weight * pl + (1.0 - self.weight) * pb
    }

    /// The light's domain when it is sampled always; the whole sphere otherwise.
    fn domain(&self) -> Domain {
        if self.weight >= 1.0 {
            self.light.domain()
        } else if self.weight <= 0.0 {
            self.bsdf.domain()
        } else {
            Domain::sphere()
        }
    }
}
