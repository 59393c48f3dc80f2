//! Chooses a light in proportion to its emitted power.
//!
//! A textured emitter is weighed as if it emitted its [`selection_radiance`]: the texture's
//! mean over the unit uv square (so an emitting mesh's triangle weighs area × mean luminance,
//! whatever part of the texture its texture coordinates cover), or the texture's maximum where
//! that mean is black (a texture black over the unit square may still emit where a mesh's
//! texture coordinates leave it). Any weight that is positive wherever the light emits keeps
//! light sampling unbiased: the estimators divide by the same probability the sampler used, and
//! the radiance at the sampled point is the texture's there. The weight only sets how often a
//! light is picked; a texture that is zero on part of its shape just wastes those samples.
//! WGSL twin: `lights/light_sampler.wgsl` and `lights/mod.wgsl`.

use super::Light;
use crate::sampling::DiscreteDistribution;
use crate::textures::Texture;
use glam::Vec3;

/// The radiance a light emitting `texture` is weighed as, in light selection and
/// [`Light::power`] (see the module doc): the texture's mean over the unit square, or its maximum
/// where the mean has no luminance. Positive wherever the texture is positive somewhere.
pub fn selection_radiance(texture: &Texture) -> Vec3 {
    let mean = texture.mean();
    if crate::math::luminance(mean) > 0.0 {
        mean
    } else {
        texture.max()
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::textures::{Checkerboard, UvTransform};
    use glam::Vec2;

    /// The mean where it has luminance, the maximum where the unit square is black.
    #[test]
    fn selection_radiance_is_the_mean_or_else_the_maximum() {
        let c0 = Vec3::new(3.0, 1.0, 0.0);
        let checker = |scale: Vec2, offset: Vec2| {
            Texture::Checkerboard(Checkerboard {
                color0: c0,
                color1: Vec3::ZERO,
                uv: UvTransform { scale, offset },
            })
        };
        let half = checker(Vec2::ONE, Vec2::ZERO);
        assert_eq!(selection_radiance(&half), half.mean());
        assert_eq!(half.mean(), 0.5 * c0);
        // uv' = (0.75, 0.25) everywhere: color1 (black) over the whole unit square.
        let black = checker(Vec2::ZERO, Vec2::new(0.75, 0.25));
        assert_eq!(black.mean(), Vec3::ZERO);
        assert_eq!(selection_radiance(&black), c0);
    }
}
