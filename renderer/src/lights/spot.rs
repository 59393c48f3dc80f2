//! Spot lights, Mitsuba 3.9.1's `spot`: a point light whose intensity `I` is shaped by a cone
//! about its axis — full within `beam_width` of the axis, falling linearly in angle to zero at
//! `cutoff_angle` (Mitsuba's `falloff_curve`; nothing at or beyond the cutoff), and optionally
//! modulated by a texture projected through the plane one unit along the axis, spanning
//! `[0, 1]²` at the cutoff (Mitsuba's `direction_to_uv`). A delta in position, sampled as
//! [`super::point`] is: the direction to the light with "pdf" 1.
//!
//! The light's frame is Mitsuba's `to_world` (made by `look_at`): `s` its local +x (`up × axis`,
//! to the left looking along the axis), `t` its local +y, `n` the axis. A textured spot's `le`
//! leaves the texture out; [`crate::scene::Scene::sample_light`] multiplies by it at the sample's
//! texture coordinates (`LightSample::b`).
//! WGSL twin: `lights/spot.wgsl`.

use super::LightSample;
use super::point::delta_sample;
use crate::geometry::primitive::NONE;
use crate::math::Frame;
use glam::{Vec2, Vec3};

/// A spot light.
#[derive(Clone, Debug)]
pub struct SpotLight {
    /// Where it is.
    pub position: Vec3,
    /// The light's frame (local x, y and the axis).
    pub frame: Frame,
    /// Radiant intensity on the axis, per channel (≥ 0).
    pub intensity: Vec3,
    /// The cutoff angle, in radians, in (0, π].
    pub cutoff: f32,
    /// cos of the cutoff angle.
    pub cos_cutoff: f32,
    /// cos of the beam width.
    pub cos_beam: f32,
    /// 1 / (cutoff − beam width) (infinite for a hard edge: then never used).
    pub inv_transition: f32,
    /// tan(cutoff): the texture spans `[-tan, tan]²` on the plane z = 1.
    pub uv_factor: f32,
    /// The texture's selection radiance (its mean, [`super::light_sampler::selection_radiance`];
    /// one without a texture), for the light's power.
    pub selection: Vec3,
    /// Emission texture ([`super::Light::texture`]), [`NONE`] for none.
    pub texture: u32,
}

impl SpotLight {
    /// A spot at `position` with frame `frame`, intensity `intensity`, cutoff and beam width in
    /// radians (`0 ≤ beam_width ≤ cutoff ≤ π`, `cutoff > 0`: the parser's rule).
    pub fn new(
        position: Vec3,
        frame: Frame,
        intensity: Vec3,
        cutoff: f32,
        beam_width: f32,
    ) -> SpotLight {
        SpotLight {
            position,
            frame,
            intensity,
            cutoff,
            cos_cutoff: cutoff.cos(),
            cos_beam: beam_width.cos(),
            inv_transition: 1.0 / (cutoff - beam_width),
            uv_factor: cutoff.tan(),
            selection: Vec3::ONE,
            texture: NONE,
        }
    }

    /// The falloff in [0, 1] towards `local` (a direction in the light's frame, any length):
    /// 1 within the beam, `(cutoff − θ) / (cutoff − beam)` beyond it, 0 from the cutoff on.
    #[inline]
    pub fn falloff(&self, local: Vec3) -> f32 {
        let cos_theta = local.normalize().z;
        // Also rejects NaN (a zero direction).
        if cos_theta.partial_cmp(&self.cos_cutoff) != Some(std::cmp::Ordering::Greater) {
            return 0.0;
        }
        if cos_theta >= self.cos_beam {
            1.0
        } else {
            (self.cutoff - cos_theta.acos()) * self.inv_transition
        }
    }

    /// The texture coordinates of `local` (in front of the light).
    #[inline]
    pub fn uv(&self, local: Vec3) -> Vec2 {
        Vec2::new(
            0.5 + 0.5 * local.x / (local.z * self.uv_factor),
            0.5 + 0.5 * local.y / (local.z * self.uv_factor),
        )
    }

