//! What the χ² test needs from a sampling routine: draw a direction, and evaluate the density it
//! claims for any direction.

use super::domain::Domain;
use glam::{Vec2, Vec3};

/// One direction drawn by a [`DirectionalSampler`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionSample {
    /// The direction (unit length).
    pub w: Vec3,
    /// The solid-angle pdf the routine reports for `w` (for a delta sample, its discrete
    /// probability).
    pub pdf: f32,
    /// True for a sample from a delta lobe: it has no density, so the histogram skips it and the
    /// expected counts cover only the non-delta mass.
    pub delta: bool,
}

/// A routine that samples directions with a known solid-angle density: the object the χ² test
/// checks. `pdf` must be the density of the non-delta samples `sample` returns; the samples that
/// `sample` rejects (`None`) or draws from delta lobes make `∫pdf` less than 1.
pub trait DirectionalSampler: Sync {
    /// Draws a direction from the uniforms `u1` (e.g. a lobe or strategy choice) and `u2`;
    /// `None` when the routine produces no sample.
    fn sample(&self, u1: f32, u2: Vec2) -> Option<DirectionSample>;

    /// The `index`-th draw of a test, from its uniforms `u1`, `u2`: [`Self::sample`] for a
    /// routine that runs here; samples computed beforehand look theirs up by position
    /// ([`crate::stats::Precomputed`]).
    fn sample_at(&self, index: usize, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        let _ = index;
        self.sample(u1, u2)
    }

    /// Solid-angle density of the non-delta samples at unit direction `w`.
    fn pdf(&self, w: Vec3) -> f32;

    /// Where to histogram: the whole sphere by default; adapters with concentrated densities
    /// (narrow lobes, small lights) override this to zoom in on them.
    fn domain(&self) -> Domain {
        Domain::sphere()
    }

    /// Whether `sample` answers any uniforms, so that a χ² test can draw again with another
    /// seed and count (its protocol's second stage, [`crate::stats::ChiSquareTest::run`]);
    /// samples computed beforehand for one seed cannot.
    fn can_resample(&self) -> bool {
        true
    }
}

impl<S: DirectionalSampler + ?Sized> DirectionalSampler for Box<S> {
    fn sample(&self, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        (**self).sample(u1, u2)
    }
    fn sample_at(&self, index: usize, u1: f32, u2: Vec2) -> Option<DirectionSample> {
        (**self).sample_at(index, u1, u2)
    }
    fn pdf(&self, w: Vec3) -> f32 {
        (**self).pdf(w)
    }
    fn domain(&self) -> Domain {
        (**self).domain()
    }
    fn can_resample(&self) -> bool {
        (**self).can_resample()
    }
}
