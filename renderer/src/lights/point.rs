//! Point lights, Mitsuba 3.9.1's `point`: a position and an intensity `I` (radiant intensity,
//! the same in every direction). A receiver at distance `d` gets radiance `I / d²` from the one
//! direction towards the light — a delta in position, so next-event estimation is the only
//! technique that finds it: the sample is that direction with "pdf" 1 (the delta's weight), and
//! BSDF sampling never hits it ([`super::Light::is_delta`] says so to the integrator).
//! WGSL twin: `lights/point.wgsl`.

use super::LightSample;
use glam::{Vec2, Vec3};

/// A point light.
#[derive(Clone, Debug)]
pub struct PointLight {
    /// Where it is.
    pub position: Vec3,
    /// Radiant intensity per channel, ≥ 0.
    pub intensity: Vec3,
}

impl PointLight {
    /// The direction from `p` towards the light, with the radiance `I / d²` arriving along it;
    /// `None` at the light's own position.
    pub fn sample(&self, p: Vec3) -> Option<LightSample> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        // Also rejects NaN.
        if dist2.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        Some(delta_sample(
            self.position,
            d / dist2.sqrt(),
            self.intensity / dist2,
            Vec2::ZERO,
        ))
    }

    /// Emitted power `4π I` (luminance).
    pub fn power(&self) -> f32 {
        4.0 * std::f32::consts::PI * crate::math::luminance(self.intensity)
    }
}

/// The sample of a light at point `y` (a delta in position) seen along the unit direction `wi`,
/// with radiance `le` arriving and texture coordinates `uv` (for a textured spot or projector):
/// "pdf" 1, no normal, no position error (the point is exact and on no surface).
#[inline]
pub(crate) fn delta_sample(y: Vec3, wi: Vec3, le: Vec3, uv: Vec2) -> LightSample {
    LightSample {
        p: y,
        p_error: Vec3::ZERO,
        n: Vec3::ZERO,
        wi,
        pdf: 1.0,
        le,
        infinite: false,
        b: uv,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `I / d²` along the direction to the light, whatever the distance; nothing at the light.
    #[test]
    fn radiance_falls_off_as_the_inverse_square() {
        let l = PointLight {
            position: Vec3::new(1.0, 2.0, 3.0),
            intensity: Vec3::new(4.0, 2.0, 1.0),
        };
        for d in [0.5f32, 1.0, 3.0, 100.0] {
            let p = l.position - Vec3::new(0.0, 0.0, d);
            let s = l.sample(p).unwrap();
            assert_eq!(s.wi, Vec3::Z);
            assert_eq!(s.pdf, 1.0);
            let want = l.intensity / (d * d);
            assert!(
                (s.le - want).abs().max_element() <= 1e-6 * want.max_element(),
                "{d}"
            );
        }
        assert!(l.sample(l.position).is_none());
    }
}
