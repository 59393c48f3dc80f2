//! Samplers: where each random number of a path sample comes from.
//!
//! * [`Sampler::Independent`] ([`independent`]): independent uniforms from the counter-based PCG
//!   stream of (seed, pixel, sample), bit for bit what the renderer drew before samplers existed.
//! * [`Sampler::ZSobol`] ([`zsobol`]): Owen-scrambled Sobol points, pixels in Morton order, every
//!   dimension with its own hashed index permutation and scramble; helpers in [`sobol`],
//!   [`owen`] and [`morton`].
//!
//! The integrator asks for numbers by name ([`Sampler::camera_2d`], [`Sampler::light_2d`], …),
//! and each name is a fixed *dimension*, so that dimension `d` of sample `s` is the same point
//! whatever the strategy or the path did before (a dimension a path does not use is skipped, not
//! shifted onto the next one). The independent sampler ignores the numbers and draws in call
//! order. Allocation (a 2-D sample takes two dimensions; bounce `b` = path vertex `b + 1`,
//! counting from 0 at the first hit):
//!
//! | dimension | use | drawn by |
//! |---|---|---|
//! | 0–1 | film position (the pixel filter's 2-D sample) | [`Sampler::camera_2d`] |
//! | 2 + 8b | one-sample mixture: light or BSDF branch | [`Sampler::mixture_1d`] |
//! | 3 + 8b | light selection | [`Sampler::light_select_1d`] |
//! | 4 + 8b, 5 + 8b | point on the light | [`Sampler::light_2d`] |
//! | 6 + 8b | BSDF lobe choice | [`Sampler::bsdf_lobe_1d`] |
//! | 7 + 8b, 8 + 8b | BSDF direction | [`Sampler::bsdf_2d`] |
//! | 9 + 8b | Russian roulette | [`Sampler::rr_1d`] |
//! | 2³² − 2, 2³² − 1 | the thin lens's point on the lens | [`Sampler::lens_2d`] |
//!
//! The lens takes the last two dimensions rather than 2–3, which would have moved every bounce's
//! dimensions and so changed every pinhole image; the bounce dimensions reach them only after
//! 2²⁹ bounces (a dimension is a hash key, not a table index, so its size costs nothing).
//!
//! **Sample counts.** The ZSobol layout gives each pixel a block of 2^12 = 4096 indices
//! ([`zsobol::EPOCH_LOG2`]), independent of the requested spp, so that sample `s` of pixel `p`
//! is the same point in every render: a `--sample-range` part, a progressive render stopped at any
//! pass, and a viewer that keeps going beyond any planned count all draw the same samples, and
//! the image is a function of the seed and the spp only. The first `4^k` samples of a pixel form a
//! (0, 2k, 2)-net in every 2-D dimension pair and are stratified in `4^k` intervals in every
//! 1-D dimension (the index permutation is base 4, as pbrt-v4's, so odd powers of two are
//! stratified only in 2-D); an spp that is not a power of four is a prefix of a net, still
//! unbiased (every point is uniformly distributed) but only partly stratified. Beyond 4096 samples a new epoch starts with an independent scramble: the error then
//! falls like that of independent replicates of 4096-point nets. The cost of this fixed layout:
//! pbrt-v4 sizes the block to the planned spp, so that at that spp neighbouring pixels' samples
//! together form one net (blue-noise error); here that holds only at 4096 spp.
//!
//! **Tests and QMC.** The image tests' block z-test uses the per-pixel sample variance, which for
//! scrambled nets overestimates the error of the mean (the samples are negatively correlated), so
//! the test is conservative for noise but still detects bias (`renderer/tests/sobol_sampler.rs`).
//!
//! **GPU.** Both samplers run on the GPU backend too, bit for bit: the sampler's tag travels in
//! the per-dispatch parameters ([`crate::gpu::scene::SamplerTag`]) and `sampler/mod.wgsl` switches on
//! it (`renderer/tests/gpu/parity_sampler.rs` compares every named dimension; `renderer/tests/gpu/sobol_images.rs`
//! whole renders).
//! WGSL twin: `sampler/mod.wgsl`.

pub mod independent;
pub mod morton;
pub mod owen;
pub mod sobol;
pub mod zsobol;

#[cfg(test)]
mod zsobol_tests;

pub use independent::IndependentSampler;
pub use zsobol::ZSobolSampler;

use crate::rng::Rng;
use glam::Vec2;

/// Which sampler a render uses (a [`crate::integrator::Settings`] field).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SamplerKind {
    /// Independent uniforms (the PCG stream per sample).
    #[default]
    Independent,
    /// Owen-scrambled Sobol, Morton-ordered pixels.
    Sobol,
}

impl SamplerKind {
    /// The name as the CLI spells it.
    pub fn name(&self) -> &'static str {
        match self {
            SamplerKind::Independent => "independent",
            SamplerKind::Sobol => "sobol",
        }
    }
}

