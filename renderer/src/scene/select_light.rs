//! Light selection for next-event estimation through the scene: the rule chosen by the
//! settings ([`LightSelection`]), dispatched over the closed set of selectors the scene holds.

use super::Scene;
use crate::lights::LightSelection;
use glam::Vec3;

impl Scene {
    /// Chooses a light for next-event estimation at a receiver `p` with shading normal `ns`
    /// (zero: none) by rule `selection`, from `u ∈ [0, 1)`: `(index, probability)`; `None` where
    /// nothing emits or (the BVH) nothing can reach `p`.
    #[inline]
    pub fn select_light(
        &self,
        selection: LightSelection,
        p: Vec3,
        ns: Vec3,
        u: f32,
    ) -> Option<(usize, f32)> {
        match selection {
            LightSelection::Power => self.light_sampler.as_ref().map(|s| s.sample(u)),
            LightSelection::Bvh => self.light_bvh.as_ref()?.sample(p, ns, u),
        }
    }

    /// The probability that [`Scene::select_light`] at `(p, ns)` chooses light `index` (for MIS
    /// weights of emission found by BSDF sampling; bit for bit the one it returns).
    #[inline]
    pub fn light_pmf(&self, selection: LightSelection, p: Vec3, ns: Vec3, index: usize) -> f32 {
        match selection {
            LightSelection::Power => self.light_sampler.as_ref().map_or(0.0, |s| s.pmf(index)),
            LightSelection::Bvh => self.light_bvh.as_ref().map_or(0.0, |b| b.pmf(p, ns, index)),
        }
    }
}