    /// The direction from `p` towards the light with the radiance `I · falloff / d²` arriving
    /// along it (the texture not applied: see the module doc); `None` outside the cone.
    pub fn sample(&self, p: Vec3) -> Option<LightSample> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        let local = self.frame.to_local(-d);
        let falloff = self.falloff(local);
        if !(falloff > 0.0 && dist2 > 0.0) {
            return None;
        }
        let uv = if self.texture == NONE {
            Vec2::ZERO
        } else {
            self.uv(local)
        };
        Some(delta_sample(
            self.position,
            d / dist2.sqrt(),
            self.intensity * (falloff / dist2),
            uv,
        ))
    }

    /// Emitted power: `I · 2π (1 − (cos cutoff + cos beam) / 2)` (luminance; the falloff's
    /// integral over the sphere approximated by the mean of the two cones', pbrt-v4's), times a
    /// texture's selection radiance.
    pub fn power(&self) -> f32 {
        let solid_angle =
            2.0 * std::f32::consts::PI * (1.0 - 0.5 * (self.cos_cutoff + self.cos_beam));
        solid_angle * crate::math::luminance(self.intensity * self.selection)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    fn spot(cutoff_deg: f32, beam_deg: f32) -> SpotLight {
        let frame = Frame {
            s: Vec3::X,
            t: Vec3::Y,
            n: Vec3::Z,
        };
        SpotLight::new(
            Vec3::ZERO,
            frame,
            Vec3::ONE,
            cutoff_deg.to_radians(),
            beam_deg.to_radians(),
        )
    }

    /// Mitsuba's falloff curve: 1 inside the beam, linear in angle to 0 at the cutoff, 0 beyond
    /// and behind.
    #[test]
    fn falloff_is_mitsubas_curve() {
        let l = spot(30.0, 10.0);
        let at = |deg: f32| {
            let t = deg.to_radians();
            l.falloff(Vec3::new(t.sin(), 0.0, t.cos()) * 3.0)
        };
        assert_eq!(at(0.0), 1.0);
        assert_eq!(at(9.9), 1.0);
        assert!((at(20.0) - 0.5).abs() < 1e-5, "{}", at(20.0));
        assert!((at(25.0) - 0.25).abs() < 1e-5, "{}", at(25.0));
        assert_eq!(at(30.1), 0.0);
        assert_eq!(at(120.0), 0.0);
        assert_eq!(l.falloff(-Vec3::Z), 0.0);
        // A hard edge: no transition.
        let hard = spot(20.0, 20.0);
        let t = 19.9f32.to_radians();
        assert_eq!(hard.falloff(Vec3::new(t.sin(), 0.0, t.cos())), 1.0);
    }

    /// The texture spans [0, 1]² at the cutoff: the axis at the centre, the cone's edge along
    /// local ±x at u = 1 and 0 (Mitsuba's `direction_to_uv`).
    #[test]
    fn texture_coordinates_span_the_cutoff() {
        let l = spot(40.0, 30.0);
        assert_eq!(l.uv(Vec3::Z), Vec2::splat(0.5));
        let t = 40f32.to_radians();
        let edge = l.uv(Vec3::new(t.sin(), 0.0, t.cos()));
        assert!(
            (edge - Vec2::new(1.0, 0.5)).abs().max_element() < 1e-6,
            "{edge}"
        );
        let edge = l.uv(Vec3::new(0.0, -t.sin(), t.cos()) * 2.0);
        assert!(
            (edge - Vec2::new(0.5, 0.0)).abs().max_element() < 1e-6,
            "{edge}"
        );
    }

    /// On a plane at distance h below the light, the irradiance at horizontal offset x is
    /// `I · falloff(θ) · cos θ / (h² + x²)` with cos θ = h / √(h² + x²): the sample's radiance
    /// times the receiver's cosine.
    #[test]
    fn irradiance_on_a_plane_is_closed_form() {
        let l = spot(45.0, 15.0);
        let h = 2.0f32;
        for x in [0.0f32, 0.3, 1.0, 1.5, 1.9, 2.1, 5.0] {
            let p = Vec3::new(x, 0.0, h);
            let e = l
                .sample(p)
                .map_or(0.0, |s| s.le.x * s.wi.dot(-Vec3::Z).abs());
            let theta = (x / h).atan();
            let f = if theta < 15f32.to_radians() {
                1.0
            } else if theta < PI / 4.0 {
                (PI / 4.0 - theta) / (30f32.to_radians())
            } else {
                0.0
            };
            let want = f * h / (h * h + x * x).powf(1.5);
            assert!(
                (e - want).abs() <= 1e-5 * want.max(1e-3),
                "x {x}: {e} vs {want}"
            );
        }
    }
}