/// The sampler's named dimensions (see the module's table).
pub mod dim {
    /// Film position (2-D).
    pub const CAMERA: u32 = 0;
    /// First dimension of bounce 0.
    pub const FIRST_BOUNCE: u32 = 2;
    /// Dimensions per bounce.
    pub const PER_BOUNCE: u32 = 8;
    /// Offset of the mixture's branch choice within a bounce.
    pub const MIXTURE: u32 = 0;
    /// Offset of light selection.
    pub const LIGHT_SELECT: u32 = 1;
    /// Offset of the point on the light (2-D).
    pub const LIGHT: u32 = 2;
    /// Offset of the BSDF lobe choice.
    pub const BSDF_LOBE: u32 = 4;
    /// Offset of the BSDF direction (2-D).
    pub const BSDF: u32 = 5;
    /// Offset of Russian roulette.
    pub const RR: u32 = 7;
    /// The thin lens's point on the lens (2-D): the last two dimensions (see the table above).
    pub const LENS: u32 = u32::MAX - 1;

    /// The dimension of `offset` at bounce `bounce` (wrapping after 2^29 bounces).
    #[inline]
    pub fn at(bounce: u32, offset: u32) -> u32 {
        FIRST_BOUNCE
            .wrapping_add(bounce.wrapping_mul(PER_BOUNCE))
            .wrapping_add(offset)
    }
}

/// The random numbers of one sample of one pixel.
#[derive(Clone, Debug)]
pub enum Sampler {
    /// Independent uniforms.
    Independent(IndependentSampler),
    /// Owen-scrambled Sobol.
    ZSobol(ZSobolSampler),
}

impl From<Rng> for Sampler {
    /// The independent sampler drawing from `rng`.
    fn from(rng: Rng) -> Sampler {
        Sampler::Independent(IndependentSampler::from_rng(rng))
    }
}

impl Sampler {
    /// Sample `sample` of pixel `(x, y)` of an image `width` pixels wide.
    pub fn new(kind: SamplerKind, seed: u32, x: u32, y: u32, width: u32, sample: u32) -> Sampler {
        match kind {
            SamplerKind::Independent => Sampler::Independent(IndependentSampler::new(
                seed,
                y.wrapping_mul(width).wrapping_add(x),
                sample,
            )),
            SamplerKind::Sobol => Sampler::ZSobol(ZSobolSampler::new(seed, x, y, sample)),
        }
    }

    /// The 1-D sample of dimension `dim`.
    #[inline]
    pub fn get_1d(&mut self, dim: u32) -> f32 {
        match self {
            Sampler::Independent(s) => s.get_1d(),
            Sampler::ZSobol(s) => s.get_1d(dim),
        }
    }

    /// The 2-D sample of dimensions `dim` and `dim + 1`.
    #[inline]
    pub fn get_2d(&mut self, dim: u32) -> Vec2 {
        match self {
            Sampler::Independent(s) => s.get_2d(),
            Sampler::ZSobol(s) => s.get_2d(dim),
        }
    }

    /// The film position's 2-D sample.
    #[inline]
    pub fn camera_2d(&mut self) -> Vec2 {
        self.get_2d(dim::CAMERA)
    }

    /// The thin lens's 2-D sample (the point on the lens), drawn after the film position.
    #[inline]
    pub fn lens_2d(&mut self) -> Vec2 {
        self.get_2d(dim::LENS)
    }

    /// The one-sample mixture's branch choice at bounce `bounce`.
    #[inline]
    pub fn mixture_1d(&mut self, bounce: u32) -> f32 {
        self.get_1d(dim::at(bounce, dim::MIXTURE))
    }

    /// Light selection at bounce `bounce`.
    #[inline]
    pub fn light_select_1d(&mut self, bounce: u32) -> f32 {
        self.get_1d(dim::at(bounce, dim::LIGHT_SELECT))
    }

    /// The point on the light at bounce `bounce`.
    #[inline]
    pub fn light_2d(&mut self, bounce: u32) -> Vec2 {
        let d = if crate::mutants::sampler_light_reuses_camera() {
            dim::CAMERA
        } else {
            dim::at(bounce, dim::LIGHT)
        };
        self.get_2d(d)
    }

    /// The BSDF lobe choice at bounce `bounce`.
    #[inline]
    pub fn bsdf_lobe_1d(&mut self, bounce: u32) -> f32 {
        self.get_1d(dim::at(bounce, dim::BSDF_LOBE))
    }

    /// The BSDF direction at bounce `bounce`.
    #[inline]
    pub fn bsdf_2d(&mut self, bounce: u32) -> Vec2 {
        let bounce = if crate::mutants::sampler_bounces_share_dimensions() {
            0
        } else {
            bounce
        };
        self.get_2d(dim::at(bounce, dim::BSDF))
    }

    /// Russian roulette at bounce `bounce`.
    #[inline]
    pub fn rr_1d(&mut self, bounce: u32) -> f32 {
        self.get_1d(dim::at(bounce, dim::RR))
    }
}
